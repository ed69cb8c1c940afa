// The catalogue table's pure layout helpers, no DOM: where to scroll a table sideways so the
// sorted column is in view beside the sticky spec column without any column left half under
// it, and where a spec may break across lines (after its commas and colons).

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
