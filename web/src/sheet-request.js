// What the design page's "Finite sheet" panel asks for and how it reads the answer, as data:
// the region text (`RxC` cells, `rect:W,H` or `disc:R` in mm, as `isogami sheet --region`),
// the query of GET /api/sheet, the equivalent `isogami sheet …` command, the DOF badge, the
// floppy tiles, the finite deployment's state at any t and the placement of tiles that are
// not in the deployed sheet. Pure functions, no DOM; finite-panel.js draws.
//
// Form state: { spec, kerf, shape: 'cells'|'rect'|'disc', rows, cols, width, height, radius }.
// A tile pose {x, y, theta} places the cell tile polygon p at (x, y) + R(theta)·p (tiling
// units), as the deployment frames do.

import { shellWord } from './export-request.js';

/** Frames of the finite deployment the panel asks for. */
export const SHEET_FRAMES = 48;

/** The region as `isogami sheet --region` writes it, or null when a size is not a positive
 * number (cells: whole numbers). */
export function regionText(form) {
  const positive = (v) => Number.isFinite(Number(v)) && Number(v) > 0 && String(v).trim() !== '';
  if (form.shape === 'rect') {
    return positive(form.width) && positive(form.height) ? `rect:${Number(form.width)},${Number(form.height)}` : null;
  }
  if (form.shape === 'disc') return positive(form.radius) ? `disc:${Number(form.radius)}` : null;
  const whole = (v) => Number.isInteger(Number(v)) && Number(v) >= 1;
  return whole(form.rows) && whole(form.cols) ? `${Number(form.rows)}x${Number(form.cols)}` : null;
}

/** The request as ordered [key, value] pairs: the keys of GET /api/sheet, which are
 * `isogami sheet`'s flags with underscores. The kerf only when it is not the default. */
export function sheetPairs(form, { defaultKerf = null, deploy = true, frames = SHEET_FRAMES } = {}) {
  const region = regionText(form);
  if (!region) return null;
  const pairs = [['design', form.spec], ['region', region]];
  const kerf = Number(form.kerf);
  if (form.kerf !== null && form.kerf !== undefined && Number.isFinite(kerf) && (defaultKerf === null || Math.abs(kerf - defaultKerf) > 1e-12)) {
    pairs.push(['kerf', String(kerf)]);
  }
  if (deploy) pairs.push(['deploy', 'true'], ['frames', String(frames)]);
  return pairs;
}

/** Whether the request names a kerf other than the default (which `isogami sheet` cannot). */
export function sheetKerfDiffers(form, options) {
  return (sheetPairs(form, options) ?? []).some(([key]) => key === 'kerf');
}

/** The query string of GET /api/sheet, or null for a region that is not valid. */
export function sheetParams(form, options) {
  const pairs = sheetPairs(form, options);
  return pairs ? new URLSearchParams(pairs) : null;
}

/** The `isogami sheet …` command that prints the same analysis (`--deploy` for the finite
 * deployment; frames are only in its --json). `isogami sheet` has no kerf flag: it uses the
 * default kerf, so a design at another kerf gets the command of the default one (see
 * `sheetKerfDiffers`). */
export function sheetCommand(form, options) {
  const pairs = sheetPairs(form, { ...options, deploy: true });
  if (!pairs) return '';
  const words = ['isogami', 'sheet'];
  for (const [key, value] of pairs) {
    if (key === 'frames' || key === 'kerf') continue;
    const flag = `--${key.replace(/_/g, '-')}`;
    if (key === 'deploy') words.push(flag);
    else if (key === 'design') words.push(flag, `'${String(value).replace(/'/g, `'\\''`)}'`);
    else words.push(flag, shellWord(value));
  }
  return words.join(' ');
}

/** Whether a mobility (the library's SheetMobility) is the design's one motion alone. */
export function isOneDof(mobility) {
  return mobility.dof === 1 && mobility.floppy.length === 0 && mobility.follows_periodic;
}

/** Every tile (index in the sheet's tiles) that moves in some extra mode, ascending: the
 * library's SheetMobility::floppy_tiles. */
export function floppyTiles(mobility) {
  return [...new Set(mobility.floppy.flatMap((m) => m.tiles))].sort((a, b) => a - b);
}

/** The badge of a mobility: {ok, text}. */
export function dofBadge(mobility) {
  if (isOneDof(mobility)) return { ok: true, text: '1 DOF ✓' };
  const n = floppyTiles(mobility).length;
  const what = n ? `${n === 1 ? 'this tile flops' : `these ${n} tiles flop`}` : 'it does not move with the periodic sheet';
  return { ok: false, text: `${mobility.dof} DOF: ${what}` };
}

/** Key of a sheet tile {cell: [i, j], tile}. */
export const tileKey = (t) => `${t.cell[0]},${t.cell[1]}#${t.tile}`;

/** Which tiles to draw and how, for the raw region or the completed sheet of an answer of
 * GET /api/sheet: [{tile, cell, pose, role}] with role 'floppy' | 'plain' (raw), or
 * 'kept' | 'added' | 'removed' (completed; removed tiles placed at their raw pose), and the
 * mobility shown. Null for `completed` when there is no completion. */
export function sheetLayers(answer, view) {
  const a = answer.analysis;
  if (view === 'raw' || !a.completion) {
    if (view !== 'raw') return null;
    const floppy = new Set(floppyTiles(a.raw_mobility));
    return {
      mobility: a.raw_mobility,
      tiles: a.raw.tiles.map((t, n) => ({ ...t, pose: answer.drawing.raw[n], role: floppy.has(n) ? 'floppy' : 'plain' })),
    };
  }
  const c = a.completion;
  const added = new Set(c.report.added.map(tileKey));
  const tiles = c.sheet.tiles.map((t, n) => ({ ...t, pose: answer.drawing.completed[n], role: added.has(tileKey(t)) ? 'added' : 'kept' }));
  const rawIndex = new Map(a.raw.tiles.map((t, n) => [tileKey(t), n]));
  for (const t of c.report.removed) {
    const n = rawIndex.get(tileKey(t));
    if (n !== undefined) tiles.push({ ...t, pose: answer.drawing.raw[n], role: 'removed' });
  }
  return { mobility: c.mobility, tiles };
}

const lerp = (a, b, s) => a + (b - a) * s;

/** The finite deployment's state at `t` in [0, 1] (its own normalised arc length): the poses of
 * its tiles between the two frames around t, the nearest frame's index and its measures. */
export function finiteFrameAt(deployment, t) {
  const frames = deployment?.frames ?? [];
  if (!frames.length) return null;
  let k = 0;
  while (k + 1 < frames.length && frames[k + 1].t <= t) k += 1;
  const a = frames[k];
  const b = frames[Math.min(k + 1, frames.length - 1)];
  const span = b.t - a.t;
  const s = span > 0 ? Math.min(1, Math.max(0, (t - a.t) / span)) : 0;
  const index = s < 0.5 ? k : Math.min(k + 1, frames.length - 1);
  return {
    t,
    index,
    measures: frames[index].measures,
    poses: a.poses.map((p, i) => ({ x: lerp(p.x, b.poses[i].x, s), y: lerp(p.y, b.poses[i].y, s), theta: lerp(p.theta, b.poses[i].theta, s) })),
  };
}

/** The lattice of a state from the poses of named sheet tiles: every tile of the infinite
 * sheet moves with the periodic mechanism's state (the finite deployment is that state with
 * contact among the sheet's tiles only), so copies of one cell tile in cells c and c' differ
 * by (c − c')·[u, w]. Least squares over those differences: {u, w}, or null when the tiles do
 * not span both lattice directions. */
export function latticeOf(tiles, poses) {
  const first = new Map();
  // Normal equations of Δp = Δi·u + Δj·w over pairs (each tile against the first copy of its
  // cell tile).
  let aii = 0;
  let aij = 0;
  let ajj = 0;
  const bi = [0, 0];
  const bj = [0, 0];
  tiles.forEach((t, n) => {
    const m = first.get(t.tile);
    if (m === undefined) {
      first.set(t.tile, n);
      return;
    }
    const di = t.cell[0] - tiles[m].cell[0];
    const dj = t.cell[1] - tiles[m].cell[1];
    const dx = poses[n].x - poses[m].x;
    const dy = poses[n].y - poses[m].y;
    aii += di * di;
    aij += di * dj;
    ajj += dj * dj;
    bi[0] += di * dx;
    bi[1] += di * dy;
    bj[0] += dj * dx;
    bj[1] += dj * dy;
  });
  const det = aii * ajj - aij * aij;
  if (!(Math.abs(det) > 1e-9)) return null;
  const solve = (c) => [(ajj * bi[c] - aij * bj[c]) / det, (aii * bj[c] - aij * bi[c]) / det];
  const [ux, wx] = solve(0);
  const [uy, wy] = solve(1);
  return { u: [ux, uy], w: [wx, wy] };
}

/** The pose of the tile {cell, tile} at a state given by the poses of a sheet's tiles (see
 * latticeOf), or null when no copy of its cell tile is in the sheet or the lattice is unknown. */
export function poseOutside(target, tiles, poses, lattice) {
  if (!lattice) return null;
  const n = tiles.findIndex((t) => t.tile === target.tile);
  if (n < 0) return null;
  const di = target.cell[0] - tiles[n].cell[0];
  const dj = target.cell[1] - tiles[n].cell[1];
  const p = poses[n];
  return { x: p.x + di * lattice.u[0] + dj * lattice.w[0], y: p.y + di * lattice.u[1] + dj * lattice.w[1], theta: p.theta };
}

/** World vertices of a cell tile polygon placed by a pose. */
export function placePolygon(polygon, pose) {
  const c = Math.cos(pose.theta);
  const s = Math.sin(pose.theta);
  return polygon.map(([px, py]) => [pose.x + c * px - s * py, pose.y + s * px + c * py]);
}
