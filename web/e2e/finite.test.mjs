// The design page's "Finite sheet" panel over a read-only `isogami serve`, in real headless
// Chromium, checked against the answers of GET /api/sheet: a one-DOF design says "1 DOF ✓" raw
// and completed and its finite deployment moves with the page's t and Play; a design whose raw
// region flops names its DOF and highlights exactly the tiles of the API's extra modes, and its
// completion draws the API's sheet with the removed tiles ghosted; a region without a one-DOF
// sheet shows the library's reason; a sheet whose path passes a singular state says where; the
// panel is on screen at 1440×900 beside the periodic sheet, and the page logs no errors.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  allApiRows, byTestId, canvasPixels, getJson, launchBrowser, newPage, nextAnswer, pixelsChanged, pollUntil, problems, screenshot, startServer,
} from './harness.mjs';

let server;
let browser;
let catalog;
/** A design whose raw 4×4 region flops and completes removing tiles, with its answer: a stored
 * one when the database has one, else LIVE_FLOPPY (deployed live). */
let floppy = null;
const LIVE_FLOPPY = 'IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-';
/** A stored design whose 4×4 region has no one-DOF sheet, with its answer. */
let refused = null;
/** A stored design whose raw 4×4 region is one DOF (rotating squares, live, when none is). */
let oneDof = null;

/** The query the page asks for the design view `view` (its kerf left out when the default). */
function sheetQuery(spec, kerf, extra = '') {
  const k = Math.abs(kerf - catalog.defaults.kerf) > 1e-12 ? `&kerf=${kerf}` : '';
  return `design=${encodeURIComponent(spec)}&region=4x4${k}${extra}`;
}

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  catalog = await getJson(`${server.base}/api/export/formats`);
  const rows = (await allApiRows(server.base)).filter((r) => r.dof === 1);
  // Analyses first (quick); the deployment, which the page asks for too, only for a candidate.
  const deployed = async (r) => {
    const res = await fetch(`${server.base}/api/sheet?${sheetQuery(r.spec, r.kerf, '&deploy=true&frames=48')}`);
    const a = res.status === 200 ? await res.json() : null;
    return a?.deployment ? a : null;
  };
  for (const r of rows.slice(0, 60)) {
    if (floppy && refused && oneDof) break;
    const res = await fetch(`${server.base}/api/sheet?${sheetQuery(r.spec, r.kerf)}`);
    if (res.status !== 200) continue;
    const a = await res.json();
    const raw = a.analysis.raw_mobility;
    const c = a.analysis.completion;
    if (!refused && a.refused) refused = { spec: r.spec, answer: a };
    if (!oneDof && raw.dof === 1 && raw.floppy.length === 0) {
      const d = await deployed(r);
      if (d) oneDof = { spec: r.spec, answer: d };
    }
    if (!floppy && raw.dof > 1 && raw.floppy.length > 0 && c && c.report.removed.length > 0) {
      const d = await deployed(r);
      if (d) floppy = { spec: r.spec, answer: d };
    }
  }
  if (!floppy) {
    const a = await deployed({ spec: LIVE_FLOPPY, kerf: catalog.defaults.kerf });
    if (a?.analysis.completion?.report.removed.length > 0) floppy = { spec: LIVE_FLOPPY, answer: a, live: true };
  }
  assert.ok(floppy, 'a design whose 4×4 region flops and completes removing tiles');
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

/** Opens the design page at 1440×900 and waits for the panel's first answer; returns that
 * answer as the page received it. */
async function openDesign(page, spec) {
  await page.setViewportSize({ width: 1440, height: 900 });
  const answer = nextAnswer(page, (r) => r.url().includes('/api/sheet?'), { status: 200 });
  await page.goto(`${server.base}/design.html?spec=${encodeURIComponent(spec)}`);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  await page.waitForFunction(() => document.querySelector('[data-testid="finite-panel"]')?.dataset.state === 'ready');
  return (await answer).json();
}

const canvas = (page) => byTestId(page, 'finite-canvas');
const data = (page, key) => canvas(page).getAttribute(`data-${key}`);

/** Pixels of an RGBA array within 12 of a #rrggbb colour in each channel. */
function pixelsOf(pixels, hex) {
  const n = parseInt(hex.slice(1), 16);
  const want = [(n >> 16) & 255, (n >> 8) & 255, n & 255];
  let count = 0;
  for (let i = 0; i < pixels.length; i += 4) {
    if (want.every((v, c) => Math.abs(pixels[i + c] - v) <= 12)) count += 1;
  }
  return count;
}

const FLOPPY_FILL = '#e4572e';

/** Every tile index the API's mobility names in some extra mode (read here from the JSON). */
function apiFloppyTiles(mobility) {
  const all = new Set();
  for (const mode of mobility.floppy) for (const t of mode.tiles) all.add(t);
  return all;
}

test('a one-DOF design: 1 DOF ✓ raw and completed, and the finite sheet moves with t and Play', async () => {
  const page = await newPage(browser);
  // A design that is not stored is deployed live (no failed request on the way).
  const spec = oneDof?.spec ?? 'rotating-squares';
  const answer = await openDesign(page, spec);
  const a = answer.analysis;
  assert.equal(a.raw_mobility.dof, 1);
  assert.equal(a.completion.mobility.dof, 1);
  assert.ok(answer.deployment.frames.length >= 2);
  // The panel says what it is, beside the periodic figures: scrolled to, it is on screen
  // together with the periodic sheet (which stays in view, sticky, since issue 24 put the
  // live-design controls first beside it).
  assert.match(await byTestId(page, 'finite-note').textContent(), /infinite periodic sheet/);
  assert.match(await byTestId(page, 'finite-note').textContent(), /cut to a region/);
  await byTestId(page, 'finite-section').evaluate((el) => el.scrollIntoView({ block: 'start' }));
  for (const id of ['finite-dof', 'finite-canvas', 'sheet']) {
    const box = await byTestId(page, id).boundingBox();
    assert.ok(box && box.y >= 0 && box.y + box.height / 2 <= 900, `${id} is on screen at 1440×900 (${JSON.stringify(box)})`);
  }
  const sheetBox = await byTestId(page, 'sheet').boundingBox();
  const finiteBox = await canvas(page).boundingBox();
  assert.ok(finiteBox.x > sheetBox.x + sheetBox.width / 2, 'the finite sheet is beside the periodic one');

  assert.equal(await byTestId(page, 'finite-dof').textContent(), '1 DOF ✓');
  await byTestId(page, 'finite-view-raw').check();
  assert.equal(await byTestId(page, 'finite-dof').textContent(), '1 DOF ✓');
  assert.equal(await data(page, 'floppy'), '0');
  assert.equal(Number(await data(page, 'tiles')), a.raw.tiles.length);
  assert.equal(pixelsOf(await canvasPixels(page, '[data-testid="finite-canvas"]'), FLOPPY_FILL), 0, 'nothing is highlighted');

  // The finite deployment follows the page's t: the first frame at 0, the last at 1.
  await byTestId(page, 'finite-view-completed').check();
  await byTestId(page, 't-slider').fill('0');
  assert.equal(await data(page, 'frame'), '0');
  const closed = await canvasPixels(page, '[data-testid="finite-canvas"]');
  await byTestId(page, 't-slider').fill('1');
  assert.equal(Number(await data(page, 'frame')), answer.deployment.frames.length - 1);
  const open = await canvasPixels(page, '[data-testid="finite-canvas"]');
  const changed = pixelsChanged(closed, open);
  assert.ok(changed > closed.length / 4 / 100, `the finite sheet opens on the canvas (${changed} pixels change)`);
  assert.match(await byTestId(page, 'finite-motion').textContent(), /Finite deployment at t = 1\.000/);
  // Play advances it: the canvas shows at least four values of t while playing (sampled until
  // then, so that a slow frame rate only takes longer).
  await byTestId(page, 't-slider').fill('0');
  await byTestId(page, 'play').click();
  const seen = new Set();
  await pollUntil(async () => seen.add(await data(page, 't')), () => seen.size >= 4, { timeout: 15000, every: 100 });
  await byTestId(page, 'play').click();
  assert.ok(seen.size >= 4, `the finite sheet's t advanced while playing: ${[...seen]}`);
  assert.ok((await screenshot(browser, page, 'design-finite')) > 50);
  assert.deepEqual(problems(page), []);
});

test('a floppy raw region names its DOF and highlights the API’s floppy tiles; its completion ghosts the removed tiles', async () => {
  const page = await newPage(browser);
  const answer = await openDesign(page, floppy.spec);
  const a = answer.analysis;
  // The page asked for what the search above found.
  assert.equal(a.raw_mobility.dof, floppy.answer.analysis.raw_mobility.dof);

  await byTestId(page, 'finite-view-raw').check();
  const badge = await byTestId(page, 'finite-dof').textContent();
  const flops = apiFloppyTiles(a.raw_mobility);
  assert.ok(flops.size > 0);
  assert.equal(Number(/^(\d+) DOF: /.exec(badge)?.[1]), a.raw_mobility.dof, badge);
  assert.ok(badge.includes(String(flops.size)), `${badge} names ${flops.size} floppy tiles`);
  assert.ok(!badge.includes('✓'));
  assert.equal(Number(await data(page, 'floppy')), flops.size, 'highlighted tiles = the API’s floppy tiles');
  assert.equal(Number(await data(page, 'tiles')), a.raw.tiles.length);
  const raw = await canvasPixels(page, '[data-testid="finite-canvas"]');
  assert.ok(pixelsOf(raw, FLOPPY_FILL) > flops.size * 4, 'the floppy tiles are filled in the highlight colour');
  assert.ok((await screenshot(browser, page, 'design-finite-raw')) > 50);

  await byTestId(page, 'finite-view-completed').check();
  await byTestId(page, 't-slider').fill('0');
  const c = a.completion;
  assert.equal(c.mobility.dof, 1);
  assert.equal(await byTestId(page, 'finite-dof').textContent(), '1 DOF ✓');
  assert.equal(Number(await data(page, 'tiles')), c.sheet.tiles.length, 'the completed sheet is drawn');
  assert.equal(Number(await data(page, 'removed')), c.report.removed.length, 'every removed tile is ghosted');
  assert.equal(Number(await data(page, 'added')), c.report.added.length);
  assert.equal(Number(await data(page, 'floppy')), 0);
  const done = await canvasPixels(page, '[data-testid="finite-canvas"]');
  assert.equal(pixelsOf(done, FLOPPY_FILL), 0, 'nothing flops in the completed sheet');
  // A ghost: the removed tiles' faint fill (12 % grey over white), which no other tile has.
  assert.ok(pixelsOf(done, '#efefef') > c.report.removed.length * 4, 'the removed tiles are drawn as ghosts');
  assert.ok(pixelsOf(done, '#7bc96f') > c.report.added.length * 4, 'the added tiles are marked');
  assert.ok(pixelsChanged(raw, done) > 0);
  const summary = await byTestId(page, 'finite-summary').textContent();
  assert.ok(summary.includes(`${c.report.removed.length} removed`), summary);
  assert.ok(summary.includes(`${(100 * c.report.covered_fraction).toFixed(1)} %`), summary);
  // Ghosts stay with the sheet as it opens (placed by the lattice of the deployed tiles).
  await byTestId(page, 't-slider').fill('1');
  assert.ok((await screenshot(browser, page, 'design-finite-completed-open')) > 50);
  assert.equal(Number(await data(page, 'removed')), c.report.removed.length);
  assert.deepEqual(problems(page), []);
});

test('a region without a one-DOF sheet shows the library’s reason and the raw region', async (t) => {
  if (!refused) {
    t.skip('no design of the test database refuses its 4×4 completion');
    return;
  }
  const page = await newPage(browser);
  const answer = await openDesign(page, refused.spec);
  assert.ok(answer.refused.startsWith('no one-DOF sheet'), answer.refused);
  assert.equal(answer.analysis.completion, null);
  const refusal = byTestId(page, 'finite-refusal');
  await refusal.waitFor({ state: 'visible' });
  assert.ok((await refusal.textContent()).includes(answer.refused));
  assert.ok(await byTestId(page, 'finite-view-completed').isDisabled());
  assert.equal(await data(page, 'view'), 'raw');
  assert.equal(Number(await data(page, 'floppy')), apiFloppyTiles(answer.analysis.raw_mobility).size);
  assert.deepEqual(problems(page), []);
});

test('a sheet whose path passes a singular state says where; one that passes none says nothing', async () => {
  // IH44's completed 4×4 sheet branches at t ≈ 0.4995 of its path (four extra motions).
  const page = await newPage(browser);
  const answer = await openDesign(page, 'IH44:0.5,0.102564102564:1x2:-aaabbaa');
  const states = [...answer.deployment.singular, ...answer.deployment.periodic_singular];
  assert.ok(answer.deployment.singular.some((s) => Math.abs(s.t - 0.4995) < 0.003 && s.extra_motions === 4), JSON.stringify(states));
  const notice = byTestId(page, 'finite-singular');
  await notice.waitFor({ state: 'visible' });
  const text = await notice.textContent();
  for (const s of states) assert.ok(text.includes(`t = ${s.t.toFixed(3)}`), text);
  assert.match(text, /4 extra first-order motions/);
  assert.deepEqual(problems(page), []);
  const squares = await newPage(browser);
  const plain = await openDesign(squares, 'rotating-squares');
  assert.equal(plain.deployment.singular.length + plain.deployment.periodic_singular.length, 0);
  assert.ok(await byTestId(squares, 'finite-singular').isHidden());
  assert.deepEqual(problems(squares), []);
});

test('a region in mm asks for that region, and a bad size asks nothing', async () => {
  const page = await newPage(browser);
  await openDesign(page, floppy.spec);
  const answered = nextAnswer(page, (r) => r.url().includes('/api/sheet?') && r.url().includes('region=disc%3A45'));
  await byTestId(page, 'finite-shape').selectOption('disc');
  await byTestId(page, 'finite-radius').fill('45');
  const res = await answered;
  assert.equal(res.status(), 200);
  const answer = await res.json();
  assert.deepEqual(answer.analysis.region, { kind: 'disc', radius_mm: 45 });
  await page.waitForFunction(() => document.querySelector('[data-testid="finite-panel"]')?.dataset.state === 'ready');
  await page.waitForFunction(
    (n) => Number(document.querySelector('[data-testid="finite-canvas"]')?.dataset.tiles) === n,
    (answer.analysis.completion?.sheet ?? answer.analysis.raw).tiles.length,
  );
  assert.match(await byTestId(page, 'finite-command').textContent(), /^isogami sheet --design '[^']+' --region disc:45 --deploy$/);
  await byTestId(page, 'finite-radius').fill('');
  assert.match(await byTestId(page, 'finite-status').textContent(), /size/);
  assert.deepEqual(problems(page), []);
});
