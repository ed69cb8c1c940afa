// fmt: numbers for tables; zero up to rounding prints 0 (issue 24: 4.441e-16 was printed for 0)
// without hiding real small values.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { fmt, fmtExpansion } from '../src/dom.js';

test('zero up to rounding of the quantities it came from prints 0', () => {
  assert.equal(fmt(4.440892098500626e-16), '0', '2 ulp of 1');
  assert.equal(fmt(-2.220446049250313e-16), '0');
  assert.equal(fmt(1 - (0.1 + 0.2) / 0.3 + 1e-300), '0', 'a difference of two equal O(1) results');
  assert.equal(fmt(-0), '0');
  assert.equal(fmt(0), '0');
});

test('real small values still print, and the scale decides what rounding means', () => {
  assert.equal(fmt(1e-9), '1.000e-9');
  assert.equal(fmt(-3.2e-12), '-3.200e-12');
  assert.equal(fmt(5e-15), '5.000e-15', 'above 16 ulp of 1');
  assert.equal(fmt(3e-16, 0), '3.000e-16', 'scale 0: exact');
  assert.equal(fmt(4e-13, 1000), '0', 'rounding of a quantity of size 1000');
  assert.equal(fmt(4e-13, 1), '4.000e-13');
});

test('ordinary numbers: 4 significant digits, integers and missing values as before', () => {
  assert.equal(fmt(0.15470053837925), '0.1547');
  assert.equal(fmt(1.3333333), '1.333');
  assert.equal(fmt(-0.004123), '-0.004123');
  assert.equal(fmt(123456.7), '1.235e+5');
  assert.equal(fmt(7), '7');
  assert.equal(fmt(null), '–');
  assert.equal(fmt(undefined), '–');
  assert.equal(fmt('x'), 'x');
});

test('a negative expansion says the sheet contracts, by how much', () => {
  assert.equal(fmtExpansion(-0.0043650022173247205), '-0.004365 (contracts 0.44 %)');
  assert.equal(fmtExpansion(-0.2287), '-0.2287 (contracts 23 %)');
  assert.equal(fmtExpansion(0.9999924), '1');
  assert.equal(fmtExpansion(-4.440892098500626e-16), '0', 'rounding is not a contraction');
  assert.equal(fmtExpansion(null), '–');
});
