// Zoom and pan of the design page's drawings (issue 42 item 15) in real headless Chromium over
// `isogami serve`: a thin-tile design (IH59 at its smallest v0 in the database, whose sheet is
// a narrow strip) can be enlarged in the sheet viewer and in the finite-sheet panel with the
// wheel and the keyboard, panned by a drag, and fitted again by a double click.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  byTestId, canvasPixels, getJson, launchBrowser, newPage, openDesign, pixelsChanged, problems, startServer,
} from './harness.mjs';

let server;
let browser;
let thin;

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  const rows = (await getJson(`${server.base}/api/designs?family=IH59&sort=v0&limit=1`)).rows;
  thin = rows[0]?.spec;
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

/** Share of a canvas's pixels that are not white (how much of it the drawing fills). */
function filled(pixels) {
  let n = 0;
  for (let i = 0; i < pixels.length; i += 4) if (pixels[i] < 250 || pixels[i + 1] < 250 || pixels[i + 2] < 250) n += 1;
  return n / (pixels.length / 4);
}

const zoomOf = async (page, id) => (await byTestId(page, id).getAttribute('data-zoom')).split(',').map(Number);

/** Zooms the canvas `id` with the wheel and the keys, pans it by a drag, fits it again. */
async function zoomAndPan(page, id) {
  const selector = `[data-testid="${id}"]`;
  const canvas = byTestId(page, id);
  await canvas.scrollIntoViewIfNeeded();
  const before = await canvasPixels(page, selector);
  const box = await canvas.boundingBox();
  const [cx, cy] = [box.x + box.width / 2, box.y + box.height / 2];
  await page.mouse.move(cx, cy);
  await page.mouse.wheel(0, -600);
  await page.waitForFunction((s) => Number(document.querySelector(s).dataset.zoom?.split(',')[0]) > 1, selector);
  const zoomed = await canvasPixels(page, selector);
  assert.ok(filled(zoomed) > 2 * filled(before), `${id}: the wheel enlarges the drawing (${filled(before)} → ${filled(zoomed)} of the canvas)`);
  // A drag pans by the drag.
  const [k, x, y] = await zoomOf(page, id);
  await page.mouse.down();
  await page.mouse.move(cx + 60, cy + 40, { steps: 4 });
  await page.mouse.up();
  const [k2, x2, y2] = await zoomOf(page, id);
  assert.equal(k2, k);
  assert.ok(Math.abs(x2 - x - 60) < 1 && Math.abs(y2 - y - 40) < 1, `${id}: panned by (${x2 - x}, ${y2 - y})`);
  // A double click fits again: the same pixels as before.
  await page.mouse.dblclick(cx, cy);
  await page.waitForFunction((s) => document.querySelector(s).dataset.zoom === '1,0,0', selector);
  assert.equal(pixelsChanged(before, await canvasPixels(page, selector)), 0, `${id}: fitted again`);
  // The keyboard: + zooms in, 0 fits.
  await canvas.focus();
  await page.keyboard.press('+');
  assert.ok((await zoomOf(page, id))[0] > 1, `${id}: + zooms in`);
  await page.keyboard.press('0');
  assert.deepEqual(await zoomOf(page, id), [1, 0, 0]);
}

test('a thin-tile design can be zoomed and panned in the viewer and the finite panel (issue 42 item 15)', async () => {
  assert.ok(thin, 'the database has an IH59 design');
  const page = await newPage(browser);
  await page.setViewportSize({ width: 1440, height: 900 });
  await openDesign(page, server.base, thin);
  await zoomAndPan(page, 'sheet');
  await page.waitForFunction(() => document.querySelector('[data-testid="finite-panel"]')?.dataset.state === 'ready', null, { timeout: 60000 });
  await zoomAndPan(page, 'finite-canvas');
  assert.deepEqual(problems(page), []);
});
