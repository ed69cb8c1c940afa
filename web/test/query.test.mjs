// The static site's catalogue queries must behave as the server's store does: OR within a
// facet, AND across facets, ranges never pass a missing measure, disjunctive facet counts,
// missing values last in both directions, ties in insertion order in the sort's direction.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { facetCounts, page, scatter, sortRows } from '../src/query.js';
import { emptyCatalogueState } from '../src/url.js';

function row(spec, o) {
  return {
    spec, origin: 'explored', family: 'IH1', cell: [1, 1], tile_count: 2, joints: 'ab', topology: spec,
    params: [0.1, 0.2], behaviour: 'isotropic_auxetic', linkage_signature: '1×4-bar', end_reason: 'contact_limit',
    method: 'rigid-modes', dof: 1, kerf: 0.01, max_expansion: 0.2, min_expansion: 0.1, max_area_ratio: 1.5,
    max_tile_rotation: 0.3, poisson_min: -1, poisson_max: -0.5, steps: 40, ...o,
  };
}

const rows = [
  row('A', { family: 'IH10', max_expansion: 0.5, poisson_min: null, poisson_max: null }),
  row('B', { family: 'IH2', cell: [2, 1], behaviour: null, max_expansion: 0.3 }),
  row('C', { family: 'IH2', max_expansion: 0.3, params: [] }),
  row('D', { family: 'IH10', cell: [2, 1], behaviour: 'orthotropic_positive_poisson', max_expansion: 0.1, origin: 'user' }),
];

const st = (f) => {
  const s = emptyCatalogueState();
  f(s);
  return s;
};

test('filters: OR within a facet, AND across facets, ranges need the measure', () => {
  const specs = (s) => page(rows, s).rows.map((r) => r.spec);
  assert.deepEqual(specs(st((s) => (s.filters.family = ['IH2', 'IH10']))), ['A', 'B', 'C', 'D']);
  assert.deepEqual(specs(st((s) => { s.filters.family = ['IH10']; s.filters.cell = ['2x1']; })), ['D']);
  assert.deepEqual(specs(st((s) => (s.filters.behaviour = ['none']))), ['B']);
  assert.deepEqual(specs(st((s) => (s.filters.behaviour = ['none', 'isotropic_auxetic']))), ['A', 'B', 'C']);
  assert.deepEqual(specs(st((s) => s.ranges.push({ measure: 'poisson_min', min: null, max: 10 }))), ['B', 'C', 'D']);
  assert.deepEqual(specs(st((s) => s.ranges.push({ measure: 'v1', min: 0, max: null }))), ['A', 'B', 'D']);
  assert.deepEqual(specs(st((s) => s.ranges.push({ measure: 'max_expansion', min: 0.3, max: 0.3 }))), ['B', 'C']);
  assert.deepEqual(specs(st((s) => (s.filters.tile_count = ['3']))), []);
});

test('facet counts are disjunctive and ordered by count, then stored value', () => {
  const s = st((x) => {
    x.filters.family = ['IH2'];
    x.filters.cell = ['1x1'];
  });
  const f = facetCounts(rows, s);
  // The family facet ignores its own selection: cell 1x1 keeps A (IH10) and C (IH2).
  assert.deepEqual(f.family, [{ value: 'IH2', count: 1 }, { value: 'IH10', count: 1 }]);
  // The cell facet ignores the cell selection: IH2 keeps B (2x1) and C (1x1).
  assert.deepEqual(f.cell, [{ value: [1, 1], count: 1 }, { value: [2, 1], count: 1 }]);
  // Other facets apply every filter: only C.
  assert.deepEqual(f.behaviour, [{ value: 'isotropic_auxetic', count: 1 }]);
  const all = facetCounts(rows, emptyCatalogueState());
  assert.deepEqual(all.behaviour.map((c) => c.value), ['isotropic_auxetic', null, 'orthotropic_positive_poisson']);
  assert.equal(all.family.reduce((n, c) => n + c.count, 0), rows.length);
});

test('sorting: missing last both ways, ties in insertion order in the same direction', () => {
  const by = (key, desc) => sortRows(rows, { key, desc }).map((r) => r.spec);
  assert.deepEqual(by('max_expansion', false), ['D', 'B', 'C', 'A']);
  assert.deepEqual(by('max_expansion', true), ['A', 'C', 'B', 'D']);
  assert.deepEqual(by('poisson_min', false), ['B', 'C', 'D', 'A']);
  assert.deepEqual(by('poisson_min', true), ['D', 'C', 'B', 'A']);
  assert.deepEqual(by('family', false), ['B', 'C', 'A', 'D']); // by number: IH2 before IH10
  assert.deepEqual(by('cell', true), ['D', 'B', 'C', 'A']);
  assert.deepEqual(by('behaviour', false), ['A', 'C', 'D', 'B']);
  assert.deepEqual(by('v1', false), ['A', 'B', 'D', 'C']);
  assert.deepEqual(sortRows(rows, null).map((r) => r.spec), ['A', 'B', 'C', 'D']);
});

test('pages and scatter', () => {
  const p = page(rows, st((s) => { s.limit = 3; s.offset = 3; }));
  assert.equal(p.total, 4);
  assert.deepEqual(p.rows.map((r) => r.spec), ['D']);
  const pts = scatter(rows, emptyCatalogueState(), 'max_expansion', 'poisson_max');
  assert.deepEqual(pts.map((x) => x.spec), ['B', 'C', 'D']);
  assert.deepEqual(pts[0], { spec: 'B', x: 0.3, y: -0.5, family: 'IH2', behaviour: null });
  assert.deepEqual(pts[2], { spec: 'D', x: 0.1, y: -0.5, family: 'IH10', behaviour: 'orthotropic_positive_poisson' });
});
