// Catalogue queries answered in JS over the array of every DesignSummary, for the static site:
// the same semantics as the server's store (crates/isogami-store/src/query). Lists of values
// within a facet are OR, facets and ranges AND; a range never passes a row that lacks the
// measure; facet counts are disjunctive (a facet's counts apply every filter but its own),
// most frequent first, then by stored value; sorting puts missing values last in both
// directions and breaks ties by insertion order in the sort's direction. Pure, no DOM.

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

/** The filtered rows, sorted. */
export function filtered(rows, state) {
  return sortRows(
    rows.filter((r) => passes(r, state)),
    state.sort,
  );
}

/** One page: `{total, offset, rows}` as /api/designs answers. */
export function page(rows, state) {
  const all = filtered(rows, state);
  return { total: all.length, offset: state.offset, rows: all.slice(state.offset, state.offset + state.limit) };
}

/** Scatter points `[{spec, x, y}]` of the filtered rows having both measures, insertion order. */
export function scatter(rows, state, x, y) {
  const out = [];
  for (const row of rows) {
    if (!passes(row, state)) continue;
    const vx = measureOf(row, x);
    const vy = measureOf(row, y);
    if (vx !== null && vy !== null) out.push({ spec: row.spec, x: vx, y: vy });
  }
  return out;
}
