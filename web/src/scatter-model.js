// The scatter's pure helpers, no DOM: designs that fall on one spot gathered into stacks (at a
// resolution tied to the view, so a stack is what the eye sees as one point), colour keys and
// palettes (behaviour or family), axis ticks whose labels stay short and distinct on any range
// (an offset label when the span is tiny next to the values, one tick when all are equal), a
// brushed rectangle as rounded range bounds, the stack under the pointer, and the nearest stack
// in an arrow key's direction.

import * as d3 from 'd3';

/** Okabe & Ito's colour-blind-safe palette (black left out), then grey for "other". */
export const PALETTE = ['#0072B2', '#E69F00', '#009E73', '#CC79A7', '#56B4E9', '#D55E00', '#F0E442'];
export const OTHER = '#8c8c8c';

/**
 * The grid step of an axis whose view spans `span`: a power of ten between span/10⁴ and
 * span/10³, so points closer than about half a pixel of a 500-pixel plot share a stack, and the
 * grid moves only when a zoom crosses a power of ten.
 */
export function stackQuantum(span) {
  if (!(span > 0) || !Number.isFinite(span)) return 0;
  return Number(`1e${Math.floor(Math.log10(span / 1000))}`);
}

/**
 * Points `{x, y, …}` gathered into stacks: by the grid cell of steps (qx, qy) they fall in
 * (exact values when a step is 0), occupied cells that touch (side or corner) joined, so two
 * points closer than a step never part on a cell border. Each stack: `{x, y}` the mean of its
 * points, `points` in input order; stacks in the order of their first point.
 */
export function stackPoints(points, qx, qy) {
  const cells = new Map();
  const key = (v, q) => (q > 0 ? Math.round(v / q) : v);
  for (const p of points) {
    const i = key(p.x, qx);
    const j = key(p.y, qy);
    const k = `${i}|${j}`;
    let c = cells.get(k);
    if (!c) {
      c = { i, j, points: [], parent: null };
      cells.set(k, c);
    }
    c.points.push(p);
  }
  const root = (c) => {
    while (c.parent) c = c.parent;
    return c;
  };
  if (qx > 0 && qy > 0) {
    for (const c of cells.values()) {
      for (let di = -1; di <= 1; di += 1) {
        for (let dj = -1; dj <= 1; dj += 1) {
          const n = cells.get(`${c.i + di}|${c.j + dj}`);
          if (!n) continue;
          const a = root(c);
          const b = root(n);
          if (a !== b) b.parent = a;
        }
      }
    }
  }
  const groups = new Map();
  for (const p of points) {
    const r = root(cells.get(`${key(p.x, qx)}|${key(p.y, qy)}`));
    let s = groups.get(r);
    if (!s) {
      s = { x: 0, y: 0, points: [] };
      groups.set(r, s);
    }
    s.points.push(p);
  }
  const stacks = [...groups.values()];
  for (const s of stacks) {
    s.x = d3.mean(s.points, (p) => p.x);
    s.y = d3.mean(s.points, (p) => p.y);
  }
  return stacks;
}

/** The category of a point under colouring `by` ('behaviour' or 'family'). */
export function categoryOf(point, by) {
  return by === 'family' ? point.family ?? 'none' : point.behaviour ?? 'unclassified';
}

const BEHAVIOUR_ORDER = ['isotropic_auxetic', 'anisotropic_auxetic', 'orthotropic_positive_poisson'];

/**
 * The legend of colouring `by` over `points`: `[{key, label, colour, count}]`. Behaviours keep
 * their fixed colours; families are ranked by count, the first PALETTE.length − (1 if more)
 * get colours and the rest share one grey entry ("k other families"). `colourOf(point)` maps a
 * point to its entry's colour, `entryOf(point)` to its entry.
 */
export function colourKey(points, by) {
  const counts = d3.rollup(points, (v) => v.length, (p) => categoryOf(p, by));
  let entries;
  if (by === 'family') {
    const ranked = [...counts].sort((a, b) => b[1] - a[1] || familyNumber(a[0]) - familyNumber(b[0]));
    const room = ranked.length > PALETTE.length ? PALETTE.length - 1 : PALETTE.length;
    entries = ranked.slice(0, room).map(([key, count], i) => ({ key, label: key, colour: PALETTE[i], count }));
    const rest = ranked.slice(room);
    if (rest.length) {
      entries.push({
        key: '*other',
        label: `${rest.length} other ${rest.length === 1 ? 'family' : 'families'}`,
        colour: OTHER,
        count: d3.sum(rest, (r) => r[1]),
        members: new Set(rest.map((r) => r[0])),
      });
    }
  } else {
    entries = [...counts]
      .sort((a, b) => rank(a[0]) - rank(b[0]))
      .map(([key, count]) => ({
        key,
        label: key === 'unclassified' ? 'unclassified' : key.replace(/_/g, ' '),
        colour: rank(key) < BEHAVIOUR_ORDER.length ? PALETTE[rank(key)] : OTHER,
        count,
      }));
  }
  const byKey = new Map(entries.map((e) => [e.key, e]));
  const other = byKey.get('*other');
  const entryOf = (p) => byKey.get(categoryOf(p, by)) ?? other;
  return { entries, entryOf, colourOf: (p) => entryOf(p)?.colour ?? OTHER };
}

function rank(behaviour) {
  const i = BEHAVIOUR_ORDER.indexOf(behaviour);
  return i < 0 ? BEHAVIOUR_ORDER.length : i;
}

function familyNumber(name) {
  const n = Number(/\d+/.exec(name)?.[0]);
  return Number.isFinite(n) ? n : Infinity;
}

/** The slices of a stack for a pie: `[{colour, count}]`, largest first. */
export function stackSlices(stack, key) {
  const counts = d3.rollup(stack.points, (v) => v.length, (p) => key.colourOf(p));
  return [...counts].map(([colour, count]) => ({ colour, count })).sort((a, b) => b.count - a.count);
}

/** The drawn radius of a stack of `count` designs (3 px for one, growing with √count, ≤ 22). */
export function stackRadius(count) {
  return Math.min(22, 3 + 2 * Math.sqrt(count - 1));
}

/** How far from a stack's centre the pointer still picks it: its radius, at least 4 px, plus
 * 3 px of slack (a lone design is a small target). */
export function pickRadius(r) {
  return Math.max(r, 4) + 3;
}

/**
 * The index of the stack that the pointer at (px, py) picks among drawn stacks `[{px, py, r}]`,
 * or -1: among stacks within their pick radius, the one nearest in units of that radius. A
 * stack's centre is always its own (distance 0), and a small stack drawn over a big one takes
 * only the part of the big disc nearer to it in those units, not its whole pick disc.
 */
export function pickStack(stacks, px, py) {
  let best = -1;
  let bestScore = Infinity;
  stacks.forEach((s, i) => {
    const reach = pickRadius(s.r);
    const score = Math.hypot(s.px - px, s.py - py) / reach;
    if (score <= 1 && score < bestScore) {
      bestScore = score;
      best = i;
    }
  });
  return best;
}

const MINUS = '\u2212';

/** A number in full for a reader (up to 12 significant digits, trailing zeros dropped). */
export function fullNumber(v) {
  return typeset(d3.format('.12~g')(v));
}

/** Hyphens (d3 leaves them in exponents) as minus signs. */
function typeset(text) {
  return text.replace(/-/g, MINUS);
}

/**
 * Ticks of an axis over `domain` with about `count` ticks: `{values, labels, offset}`. Labels
 * carry as many decimals as the tick step needs and no more; when the span is under 10⁻⁴ of the
 * values, ticks are labelled by their difference from `offset` (a round value inside the
 * domain with the fewest digits, `{value, label}`), so the labels stay short and distinct; an empty domain (lo = hi)
 * gets one tick labelled in full.
 */
export function axisTicks([lo, hi], count) {
  if (!(hi > lo)) return { values: [lo], labels: [fullNumber(lo)], offset: null };
  const values = d3.ticks(lo, hi, count);
  const step = d3.tickStep(lo, hi, count);
  const mag = Math.max(Math.abs(lo), Math.abs(hi));
  if (step < mag * 1e-4) {
    const ref = roundestInside(lo, hi, step);
    const deltas = values.map((v) => v - ref);
    const big = d3.max(deltas, Math.abs) || step;
    const digits = Math.max(0, Math.floor(Math.log10(big)) - Math.floor(Math.log10(step)));
    const f = d3.format(`+.${digits}~e`);
    return {
      values,
      labels: deltas.map((d) => (Math.abs(d) < step / 2 ? '0' : typeset(f(d)))),
      offset: { value: ref, label: fullNumber(ref) },
    };
  }
  let format;
  if (mag >= 1e6 || (mag < 1e-3 && mag > 0)) {
    const digits = Math.max(0, Math.floor(Math.log10(mag)) - Math.floor(Math.log10(step)));
    format = d3.format(`.${digits}~e`);
  } else {
    format = d3.format(`.${d3.precisionFixed(step)}f`);
  }
  return { values, labels: values.map((v) => typeset(format(v))), offset: null };
}

/** The number inside [lo, hi] with the fewest significant digits (at worst a multiple of
 * `step`, as a tick is). */
function roundestInside(lo, hi, step) {
  const top = Math.ceil(Math.log10(Math.max(Math.abs(lo), Math.abs(hi))));
  for (let k = top; k >= Math.floor(Math.log10(step)) - 1; k -= 1) {
    const unit = Number(`1e${k}`);
    const c = Number((Math.ceil(lo / unit) * unit).toPrecision(15));
    if (c >= lo && c <= hi) return c;
  }
  return (lo + hi) / 2;
}

/** Ticks over `domain` whose labels (≈ `charWidth` px per character, `gap` px apart) fit in
 * `length` px: the largest count ≤ `want` that fits (at least one tick). */
export function fittingTicks(domain, length, want, { charWidth = 7, gap = 10, vertical = false } = {}) {
  for (let n = want; n >= 1; n -= 1) {
    const t = axisTicks(domain, n);
    const widest = vertical ? 14 : d3.max(t.labels, (l) => l.length * charWidth) ?? 0;
    if (t.values.length <= 1 || t.values.length * (widest + gap) <= length) return t;
  }
  return axisTicks(domain, 1);
}

/**
 * A brushed interval [a, b] as range bounds rounded outward to 3 significant digits of its
 * width (so every value inside stays inside and the URL stays short): `{min, max}`.
 */
export function roundedRange(a, b) {
  const lo = Math.min(a, b);
  const hi = Math.max(a, b);
  const span = hi - lo;
  if (!(span > 0)) return { min: lo, max: hi };
  const q = 10 ** (Math.floor(Math.log10(span)) - 2);
  const digits = Math.max(0, -Math.floor(Math.log10(q)));
  const min = Number((Math.floor(lo / q) * q).toFixed(Math.min(digits, 100)));
  const max = Number((Math.ceil(hi / q) * q).toFixed(Math.min(digits, 100)));
  return { min: min > lo ? lo : min, max: max < hi ? hi : max };
}

const DIRECTIONS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };

/**
 * The index of the stack nearest to `from` (pixel positions `{px, py}`) in the direction of
 * arrow key `key` (screen coordinates, y down): among stacks lying within 60° of that
 * direction, the one with the least distance plus twice its sideways offset; -1 when none.
 */
export function nearestInDirection(stacks, from, key) {
  const dir = DIRECTIONS[key];
  if (!dir) return -1;
  let best = -1;
  let bestScore = Infinity;
  stacks.forEach((s, i) => {
    const dx = s.px - from.px;
    const dy = s.py - from.py;
    const along = dx * dir[0] + dy * dir[1];
    const side = Math.abs(dx * dir[1] - dy * dir[0]);
    if (along <= 0 || side > along * Math.tan(Math.PI / 3)) return;
    const score = Math.hypot(dx, dy) + 2 * side;
    if (score < bestScore) {
      bestScore = score;
      best = i;
    }
  });
  return best;
}
