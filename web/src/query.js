// Catalogue queries answered in JS over the array of every DesignSummary, for the static site:
// the same semantics as the server's store (crates/isogami-store/src/query). Lists of values
// within a facet are OR, facets and ranges AND; a range never passes a row that lacks the
// measure; facet counts are disjunctive (a facet's counts apply every filter but its own),
// most frequent first, then by stored value; sorting puts missing values last in both
// directions and breaks ties by insertion order in the sort's direction. Pure, no DOM.

import { isBuildable } from './buildable.js';
import { FACETS, facetMatches, facetOf, measureOf } from './schema.js';

/** Does `row` pass every filter of `state`, except the selection of facet `skip`? */
export function passes(row, state, skip = null) {
  for (const f of FACETS) {
    if (f.name === skip) continue;
    const wanted = state.filters[f.name];
    if (wanted.length && !wanted.some((t) => facetMatches(f.name, facetOf(row, f.name), t))) return false;
  }
  for (const r of state.ranges) {
    const v = measureOf(row, r.measure);
    if (v === null) return false;
    if (r.min !== null && v < r.min) return false;
    if (r.max !== null && v > r.max) return false;
  }
  return true;
}

/** The stored (SQL) value a facet value sorts by: families by number, cells as "AxB" text. */
function storedFacetKey(name, value) {
  if (value === null) return null;
  if (name === 'family') return Number(String(value).replace(/^IH/, ''));
  if (name === 'cell') return `${value[0]}x${value[1]}`;
  return value;
}

/** SQLite's order of values: NULL first, numbers, then text (binary). */
function sqlCompare(a, b) {
  if (a === b) return 0;
  if (a === null) return -1;
  if (b === null) return 1;
  const ta = typeof a === 'number';
  const tb = typeof b === 'number';
  if (ta !== tb) return ta ? -1 : 1;
  return a < b ? -1 : a > b ? 1 : 0;
}

/** Facet counts of every facet under `state`: `{facet: [{value, count}]}`. */
export function facetCounts(rows, state) {
  const out = {};
  for (const f of FACETS) {
    const counts = new Map();
    for (const row of rows) {
      if (!passes(row, state, f.name)) continue;
      const value = facetOf(row, f.name);
      const key = JSON.stringify(value);
      const c = counts.get(key);
      if (c) c.count += 1;
      else counts.set(key, { value, count: 1 });
    }
    out[f.name] = [...counts.values()].sort(
      (a, b) => b.count - a.count || sqlCompare(storedFacetKey(f.name, a.value), storedFacetKey(f.name, b.value)),
    );
  }
  return out;
}

/** The sort key of a row as a list of comparable values (null = missing). */
function sortValues(row, key) {
  switch (key) {
    case 'spec':
      return [row.spec];
    case 'family':
      return [storedFacetKey('family', row.family)];
    case 'cell':
      return [row.cell[0], row.cell[1]];
    case 'behaviour':
    case 'linkage_signature':
    case 'end_reason':
    case 'origin':
      return [row[key] ?? null];
    default:
      return [measureOf(row, key)];
  }
}

/** Rows (in insertion order) sorted as the server sorts; default spec ascending. */
export function sortRows(rows, sort) {
  const { key, desc } = sort || { key: 'spec', desc: false };
  const dir = desc ? -1 : 1;
  const keyed = rows.map((row, i) => ({ row, i, k: sortValues(row, key) }));
  keyed.sort((a, b) => {
    for (let j = 0; j < a.k.length; j += 1) {
      const x = a.k[j];
      const y = b.k[j];
      if (x === null && y === null) continue;
      if (x === null) return 1; // missing last, either direction
      if (y === null) return -1;
      if (x < y) return -dir;
      if (x > y) return dir;
    }
    return (a.i - b.i) * dir;
  });
  return keyed.map((x) => x.row);
}

/** The filtered rows, sorted; buildable ones first when `state.lead` is 'buildable' (the API's
 * lead=buildable: a stable partition of the sorted rows). */
export function filtered(rows, state) {
  const sorted = sortRows(
    rows.filter((r) => passes(r, state)),
    state.sort,
  );
  if (state.lead !== 'buildable') return sorted;
  return [...sorted.filter(isBuildable), ...sorted.filter((r) => !isBuildable(r))];
}

/** One page: `{total, offset, rows}` as /api/designs answers. */
export function page(rows, state) {
  const all = filtered(rows, state);
  return { total: all.length, offset: state.offset, rows: all.slice(state.offset, state.offset + state.limit) };
}

/** Scatter points `[{spec, x, y, family, behaviour}]` of the filtered rows having both measures,
 * insertion order (what /api/scatter answers). */
export function scatter(rows, state, x, y) {
  const out = [];
  for (const row of rows) {
    if (!passes(row, state)) continue;
    const vx = measureOf(row, x);
    const vy = measureOf(row, y);
    if (vx !== null && vy !== null) {
      out.push({ spec: row.spec, x: vx, y: vy, family: row.family, behaviour: row.behaviour ?? null });
    }
  }
  return out;
}

/** The mechanisms view (GET /api/motions, crates/isogami-store/src/motion_groups.rs): the
 * filtered, sorted rows grouped by the motion class of their topology (`motions.classes`:
 * topology → representative, from data/motions.json), groups in the order of their first
 * member, designs without a class in one `unclassified` group. */
export function motionGroups(rows, motions, state) {
  const classes = (motions && motions.classes) || {};
  const groups = [];
  const index = new Map();
  let unclassified = null;
  const all = filtered(rows, state);
  const span = (v) => ({ min: v, max: v });
  const widen = (s, lo, hi) => {
    s.min = Math.min(s.min, lo);
    s.max = Math.max(s.max, hi);
  };
  const make = (representative, r) => ({
    representative,
    designs: 0,
    topologies: 0,
    families: [],
    cells: [],
    behaviours: [],
    max_area_ratio: span(r.max_area_ratio),
    max_expansion: span(r.max_expansion),
    min_expansion: span(r.min_expansion),
    max_tile_rotation: span(r.max_tile_rotation),
    poisson: null,
    members: [],
  });
  for (const r of all) {
    const rep = Object.hasOwn(classes, r.topology) ? classes[r.topology] : null;
    let g;
    if (rep === null) g = unclassified ??= make(null, r);
    else {
      if (!index.has(rep)) {
        index.set(rep, groups.length);
        groups.push(make(rep, r));
      }
      g = groups[index.get(rep)];
    }
    g.designs += 1;
    widen(g.max_area_ratio, r.max_area_ratio, r.max_area_ratio);
    widen(g.max_expansion, r.max_expansion, r.max_expansion);
    widen(g.min_expansion, r.min_expansion, r.min_expansion);
    widen(g.max_tile_rotation, r.max_tile_rotation, r.max_tile_rotation);
    const [lo, hi] = [r.poisson_min ?? null, r.poisson_max ?? null];
    if (lo !== null && hi !== null) {
      if (g.poisson) widen(g.poisson, lo, hi);
      else g.poisson = { min: lo, max: hi };
    }
    const behaviour = r.behaviour ?? null;
    const b = g.behaviours.find((x) => x.value === behaviour);
    if (b) b.count += 1;
    else g.behaviours.push({ value: behaviour, count: 1 });
    g.members.push({
      spec: r.spec,
      family: r.family,
      cell: r.cell,
      topology: r.topology,
      behaviour,
      max_area_ratio: r.max_area_ratio,
      max_expansion: r.max_expansion,
      min_expansion: r.min_expansion,
    });
  }
  const famNo = (f) => Number(String(f).replace(/^IH/, ''));
  for (const g of unclassified ? [...groups, unclassified] : groups) {
    g.topologies = new Set(g.members.map((m) => m.topology)).size;
    g.families = [...new Set(g.members.map((m) => m.family))].sort((a, b) => famNo(a) - famNo(b));
    const cells = new Map(g.members.map((m) => [`${m.cell[0]}x${m.cell[1]}`, m.cell]));
    g.cells = [...cells.values()].sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    g.behaviours.sort((x, y) => {
      if (x.count !== y.count) return y.count - x.count;
      if (x.value === y.value) return 0;
      if (x.value === null) return 1;
      if (y.value === null) return -1;
      return x.value < y.value ? -1 : 1;
    });
  }
  return { computed: Boolean(motions && motions.computed), total: all.length, groups, unclassified };
}

/** "Same motion elsewhere" (GET /api/motion, crates/isogami-store/src/motions.rs) in the
 * browser: the stored design `spec`'s topology and its class with every topology of the class
 * (in spec order), each with its family, cell, design count, first design by spec (the
 * example), the example's area ratio and the topology's area-ratio range. */
export function motionOf(rows, motions, spec) {
  const classes = (motions && motions.classes) || {};
  const row = rows.find((r) => r.spec === spec);
  if (!row) return { topology: null, class: null };
  const rep = Object.hasOwn(classes, row.topology) ? classes[row.topology] : null;
  if (rep === null) return { topology: row.topology, class: null };
  const by = new Map();
  for (const r of rows) {
    if (classes[r.topology] !== rep || !Object.hasOwn(classes, r.topology)) continue;
    const v = by.get(r.topology);
    if (!v) {
      by.set(r.topology, { rows: [r] });
    } else v.rows.push(r);
  }
  const cmp = (a, b) => (a < b ? -1 : a > b ? 1 : 0);
  const variants = [...by.entries()]
    .sort((a, b) => cmp(a[0], b[0]))
    .map(([topology, { rows: rs }]) => {
      const example = rs.reduce((a, b) => (b.spec < a.spec ? b : a));
      const cellOf = (r) => `${r.cell[0]}x${r.cell[1]}`;
      return {
        topology,
        family: `IH${Math.min(...rs.map((r) => Number(String(r.family).replace(/^IH/, ''))))}`,
        cell: rs.map(cellOf).reduce((a, b) => (b < a ? b : a)),
        designs: rs.length,
        example: example.spec,
        example_area_ratio: example.max_area_ratio,
        area_ratio: [Math.min(...rs.map((r) => r.max_area_ratio)), Math.max(...rs.map((r) => r.max_area_ratio))],
      };
    });
  return { topology: row.topology, class: { representative: rep, variants } };
}
