// Unit tests of the canvas zoom and pan model (src/zoom-pan.js).

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { FIT, MAX_ZOOM, panBy, zoomAbout, zoomPoint, zoomedTransform } from '../src/zoom-pan.js';

const close = (a, b, msg) => assert.ok(Math.abs(a - b) < 1e-9 * Math.max(1, Math.abs(a), Math.abs(b)), `${msg}: ${a} vs ${b}`);

test('zooming about a point keeps that point fixed; panning moves everything by the drag', () => {
  // Random zoom sequences (seeded) on a 600×400 canvas.
  let seed = 3;
  const rand = () => {
    seed = (seed * 1103515245 + 12345) % 2 ** 31;
    return seed / 2 ** 31;
  };
  const [w, h] = [600, 400];
  for (let trial = 0; trial < 100; trial += 1) {
    let z = FIT;
    for (let step = 0; step < 6; step += 1) {
      const c = [rand() * w, rand() * h];
      const factor = 0.5 + rand() * 2.5;
      // The drawing's point under c before the zoom (inverting the zoom by its definition).
      const under = [(c[0] - w / 2 - z.x) / z.k + w / 2, (c[1] - h / 2 - z.y) / z.k + h / 2];
      const next = zoomAbout(z, factor, c[0], c[1], w, h);
      assert.ok(next.k >= 1 && next.k <= MAX_ZOOM);
      if (next.k > 1 && next.k < MAX_ZOOM && z.k * factor > 1) {
        const [x, y] = zoomPoint(next, w, h, under);
        close(x, c[0], `trial ${trial} x`);
        close(y, c[1], `trial ${trial} y`);
      }
      z = next;
      const d = [rand() * 40 - 20, rand() * 40 - 20];
      const p = [rand() * w, rand() * h];
      const moved = panBy(z, ...d);
      if (z.k > 1) {
        const [a, b] = zoomPoint(z, w, h, p);
        const [a2, b2] = zoomPoint(moved, w, h, p);
        close(a2 - a, d[0], 'pan x');
        close(b2 - b, d[1], 'pan y');
      } else assert.deepEqual(moved, FIT, 'nothing to pan when fitted');
      z = moved;
    }
  }
});

test('zooming out to 1 fits again; the canvas transform agrees with zoomPoint', () => {
  const z = zoomAbout(FIT, 4, 100, 50, 600, 400);
  assert.equal(z.k, 4);
  assert.deepEqual(zoomAbout(z, 0.1, 300, 300, 600, 400), FIT);
  // World (x, y) → fit (s·x + tx, −s·y + ty) → zoom; the transform maps it the same way.
  const fit = [12.5, 300, 200];
  const ratio = 2;
  const [a, b, c, d, e, f] = zoomedTransform(z, 600, 400, ratio, fit);
  for (const [x, y] of [[0, 0], [3, -2], [-7.5, 11]]) {
    const [px, py] = zoomPoint(z, 600, 400, [fit[0] * x + fit[1], -fit[0] * y + fit[2]]);
    close((a * x + c * y + e) / ratio, px, 'x');
    close((b * x + d * y + f) / ratio, py, 'y');
  }
});
