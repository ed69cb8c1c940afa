// patch.js: tile colours by linkage only where a tile is in one linkage (issue 24 item 5: a tile
// in several linkages got the smallest one's colour, so IH16 showed one colour), and linkage
// loops per cell copy whose tiles lie in the patch.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  linkageColour, linkageFill, NO_LINKAGE_COLOUR, patchLinkages, SHARED_LINKAGE_COLOUR, tileColours, tileLinkageKinds,
} from '../src/patch.js';

const square = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
const pose = (x, y) => ({ x, y, theta: 0 });

/** Three unit squares in a row per cell (u = (3, 0), w = (0, 1)); a "linkage" through tiles
 * 0 and 1 of cell 0 and tile 0 of the next cell along u. */
function view(tileLinkages) {
  return {
    geometry: {
      tiles: [square, square, square],
      edges: [
        { tile_a: 0, a: [0.5, -0.5], b: [0.5, 0.5], joint: 'a' },
        { tile_a: 1, a: [1.5, -0.5], b: [1.5, 0.5], joint: 'b' },
        { tile_a: 2, a: [2.5, -0.5], b: [2.5, 0.5], joint: 'a' },
      ],
    },
    report: { frames: [{ t: 0, u: [3, 0], w: [0, 1], tiles: [pose(0, 0), pose(1, 0), pose(2, 0)] }] },
    linkages: {
      linkages: [
        {
          bars: 3,
          nodes: [[0, [0, 0]], [1, [0, 0]], [0, [1, 0]]],
          joints: [
            { edge: 0, end: 'A', cell: [0, 0] },
            { edge: 1, end: 'B', cell: [0, 0] },
            { edge: 2, end: 'A', cell: [0, 0] },
          ],
        },
        { bars: 3, nodes: [[1, [0, 0]]], joints: [{ edge: 1, end: 'A', cell: [0, 0] }] },
      ],
    },
    tile_linkages: tileLinkages,
  };
}

test('a tile takes a linkage colour only when it is in that linkage alone', () => {
  const v = view([[0], [0, 1], []]);
  const fill = tileColours(v, v.report.frames[0], 'linkage');
  assert.equal(fill(0), linkageFill(0));
  assert.equal(fill(1), SHARED_LINKAGE_COLOUR, 'shared by two: not the smaller one');
  assert.equal(fill(2), NO_LINKAGE_COLOUR);
  assert.deepEqual(tileLinkageKinds(v), { single: 1, shared: 1, none: 1 });
  assert.notEqual(linkageFill(0), linkageFill(1));
  assert.notEqual(linkageFill(0), SHARED_LINKAGE_COLOUR);
  assert.notEqual(linkageColour(0), linkageColour(1));
  assert.match(linkageFill(0), /^#[0-9a-f]{6}$/);
});

test('all three IH16-like tiles in all linkages: every tile grey, none coloured', () => {
  const v = view([[0, 1], [0, 1], [0, 1]]);
  const fill = tileColours(v, v.report.frames[0], 'linkage');
  assert.deepEqual([0, 1, 2].map(fill), [SHARED_LINKAGE_COLOUR, SHARED_LINKAGE_COLOUR, SHARED_LINKAGE_COLOUR]);
});

test('loops are drawn where all their tiles lie in the patch, through their joints', () => {
  const v = view([[0], [0, 1], []]);
  const frame = { ...v.report.frames[0] };
  const loops = patchLinkages(v, frame, 2, 2).filter((l) => l.index === 0);
  // The first linkage reaches one cell along u: in a 2×2 patch only column 0 holds it whole.
  assert.deepEqual(loops.map((l) => l.cell), [[0, 0], [0, 1]]);
  assert.deepEqual(loops[1].points, [[0.5, 0.5], [1.5, 1.5], [2.5, 0.5]], 'joint ends A, B, A of cell (0, 1)');
  const small = patchLinkages(v, frame, 1, 1).filter((l) => l.index === 0);
  assert.deepEqual(small.map((l) => l.cell), [[0, 0]], 'a patch too small for any copy still shows one');
});
