// The finite-sheet panel's pure helpers: the region text and query of GET /api/sheet and the
// `isogami sheet` command say the same thing; the DOF badge and floppy tiles read the
// library's SheetMobility; the layers of an answer; the finite deployment between frames; tiles
// outside the deployed sheet placed by the lattice of its tiles.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  dofBadge, finiteFrameAt, floppyTiles, latticeOf, placePolygon, poseOutside, regionText, sheetCommand,
  sheetKerfDiffers, sheetLayers, sheetPairs, sheetParams, SHEET_FRAMES,
} from '../src/sheet-request.js';
import { shellSplit } from './shell.mjs';

const form = (extra = {}) => ({ spec: 'IH1:0.12,0.5:2x1:--bbb-', kerf: 0.01, shape: 'cells', rows: '3', cols: '5', width: '', height: '', radius: '', ...extra });

test('regions are written as `isogami sheet --region` reads them; bad sizes give none', () => {
  assert.equal(regionText(form()), '3x5');
  assert.equal(regionText(form({ shape: 'rect', width: '120', height: '80.5' })), 'rect:120,80.5');
  assert.equal(regionText(form({ shape: 'disc', radius: '40' })), 'disc:40');
  for (const bad of [form({ rows: '0' }), form({ cols: '2.5' }), form({ rows: '' }), form({ shape: 'rect', width: '-1', height: '3' }), form({ shape: 'disc', radius: '' }), form({ shape: 'disc', radius: 'x' })]) {
    assert.equal(regionText(bad), null, JSON.stringify(bad));
    assert.equal(sheetParams(bad), null);
  }
});

test('the query asks for the deployment and leaves the default kerf out; the command says the same', () => {
  const p = sheetParams(form(), { defaultKerf: 0.01 });
  assert.deepEqual([...p], [['design', 'IH1:0.12,0.5:2x1:--bbb-'], ['region', '3x5'], ['deploy', 'true'], ['frames', String(SHEET_FRAMES)]]);
  assert.equal(new Map(sheetPairs(form({ kerf: 0.02 }), { defaultKerf: 0.01 })).get('kerf'), '0.02');
  assert.equal(new Map(sheetPairs(form(), { defaultKerf: 0.01, deploy: false })).get('deploy'), undefined);
  const words = shellSplit(sheetCommand(form({ shape: 'disc', radius: '35' }), { defaultKerf: 0.01 }));
  assert.deepEqual(words, ['isogami', 'sheet', '--design', 'IH1:0.12,0.5:2x1:--bbb-', '--region', 'disc:35', '--deploy']);
  // `isogami sheet` has no kerf flag: a design at another kerf is said to differ.
  assert.ok(!sheetCommand(form({ kerf: 0.02 }), { defaultKerf: 0.01 }).includes('kerf'));
  assert.equal(sheetKerfDiffers(form({ kerf: 0.02 }), { defaultKerf: 0.01 }), true);
  assert.equal(sheetKerfDiffers(form(), { defaultKerf: 0.01 }), false);
  assert.deepEqual(shellSplit(sheetCommand(form({ spec: "it's" })))[3], "it's");
});

const mobility = (extra = {}) => ({ dof: 1, floppy: [], follows_periodic: true, loose_tiles: [], ...extra });

test('the badge: one DOF with the periodic motion, or the DOF and how many tiles flop', () => {
  assert.deepEqual(dofBadge(mobility()), { ok: true, text: '1 DOF ✓' });
  const floppy = mobility({ dof: 3, floppy: [{ tiles: [4, 2, 9] }, { tiles: [9, 11] }] });
  assert.deepEqual(floppyTiles(floppy), [2, 4, 9, 11]);
  assert.deepEqual(dofBadge(floppy), { ok: false, text: '3 DOF: these 4 tiles flop' });
  assert.equal(dofBadge(mobility({ dof: 2, floppy: [{ tiles: [0] }] })).text, '2 DOF: this tile flops');
  // One DOF that is not the periodic motion is not "✓".
  assert.equal(dofBadge(mobility({ follows_periodic: false })).ok, false);
});

const tile = (i, j, k) => ({ cell: [i, j], tile: k });
const pose = (x, y, theta = 0) => ({ x, y, theta });

/** An answer of GET /api/sheet: a raw 2×1 region of a 2-tile cell, tile [1,0]#1 floppy and
 * removed, [2,0]#0 added. */
function answer() {
  const raw = [tile(0, 0, 0), tile(0, 0, 1), tile(1, 0, 0), tile(1, 0, 1)];
  const done = [tile(0, 0, 0), tile(0, 0, 1), tile(1, 0, 0), tile(2, 0, 0)];
  return {
    analysis: {
      raw: { tiles: raw, joints: [] },
      raw_mobility: mobility({ dof: 2, floppy: [{ tiles: [3] }] }),
      completion: {
        sheet: { tiles: done, joints: [] },
        mobility: mobility(),
        report: { requested: 4, kept: 3, removed: [tile(1, 0, 1)], added: [tile(2, 0, 0)], covered_fraction: 0.75 },
      },
    },
    drawing: {
      tiles: [[[0, 0], [1, 0], [0, 1]], [[0, 0], [1, 1], [0, 1]]],
      raw: raw.map((t) => pose(t.cell[0] * 10 + t.tile, 0)),
      completed: done.map((t) => pose(t.cell[0] * 10 + t.tile, 0)),
    },
  };
}

test('layers: the raw region with its floppy tiles; the completion with kept, added and removed tiles', () => {
  const a = answer();
  const raw = sheetLayers(a, 'raw');
  assert.deepEqual(raw.tiles.map((t) => t.role), ['plain', 'plain', 'plain', 'floppy']);
  assert.equal(raw.mobility.dof, 2);
  const done = sheetLayers(a, 'completed');
  assert.deepEqual(done.tiles.map((t) => `${t.cell[0]}#${t.tile}:${t.role}`), ['0#0:kept', '0#1:kept', '1#0:kept', '2#0:added', '1#1:removed']);
  // A removed tile is placed where the raw region had it.
  assert.deepEqual(done.tiles[4].pose, a.drawing.raw[3]);
  assert.equal(done.mobility.dof, 1);
  a.analysis.completion = null;
  assert.equal(sheetLayers(a, 'completed'), null);
});

test('the finite deployment between frames, and its nearest frame', () => {
  const d = {
    frames: [
      { t: 0, measures: { hull_area_ratio: 1 }, poses: [pose(0, 0, 0), pose(1, 0, 0)] },
      { t: 0.5, measures: { hull_area_ratio: 1.5 }, poses: [pose(0, 0, 0.2), pose(3, 0, 0.4)] },
      { t: 1, measures: { hull_area_ratio: 2 }, poses: [pose(0, 0, 0.4), pose(5, 0, 0.8)] },
    ],
  };
  const f = finiteFrameAt(d, 0.25);
  assert.equal(f.poses[1].x, 2);
  assert.ok(Math.abs(f.poses[1].theta - 0.2) < 1e-12);
  assert.equal(f.index, 1);
  assert.equal(finiteFrameAt(d, 0.2).index, 0);
  assert.equal(finiteFrameAt(d, 1).index, 2);
  assert.equal(finiteFrameAt(d, 1).measures.hull_area_ratio, 2);
  assert.equal(finiteFrameAt({ frames: [] }, 0.5), null);
});

test('tiles outside a sheet are placed by the lattice its tiles span', () => {
  const u = [2, 0.5];
  const w = [-0.3, 1.7];
  const base = [pose(0.1, 0.2, 0.3), pose(0.9, 0.4, -0.2)];
  const at = (t) => {
    const b = base[t.tile];
    return pose(b.x + t.cell[0] * u[0] + t.cell[1] * w[0], b.y + t.cell[0] * u[1] + t.cell[1] * w[1], b.theta);
  };
  const tiles = [tile(0, 0, 0), tile(1, 0, 0), tile(0, 1, 0), tile(1, 1, 1), tile(2, 1, 1)];
  const poses = tiles.map(at);
  const lattice = latticeOf(tiles, poses);
  for (const [got, want] of [[lattice.u, u], [lattice.w, w]]) {
    for (let d = 0; d < 2; d += 1) assert.ok(Math.abs(got[d] - want[d]) < 1e-12, `${got} vs ${want}`);
  }
  for (const target of [tile(3, -2, 0), tile(-1, 4, 1)]) {
    const got = poseOutside(target, tiles, poses, lattice);
    const want = at(target);
    assert.ok(Math.abs(got.x - want.x) < 1e-12 && Math.abs(got.y - want.y) < 1e-12 && got.theta === want.theta);
  }
  // One row of cells does not span w; a cell tile with no copy in the sheet cannot be placed.
  assert.equal(latticeOf([tile(0, 0, 0), tile(1, 0, 0)], [pose(0, 0), pose(2, 0)]), null);
  assert.equal(poseOutside(tile(0, 0, 2), tiles, poses, lattice), null);
});

test('a polygon placed by a pose turns about its centroid and moves to it', () => {
  const got = placePolygon([[1, 0], [0, 2]], pose(5, -1, Math.PI / 2));
  assert.ok(Math.abs(got[0][0] - 5) < 1e-12 && Math.abs(got[0][1] - 0) < 1e-12);
  assert.ok(Math.abs(got[1][0] - 3) < 1e-12 && Math.abs(got[1][1] + 1) < 1e-12);
});
