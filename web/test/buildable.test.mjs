// Buildability (issue 40): the measures the pages take from the server (schema.js's
// setMeasures), URL ranges on the finite-sheet measures, the table's columns, and
// buildable.js's badge text, neighbour query and sheet-check query.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  HAS_SHEET_RANGE, familyOfSpec, findNeighbour, neighbourHref, neighbourState, percentText, refusalReason,
  sheetCheckQuery, sheetStatus,
} from '../src/buildable.js';
import { MEASURES, MEASURE_NAMES, SORT_KEYS, measureHelp, measureLabel, setMeasures } from '../src/schema.js';
import { catalogueSearch, pageParams, parseCatalogueState } from '../src/url.js';
import { tableColumns } from '../src/table-model.js';
import { page } from '../src/query.js';
import { regionProblem } from '../src/graded-model.js';

const builtIn = MEASURES.map((m) => ({ name: m.name }));

test('a range and a sort on the finite-sheet measures survive the URL (they were dropped)', () => {
  const s = parseCatalogueState('?range=finite_covered:0.9:&range=finite_raw_dof:1:1&sort=-finite_covered');
  assert.deepEqual(s.ranges, [
    { measure: 'finite_covered', min: 0.9, max: null },
    { measure: 'finite_raw_dof', min: 1, max: 1 },
  ]);
  assert.deepEqual(s.sort, { key: 'finite_covered', desc: true });
  assert.equal(catalogueSearch(s), '?range=finite_covered%3A0.9%3A&range=finite_raw_dof%3A1%3A1&sort=-finite_covered');
  assert.deepEqual(pageParams(s).getAll('range'), ['finite_covered:0.9:', 'finite_raw_dof:1:1']);
});

test('the server’s list of measures replaces the page’s, in place, before a URL is read', () => {
  try {
    setMeasures([
      { name: 'max_area_ratio', type: 'number', unit: '1', meaning: 'Largest area ratio det F reached' },
      { name: 'finite_covered', type: 'number|null', unit: '1', meaning: 'Fraction kept' },
      { name: 'shape_tolerance', type: 'number|null', unit: '1', meaning: 'How far the shape may move' },
    ]);
    assert.deepEqual(MEASURES.map((m) => m.name), ['max_area_ratio', 'finite_covered', 'shape_tolerance']);
    assert.ok(MEASURE_NAMES.has('shape_tolerance') && !MEASURE_NAMES.has('steps'));
    assert.ok(SORT_KEYS.has('shape_tolerance') && SORT_KEYS.has('spec') && !SORT_KEYS.has('steps'));
    assert.equal(measureLabel('shape_tolerance'), 'shape tolerance', 'an unknown measure is labelled by its name');
    assert.equal(measureLabel('max_area_ratio'), 'max area ratio', 'a known one keeps its label');
    assert.equal(measureHelp('shape_tolerance'), 'How far the shape may move');
    const s = parseCatalogueState('?range=shape_tolerance::0.01&range=steps:1:&sort=shape_tolerance');
    assert.deepEqual(s.ranges, [{ measure: 'shape_tolerance', min: null, max: 0.01 }]);
    assert.deepEqual(s.sort, { key: 'shape_tolerance', desc: false });
    // An empty or missing list keeps the current one.
    setMeasures([]);
    setMeasures(null);
    assert.equal(MEASURES.length, 3);
  } finally {
    setMeasures(builtIn);
  }
  assert.ok(MEASURE_NAMES.has('steps') && MEASURE_NAMES.has('v5'));
});

test('the table has a column for every measure but the shape parameters, the finite-sheet ones included', () => {
  const columns = tableColumns(MEASURES);
  const keys = columns.map(([k]) => k);
  assert.deepEqual(keys.slice(0, 7), ['spec', 'family', 'cell', 'tile_count', 'behaviour', 'linkage_signature', 'end_reason']);
  assert.equal(keys.at(-1), 'origin');
  for (const k of ['max_area_ratio', 'steps', 'kerf', 'finite_raw_dof', 'finite_covered']) assert.ok(keys.includes(k), k);
  assert.ok(!keys.some((k) => /^v\d$/.test(k)));
  assert.equal(new Set(keys).size, keys.length, 'no column twice');
  assert.equal(Object.fromEntries(columns).finite_covered, 'one-DOF sheet');
  // A measure the server adds is a column before the origin, headed by its short label.
  const more = tableColumns([...MEASURES, { name: 'open_area', short: 'open area' }]);
  assert.deepEqual(more.slice(-2), [['open_area', 'open area'], ['origin', 'origin']]);
});

test('the badge: the covered fraction, no one-DOF sheet, or not measured', () => {
  const sheet = sheetStatus({ finite_raw_dof: 3, finite_covered: 0.923 });
  assert.equal(sheet.kind, 'sheet');
  assert.equal(sheet.text, 'one-DOF sheet · 92 % kept');
  assert.equal(sheet.short, '92 %');
  assert.match(sheet.title, /keeps 92 % of its area/);
  assert.match(sheet.title, /3 DOF/);
  assert.match(sheetStatus({ finite_raw_dof: 1, finite_covered: 1 }).title, /already opens with one motion/);
  const none = sheetStatus({ finite_raw_dof: 21, finite_covered: null });
  assert.equal(none.kind, 'none');
  assert.equal(none.text, 'no one-DOF sheet');
  assert.match(none.title, /21 DOF/);
  assert.match(none.title, /raw rectangle \(--raw\)/);
  assert.match(none.title, /another region/);
  for (const row of [null, undefined, { finite_raw_dof: null, finite_covered: null }, {}]) {
    assert.equal(sheetStatus(row).kind, 'unknown');
  }
  assert.equal(percentText(1), '100');
  assert.equal(percentText(0.999), '99', 'only a whole sheet says 100 %');
  assert.equal(percentText(0.5), '50');
});

test('neighbours with a sheet: the same family, a range on finite_covered, the largest first', () => {
  const s = neighbourState('IH22');
  assert.deepEqual(s.filters.family, ['IH22']);
  assert.deepEqual(s.ranges, [{ ...HAS_SHEET_RANGE }]);
  assert.deepEqual(s.sort, { key: 'finite_covered', desc: true });
  assert.equal(neighbourHref('IH22'), './index.html?family=IH22&range=finite_covered%3A0%3A&sort=-finite_covered&view=grid');
  assert.equal(neighbourHref(null), './index.html?range=finite_covered%3A0%3A&sort=-finite_covered&view=grid');
  assert.equal(familyOfSpec('IH22:0.1,0.2:1x1:aa-a-'), 'IH22');
  assert.equal(familyOfSpec(' IH4:0.5:2x1:ab'), 'IH4');
  assert.equal(familyOfSpec('rotating-squares'), null);
});

test('findNeighbour answers from the query engine: same family, with a sheet, not the design itself', async () => {
  const row = (spec, family, covered, n) => ({
    spec, family, cell: [1, 1], tile_count: 2, behaviour: null, linkage_signature: null, end_reason: 'locked', origin: 'explored',
    params: [], finite_raw_dof: 3, finite_covered: covered, max_area_ratio: n,
  });
  const rows = [
    row('IH22:a', 'IH22', null, 3),
    row('IH22:b', 'IH22', 0.8, 2),
    row('IH22:c', 'IH22', 0.95, 1),
    row('IH4:d', 'IH4', 1, 5),
  ];
  const data = { designs: async (state) => page(rows, state) };
  assert.equal((await findNeighbour(data, 'IH22', 'IH22:a')).spec, 'IH22:c');
  assert.equal((await findNeighbour(data, 'IH22', 'IH22:c')).spec, 'IH22:b');
  assert.equal(await findNeighbour(data, 'IH9', 'IH9:x'), null);
  assert.equal(await findNeighbour(data, null, 'rotating-squares'), null);
  // The static site's engine passes only the rows with a one-DOF sheet to the range.
  assert.deepEqual(page(rows, parseCatalogueState('?range=finite_covered:0:')).rows.map((r) => r.spec).sort(), ['IH22:b', 'IH22:c', 'IH4:d']);
});

test('the graded page asks about its design and region only when the form can be asked', () => {
  const limits = { side: 8, cells: 36 };
  const problem = (f) => regionProblem(f, limits);
  assert.equal(sheetCheckQuery({ design: ' IH22:x:1x1:a ', rows: '3', cols: '4' }, problem), 'design=IH22%3Ax%3A1x1%3Aa&region=3x4');
  assert.equal(sheetCheckQuery({ design: '', rows: '3', cols: '3' }, problem), null);
  assert.equal(sheetCheckQuery({ design: 'rotating-squares', rows: '', cols: '3' }, problem), null);
  assert.equal(sheetCheckQuery({ design: 'rotating-squares', rows: '9', cols: '3' }, problem), null);
  assert.equal(refusalReason('no one-DOF sheet in this region: every sheet flops'), 'every sheet flops');
  assert.equal(refusalReason('something else'), 'something else');
});
