// Design page over `isogami serve` (on a private copy of the database, since saving writes
// to it) in real headless Chromium: scrubbing t changes the canvas and the plots; moving a
// shape slider brings a new trajectory from /api/deploy and the plot changes; making the
// design rigid with the joint editor shows the explanation in place; a tuned design is
// saved as a user design and shared by URL; the downloads hold the trajectory.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  allApiRows, byTestId, canvasColours, canvasPixels, copyDb, downloadText, getJson, launchBrowser,
  moveSlider, newPage, parseCsv, pixelsChanged, problems, screenshot, startServer,
} from './harness.mjs';

let db;
let server;
let browser;
let designs;

before(async () => {
  db = await copyDb();
  server = await startServer({ db: db.file });
  browser = await launchBrowser();
  designs = (await allApiRows(server.base)).filter((r) => r.params.length > 0 && r.dof === 1);
  assert.ok(designs.length > 0, 'the test database has a design with shape parameters');
});

after(async () => {
  await browser?.close();
  await server?.stop();
  await db?.remove();
});

async function openDesign(page, spec, extra = '') {
  await page.goto(`${server.base}/design.html?spec=${encodeURIComponent(spec)}${extra}`);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
}

const deployments = (page) => page.evaluate(() => Number(document.body.dataset.deployments || 0));

test('scrubbing t changes the canvas, the marker and the polar profile', async () => {
  const page = await newPage(browser);
  const spec = designs[0].spec;
  await openDesign(page, spec);
  assert.equal(await byTestId(page, 'spec').textContent(), spec);
  const closed = await canvasPixels(page, '[data-testid="sheet"]');
  assert.ok(canvasColours(closed) > 3, 'the patch is drawn');
  const marker0 = await byTestId(page, 'plot-marker').getAttribute('x1');
  const polar0 = await byTestId(page, 'polar-profile').getAttribute('d');
  await byTestId(page, 't-slider').fill('1');
  const open = await canvasPixels(page, '[data-testid="sheet"]');
  const changed = pixelsChanged(closed, open);
  assert.ok(changed > closed.length / 4 / 100, `at least 1% of the canvas changes (${changed} pixels)`);
  assert.notEqual(await byTestId(page, 'plot-marker').getAttribute('x1'), marker0);
  assert.notEqual(await byTestId(page, 'polar-profile').getAttribute('d'), polar0);
  // The URL follows the view a moment later (debounced).
  await page.waitForFunction(() => new URL(location.href).searchParams.get('t') === '1');
  for (const id of ['show-cell', 'show-links']) await byTestId(page, id).check();
  await byTestId(page, 'colour').selectOption('rotation');
  const decorated = await canvasPixels(page, '[data-testid="sheet"]');
  assert.ok(pixelsChanged(open, decorated) > 0, 'cell, loops and rotation colours are drawn');
  assert.ok((await screenshot(browser, page, 'design')) > 50, 'the design page screenshot is not blank');
  assert.deepEqual(problems(page), []);
});

test('moving a shape slider brings a new trajectory and the plot changes', async () => {
  const page = await newPage(browser);
  let done = false;
  for (const design of designs.slice(0, 5)) {
    await openDesign(page, design.spec);
    const before = await byTestId(page, 'series-max').getAttribute('d');
    const count = await deployments(page);
    for (const key of ['ArrowRight', 'ArrowLeft']) {
      // The key presses may start more than one deployment (the throttle sends the latest
      // value, aborting a slower one); once the edit has settled the page shows the last.
      const res = await moveSlider(page, 'param-v0', key, 6);
      if (res.status() !== 200) continue; // this move gave an invalid tile; the other way may not
      await page.waitForFunction((n) => Number(document.body.dataset.deployments) > n, count);
      const body = await res.json();
      assert.equal(await byTestId(page, 'spec').textContent(), body.spec);
      assert.notEqual(body.spec, design.spec);
      assert.equal(body.origin, null, 'a tuned design is live, not stored');
      assert.notEqual(await byTestId(page, 'series-max').getAttribute('d'), before, 'the expansion plot changed');
      await page.waitForFunction((s) => new URL(location.href).searchParams.get('spec') === s, body.spec);
      assert.match(await byTestId(page, 'origin').textContent(), /live/);
      done = true;
      break;
    }
    if (done) break;
  }
  assert.ok(done, 'a slider move on one of five designs was deployed');
  assert.ok((await screenshot(browser, page, 'design-live')) > 50);

  // The edited design opened from its URL (a reload, a shared link): it is not stored, so it
  // is deployed live, and no request of the page fails on the way (the page asked for its
  // stored view first and logged a 404 for every edited design opened).
  const edited = await newPage(browser);
  await edited.goto(page.url());
  await edited.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  assert.equal(await byTestId(edited, 'spec').textContent(), await byTestId(page, 'spec').textContent());
  assert.match(await byTestId(edited, 'origin').textContent(), /live/);
  assert.deepEqual(problems(edited), []);

  // The tuned design can be saved, then is stored as a user design and opens from its URL.
  const spec = await byTestId(page, 'spec').textContent();
  await byTestId(page, 'save').click();
  await page.waitForFunction(() => /saved/.test(document.querySelector('[data-testid="save-status"]').textContent));
  const stored = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(spec)}`);
  assert.equal(stored.origin, 'user');
  const shared = await newPage(browser);
  await openDesign(shared, spec, `&kerf=${stored.report.kerf}`);
  assert.match(await byTestId(shared, 'origin').textContent(), /user/);
  // A slider move the server refuses (an invalid tile) is a 422; nothing else may fail.
  assert.deepEqual(problems(page, [/^422 POST \S+\/api\/deploy$/]), []);
  assert.deepEqual(problems(shared), []);
});

test('making the design rigid with the joint editor explains it in place', async () => {
  const page = await newPage(browser);
  await openDesign(page, designs[0].spec);
  const edges = await page.locator('[data-testid^="edge-"]').count();
  assert.ok(edges > 0);
  // Weld every edge (cycle none → A → B → both); the last change is the one deployed.
  for (let i = 0; i < edges; i += 1) {
    const edge = byTestId(page, `edge-${i}`);
    for (let k = 0; k < 4 && !/welded/.test(await edge.getAttribute('aria-label')); k += 1) {
      await edge.focus();
      await edge.press('Enter');
    }
    assert.match(await edge.getAttribute('aria-label'), /welded/);
  }
  assert.equal(await byTestId(page, 'joints').textContent(), 'x'.repeat(edges));
  const notice = page.locator('.notice[data-kind="rigid"]');
  await notice.waitFor({ state: 'visible' });
  const text = await notice.textContent();
  assert.ok((await notice.locator('strong').textContent()).length > 5, 'a message');
  assert.ok((await notice.locator('.hint').textContent()).length > 5, `a hint on what to do: ${text}`);
  assert.ok(canvasColours(await canvasPixels(page, '[data-testid="sheet"]')) > 3, 'never a blank page');
  assert.ok((await screenshot(browser, page, 'design-rigid')) > 50);
  // The refused deployments are 422s, and so is the shape analysis of a design that does not
  // move (it has no shape class); nothing else may fail.
  await page.waitForFunction(() => /degrees of freedom/.test(document.querySelector('[data-testid="shape-status"]').textContent));
  assert.deepEqual(problems(page, [/^422 POST \S+\/api\/deploy$/, /^422 GET \S+\/api\/shape\?/]), []);
});

test('downloads hold the trajectory: CSV one row per frame per tile, SVG of the patch', async () => {
  const page = await newPage(browser);
  const spec = designs[0].spec;
  await openDesign(page, spec, '&R=2&C=3');
  const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(spec)}`);
  const frames = view.report.frames.length;
  const tiles = view.geometry.tiles.length;
  const json = JSON.parse((await downloadText(page, () => byTestId(page, 'download-trajectory-json').click())).text);
  assert.equal(json.frames.length, frames);
  assert.equal(json.design, view.report.design);
  const csv = parseCsv((await downloadText(page, () => byTestId(page, 'download-trajectory-csv').click())).text);
  assert.equal(csv.length - 1, frames * tiles);
  assert.deepEqual(csv[0].slice(0, 4), ['frame', 'step', 't', 'tile']);
  const svg = (await downloadText(page, () => byTestId(page, 'download-svg').click())).text;
  // Tiles (the linkage loops are polygons too, without data-tile).
  assert.equal((svg.match(/<polygon data-tile=/g) || []).length, 2 * 3 * tiles);
  assert.ok(!/NaN|undefined/.test(svg));
  const gif = await page.request.get(`${server.base}/api/gif?spec=${encodeURIComponent(spec)}`);
  assert.equal(gif.headers()['content-type'], 'image/gif');
  assert.deepEqual(problems(page), []);
});
