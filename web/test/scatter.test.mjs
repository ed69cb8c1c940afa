// Unit tests of the scatter's pure helpers (src/scatter-model.js): stacks, colour keys, axis
// ticks on any range, brushed ranges and arrow-key navigation.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  PALETTE, OTHER, axisTicks, colourKey, fittingTicks, nearestInDirection, pickRadius, pickStack, roundedRange,
  stackPoints, stackQuantum, stackRadius, stackSlices,
} from '../src/scatter-model.js';

/** A tick label (with its axis offset) read back as a number. */
function labelValue(label, offset) {
  const v = Number(label.replace(/\u2212/g, '-'));
  return offset ? offset.value + v : v;
}

test('points on one spot up to the grid share a stack; counts add up to the points', () => {
  const pts = [
    { spec: 'a', x: 0.414213052623686, y: 1.999998558209402 },
    { spec: 'b', x: 0.4142130526236858, y: 1.9999985582094015 },
    { spec: 'c', x: 0.41421305262304875, y: 1.999998558209402 },
    { spec: 'd', x: 0.2, y: 1.5 },
    { spec: 'e', x: 0.2, y: 1.5 },
    { spec: 'f', x: 0.3, y: 1.5 },
  ];
  // Exact stacking sees five positions; the view's grid (span 0.2 and 0.5) sees three.
  assert.equal(stackPoints(pts, 0, 0).length, 5);
  const stacks = stackPoints(pts, stackQuantum(0.2), stackQuantum(0.5));
  assert.deepEqual(stacks.map((s) => s.points.map((p) => p.spec).join('')), ['abc', 'de', 'f']);
  assert.equal(stacks.reduce((n, s) => n + s.points.length, 0), pts.length);
  assert.ok(Math.abs(stacks[0].x - 0.4142130526) < 1e-9);
  // Two points a hair apart on either side of a cell border stay together; a point two cells
  // away does not join them.
  const border = stackPoints([{ x: 0.00049, y: 0 }, { x: 0.00051, y: 0 }, { x: 0.0025, y: 0 }], 0.001, 0.001);
  assert.deepEqual(border.map((s) => s.points.length), [2, 1]);
  // Zoomed in far enough (span 1e-9), the near-equal points come apart.
  assert.ok(stackPoints(pts.slice(0, 3), stackQuantum(1e-12), stackQuantum(1e-12)).length > 1);
});

test('the stack grid is a power of ten tied to the span', () => {
  assert.equal(stackQuantum(1), 0.001);
  assert.equal(stackQuantum(0.05), 1e-5);
  assert.equal(stackQuantum(0), 0);
  assert.ok(stackRadius(1) < stackRadius(2) && stackRadius(2) < stackRadius(50));
  assert.ok(stackRadius(10000) <= 22);
});

test('colour keys: behaviours fixed, families ranked with the rest grouped', () => {
  const pts = [];
  for (let f = 1; f <= 10; f += 1) {
    for (let k = 0; k < 11 - f; k += 1) pts.push({ family: `IH${f}`, behaviour: k % 2 ? 'isotropic_auxetic' : null });
  }
  const fam = colourKey(pts, 'family');
  assert.equal(fam.entries.length, PALETTE.length);
  assert.equal(fam.entries[0].key, 'IH1');
  const other = fam.entries.at(-1);
  assert.equal(other.colour, OTHER);
  assert.equal(other.label, '4 other families');
  assert.equal(fam.entries.reduce((n, e) => n + e.count, 0), pts.length);
  assert.equal(fam.colourOf({ family: 'IH10' }), OTHER);
  assert.equal(new Set(fam.entries.map((e) => e.colour)).size, fam.entries.length);
  const beh = colourKey(pts, 'behaviour');
  assert.deepEqual(beh.entries.map((e) => e.label), ['isotropic auxetic', 'unclassified']);
  assert.equal(beh.colourOf({ behaviour: null }), OTHER);
  const stack = { points: [pts[0], pts[1], pts[2]] };
  assert.deepEqual(stackSlices(stack, beh).map((s) => s.count), [2, 1]);
});

test('tick labels are distinct, short and read back as their ticks on any range', () => {
  const domains = [
    [0, 1], [-1.0000000001, -0.9999999], [-1.0000000000001, -0.99999999999], [1.3333, 1.3334],
    [0.001, 0.02], [1e-7, 3e-7], [2e5, 9e7], [-5, 5], [40, 400], [0.41421305262304875, 0.414213052623686],
    [1e12, 1e12 + 1], [-3e-9, 4e-9],
  ];
  for (const d of domains) {
    for (const n of [2, 5, 8]) {
      const t = axisTicks(d, n);
      assert.ok(t.values.length >= 1, `${d} ${n}`);
      assert.equal(new Set(t.labels).size, t.labels.length, `${d}: ${t.labels}`);
      const step = t.values.length > 1 ? t.values[1] - t.values[0] : Math.abs(d[0]) || 1;
      t.labels.forEach((l, i) => {
        assert.ok(l.length <= 9, `${d}: ${l} too long`);
        assert.ok(Math.abs(labelValue(l, t.offset) - t.values[i]) <= step / 2, `${d}: ${l} is not ${t.values[i]}`);
      });
      if (t.offset) assert.ok(t.offset.value >= d[0] && t.offset.value <= d[1], `${d}: offset ${t.offset.value}`);
    }
  }
  // The reproducer's narrow range needs an offset; an ordinary one does not.
  assert.ok(axisTicks([-1.0000000001, -0.9999999], 6).offset);
  assert.equal(axisTicks([0, 2], 6).offset, null);
});

test('all values equal: one tick, in full', () => {
  const t = axisTicks([1.333333333333, 1.333333333333], 6);
  assert.deepEqual(t.values, [1.333333333333]);
  assert.deepEqual(t.labels, ['1.33333333333']);
});

test('fitting ticks leave room between labels', () => {
  const t = fittingTicks([0.123456, 0.123999], 200, 10, { charWidth: 7, gap: 10 });
  const widest = Math.max(...t.labels.map((l) => l.length * 7));
  assert.ok(t.values.length * (widest + 10) <= 200 || t.values.length === 1);
  assert.ok(fittingTicks([0, 1], 1000, 10).values.length >= 6);
});

test('brushed ranges round outward to short numbers', () => {
  for (const [a, b] of [[0.123456, 0.3456789], [1.99999, 2.0001], [-1.0000000001, -0.9999999], [5, 5], [120.5, 3.2]]) {
    const r = roundedRange(a, b);
    assert.ok(r.min <= Math.min(a, b) && r.max >= Math.max(a, b), `${a} ${b}: ${r.min} ${r.max}`);
    const span = Math.abs(b - a);
    if (span > 0) assert.ok(r.max - r.min <= span * 1.05, `${a} ${b}: too wide ${r.min} ${r.max}`);
    assert.ok(String(r.min).length <= 14 && String(r.max).length <= 14, `${r.min} ${r.max}`);
  }
  assert.deepEqual(roundedRange(0.123456, 0.3456789), { min: 0.123, max: 0.346 });
});

test('arrow keys go to the nearest stack in their direction', () => {
  const s = [
    { px: 100, py: 100 }, { px: 150, py: 100 }, { px: 300, py: 104 }, { px: 140, py: 30 },
    { px: 100, py: 200 }, { px: 40, py: 300 },
  ];
  assert.equal(nearestInDirection(s, s[0], 'ArrowRight'), 1);
  assert.equal(nearestInDirection(s, s[1], 'ArrowRight'), 2);
  assert.equal(nearestInDirection(s, s[0], 'ArrowUp'), 3);
  assert.equal(nearestInDirection(s, s[0], 'ArrowDown'), 4);
  assert.equal(nearestInDirection(s, s[0], 'ArrowLeft'), -1);
  assert.equal(nearestInDirection(s, s[2], 'ArrowRight'), -1);
  assert.equal(nearestInDirection(s, s[0], 'Enter'), -1);
});

test('the pointer picks each stack at its centre, and a big stack keeps most of its disc', () => {
  // Random layouts (seeded): one big stack with small stacks scattered over and around it.
  let seed = 42;
  const rand = () => {
    seed = (seed * 1103515245 + 12345) % 2 ** 31;
    return seed / 2 ** 31;
  };
  for (let trial = 0; trial < 50; trial += 1) {
    const big = { px: 100, py: 100, r: stackRadius(124) };
    const stacks = [big];
    const n = 1 + Math.floor(rand() * 6);
    for (let k = 0; k < n; k += 1) {
      const a = rand() * 2 * Math.PI;
      const d = 1 + rand() * (big.r + 8);
      stacks.push({ px: 100 + d * Math.cos(a), py: 100 + d * Math.sin(a), r: stackRadius(1 + Math.floor(rand() * 4)) });
    }
    // Every centre picks its own stack, whatever the drawing order.
    for (const order of [stacks, [...stacks].reverse()]) {
      order.forEach((s, i) => assert.equal(pickStack(order, s.px, s.py), i, `trial ${trial}`));
    }
    // Each small stack takes at most the part of the big disc nearer to it in pick radii: at
    // most (r_s / r_b)² of the big disc each, so the big one keeps at least half here.
    let own = 0;
    let all = 0;
    for (let x = big.px - big.r; x <= big.px + big.r; x += 0.5) {
      for (let y = big.py - big.r; y <= big.py + big.r; y += 0.5) {
        if (Math.hypot(x - big.px, y - big.py) > big.r) continue;
        all += 1;
        if (pickStack(stacks, x, y) === 0) own += 1;
      }
    }
    assert.ok(own / all >= 0.5, `trial ${trial}: the big stack keeps ${own / all} of its disc`);
  }
  // Outside every pick radius, nothing.
  assert.equal(pickStack([{ px: 0, py: 0, r: 3 }], pickRadius(3) + 0.1, 0), -1);
  assert.equal(pickStack([{ px: 0, py: 0, r: 3 }], pickRadius(3) - 0.1, 0), 0);
});
