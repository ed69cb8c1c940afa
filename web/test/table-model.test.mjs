// Unit tests of the catalogue table's layout helpers (src/table-model.js).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { revealedScroll, specBreaks } from '../src/table-model.js';

/** Columns of the given widths laid side by side from 0. */
function laidOut(widths) {
  let left = 0;
  return widths.map((width) => {
    const c = { left, width };
    left += width;
    return c;
  });
}

test('the sorted column is shown whole and no column is left half under the sticky one', () => {
  // Random tables (seeded): widths 30–200 px, a sticky column 80–260 px, views 300–1200 px,
  // every column sorted in turn, from any starting scroll.
  let seed = 7;
  const rand = () => {
    seed = (seed * 1103515245 + 12345) % 2 ** 31;
    return seed / 2 ** 31;
  };
  for (let trial = 0; trial < 200; trial += 1) {
    const n = 3 + Math.floor(rand() * 14);
    const widths = [80 + rand() * 180, ...Array.from({ length: n - 1 }, () => 30 + rand() * 170)];
    const cols = laidOut(widths);
    const sticky = widths[0];
    const view = sticky + 200 + rand() * 900;
    const end = cols[n - 1].left + cols[n - 1].width;
    for (let i = 1; i < n; i += 1) {
      const start = rand() * Math.max(0, end - view);
      const { scroll, tail } = revealedScroll(cols, i, view, start);
      const msg = `trial ${trial}, column ${i}: scroll ${scroll}, tail ${tail}`;
      // Reachable with the tail added after the last column.
      assert.ok(scroll >= 0 && scroll <= Math.max(0, end + tail - view) + 1e-9, msg);
      const seen = (c) => ({ left: c.left - scroll, right: c.left + c.width - scroll });
      const s = seen(cols[i]);
      if (widths[i] <= view - sticky) assert.ok(s.left >= sticky - 0.5 && s.right <= view + 0.5, `${msg}: sorted column in view`);
      for (const c of cols.slice(1).map(seen)) {
        assert.ok(!(c.left < sticky - 0.5 && c.right > sticky + 0.5), `${msg}: a column straddles the sticky edge`);
      }
      // Already a good position: kept.
      assert.deepEqual(revealedScroll(cols, i, view, scroll), { scroll, tail }, msg);
    }
  }
});

test('a table that fits shows from its start', () => {
  const cols = laidOut([100, 50, 50, 50]);
  assert.deepEqual(revealedScroll(cols, 3, 400, 0), { scroll: 0, tail: 0 });
  assert.deepEqual(revealedScroll(cols, 0, 400, 0), { scroll: 0, tail: 0 });
});

test('specs break after commas and colons and read back whole', () => {
  for (const spec of ['IH84:0.65,0.121416770201:1x1:aaa', 'rotating-squares', 'IH2:0.1,0.5,0.2,0.2:2x1:aa-aa-']) {
    const pieces = specBreaks(spec);
    assert.equal(pieces.join(''), spec);
    for (const p of pieces.slice(0, -1)) assert.match(p, /[,:]$/);
    assert.ok(pieces.every((p) => !/[,:]./.test(p)), 'one break after each comma and colon');
  }
});
