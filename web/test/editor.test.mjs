// The live design panel's pure helpers (editor.js): slider values stay inside the valid range
// after rounding, and pins meeting at one corner of the joint editor are spread apart.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { paramRange, sliderSpan, sliderValue, spreadPins } from '../src/editor.js';

test('a rounded slider value never leaves [min, max]', () => {
  // The library's range ends have 12 digits; rounding to 4 decimals could step past them.
  assert.equal(sliderValue('0.37456', 0.1, 0.374562), 0.3746 > 0.374562 ? 0.374562 : 0.3746);
  assert.equal(sliderValue('0.374562', 0.1, 0.374562), 0.374562);
  assert.equal(sliderValue('-0.08321', -0.083213, 1), -0.0832);
  assert.equal(sliderValue('-0.083213', -0.083213, 1), -0.083213);
  assert.equal(sliderValue('0.25', 0, 1), 0.25);
});

test('pins of edges that meet at a small angle at one corner are spread apart', () => {
  const r = 0.02;
  const corner = [0, 0];
  // Five edges leaving one corner 5° apart: pins at a fixed distance would overlap.
  const pins = [0, 5, 10, 15, 20].map((deg) => {
    const a = (deg * Math.PI) / 180;
    return { end: corner, other: [Math.cos(a), Math.sin(a)] };
  });
  const at = spreadPins(pins, r);
  for (let i = 0; i < at.length; i += 1) {
    // Each pin stays on its edge, within 45 % of it from the pinned end.
    const { other } = pins[i];
    const cross = at[i][0] * other[1] - at[i][1] * other[0];
    assert.ok(Math.abs(cross) < 1e-12, 'on its edge');
    assert.ok(Math.hypot(...at[i]) <= 0.45 + 1e-12);
    for (let j = i + 1; j < at.length; j += 1) {
      const d = Math.hypot(at[i][0] - at[j][0], at[i][1] - at[j][1]);
      assert.ok(d >= 2 * r, `pins ${i} and ${j} ${d} apart`);
    }
  }
});

test('pins far apart stay near their corner', () => {
  const at = spreadPins([{ end: [0, 0], other: [1, 0] }, { end: [1, 1], other: [0, 1] }], 0.02);
  assert.ok(Math.abs(at[0][0] - 0.044) < 1e-12 && at[0][1] === 0);
  assert.ok(Math.abs(at[1][0] - (1 - 0.044)) < 1e-12);
});

test('a slider where the tile is not well-shaped reaches back to the family default span', () => {
  // Every default from −2 to 2 in steps of 0.25, the value far away on either side.
  for (let d = -2; d <= 2; d += 0.25) {
    for (const value of [d + 9, d - 9]) {
      const r = { lo: value - 0.9, hi: value + 0.9, well_shaped: null };
      const [min, max] = sliderSpan(r, d);
      const [lo, hi] = paramRange(d);
      assert.ok(min <= lo && max >= hi, `default span ${lo} … ${hi} inside ${min} … ${max}`);
      assert.ok(min <= r.lo && max >= r.hi, 'the valid interval stays inside');
      // Well-shaped: exactly the valid interval (nothing to go back to).
      assert.deepEqual(sliderSpan({ ...r, well_shaped: [r.lo, r.hi] }, d), [r.lo, r.hi]);
    }
  }
  // No default known: the valid interval.
  assert.deepEqual(sliderSpan({ lo: 1, hi: 2, well_shaped: null }, undefined), [1, 2]);
});
