import { test } from 'node:test';
import assert from 'node:assert/strict';
import { areaText, variantRows } from '../src/motion-panel.js';

const v = (topology, family, cell, designs, example, area, range) => ({
  topology, family, cell, designs, example, example_area_ratio: area, area_ratio: range,
});

test('the panel lists every other topology of the class with its own area ratio', () => {
  const klass = {
    representative: 'IH28:0.45,0.5:1x1:a--a-b-bbb',
    variants: [
      v('IH28:0.45,0.5:1x1:a--a-b-bbb', 'IH28', '1x1', 4, 'IH28:0.4,0.5:1x1:a--a-b-bbb', 1.5, [1.2, 1.6]),
      v('IH29:0.37:1x1:a--a-b-bbb', 'IH29', '1x1', 1, 'IH29:0.37:1x1:a--a-b-bbb', 1.3, [1.3, 1.3]),
    ],
  };
  assert.deepEqual(variantRows(klass, 'IH28:0.45,0.5:1x1:a--a-b-bbb'), [
    { label: 'IH29 1×1', spec: 'IH29:0.37:1x1:a--a-b-bbb', designs: 1, topology: 'IH29:0.37:1x1:a--a-b-bbb', area: 1.3, range: [1.3, 1.3] },
  ]);
  assert.equal(variantRows(klass, 'IH29:0.37:1x1:a--a-b-bbb')[0].label, 'IH28 1×1');
  assert.deepEqual(variantRows(null, 'x'), []);
});

test('rows sort by family number, then cell, then area ratio (largest first)', () => {
  const klass = {
    variants: [
      v('me', 'IH5', '1x1', 1, 'me', 2, [2, 2]),
      v('t10', 'IH10', '1x1', 1, 'e10', 1.1, [1.1, 1.1]),
      v('t1b', 'IH1', '2x1', 1, 'e1b', 1.9, [1.9, 1.9]),
      v('t1a', 'IH1', '1x1', 1, 'e1a', 1.2, [1.2, 1.2]),
      v('t2', 'IH2', '1x2', 1, 'e2', 1.3, [1.3, 1.3]),
      v('t2b', 'IH2', '1x1', 1, 'e2b', 1.4, [1.4, 1.4]),
      v('t1c', 'IH1', '1x1', 1, 'e1c', 1.7, [1.7, 1.7]),
    ],
  };
  // As text, IH10 would come before IH2 and IH1 2×1 before IH1 1×1 ties.
  assert.deepEqual(variantRows(klass, 'me').map((r) => r.spec), ['e1c', 'e1a', 'e1b', 'e2b', 'e2', 'e10']);
});

test('area text: the example\'s own ratio, and its designs\' range when they differ', () => {
  assert.equal(areaText({ area: 1.33333, designs: 1, range: [1.33333, 1.33333] }), 'opens to 1.333×');
  assert.equal(areaText({ area: 1.5, designs: 3, range: [1.2, 1.5] }), 'opens to 1.5× · its 3 designs 1.2–1.5×');
  assert.equal(areaText({ area: null, designs: 1, range: null }), '');
});
