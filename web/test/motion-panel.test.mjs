import { test } from 'node:test';
import assert from 'node:assert/strict';
import { variantRows } from '../src/motion-panel.js';

test('the panel lists every other topology of the class with a stored example', () => {
  const klass = {
    representative: 'IH28:0.45,0.5:1x1:a--a-b-bbb',
    variants: [
      { topology: 'IH28:0.45,0.5:1x1:a--a-b-bbb', family: 'IH28', cell: '1x1', designs: 4, example: 'IH28:0.4,0.5:1x1:a--a-b-bbb' },
      { topology: 'IH29:0.37:1x1:a--a-b-bbb', family: 'IH29', cell: '1x1', designs: 1, example: 'IH29:0.37:1x1:a--a-b-bbb' },
    ],
  };
  assert.deepEqual(variantRows(klass, 'IH28:0.45,0.5:1x1:a--a-b-bbb'), [
    { label: 'IH29 1x1', spec: 'IH29:0.37:1x1:a--a-b-bbb', designs: 1, topology: 'IH29:0.37:1x1:a--a-b-bbb' },
  ]);
  assert.equal(variantRows(klass, 'IH29:0.37:1x1:a--a-b-bbb')[0].label, 'IH28 1x1');
  assert.deepEqual(variantRows(null, 'x'), []);
});
