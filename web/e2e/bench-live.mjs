// Live-design benchmark (issue 24 item 7; not part of the test run): slider input → the new
// motion drawn on the design page, measured in real headless Chromium by the page itself
// (design.js records performance.now() from the slider's input event to the end of the
// synchronous redraw of the answer in window.isogamiLive, with the request's and the
// redraw's shares). Opens designs with shape parameters spread over the database, drags the
// first shape slider's thumb back and forth for --drag-ms (a mouse move every ~16 ms), and
// prints the median and p95 over every answer drawn, with the machine's load.
//
//   CHROMIUM=/usr/bin/chromium ISOGAMI_BIN=../target/debug/isogami ISOGAMI_DB=/tmp/full.db \
//     node e2e/bench-live.mjs [--designs 20] [--drag-ms 1500]

import { readFileSync } from 'node:fs';
import { allApiRows, launchBrowser, newPage, openDesign, startServer } from './harness.mjs';

const arg = (name, fallback) => {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? Number(process.argv[i + 1]) : fallback;
};
const DESIGNS = arg('designs', 20);
const DRAG_MS = arg('drag-ms', 1500);

const quantile = (xs, q) => {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor(q * s.length))];
};

const server = await startServer({ args: ['--read-only'] });
const browser = await launchBrowser();
const all = [];
const request = [];
const draw = [];
try {
  const rows = (await allApiRows(server.base)).filter((r) => r.params.length > 0);
  // Spread over the catalogue: every k-th design with shape parameters.
  const step = Math.max(1, Math.floor(rows.length / DESIGNS));
  const picked = rows.filter((_, i) => i % step === 0).slice(0, DESIGNS);
  const page = await newPage(browser);
  await page.setViewportSize({ width: 1440, height: 900 });
  for (const row of picked) {
    await openDesign(page, server.base, row.spec);
    await page.evaluate(() => {
      window.isogamiLive = [];
    });
    const slider = page.locator('[data-testid="param-v0"]');
    if (await slider.isDisabled()) continue; // pinned by its shape constraint
    await page.waitForFunction(() => document.querySelector('[data-testid="param-v0"]')?.dataset.lo !== undefined, null, { timeout: 10000 }).catch(() => {});
    // A continuous drag of the slider's thumb: a mouse move every ~16 ms for DRAG_MS.
    const box = await slider.boundingBox();
    const [lo, hi, value] = await slider.evaluate((el) => [Number(el.min), Number(el.max), Number(el.value)]);
    const x0 = box.x + ((value - lo) / (hi - lo)) * box.width;
    const y = box.y + box.height / 2;
    await page.mouse.move(x0, y);
    await page.mouse.down();
    const start = Date.now();
    for (let k = 1; Date.now() - start < DRAG_MS; k += 1) {
      const x = x0 + Math.sin(((Date.now() - start) / DRAG_MS) * Math.PI * 2) * box.width * 0.15;
      await page.mouse.move(Math.min(box.x + box.width - 1, Math.max(box.x + 1, x)), y);
      await page.waitForTimeout(16);
    }
    await page.mouse.up();
    await page.waitForFunction(() => !document.body.classList.contains('simulating'), null, { timeout: 10000 }).catch(() => {});
    const got = await page.evaluate(() => window.isogamiLive);
    all.push(...got.map((x) => x.ms));
    request.push(...got.map((x) => x.requestMs));
    draw.push(...got.map((x) => x.drawMs));
    process.stderr.write(`${row.spec}: ${got.map((x) => `${x.ms.toFixed(0)}(${x.requestMs.toFixed(0)}+${x.drawMs.toFixed(0)})`).join(' ')}\n`);
  }
} finally {
  await browser.close();
  await server.stop();
}
const load = readFileSync('/proc/loadavg', 'utf8').split(' ').slice(0, 3).join(' ');
console.log(JSON.stringify({
  samples: all.length,
  median_ms: Number(quantile(all, 0.5).toFixed(1)),
  p95_ms: Number(quantile(all, 0.95).toFixed(1)),
  request_median_ms: Number(quantile(request, 0.5).toFixed(1)),
  request_p95_ms: Number(quantile(request, 0.95).toFixed(1)),
  draw_median_ms: Number(quantile(draw, 0.5).toFixed(1)),
  draw_p95_ms: Number(quantile(draw, 0.95).toFixed(1)),
  loadavg: load,
}));
