// Leading with what can be made (issue 40): the catalogue's default order puts buildable designs
// first (the API's lead=buildable), each part in the sort's order; `?lead=all` turns it off.
// The static site's query.js orders the same way, by buildable.js's rule.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FABRICATION_TOLERANCE, isBuildable, shapeStatus } from '../src/buildable.js';
import { catalogueSearch, emptyCatalogueState, pageParams, parseCatalogueState } from '../src/url.js';
import { page, sortRows } from '../src/query.js';

test('buildable first is the default, told to the API, and left out of the page URL', () => {
  const s = parseCatalogueState('');
  assert.equal(s.lead, 'buildable');
  assert.equal(pageParams(s).get('lead'), 'buildable');
  assert.equal(catalogueSearch(s), '');
  const all = parseCatalogueState('?lead=all');
  assert.equal(all.lead, 'all');
  assert.equal(pageParams(all).get('lead'), null);
  assert.equal(catalogueSearch(all), '?lead=all');
  assert.equal(parseCatalogueState('?lead=nonsense').lead, 'buildable');
});

test('the rule: a one-DOF sheet, margins measured, tolerance at least the fabrication one or none', () => {
  const base = { finite_covered: 0.9, open_t: 0.5, shape_tolerance: FABRICATION_TOLERANCE };
  assert.equal(isBuildable(base), true);
  assert.equal(isBuildable({ ...base, shape_tolerance: null }), true, 'a fixed shape');
  assert.equal(isBuildable({ ...base, shape_tolerance: FABRICATION_TOLERANCE / 2.5 }), false);
  assert.equal(isBuildable({ ...base, shape_tolerance: 0 }), false, 'special');
  assert.equal(isBuildable({ ...base, finite_covered: null }), false, 'no sheet');
  assert.equal(isBuildable({ ...base, open_t: null }), false, 'not measured (a user design)');
  assert.equal(shapeStatus({ ...base, shape_tolerance: 0 }).kind, 'special');
  assert.equal(shapeStatus({ ...base, shape_tolerance: 0.01 }).text, '±0.2 mm');
  assert.equal(shapeStatus({ ...base, shape_tolerance: 1e-4 }).kind, 'tight');
});

test('random catalogues: buildable rows first, each part in the sort order (seeded)', () => {
  let seed = 40;
  const rnd = () => {
    seed = (seed * 1103515245 + 12345) % 2147483648;
    return seed / 2147483648;
  };
  const pick = (xs) => xs[Math.floor(rnd() * xs.length)];
  for (let round = 0; round < 50; round += 1) {
    const rows = Array.from({ length: 1 + Math.floor(rnd() * 40) }, (_, i) => ({
      spec: `IH${1 + Math.floor(rnd() * 90)}::1x1:${i}`,
      max_area_ratio: 1 + rnd(),
      finite_covered: rnd() < 0.7 ? 0.5 + rnd() / 2 : null,
      open_t: rnd() < 0.9 ? rnd() : null,
      shape_tolerance: pick([null, 0, 1e-4, FABRICATION_TOLERANCE, 0.01, 0.025]),
    }));
    const state = { ...emptyCatalogueState(), limit: 1000 };
    const got = page(rows, state).rows;
    const sorted = sortRows(rows, state.sort);
    const want = [...sorted.filter(isBuildable), ...sorted.filter((r) => !isBuildable(r))];
    assert.deepEqual(got.map((r) => r.spec), want.map((r) => r.spec));
    const firstOther = got.findIndex((r) => !isBuildable(r));
    assert.ok(firstOther < 0 || got.slice(firstOther).every((r) => !isBuildable(r)));
    assert.deepEqual(page(rows, { ...state, lead: 'all' }).rows.map((r) => r.spec), sorted.map((r) => r.spec));
  }
});
