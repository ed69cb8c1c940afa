// The catalogue table's pure layout helpers, no DOM: where to scroll a table sideways so the
// sorted column is in view beside the sticky spec column without any column left half under
// it, where a spec may break across lines (after its commas and colons), and the table's
// columns (the text columns, then every measure of the server's list but the shape parameters).

/** The text columns before the measures, as [key, heading]. */
const LEADING = [
  ['spec', 'spec'], ['family', 'family'], ['cell', 'cell'], ['tile_count', 'tiles'],
  ['behaviour', 'behaviour'], ['linkage_signature', 'linkages'], ['end_reason', 'end'],
];

/** Headings of measures shorter than their labels. */
const HEADINGS = {
  max_expansion: 'max ε', min_expansion: 'min ε', max_area_ratio: 'area ratio', max_tile_rotation: 'max rotation',
  poisson_min: 'ν min', poisson_max: 'ν max', finite_raw_dof: 'raw DOF', finite_covered: 'one-DOF sheet',
};

/** The catalogue table's columns as [key, heading]: the text columns, every measure of
 * `measures` (schema.js's MEASURES: {name, short}) in its order except the shape parameters
 * v0…v5 and the tile count (a text column already), then the origin. A measure the server adds
 * becomes a column. */
export function tableColumns(measures) {
  const shown = new Set(LEADING.map(([k]) => k));
  const middle = measures
    .filter((m) => !/^v\d+$/.test(m.name) && !shown.has(m.name))
    .map((m) => [m.name, HEADINGS[m.name] ?? m.short ?? m.name]);
  return [...LEADING, ...middle, ['origin', 'origin']];
}

/**
 * The scroll position (px) that shows column `i` whole beside a sticky first column, with
 * every other column either whole or wholly under the sticky one. `columns` are
 * `[{left, width}]` in table coordinates (the sticky column first), `view` the visible width,
 * `scroll` the current position. Returns `{scroll, tail}`: `tail` is how much room (px) the
 * table needs after its last column for that position to be reachable (0 when it already is).
 * Keeps `scroll` when it already qualifies (and then asks the same tail).
 */
export function revealedScroll(columns, i, view, scroll) {
  if (!(i > 0) || i >= columns.length) return { scroll, tail: 0 };
  const sticky = columns[0].left + columns[0].width;
  const end = columns[columns.length - 1].left + columns[columns.length - 1].width;
  // Column k first beside the sticky one: the table scrolled by its left edge minus the
  // sticky column's right edge.
  const aligned = columns.slice(1).map((c) => c.left - sticky);
  const col = columns[i];
  const shows = (s) => col.left - s >= sticky - 0.5 && col.left + col.width - s <= view + 0.5;
  const at = (s) => ({ scroll: s, tail: Math.max(0, Math.ceil(s + view - Math.max(end, view))) });
  if (aligned.some((s) => Math.abs(s - scroll) < 0.5) && shows(scroll)) return at(scroll);
  if (scroll < 0.5 && shows(0)) return at(0);
  return at(aligned.find((a) => a >= 0 && shows(a)) ?? aligned[i - 1]);
}

/** A spec's pieces with a break opportunity after each comma and colon: an array of strings
 * to join with `<wbr>` (the text itself is unchanged). */
export function specBreaks(spec) {
  return spec.split(/(?<=[,:])/);
}
