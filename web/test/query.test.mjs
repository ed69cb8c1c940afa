// The static site's catalogue queries must behave as the server's store does: OR within a
// facet, AND across facets, ranges never pass a missing measure, disjunctive facet counts,
// missing values last in both directions, ties in insertion order in the sort's direction.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { facetCounts, motionGroups, motionOf, page, scatter, sortRows } from '../src/query.js';
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

// The engine's own default order (spec ascending, as the API's); the page asks for its own.
const st = (f) => {
  const s = emptyCatalogueState();
  s.sort = null;
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
  const pts = scatter(rows, st(() => {}), 'max_expansion', 'poisson_max');
  assert.deepEqual(pts.map((x) => x.spec), ['B', 'C', 'D']);
  assert.deepEqual(pts[0], { spec: 'B', x: 0.3, y: -0.5, family: 'IH2', behaviour: null });
  assert.deepEqual(pts[2], { spec: 'D', x: 0.1, y: -0.5, family: 'IH10', behaviour: 'orthotropic_positive_poisson' });
});

test('mechanisms: groups by class in the order of their first member, ranges over matching designs', () => {
  const motions = { computed: true, classes: { A: 'A', C: 'A', D: 'D' } }; // B has no class
  const s = st((x) => (x.sort = { key: 'max_expansion', desc: true }));
  const m = motionGroups(rows, motions, s);
  assert.equal(m.total, 4);
  // A 0.5, then C and B tie at 0.3 (later insertion first when descending), D 0.1.
  assert.deepEqual(m.groups.map((g) => [g.representative, g.members.map((x) => x.spec)]), [['A', ['A', 'C']], ['D', ['D']]]);
  assert.deepEqual(m.unclassified.members.map((x) => x.spec), ['B']);
  assert.equal(m.unclassified.representative, null);
  const g = m.groups[0];
  assert.deepEqual(g.max_expansion, { min: 0.3, max: 0.5 });
  assert.deepEqual(g.poisson, { min: -1, max: -0.5 }, 'only C has a Poisson-like ratio');
  assert.deepEqual(g.families, ['IH2', 'IH10'], 'families by number');
  assert.equal(g.topologies, 2);
  assert.deepEqual(g.behaviours, [{ value: 'isotropic_auxetic', count: 2 }]);
  // A filter keeps a class when any of its designs matches, with its ranges over those only.
  const f = motionGroups(rows, motions, st((x) => (x.filters.family = ['IH2'])));
  assert.deepEqual(f.groups.map((x) => [x.representative, x.designs, x.max_expansion.max]), [['A', 1, 0.3]]);
  // No classes computed: every design unclassified, none dropped.
  const none = motionGroups(rows, { computed: false, classes: {} }, st(() => {}));
  assert.equal(none.computed, false);
  assert.deepEqual(none.groups, []);
  assert.equal(none.unclassified.designs, 4);
});

test('same motion elsewhere: every topology of the class with its example and area ratios', () => {
  const rs = [
    row('IH2:x:1x1:a', { topology: 'T2', family: 'IH2', max_area_ratio: 1.2 }),
    row('IH2:y:1x1:a', { topology: 'T2', family: 'IH2', max_area_ratio: 1.4 }),
    row('IH10:x:2x1:a', { topology: 'T10', family: 'IH10', cell: [2, 1], max_area_ratio: 1.9 }),
    row('IH3:x:1x1:a', { topology: 'T3', family: 'IH3' }),
  ];
  const motions = { computed: true, classes: { T2: 'T10', T10: 'T10' } };
  const m = motionOf(rs, motions, 'IH2:y:1x1:a');
  assert.equal(m.topology, 'T2');
  assert.deepEqual(m.class.variants, [
    { topology: 'T10', family: 'IH10', cell: '2x1', designs: 1, example: 'IH10:x:2x1:a', example_area_ratio: 1.9, area_ratio: [1.9, 1.9] },
    { topology: 'T2', family: 'IH2', cell: '1x1', designs: 2, example: 'IH2:x:1x1:a', example_area_ratio: 1.2, area_ratio: [1.2, 1.4] },
  ]);
  assert.deepEqual(motionOf(rs, motions, 'IH3:x:1x1:a'), { topology: 'T3', class: null });
  assert.deepEqual(motionOf(rs, motions, 'nope'), { topology: null, class: null });
});
