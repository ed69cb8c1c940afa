// plots.js's scale choice for the inverse page's best objective (issue 24: on a linear scale the
// objective, spanning decades, was flat after ~100 evaluations): log when every value is
// positive, whole decades around the values; linear for objectives that can be negative.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { logDomain, useLogScale } from '../src/plots.js';

test('a positive objective is drawn on a log scale, a signed one linearly', () => {
  assert.equal(useLogScale([3.2, 0.5, 1e-6], true), true);
  assert.equal(useLogScale([3.2, 0.5, 1e-6], false), false, 'only when asked');
  assert.equal(useLogScale([-1.5, -1], true), false, 'a largest-area objective is negative');
  assert.equal(useLogScale([0, 1], true), false, 'zero has no logarithm');
  assert.equal(useLogScale([], true), false);
});

test('the log domain spans whole decades around the values', () => {
  assert.deepEqual(logDomain([3.2, 0.5, 2e-6]), [1e-6, 10]);
  assert.deepEqual(logDomain([0.01]), [0.01, 0.1], 'one value: one decade');
  const [a, b] = logDomain([0.37, 0.42]);
  assert.ok(a <= 0.37 && b >= 0.42 && b / a >= 10);
});
