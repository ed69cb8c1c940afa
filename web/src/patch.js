// Geometry of an R×C patch of a design at any t, from a DesignView: frames interpolated in t,
// world polygons of every tile copy, pin positions, linkage loops (each through its joints, in
// its linkage's colour, as the paper's Fig. 6), bounds over the whole motion, and tile colours
// (by linkage — only for a tile in exactly one linkage; tiles shared by several are grey — or
// by rotation). Shared by the canvas (sheet.js) and the SVG export so both draw the same
// thing. Pure functions, no DOM.
//
// Tile k of cell (i, j) in a frame: world = (x, y) + R(θ)·p + i·u + j·w, with p the tile's
// polygon in its own frame (geometry.tiles[k]) and (x, y, θ) its pose in the frame.

import * as d3 from 'd3';

const lerp = (a, b, s) => a + (b - a) * s;
const lerp2 = (a, b, s) => [lerp(a[0], b[0], s), lerp(a[1], b[1], s)];

/** The state of the sheet at `t`: poses, u, w, F and tile rotations, between two frames. */
export function frameAt(report, t) {
  const frames = report.frames;
  if (!frames.length) return null;
  let k = 0;
  while (k + 1 < frames.length && frames[k + 1].t <= t) k += 1;
  const a = frames[k];
  const b = frames[Math.min(k + 1, frames.length - 1)];
  const span = b.t - a.t;
  const s = span > 0 ? Math.min(1, Math.max(0, (t - a.t) / span)) : 0;
  return {
    t,
    index: s < 0.5 ? k : Math.min(k + 1, frames.length - 1),
    u: lerp2(a.u, b.u, s),
    w: lerp2(a.w, b.w, s),
    F: [lerp2(a.F[0], b.F[0], s), lerp2(a.F[1], b.F[1], s)],
    tiles: a.tiles.map((p, i) => ({
      x: lerp(p.x, b.tiles[i].x, s),
      y: lerp(p.y, b.tiles[i].y, s),
      theta: lerp(p.theta, b.tiles[i].theta, s),
    })),
    rotations: a.measures.tile_rotations.map((r, i) => lerp(r, b.measures.tile_rotations[i], s)),
  };
}

function place(pose, p, shift) {
  const c = Math.cos(pose.theta);
  const s = Math.sin(pose.theta);
  return [pose.x + c * p[0] - s * p[1] + shift[0], pose.y + s * p[0] + c * p[1] + shift[1]];
}

function shiftOf(frame, i, j) {
  return [i * frame.u[0] + j * frame.w[0], i * frame.u[1] + j * frame.w[1]];
}

/** Cells (i, j) of an R×C patch: i along u (columns), j along w (rows). */
export function patchCells(rows, cols) {
  const out = [];
  for (let j = 0; j < rows; j += 1) for (let i = 0; i < cols; i += 1) out.push([i, j]);
  return out;
}

/** World polygons `[{tile, cell:[i,j], points}]` of the patch in `frame`. */
export function patchPolygons(view, frame, rows, cols) {
  const out = [];
  for (const [i, j] of patchCells(rows, cols)) {
    const shift = shiftOf(frame, i, j);
    view.geometry.tiles.forEach((poly, k) => {
      out.push({ tile: k, cell: [i, j], points: poly.map((p) => place(frame.tiles[k], p, shift)) });
    });
  }
  return out;
}

/** A closed-state point on tile `k` in that tile's own frame (inverse of the first frame's pose). */
function localPoint(view, k, point) {
  const pose = view.report.frames[0].tiles[k];
  const dx = point[0] - pose.x;
  const dy = point[1] - pose.y;
  const c = Math.cos(pose.theta);
  const s = Math.sin(pose.theta);
  return [c * dx + s * dy, -s * dx + c * dy];
}

/** Pins of the patch in `frame`: `[[x, y]]`, one per jointed edge end per cell copy. */
export function patchPins(view, frame, rows, cols) {
  const local = [];
  for (const e of view.geometry.edges) {
    const ends = e.joint === 'a' ? [e.a] : e.joint === 'b' ? [e.b] : e.joint === 'x' ? [e.a, e.b] : [];
    for (const end of ends) local.push([e.tile_a, localPoint(view, e.tile_a, end)]);
  }
  const out = [];
  for (const [i, j] of patchCells(rows, cols)) {
    const shift = shiftOf(frame, i, j);
    for (const [k, p] of local) out.push(place(frame.tiles[k], p, shift));
  }
  return out;
}

/** Linkage loops of the patch: `[{index, bars, cell, points}]`, one polygon through the joints of
 * each linkage per cell copy whose tiles all lie in the patch's cells (a linkage none of whose
 * copies fits, in a small patch, is drawn once, from cell (0, 0)). */
export function patchLinkages(view, frame, rows, cols) {
  const analysis = view.linkages;
  if (!analysis) return [];
  const edges = view.geometry.edges;
  const inside = (i, j) => i >= 0 && j >= 0 && i < cols && j < rows;
  const out = [];
  analysis.linkages.forEach((linkage, index) => {
    const joints = linkage.joints.map((jt) => {
      const e = edges[jt.edge];
      const end = String(jt.end).toLowerCase() === 'a' ? e.a : e.b;
      return { tile: e.tile_a, cell: jt.cell, p: localPoint(view, e.tile_a, end) };
    });
    const loop = (i, j) => ({
      index,
      bars: linkage.bars,
      cell: [i, j],
      points: joints.map((jt) => place(frame.tiles[jt.tile], jt.p, shiftOf(frame, i + jt.cell[0], j + jt.cell[1]))),
    });
    const cells = patchCells(rows, cols).filter(([i, j]) =>
      linkage.nodes.every(([, c]) => inside(i + c[0], j + c[1])),
    );
    for (const [i, j] of cells.length ? cells : [[0, 0]]) out.push(loop(i, j));
  });
  return out;
}

/** The unit cell at the centre of the patch: its parallelogram corners and origin. */
export function unitCell(view, frame, rows, cols) {
  const n = frame.tiles.length;
  const cx = frame.tiles.reduce((s, p) => s + p.x, 0) / n;
  const cy = frame.tiles.reduce((s, p) => s + p.y, 0) / n;
  const [si, sj] = shiftOf(frame, Math.floor(cols / 2), Math.floor(rows / 2));
  const o = [cx + si - (frame.u[0] + frame.w[0]) / 2, cy + sj - (frame.u[1] + frame.w[1]) / 2];
  const { u, w } = frame;
  return {
    origin: o,
    u,
    w,
    corners: [o, [o[0] + u[0], o[1] + u[1]], [o[0] + u[0] + w[0], o[1] + u[1] + w[1]], [o[0] + w[0], o[1] + w[1]]],
  };
}

/** Bounding box `[minX, minY, maxX, maxY]` of the patch over the whole motion. */
export function motionBounds(view, rows, cols) {
  let b = [Infinity, Infinity, -Infinity, -Infinity];
  const frames = view.report.frames;
  const step = Math.max(1, Math.floor(frames.length / 30));
  for (let f = 0; f < frames.length; f += step) b = grow(b, view, frameAt(view.report, frames[f].t), rows, cols);
  b = grow(b, view, frameAt(view.report, frames[frames.length - 1].t), rows, cols);
  return b;
}

function grow(b, view, frame, rows, cols) {
  const out = [...b];
  for (const poly of patchPolygons(view, frame, rows, cols)) {
    for (const [x, y] of poly.points) {
      out[0] = Math.min(out[0], x);
      out[1] = Math.min(out[1], y);
      out[2] = Math.max(out[2], x);
      out[3] = Math.max(out[3], y);
    }
  }
  return out;
}

// Loop colours: the Okabe–Ito colour-blind-safe set (without black and the low-contrast yellow)
// and two more; strong enough to read as lines over the tiles.
const LINKAGE_COLOURS = ['#0072b2', '#e69f00', '#009e73', '#cc79a7', '#d55e00', '#56b4e9', '#6a3d9a', '#8c6d1f'];
/** Fill of a tile shared by several linkages: the assignment does not tell them apart. */
export const SHARED_LINKAGE_COLOUR = '#d9d9d9';
/** Fill of a tile in no linkage. */
export const NO_LINKAGE_COLOUR = '#ffffff';

/** Colour of linkage `index`: its loop's stroke and legend swatch. */
export function linkageColour(index) {
  return LINKAGE_COLOURS[index % LINKAGE_COLOURS.length];
}

/** Fill of a tile in linkage `index` only: its loop colour mixed 70 % with white. */
export function linkageFill(index) {
  const n = parseInt(linkageColour(index).slice(1), 16);
  const ch = (shift) => Math.round(255 - (255 - ((n >> shift) & 255)) * 0.3);
  return `#${[ch(16), ch(8), ch(0)].map((v) => v.toString(16).padStart(2, '0')).join('')}`;
}

/** Every linkage through tile `k` (indices, ascending). */
export function tileLinkageSet(view, k) {
  return (view.tile_linkages || [])[k] || [];
}

/** How the linkage colouring reads for this view: `{single, shared, none}` counts of tiles in
 * one, several and no linkage — the legend shows only the kinds present. */
export function tileLinkageKinds(view) {
  const kinds = { single: 0, shared: 0, none: 0 };
  view.geometry.tiles.forEach((_, k) => {
    const n = tileLinkageSet(view, k).length;
    kinds[n === 0 ? 'none' : n === 1 ? 'single' : 'shared'] += 1;
  });
  return kinds;
}

/** A function tile → fill colour for the chosen colouring. By linkage: a tile in exactly one
 * linkage takes that linkage's pale colour, a tile in several is grey, a tile in none white. */
export function tileColours(view, frame, colour) {
  if (colour === 'rotation') {
    const m = Math.max(1e-6, view.report.max_tile_rotation || 0);
    const scale = d3.scaleDiverging(d3.interpolateRdBu).domain([m, 0, -m]);
    return (k) => scale(frame.rotations[k] ?? 0);
  }
  return (k) => {
    const set = tileLinkageSet(view, k);
    if (set.length === 1) return linkageFill(set[0]);
    return set.length ? SHARED_LINKAGE_COLOUR : NO_LINKAGE_COLOUR;
  };
}
