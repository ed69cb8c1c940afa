// Editing in view (issue 24 items 3, 4, 7 and the design page's smaller points of item 8) in
// real headless Chromium over `isogami serve`: at 1440×900 the sheet stays in view beside the
// shape sliders and the joint editor; at 390 px nothing is wider than the window; a refused
// joint edit shows its reason next to the joint editor and marks every panel stale until a
// valid design is shown again; the shape sliders say what each parameter does and are limited
// to the library's valid range with the well-shaped band shaded; a continuous 1 s drag
// redraws the sheet at least 5 times and every measure (the Poisson-like ratio too) is
// recomputed; the joint editor has a legend and no two pins overlap.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  byTestId, copyDb, getJson, launchBrowser, newPage, openDesign as openHarnessDesign, problems, screenshot, startServer,
} from './harness.mjs';

// Stored in the quick exploration; one DOF at every nearby shape (generic), two parameters.
const GENERIC = 'IH28:0.316978918628,0.35:1x1:a--a-b-bbb';

let server;
let browser;
let db;

before(async () => {
  db = await copyDb();
  server = await startServer({ db: db.file, args: ['--read-only'] });
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
  await db?.remove();
});

/** A page of the given viewport size. */
async function pageOf(width, height) {
  const page = await newPage(browser);
  await page.setViewportSize({ width, height });
  return page;
}

const openDesign = (page, spec) => openHarnessDesign(page, server.base, spec);
const deployments = (page) => page.evaluate(() => Number(document.body.dataset.deployments || 0));

/** Whether the element's box lies inside the viewport (at least `share` of its height). */
async function inView(page, selector, share = 0.9) {
  return page.$eval(
    selector,
    (el, s) => {
      const r = el.getBoundingClientRect();
      const visible = Math.min(r.bottom, innerHeight) - Math.max(r.top, 0);
      return r.height > 0 && visible >= s * r.height && r.left >= 0 && r.right <= innerWidth;
    },
    share,
  );
}

test('at 1440×900 the sheet stays in view beside the shape sliders and the joint editor', async () => {
  const page = await pageOf(1440, 900);
  await openDesign(page, GENERIC);
  await page.waitForSelector('[data-testid="param-v0"]');
  assert.ok(await inView(page, '[data-testid="sheet"]'), 'canvas in view at the top');
  assert.ok(await inView(page, '[data-testid="param-v0"]', 1), 'the first shape slider in view at the top');
  // Scroll until the joint editor is in view: the canvas is still in view (sticky).
  await byTestId(page, 'joint-editor').scrollIntoViewIfNeeded();
  assert.ok(await inView(page, '[data-testid="joint-editor"] svg', 0.5), 'joint editor in view');
  assert.ok(await inView(page, '[data-testid="sheet"]'), 'canvas still in view beside the joint editor');
  // Mid-edit: a slider moved, the sheet redrawn beside it.
  await page.evaluate(() => window.scrollTo(0, 0));
  const n = await deployments(page);
  const slider = byTestId(page, 'param-v1');
  await slider.focus();
  for (let k = 0; k < 5; k += 1) await slider.press('ArrowRight');
  await page.waitForFunction((m) => Number(document.body.dataset.deployments) > m, n);
  await page.screenshot({ path: new URL('./artifacts/editing-1440x900.png', import.meta.url).pathname });
  assert.deepEqual(problems(page), []);
  await page.close();
});

test('at 390 px wide the design page is no wider than the window', async () => {
  const page = await pageOf(390, 844);
  await openDesign(page, GENERIC);
  await page.waitForSelector('[data-testid="param-v0"]');
  await page.waitForSelector('[data-testid="export-panel"] select');
  const widths = await page.evaluate(() => ({
    doc: document.documentElement.scrollWidth,
    body: document.body.scrollWidth,
    wide: [...document.querySelectorAll('body *')]
      .filter((el) => el.getBoundingClientRect().right > innerWidth + 0.5)
      .slice(0, 5)
      .map((el) => `${el.tagName}.${el.className}#${el.id} ${Math.round(el.getBoundingClientRect().right)}`),
  }));
  assert.ok(widths.doc <= 390, `scrollWidth ${widths.doc}: ${widths.wide.join(', ')}`);
  await screenshot(browser, page, 'editing-390');
  // Mid-edit at 390 px: the sliders in view, one moved.
  await byTestId(page, 'param-v0').scrollIntoViewIfNeeded();
  const n = await deployments(page);
  await byTestId(page, 'param-v0').focus();
  await page.keyboard.press('ArrowLeft');
  await page.waitForFunction((m) => Number(document.body.dataset.deployments) > m, n);
  await page.evaluate(() => document.querySelector('.live').scrollIntoView());
  await page.screenshot({ path: new URL('./artifacts/editing-390-mid-edit.png', import.meta.url).pathname });
  assert.deepEqual(problems(page), []);
  await page.close();
});

test('shape sliders say what the parameter does and are limited to the library valid range', async () => {
  const page = await pageOf(1440, 900);
  await openDesign(page, GENERIC);
  const families = await getJson(`${server.base}/api/families`);
  const family = families.find((f) => f.name === 'IH28');
  const ranges = await getJson(`${server.base}/api/shape/ranges?design=${encodeURIComponent(GENERIC)}&kerf=0.01`);
  await page.waitForFunction(() => document.querySelector('[data-testid="param-v0"]')?.dataset.lo !== undefined);
  for (const r of ranges.ranges) {
    const k = r.index;
    const doc = await byTestId(page, `param-v${k}-doc`).textContent();
    assert.ok(doc.includes(family.param_effects[k].description), `v${k} label: ${doc}`);
    const [min, max] = await byTestId(page, `param-v${k}`).evaluate((el) => [Number(el.min), Number(el.max)]);
    assert.equal(min, r.lo, `v${k} min`);
    assert.equal(max, r.hi, `v${k} max`);
    const well = await byTestId(page, `param-v${k}-band`).getAttribute('data-well');
    if (r.well_shaped) assert.deepEqual(well.split(',').map(Number), r.well_shaped);
    assert.match(await byTestId(page, `param-v${k}-range`).textContent(), /^valid /);
  }
  // The corners the words name are labelled on tile 0 of the joint editor.
  const corners = await page.$$eval('[data-testid="tile0-corners"] text', (ts) => ts.map((t) => t.textContent));
  assert.deepEqual(corners, corners.map((_, k) => String(k)), 'corners 0…n-1');
  for (const e of family.param_effects) {
    for (const c of [...e.opens, ...e.closes, ...e.lengthens, ...e.shortens]) assert.ok(c < corners.length, `v${e.index} names ${c}`);
  }
  // The slider's ends deploy (no ill-shaped refusal at either end).
  const n = await deployments(page);
  const slider = byTestId(page, 'param-v1');
  await slider.focus();
  await slider.press('End');
  await page.waitForFunction((m) => Number(document.body.dataset.deployments) > m, n, { timeout: 20000 }).catch(() => {});
  const kinds = await page.$$eval('[data-testid="notice"]', (els) => els.map((e) => e.dataset.kind));
  assert.ok(!kinds.includes('ill_shaped'), `no ill-shaped refusal at the slider's end: ${kinds}`);
  assert.deepEqual(problems(page, [/422 POST \S+\/api\/deploy/]), []);
  await page.close();
});

test('a design whose tile is not well-shaped cannot be saved, and its sliders reach back to the defaults (issue 42 item 17)', async () => {
  // The reproducer: IH28 with both parameters at 9, far outside the family's shapes
  // (it builds, so it deploys, but the library finds no well-shaped band around it).
  const DEGENERATE = 'IH28:9,9:1x1:a--a-b-bbb';
  const ranges = await getJson(`${server.base}/api/shape/ranges?design=${encodeURIComponent(DEGENERATE)}&kerf=0.01`);
  assert.ok(ranges.ranges.every((r) => r.well_shaped === null), 'the library calls it not well-shaped');
  const family = (await getJson(`${server.base}/api/families`)).find((f) => f.name === 'IH28');
  const page = await pageOf(1440, 900);
  await openDesign(page, DEGENERATE);
  await page.waitForFunction(() => document.querySelector('[data-testid="param-v0"]')?.dataset.lo !== undefined);
  await page.waitForFunction(() => /not well-shaped/.test(document.querySelector('[data-testid="save-status"]').textContent));
  assert.equal(await byTestId(page, 'save').isDisabled(), true, 'Save is disabled');
  // Every slider reaches the family's default value (the valid interval alone, 8.1 … 9.9,
  // trapped it near 9).
  for (const r of ranges.ranges) {
    const k = r.index;
    const [min, max] = await byTestId(page, `param-v${k}`).evaluate((el) => [Number(el.min), Number(el.max)]);
    const d = family.default_params[k];
    assert.ok(min <= d && d <= max, `v${k}: default ${d} within the slider's ${min} … ${max}`);
    assert.ok(min <= r.lo && r.hi <= max, `v${k}: the valid interval stays within the slider`);
  }
  await page.close();

  // A live well-shaped design of the same family can be saved.
  const fine = 'IH28:0.316978918628,0.36:1x1:a--a-b-bbb';
  const good = await pageOf(1440, 900);
  await openDesign(good, fine);
  await good.waitForFunction(() => document.querySelector('[data-testid="param-v0"]')?.dataset.lo !== undefined);
  await good.waitForFunction(() => !document.querySelector('[data-testid="save"]').disabled);
  assert.equal(await byTestId(good, 'save-status').textContent(), '');
  assert.deepEqual(problems(good), []);
  await good.close();
});

test('a refused joint edit is explained beside the joint editor and marks every panel stale', async () => {
  const page = await pageOf(1440, 900);
  await openDesign(page, GENERIC);
  const original = await byTestId(page, 'joints').textContent();
  // Weld every edge (x): the sheet is rigid, which the server refuses.
  const order = ['-', 'a', 'b', 'x'];
  const refused = page.waitForResponse((r) => r.url().endsWith('/api/deploy') && r.status() === 422, { timeout: 30000 });
  for (let i = 0; i < original.length; i += 1) {
    const presses = (4 + order.indexOf('x') - order.indexOf(original[i])) % 4;
    for (let k = 0; k < presses; k += 1) {
      await byTestId(page, `edge-${i}`).focus();
      await page.keyboard.press('Enter');
    }
  }
  assert.equal(await byTestId(page, 'joints').textContent(), 'x'.repeat(original.length));
  await refused;
  // Stale once the last edit's answer is in: a refused joint string on the way marks the page
  // stale too, and a valid one answered after it clears that again.
  await page.waitForFunction(() => document.body.dataset.stale === 'true' && !document.body.classList.contains('simulating'));
  // The reason is next to the joint editor, not at the page top.
  const local = byTestId(page, 'notice-joints');
  assert.ok(await local.isVisible(), 'notice beside the joint editor');
  assert.equal(await local.locator('[data-testid="notice"]').getAttribute('data-kind'), 'rigid');
  assert.ok(await byTestId(page, 'notice-joints').evaluate((el) => el.getAttribute('aria-live')), 'an aria-live region');
  assert.ok(await page.locator('#notice').isHidden(), 'nothing at the page top');
  // Every panel that still shows the last valid design says so.
  for (const sel of ['.viewer', '.charts', '.measures', '.finite', '.export', '.downloads', '.spec-line']) {
    assert.equal(await page.locator(sel).getAttribute('data-stale'), 'true', `${sel} marked stale`);
    assert.equal(await page.locator(sel).getAttribute('aria-describedby'), 'stale-badge');
  }
  const badge = byTestId(page, 'stale-badge');
  assert.ok(await badge.isVisible(), 'the stale badge is shown');
  assert.match(await badge.textContent(), /stale/);
  // The header still names the last valid design (an intermediate joint string the throttle
  // deployed on the way, or the original), never the refused one.
  const shown = await byTestId(page, 'spec').textContent();
  assert.ok(!shown.endsWith(`:${'x'.repeat(original.length)}`), `header ${shown}`);
  assert.ok((await badge.textContent()).includes(shown), 'the badge names the design still shown');
  assert.ok(await inView(page, '[data-testid="stale-badge"]', 1), 'the badge is in view while editing');
  const opacity = await page.locator('[data-testid="measures"]').evaluate((el) => Number(getComputedStyle(el).opacity));
  assert.ok(opacity < 0.6, `measures dimmed: ${opacity}`);
  assert.ok(await byTestId(page, 'save').isDisabled(), 'nothing stale can be saved');
  await page.screenshot({ path: new URL('./artifacts/editing-stale.png', import.meta.url).pathname });

  // Back to the original joints: a valid design again, nothing stale.
  for (let i = 0; i < original.length; i += 1) {
    const presses = (4 + order.indexOf(original[i]) - order.indexOf('x')) % 4;
    for (let k = 0; k < presses; k += 1) {
      await byTestId(page, `edge-${i}`).focus();
      await page.keyboard.press('Enter');
    }
  }
  // Wait for the original design's answer (intermediate joint strings may be answered, valid
  // or refused, on the way).
  await page.waitForFunction(
    (joints) => document.querySelector('[data-testid="spec"]').textContent.endsWith(`:${joints}`)
      && !document.body.classList.contains('simulating'),
    original,
    { timeout: 30000 },
  ).catch(async (e) => {
    const state = await page.evaluate(() => ({
      spec: document.querySelector('[data-testid="spec"]').textContent,
      joints: document.querySelector('[data-testid="joints"]').textContent,
      classes: document.body.className,
    }));
    throw new Error(`${e.message}: ${JSON.stringify(state)} ${page.errors.join('; ')}`);
  });
  assert.equal(await page.evaluate(() => document.body.dataset.stale), undefined);
  assert.equal(await page.locator('.measures').getAttribute('data-stale'), null);
  assert.ok(await badge.isHidden());
  assert.ok(await byTestId(page, 'notice-joints').isHidden(), 'the notice is gone');
  // Refused on the way: the deployments, and the shape class and finite sheet of the
  // intermediate designs (rigid or not one DOF), which their own panels explain.
  assert.deepEqual(problems(page, [/422 (POST \S+\/api\/deploy|GET \S+\/api\/(shape|sheet)\?)/]), []);
  await page.close();
});

test('a continuous 1 s drag redraws the sheet at least 5 times and recomputes every measure', async () => {
  const page = await pageOf(1440, 900);
  await openDesign(page, GENERIC);
  await page.waitForFunction(() => document.querySelector('[data-testid="param-v1"]')?.dataset.lo !== undefined);
  await page.evaluate(() => window.scrollTo(0, 0));
  // Count real canvas redraws: a checksum of the canvas's pixels on every animation frame.
  await page.evaluate(() => {
    const canvas = document.querySelector('[data-testid="sheet"]');
    const ctx = canvas.getContext('2d');
    window.redraws = { changes: 0, last: null, on: true };
    const tick = () => {
      if (!window.redraws.on) return;
      const d = ctx.getImageData(0, 0, canvas.width, canvas.height).data;
      let sum = 0;
      for (let i = 0; i < d.length; i += 97) sum = (sum * 31 + d[i]) >>> 0;
      if (window.redraws.last !== null && sum !== window.redraws.last) window.redraws.changes += 1;
      window.redraws.last = sum;
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  });
  const box = await byTestId(page, 'param-v1').boundingBox();
  const y = box.y + box.height / 2;
  const [lo, hi, value] = await byTestId(page, 'param-v1').evaluate((el) => [Number(el.min), Number(el.max), Number(el.value)]);
  const thumbX = box.x + ((value - lo) / (hi - lo)) * box.width;
  const before = await deployments(page);
  await page.mouse.move(thumbX, y);
  await page.mouse.down();
  const start = Date.now();
  const steps = 50;
  for (let k = 1; k <= steps; k += 1) {
    // Back and forth over a fifth of the track, ~1 s in all.
    const x = thumbX + Math.sin((k / steps) * Math.PI * 2) * box.width * 0.1;
    await page.mouse.move(x, y);
    await new Promise((r) => setTimeout(r, Math.max(0, start + (k * 1000) / steps - Date.now())));
  }
  const during = (await deployments(page)) - before;
  const canvasChanges = await page.evaluate(() => window.redraws.changes);
  await page.mouse.up();
  await page.evaluate(() => {
    window.redraws.on = false;
  });
  assert.ok(during >= 5, `designs drawn during the drag: ${during}`);
  assert.ok(canvasChanges >= 5, `canvas redraws during the drag: ${canvasChanges}`);
  // Every measure of the live design, the Poisson-like ratio included.
  await page.waitForFunction(() => !document.body.classList.contains('simulating'));
  const poisson = await page.$$eval('[data-testid="measures"] tr', (rows) => {
    const row = rows.find((r) => r.querySelector('th')?.textContent === 'Poisson-like ratio');
    return row?.querySelector('td')?.textContent;
  });
  // The same range as the live deployment's own report (the page showed "–" for every live
  // design, reading only the catalogue row).
  const spec = await byTestId(page, 'spec').textContent();
  const res = await fetch(`${server.base}/api/deploy`, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify({ design: spec, kerf: 0.01 }),
  });
  const range = (await res.json()).report.poisson_range;
  assert.ok(range, `${spec} opens: it has a Poisson-like range`);
  assert.ok(poisson && poisson !== '–', `Poisson-like ratio after a live move of ${spec}: ${poisson}`);
  const [a, b] = poisson.split(' … ').map(Number);
  assert.ok(Math.abs(a - range[0]) < 1e-3 * Math.max(1, Math.abs(range[0])), `${poisson} vs ${range}`);
  assert.ok(Math.abs(b - range[1]) < 1e-3 * Math.max(1, Math.abs(range[1])), `${poisson} vs ${range}`);
  assert.match(await byTestId(page, 'origin').textContent(), /live/);
  // A shape far along the drag may have no one-DOF finite sheet: the finite panel says so.
  assert.deepEqual(problems(page, [/422 GET \S+\/api\/sheet\?/]), []);
  await page.close();
});

test('the joint editor has a legend and no two pins overlap', async () => {
  const page = await pageOf(1440, 900);
  for (const spec of [GENERIC, 'IH16:0.216506350946:1x1:-a-a-aaaa', 'rotating-squares']) {
    await openDesign(page, spec);
    const legend = byTestId(page, 'joint-legend');
    assert.ok(await legend.isVisible());
    const text = await legend.textContent();
    for (const word of ['grey', 'black', 'pin', 'A', 'B', 'welded']) assert.ok(text.includes(word), `legend says ${word}: ${text}`);
    const pins = await page.$$eval('[data-testid="joint-editor"] circle.pin', (cs) =>
      cs.map((c) => ({ x: Number(c.getAttribute('cx')), y: Number(c.getAttribute('cy')), r: Number(c.getAttribute('r')) })));
    const joints = await byTestId(page, 'joints').textContent();
    const expected = [...joints].reduce((n, c) => n + (c === 'x' ? 2 : c === '-' ? 0 : 1), 0);
    assert.equal(pins.length, expected, `${spec}: one pin per jointed end`);
    for (let i = 0; i < pins.length; i += 1) {
      for (let j = i + 1; j < pins.length; j += 1) {
        const d = Math.hypot(pins[i].x - pins[j].x, pins[i].y - pins[j].y);
        assert.ok(d >= 2 * pins[i].r, `${spec}: pins ${i} and ${j} overlap (${d} < ${2 * pins[i].r})`);
      }
    }
  }
  await page.close();
});
