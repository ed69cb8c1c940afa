// The graded-sheet page over `isogami serve`, in real headless Chromium: reached from the
// catalogue's navigation, a small sheet (3×3 cells of rotating squares, few iterations) grades
// while the page watches, the report appears, the player's closed and opened ends differ and
// the tiles drawn there are the run's poses, the download is the job's result; the region is
// checked against the caps as typed; a non-star polygon drawn on the pad shows the library's
// one-line error and starts nothing; a longer run's drawing of the sheet as it stands changes
// while it runs, and Stop ends it; a design page's "grade this design" pre-fills the design; on the
// static site the page shows the command instead of running. A field target (3×3 cells, few
// iterations) reports each cell's asked and achieved area ratio and its largest error, and the
// graded sheet downloads as laser and print files (the SVG in mm and what the shown
// `isogami export --sheet` writes, the DXF with its header, the STL with triangles); an
// uploaded SVG file is read by the library — a bad one shows its one-line error and starts
// nothing, a good one is drawn and graded towards. A finished job shows the library's verdict
// in its own words and the outline's fit figures, marks the worst boundary point on the
// opened sheet beside the target, and — graded without the fall-back towards an L the sheet
// cannot open into — fills the deepest overlapping pair of tiles with its depth in mm.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { mkdtemp, readFile, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';
import {
  buildSite, byTestId, downloadText, env, getJson, launchBrowser, newPage, problems, screenshot, serveFolder, startServer,
} from './harness.mjs';
import { posedPolygons } from '../src/graded-model.js';
import { shellSplit } from '../test/shell.mjs';

let server;
let browser;

before(async () => {
  server = await startServer();
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

/** Stops every running job (so that a test's page does not attach to one a failed test left). */
async function stopAll() {
  for (const id of (await getJson(`${server.base}/api/graded`)).running) {
    await fetch(`${server.base}/api/graded/${id}`, { method: 'DELETE' });
    while ((await getJson(`${server.base}/api/graded/${id}`)).state === 'running') await new Promise((ok) => setTimeout(ok, 50));
  }
}

const state = (page) => page.evaluate(() => document.body.dataset.gradedState ?? '');

/** The polygons drawn as tiles in an SVG of the page, as numbers. */
function drawnTiles(page, testid) {
  return page.$$eval(`[data-testid="${testid}"] polygon.tile`, (els) =>
    els.map((e) => e.getAttribute('points').trim().split(/\s+/).map((p) => p.split(',').map(Number))));
}

function assertSamePolygons(drawn, expected, what) {
  assert.equal(drawn.length, expected.length, `${what}: tile count`);
  let worst = 0;
  drawn.forEach((poly, i) => {
    assert.equal(poly.length, expected[i].length, `${what}: corners of tile ${i}`);
    poly.forEach(([x, y], k) => {
      worst = Math.max(worst, Math.abs(x - expected[i][k][0]), Math.abs(y - expected[i][k][1]));
    });
  });
  assert.ok(worst < 1e-5, `${what}: drawn tiles ${worst} from the poses`);
}

/** Records every drawing of the live sheet, with the job's state then, in window.liveDrawings. */
function recordLiveDrawings(page) {
  return page.evaluate(() => {
    window.liveDrawings = [];
    const svg = document.querySelector('[data-testid="live-sheet"]');
    new MutationObserver(() => {
      if (svg.firstChild) window.liveDrawings.push({ state: document.body.dataset.gradedState, iteration: svg.dataset.iteration, svg: svg.innerHTML });
    }).observe(svg, { childList: true });
  });
}

/** Clicks the pad at outline coordinates (x, y), y up (mapped to the screen by the pad's own
 * transform, so the page reads back the same point to its rounding). */
async function clickPad(page, x, y) {
  const at = await page.evaluate(([px, py]) => {
    const g = document.querySelector('[data-testid="draw-pad"] g');
    const p = new DOMPoint(px, py).matrixTransform(g.getScreenCTM());
    return [p.x, p.y];
  }, [x, y]);
  await page.mouse.click(at[0], at[1]);
}

test('a small sheet grades while the page watches, then reports, plays and downloads', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/index.html`);
  await byTestId(page, 'nav-graded').click();
  await page.waitForURL(/graded\.html$/);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  assert.equal(await byTestId(page, 'design').inputValue(), 'rotating-squares');
  // Every field has a label; the caps come from the server and are checked as typed.
  const unlabelled = await page.$$eval('#graded-form input', (els) =>
    els.filter((e) => e.labels.length === 0 && !e.getAttribute('aria-label')).map((e) => e.id || e.name));
  assert.deepEqual(unlabelled, []);
  const settings = await getJson(`${server.base}/api/graded`);
  assert.equal(await byTestId(page, 'rows').getAttribute('max'), String(settings.limits.side));
  await byTestId(page, 'cols').fill('9');
  assert.equal(await byTestId(page, 'region-error').textContent(), `columns 9 is above this server's limit of ${settings.limits.side}`, 'region error for 3x9');
  await byTestId(page, 'rows').fill('7');
  await byTestId(page, 'cols').fill('7');
  assert.match(await byTestId(page, 'region-error').textContent(), /49 cells is above this server's limit of 36 cells/);
  await byTestId(page, 'rows').fill('3');
  await byTestId(page, 'cols').fill('3');
  assert.equal(await byTestId(page, 'region-error').textContent(), '', 'no region error for 3x3');
  await byTestId(page, 'iterations').fill('150');
  assert.deepEqual(shellSplit(await byTestId(page, 'graded-command').textContent()),
    ['isogami', 'graded', '--design', 'rotating-squares', '--region', '3x3', '--target', 'disc', '--iterations', '150', '--out', 'graded.json']);

  await recordLiveDrawings(page);
  // The job's first view held back a moment: until it comes the page says it is setting up
  // (CI once read an empty line in that moment).
  let firstView = true;
  await page.route(/\/api\/graded\/\d+$/, async (route) => {
    if (firstView) {
      firstView = false;
      await new Promise((done) => setTimeout(done, 500));
    }
    await route.continue();
  });
  const started = page.waitForResponse((r) => r.url().endsWith('/api/graded') && r.request().method() === 'POST');
  await byTestId(page, 'run').click();
  assert.equal((await started).status(), 202);
  await page.waitForFunction(() => document.body.dataset.gradedState === 'running');
  assert.equal(await byTestId(page, 'progress-line').textContent(), 'Setting up the sheet…');
  await page.waitForFunction(() => ['done', 'failed', 'stopped'].includes(document.body.dataset.gradedState), null, { timeout: 60000 });
  assert.equal(await state(page), 'done', await page.locator('#notice').textContent());
  // The sheet as it ended is drawn over the fitted target, however many polls saw it running
  // (this run takes about a second: how many is up to the machine; a longer run's drawing
  // changing while it runs is the Stop test's).
  const drawings = await page.evaluate(() => window.liveDrawings);
  assert.ok(drawings.length >= 1, 'the live sheet was drawn');
  assert.equal(drawings.at(-1).state, 'done', `the last drawing is the finished job's (${drawings.map((d) => d.state)})`);
  assert.match(await page.locator('#live-target-note').textContent(), /fitted scale/);
  assert.equal(await byTestId(page, 'progress-bar').evaluate((b) => b.value === b.max), true);
  assert.ok(await byTestId(page, 'live-sheet').isVisible(), 'the live drawing is on screen');
  const liveBox = await byTestId(page, 'live-sheet').boundingBox();
  assert.ok(liveBox.width > 200 && liveBox.height > 200, `live drawing ${liveBox.width}x${liveBox.height}`);

  // The report, as the job says.
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const job = await getJson(`${server.base}/api/graded/${id}`);
  const result = job.result;
  const liveTarget = await page.$eval('[data-testid="live-sheet"] polygon.target', (e) =>
    e.getAttribute('points').trim().split(/\s+/).map((p) => p.split(',').map(Number)));
  assertSamePolygons([liveTarget], [result.report.target], 'the live drawing’s fitted target');
  const fit = await byTestId(page, 'report-fit').textContent();
  assert.ok(fit.includes(`within ${(100 * result.report.max_outline_error).toFixed(2)} %`), fit);
  const path = await byTestId(page, 'report-path').textContent();
  assert.match(path, result.path.reached ? /^Opens along one motion/ : /^Does NOT open along one motion/);
  assert.match(await byTestId(page, 'report-overlaps').textContent(), /^(No two tiles overlap|Overlaps: tiles \d+ and \d+)/);

  // The player starts at the opened end: the tiles drawn are the optimised state's poses,
  // over the fitted target.
  const n = result.path.states.length;
  assert.equal(await byTestId(page, 'state-slider').getAttribute('max'), String(n - 1));
  assert.equal(await byTestId(page, 'state-slider').inputValue(), String(n - 1));
  const opened = await drawnTiles(page, 'player-sheet');
  assertSamePolygons(opened, posedPolygons(result.sheet, result.path.states[0].poses), 'opened end');
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.target').count(), 1);
  const openedShot = await byTestId(page, 'player-sheet').screenshot();
  // The closed end (Home on the slider): the closed tiling, no target.
  await byTestId(page, 'state-slider').focus();
  await page.keyboard.press('Home');
  assert.equal(await page.evaluate(() => document.querySelector('[data-testid="player-sheet"]').dataset.state), '0');
  const closed = await drawnTiles(page, 'player-sheet');
  assertSamePolygons(closed, posedPolygons(result.sheet, result.path.states[n - 1].poses), 'closed end');
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.target').count(), 0);
  const moved = Math.max(...closed.flatMap((poly, i) => poly.map(([x, y], k) => Math.hypot(x - opened[i][k][0], y - opened[i][k][1]))));
  assert.ok(moved > 0.1, `tiles moved ${moved} between the ends`);
  const closedShot = await byTestId(page, 'player-sheet').screenshot();
  assert.ok(!openedShot.equals(closedShot), 'the drawings of the two ends differ');
  assert.match(await byTestId(page, 'state-value').textContent(), /^0 % open/);
  // Play moves through the states.
  await byTestId(page, 'play').click();
  await page.waitForFunction(() => Number(document.querySelector('[data-testid="player-sheet"]').dataset.state) >= 3);
  await byTestId(page, 'play').click();
  assert.equal(await byTestId(page, 'play').getAttribute('aria-pressed'), 'false');

  // The download is the job's result, as `isogami graded --out` writes it.
  const file = await downloadText(page, () => byTestId(page, 'download').click());
  assert.equal(file.name, 'graded-3x3.json');
  assert.deepEqual(JSON.parse(file.text), result);
  assert.ok((await screenshot(browser, page, 'graded-done')) > 20);
  assert.deepEqual(problems(page), []);
});

test('a polygon drawn on the pad: a non-star one shows the library’s error and starts nothing', async () => {
  await stopAll();
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  // A U: its centroid does not see the inside of the notch.
  const u = [[-1, -1], [1, -1], [1, 1], [0.5, 1], [0.5, -0.5], [-0.5, -0.5], [-0.5, 1], [-1, 1]];
  for (const [x, y] of u) await clickPad(page, x, y);
  assert.equal(await byTestId(page, 'outline-polygon').isChecked(), true);
  // The library's answer for all eight points (one for fewer points, if the clicks were slow,
  // is not it: the page checks those itself until the answer for the eight comes).
  await page.waitForFunction(() => {
    const pad = document.querySelector('[data-testid="draw-pad"]');
    return pad.dataset.points === '8' && pad.dataset.checked === 'true';
  });
  const shown = await byTestId(page, 'outline-error').textContent();
  // The library's message for the outline the page would send (the command's --target).
  const words = shellSplit(await byTestId(page, 'graded-command').textContent());
  const target = words[words.indexOf('--target') + 1];
  assert.match(target, /^polygon:(-?[\d.]+,-?[\d.]+;){7}-?[\d.]+,-?[\d.]+$/);
  const res = await fetch(`${server.base}/api/graded/outline?outline=${encodeURIComponent(target)}`);
  assert.equal(res.status, 400);
  assert.equal(shown, (await res.json()).error);
  assert.match(shown, /not seen whole from its centroid/);
  assert.equal(await byTestId(page, 'draw-pad').getAttribute('data-bad'), 'true');
  assert.ok((await screenshot(browser, page, 'graded-bad-polygon')) > 20);
  // Grade starts nothing.
  let posted = false;
  page.on('request', (r) => {
    if (r.url().endsWith('/api/graded') && r.method() === 'POST') posted = true;
  });
  await byTestId(page, 'run').click();
  await page.waitForTimeout(300);
  assert.equal(posted, false);
  assert.equal(await state(page), '', 'no job attached or started');
  // A diamond is fine.
  await byTestId(page, 'clear-points').click();
  for (const [x, y] of [[0, -1], [1, 0], [0, 1], [-1, 0]]) await clickPad(page, x, y);
  await page.waitForFunction(() => {
    const pad = document.querySelector('[data-testid="draw-pad"]');
    return pad.dataset.points === '4' && pad.dataset.checked === 'true';
  });
  assert.equal(await byTestId(page, 'outline-error').textContent(), '');
  assert.equal(await byTestId(page, 'draw-pad').getAttribute('data-bad'), 'false');
  // Where the clicks landed, to the pixel (the pad is 240 px across 2.5 units).
  const drawn = shellSplit(await byTestId(page, 'graded-command').textContent());
  const corners = drawn[drawn.indexOf('--target') + 1].replace('polygon:', '').split(';').map((p) => p.split(',').map(Number));
  [[0, -1], [1, 0], [0, 1], [-1, 0]].forEach(([x, y], k) => {
    assert.ok(Math.hypot(corners[k][0] - x, corners[k][1] - y) < 0.02, `corner ${k}: ${corners[k]}`);
  });
  // The problems of the page are the 400s of the checked outline alone.
  assert.deepEqual(problems(page, [/^400 GET .*\/api\/graded\/outline\?outline=polygon/]), []);
});

test('a run’s drawing changes while it runs, Stop ends it, and a design page’s link pre-fills the design', async () => {
  await stopAll();
  const page = await newPage(browser);
  const rows = await getJson(`${server.base}/api/designs?limit=1`);
  const spec = rows.rows[0].spec;
  await page.goto(`${server.base}/design.html?spec=${encodeURIComponent(spec)}`);
  await page.waitForFunction((s) => document.querySelector('[data-testid="grade-link"]').getAttribute('href').includes(encodeURIComponent(s)), spec);
  await byTestId(page, 'grade-link').click();
  await page.waitForURL(/graded\.html\?design=/);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  assert.equal(await byTestId(page, 'design').inputValue(), spec);

  await byTestId(page, 'design').fill('rotating-squares');
  await byTestId(page, 'rows').fill('6');
  await byTestId(page, 'cols').fill('6');
  await byTestId(page, 'outline-ellipse').check();
  // 6×6 cells at the default iterations run for most of a minute here: the page sees the sheet
  // change several times before Stop.
  await recordLiveDrawings(page);
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => {
    const running = (window.liveDrawings ?? []).filter((d) => d.state === 'running');
    return new Set(running.map((d) => d.iteration)).size >= 2;
  }, null, { timeout: 30000 });
  assert.equal(await state(page), 'running');
  const whileRunning = (await page.evaluate(() => window.liveDrawings)).filter((d) => d.state === 'running');
  assert.ok(new Set(whileRunning.map((d) => d.svg)).size >= 2, 'the drawing changed during the run');
  await byTestId(page, 'stop').click();
  await page.waitForFunction(() => document.body.dataset.gradedState === 'stopped', null, { timeout: 15000 });
  assert.match(await page.locator('#notice').textContent(), /grading stopped by request/);
  assert.ok(await page.locator('#results-section').isHidden());
  assert.ok(await byTestId(page, 'live-sheet').isVisible(), 'the sheet as it stood is still shown');
  assert.equal(await byTestId(page, 'run').isDisabled(), false);
  assert.deepEqual(problems(page), []);
});

test('on the static site the page says the optimiser needs the server', async () => {
  const site = await buildSite();
  const files = await serveFolder(site.dir, '/sub');
  try {
    const page = await newPage(browser);
    await page.goto(`${files.base}/index.html`);
    await byTestId(page, 'nav-graded').click();
    await page.waitForURL(/graded\.html$/);
    await page.waitForFunction(() => document.body.dataset.ready === 'true' && document.body.dataset.mode === 'static');
    assert.ok(await byTestId(page, 'run').isDisabled());
    assert.match(await byTestId(page, 'run-note').textContent(), /needs `isogami serve`/);
    assert.ok(await page.locator('#progress-section').isHidden());
    await byTestId(page, 'outline-ellipse').check();
    assert.match(await byTestId(page, 'graded-command').textContent(), /--target ellipse:1\.4,1/);
    // The drawn polygon is checked in the page (the library's rule and words).
    for (const [x, y] of [[-1, -1], [1, -1], [1, 1], [0.5, 1], [0.5, -0.5], [-0.5, -0.5], [-0.5, 1], [-1, 1]]) await clickPad(page, x, y);
    assert.match(await byTestId(page, 'outline-error').textContent(), /^bad target: the outline is not seen whole from its centroid/);
    assert.deepEqual(problems(page), []);
  } finally {
    await files.stop();
    await site.remove();
  }
});

/** Clicks an export button; the downloaded file's name and bytes. */
async function downloadExport(page, format) {
  const [dl] = await Promise.all([page.waitForEvent('download'), byTestId(page, `export-${format}`).click()]);
  return { name: dl.suggestedFilename(), bytes: await readFile(await dl.path()) };
}

test('a field target reports each cell’s area ratio, and the graded sheet downloads as laser and print files', async () => {
  await stopAll();
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  await byTestId(page, 'rows').fill('3');
  await byTestId(page, 'cols').fill('3');
  await byTestId(page, 'iterations').fill('40');
  await byTestId(page, 'outline-field').check();
  await byTestId(page, 'field-from').fill('0.9');
  assert.match(await byTestId(page, 'outline-error').textContent(), /above 1/);
  await byTestId(page, 'field-from').fill('1.3');
  await byTestId(page, 'field-to').fill('1.7');
  await byTestId(page, 'field-degrees').fill('90');
  assert.equal(await byTestId(page, 'outline-error').textContent(), '');
  const words = shellSplit(await byTestId(page, 'graded-command').textContent());
  assert.equal(words[words.indexOf('--target') + 1], 'field:1.3,1.7,90');
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => ['done', 'failed', 'stopped'].includes(document.body.dataset.gradedState), null, { timeout: 60000 });
  assert.equal(await state(page), 'done', await page.locator('#notice').textContent());
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const result = (await getJson(`${server.base}/api/graded/${id}`)).result;
  assert.ok(result.field.length >= 4, `${result.field.length} field cells`);
  assert.ok(new Set(result.field.map((c) => c.target.toFixed(6))).size >= 2, 'a ramp: cells asked for different ratios');
  // The report's fit is the field's error; the table has every cell, asked and achieved.
  const fit = await byTestId(page, 'report-fit').textContent();
  assert.ok(fit.includes(`within ${result.report.max_field_error.toFixed(4)} of the field in each of ${result.field.length} cells`), fit);
  const rows = await page.$$eval('[data-testid="field-table"] tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((td) => td.textContent)));
  assert.equal(rows.length, result.field.length);
  rows.forEach((row, k) => {
    const c = result.field[k];
    assert.deepEqual(row.slice(0, 3), [String(k + 1), c.target.toFixed(4), c.ratio.toFixed(4)]);
  });
  assert.ok(await byTestId(page, 'field-result').isVisible());
  // The cells coloured at the opened end, none at the closed end; no target outline.
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.field-cell').count(), result.field.length);
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.target').count(), 0);
  const errors = await page.$$eval('[data-testid="player-sheet"] polygon.field-cell', (els) => els.map((e) => Number(e.dataset.error)));
  errors.forEach((e, k) => assert.ok(Math.abs(e - (result.field[k].ratio - result.field[k].target)) < 1e-6));
  assert.ok((await screenshot(browser, page, 'graded-field')) > 20);

  // Laser SVG: millimetres, and what the shown command writes from the downloaded sheet.
  const svg = await downloadExport(page, 'svg');
  assert.equal(svg.name, 'graded-3x3.svg');
  const text = svg.bytes.toString('utf8');
  assert.match(text, /<svg[^>]* width="[\d.]+mm" height="[\d.]+mm"/);
  assert.match(await byTestId(page, 'export-status').textContent(), /^saved graded-3x3\.svg/);
  const command = shellSplit(await byTestId(page, 'export-command').textContent());
  assert.deepEqual(command.slice(0, 6), ['isogami', 'export', '--sheet', 'graded-3x3.json', '--format', 'svg']);
  const dir = await mkdtemp(join(tmpdir(), 'isogami-graded-'));
  try {
    const sheet = await fetch(`${server.base}/api/graded/${id}/sheet`);
    await writeFile(join(dir, 'graded-3x3.json'), Buffer.from(await sheet.arrayBuffer()));
    await promisify(execFile)(env().bin, command.slice(1), { cwd: dir });
    assert.ok((await readFile(join(dir, 'graded-3x3.svg'))).equals(svg.bytes), 'the CLI writes the same SVG');
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
  // Laser DXF with its header; print STL with triangles (binary: 80-byte header, a count, 50 bytes each).
  await byTestId(page, 'export-edge').fill('15');
  const dxf = await downloadExport(page, 'dxf');
  assert.equal(dxf.name, 'graded-3x3.dxf');
  assert.match(dxf.bytes.toString('utf8'), /\n\s*0\r?\nSECTION\r?\n\s*2\r?\nHEADER\r?\n[\s\S]*\$INSUNITS/);
  const stl = await downloadExport(page, 'stl');
  assert.equal(stl.name, 'graded-3x3.stl');
  const triangles = stl.bytes.readUInt32LE(80);
  assert.ok(triangles > 0, `${triangles} triangles`);
  assert.equal(stl.bytes.length, 84 + 50 * triangles);
  // A bad edge length disables the buttons and says why.
  await byTestId(page, 'export-edge').fill('-1');
  assert.equal(await byTestId(page, 'export-svg').isDisabled(), true);
  assert.match(await byTestId(page, 'export-status').textContent(), /positive number of mm/);
  assert.deepEqual(problems(page), []);
});

test('an uploaded SVG outline: a bad file shows the library’s one-line error, a good one is graded towards', async () => {
  await stopAll();
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  await byTestId(page, 'rows').fill('2');
  await byTestId(page, 'cols').fill('2');
  await byTestId(page, 'iterations').fill('30');
  const two = '<svg xmlns="http://www.w3.org/2000/svg"><rect width="1" height="1"/><rect x="3" width="1" height="1"/></svg>';
  await byTestId(page, 'svg-file').setInputFiles({ name: 'two.svg', mimeType: 'image/svg+xml', buffer: Buffer.from(two) });
  await page.waitForFunction(() => Number(document.body.dataset.svgChecks || 0) >= 1);
  assert.equal(await byTestId(page, 'outline-svg').isChecked(), true);
  const shown = await byTestId(page, 'outline-error').textContent();
  const res = await fetch(`${server.base}/api/graded/svg?name=two.svg`, { method: 'POST', body: two });
  assert.equal(res.status, 400);
  assert.equal(shown, (await res.json()).error);
  assert.match(shown, /^two\.svg: /);
  assert.ok(!shown.includes('\n'));
  let posted = false;
  page.on('request', (r) => {
    if (r.url().endsWith('/api/graded') && r.method() === 'POST') posted = true;
  });
  await byTestId(page, 'run').click();
  await page.waitForTimeout(300);
  assert.equal(posted, false, 'a bad file starts nothing');

  const pentagon = '<svg xmlns="http://www.w3.org/2000/svg" viewBox="-3 -3 6 6"><path d="M 0 -2 L 2 -0.5 L 1.2 2 L -1.2 2 L -2 -0.5 Z"/></svg>';
  await byTestId(page, 'svg-file').setInputFiles({ name: 'pentagon.svg', mimeType: 'image/svg+xml', buffer: Buffer.from(pentagon) });
  await page.waitForFunction(() => Number(document.body.dataset.svgChecks || 0) >= 2);
  assert.equal(await byTestId(page, 'outline-error').textContent(), '');
  assert.match(await byTestId(page, 'outline-status').textContent(), /^pentagon\.svg: an outline of 5 corners/);
  assert.equal(await page.locator('[data-testid="draw-pad"] polygon[data-outline="svg"]').count(), 1);
  const words = shellSplit(await byTestId(page, 'graded-command').textContent());
  assert.equal(words[words.indexOf('--target') + 1], '@pentagon.svg');
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => ['done', 'failed', 'stopped'].includes(document.body.dataset.gradedState), null, { timeout: 60000 });
  assert.equal(await state(page), 'done', await page.locator('#notice').textContent());
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const job = await getJson(`${server.base}/api/graded/${id}`);
  assert.equal(job.request.outline, '@pentagon.svg');
  assert.equal(job.request.outline_points.length, 5);
  assert.ok(await byTestId(page, 'field-result').isHidden(), 'no field table for an outline');
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.target').count(), 1);
  assert.deepEqual(problems(page, [/^400 POST .*\/api\/graded\/svg/]), []);
});

test('the polygon target from the keyboard: a labelled field of corners bound both ways with the pad', async () => {
  await stopAll();
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  // The field is found by its label, as a screen reader names it.
  const field = page.getByLabel(/^polygon corners/);
  assert.equal(await field.count(), 1);
  await field.focus();
  await page.keyboard.type('0,1; -1,-1; 1,-1');
  assert.equal(await byTestId(page, 'outline-polygon').isChecked(), true, 'typing corners chooses the polygon');
  await page.waitForFunction(() => {
    const pad = document.querySelector('[data-testid="draw-pad"]');
    return pad.dataset.points === '3' && pad.dataset.checked === 'true';
  });
  assert.equal(await byTestId(page, 'outline-error').textContent(), '');
  const target = async () => {
    const words = shellSplit(await byTestId(page, 'graded-command').textContent());
    return words[words.indexOf('--target') + 1];
  };
  assert.equal(await target(), 'polygon:0,1;-1,-1;1,-1');
  assert.equal(await page.locator('[data-testid="draw-pad"] circle.corner').count(), 3);

  // A click on the pad adds a corner, and the field says so.
  await clickPad(page, 0.6, 0.6);
  await page.waitForFunction(() => document.querySelector('[data-testid="draw-pad"]').dataset.points === '4');
  const typed = (await field.inputValue()).split(';').map((p) => p.split(',').map(Number));
  assert.equal(typed.length, 4);
  assert.deepEqual(typed.slice(0, 3), [[0, 1], [-1, -1], [1, -1]]);
  assert.ok(Math.hypot(typed[3][0] - 0.6, typed[3][1] - 0.6) < 0.02, `the clicked corner ${typed[3]}`);
  // Undo (a button, by keyboard) takes it off the field too.
  await byTestId(page, 'undo-point').focus();
  await page.keyboard.press('Enter');
  await page.waitForFunction(() => document.querySelector('[data-testid="draw-pad"]').dataset.points === '3');
  assert.equal((await field.inputValue()).split(';').length, 3);

  // Moving a corner: edit its numbers.
  await field.fill('0,1.2; -1,-1; 1,-1');
  await page.waitForFunction(() => document.querySelector('[data-testid="draw-pad"]').dataset.checked === 'true');
  assert.equal(await target(), 'polygon:0,1.2;-1,-1;1,-1');
  const top = await page.$eval('[data-testid="draw-pad"] circle.corner', (c) => Number(c.getAttribute('cy')));
  assert.equal(top, 1.2);

  // The corners themselves take the keyboard: Tab reaches them, the arrows move the focused
  // one (Shift: finer), Delete removes it; the field follows.
  const corner = page.locator('[data-testid="draw-pad"] circle.corner');
  assert.match(await corner.first().getAttribute('aria-label'), /^corner 1 of 3 at 0, 1\.2: arrow keys move it/);
  await field.focus();
  for (let k = 0; k < 3; k += 1) await page.keyboard.press('Shift+Tab');
  assert.equal(await page.evaluate(() => document.activeElement?.dataset.corner), '0', 'Shift+Tab from the field reaches corner 1');
  await page.keyboard.press('ArrowDown');
  await page.keyboard.press('ArrowDown');
  await page.keyboard.press('Shift+ArrowRight');
  assert.equal(await field.inputValue(), '0.01,1.1; -1,-1; 1,-1');
  assert.equal(await target(), 'polygon:0.01,1.1;-1,-1;1,-1');
  assert.equal(await page.evaluate(() => document.activeElement?.dataset.corner), '0', 'the moved corner keeps the focus');
  await page.keyboard.press('Delete');
  assert.equal(await field.inputValue(), '-1,-1; 1,-1');
  assert.equal(await byTestId(page, 'draw-pad').getAttribute('data-points'), '2');

  // Text that is not corners: the reason beside the field, and Grade starts nothing.
  await field.fill('0,1; -1');
  assert.match(await byTestId(page, 'outline-error').textContent(), /corner 2/);
  let posted = false;
  page.on('request', (r) => {
    if (r.url().endsWith('/api/graded') && r.method() === 'POST') posted = true;
  });
  await byTestId(page, 'run').click();
  await page.waitForTimeout(300);
  assert.equal(posted, false);
  assert.deepEqual(problems(page), []);
});

/** Waits for the page's job to end; the job's view from the API once it is done. */
async function finishedJob(page) {
  await page.waitForFunction(() => ['done', 'failed', 'stopped'].includes(document.body.dataset.gradedState), null, { timeout: 60000 });
  assert.equal(await state(page), 'done', await page.locator('#notice').textContent());
  const id = await page.evaluate(() => document.body.dataset.jobId);
  return getJson(`${server.base}/api/graded/${id}`);
}

/** The centre and label of the worst-point marker drawn in an SVG of the page (null if none). */
function worstMarker(page, testid) {
  return page.evaluate((t) => {
    const svg = document.querySelector(`[data-testid="${t}"]`);
    const c = svg.querySelector('circle[data-worst]');
    const label = svg.querySelector('text[data-worst-label]');
    return c && { x: Number(c.getAttribute('cx')), y: Number(c.getAttribute('cy')), label: label?.textContent ?? null };
  }, testid);
}

test('a finished job shows the library’s verdict, the fit figures and the worst boundary stretch', async () => {
  await stopAll();
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  // 2×2 rotating squares towards a disc, 60 iterations: it opens but misses the 5 % tolerance.
  await byTestId(page, 'rows').fill('2');
  await byTestId(page, 'cols').fill('2');
  await byTestId(page, 'iterations').fill('60');
  assert.equal(await byTestId(page, 'tolerance').getAttribute('placeholder'), '0.05', 'the library’s default, from the server');
  assert.equal(await byTestId(page, 'fall-back').isChecked(), true);
  await byTestId(page, 'run').click();
  const { result } = await finishedJob(page);
  const verdict = byTestId(page, 'verdict');
  assert.equal(await verdict.textContent(), result.verdict.text, 'the verdict is the library’s line');
  assert.match(result.verdict.text, /^opens along one motion; MISSES the target: off by [\d.]+ % \(tolerance 5\.00 %\)$/);
  assert.equal(await verdict.getAttribute('data-level'), 'misses');
  assert.ok(await verdict.isVisible());
  assert.equal(await byTestId(page, 'report-path').getAttribute('data-reached'), String(result.verdict.opens));
  // The fit figures, in % of the target's equivalent radius.
  const figures = await page.$$eval('[data-testid="fit-figures"] dl > div', (els) => els.map((e) => [e.dataset.key, e.querySelector('dd').textContent]));
  assert.deepEqual(figures, ['hausdorff', 'mean', 'inside', 'outside'].map((k) => [k, `${(100 * result.fit[k]).toFixed(2)} %`]));
  assert.ok(await byTestId(page, 'fit-figures').isVisible());
  // The worst boundary point, marked and labelled on the opened sheet beside the target, and
  // on the finished live drawing; not at the closed end.
  for (const svg of ['player-sheet', 'live-sheet']) {
    const mark = await worstMarker(page, svg);
    assert.ok(mark, `${svg}: a worst-point marker`);
    assert.ok(Math.hypot(mark.x - result.fit.worst[0], mark.y - result.fit.worst[1]) < 1e-5, `${svg}: at ${mark.x},${mark.y}, not ${result.fit.worst}`);
    assert.equal(mark.label, 'worst');
  }
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon.target').count(), 1);
  assert.ok(await page.locator('[data-testid="player-sheet"] circle[data-worst]').isVisible());
  await byTestId(page, 'state-slider').focus();
  await page.keyboard.press('Home');
  assert.equal(await worstMarker(page, 'player-sheet'), null, 'no marker at the closed end');
  // No overlap: nothing filled, no button to find one.
  assert.equal(result.verdict.deepest_overlap_tiles, null);
  assert.ok(await byTestId(page, 'show-overlap').isHidden());
  assert.equal(await page.locator('[data-testid="player-sheet"] polygon[data-overlap]').count(), 0);
  assert.ok((await screenshot(browser, page, 'graded-verdict')) > 20);
  assert.deepEqual(problems(page), []);
});

test('without the fall-back, a sheet that does not open: its deepest overlapping tiles are filled with their depth in mm', async () => {
  await stopAll();
  const page = await newPage(browser);
  // A design whose 2×2 sheet, graded 30 iterations towards an L with no fall-back, ends with
  // two tiles overlapping (about 0.3 mm at 20 mm edges) at its opened state: 4 s or so.
  const design = 'IH53:0.5,0.027564102564,0.027564102564:1x1:aaaabbbb';
  await page.goto(`${server.base}/graded.html?design=${encodeURIComponent(design)}`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  await byTestId(page, 'rows').fill('2');
  await byTestId(page, 'cols').fill('2');
  await byTestId(page, 'iterations').fill('30');
  await page.getByLabel(/^polygon corners/).fill('0,0; 2,0; 2,1; 1,1; 1,2; 0,2');
  await page.waitForFunction(() => document.querySelector('[data-testid="draw-pad"]').dataset.checked === 'true');
  assert.equal(await byTestId(page, 'outline-error').textContent(), '');
  await byTestId(page, 'fall-back').uncheck();
  const words = shellSplit(await byTestId(page, 'graded-command').textContent());
  assert.deepEqual(words.slice(-3), ['--no-fallback', '--out', 'graded.json']);
  await byTestId(page, 'run').click();
  const job = await finishedJob(page);
  assert.equal(job.request.fall_back, false);
  const { result } = job;
  const v = result.verdict;
  assert.equal(v.target_fraction, 1, 'the sheet graded towards the L itself');
  assert.equal(v.opens, false);
  assert.equal(await byTestId(page, 'verdict').textContent(), v.text);
  assert.equal(await byTestId(page, 'verdict').getAttribute('data-level'), 'fails');
  assert.ok(Array.isArray(v.deepest_overlap_tiles), `an overlap in this case (the library's verdict: ${v.text})`);
  // The player goes to the deepest overlap's state: its two tiles filled, the depth labelled.
  await byTestId(page, 'state-slider').focus();
  await page.keyboard.press('Home');
  await byTestId(page, 'show-overlap').click();
  const k = Number(await byTestId(page, 'state-slider').inputValue());
  const states = [...result.path.states].reverse();
  assert.ok(Math.abs(states[k].opening - v.deepest_overlap_at) < 1e-9, `state ${k} is ${states[k].opening} open`);
  assert.equal(await page.evaluate(() => document.querySelector('[data-testid="player-sheet"]').dataset.state), String(k));
  const filled = await page.$$eval('[data-testid="player-sheet"] polygon.tile.overlap.deepest', (els) => els.map((e) => Number(e.dataset.tile)));
  assert.deepEqual(filled.sort((a, b) => a - b), [...v.deepest_overlap_tiles].sort((a, b) => a - b));
  const label = await page.$eval('[data-testid="player-sheet"] text[data-overlap-label]', (e) => e.textContent);
  assert.equal(label, `${(20 * v.deepest_overlap).toFixed(3)} mm`);
  assert.ok(v.text.includes(`tiles overlap ${(20 * v.deepest_overlap).toFixed(3)} mm at 20 mm edges`), 'the same depth as the verdict says');
  assert.match(await byTestId(page, 'state-value').textContent(), /overlap [\d.]+ mm at 20 mm edges \(deepest\)$/);
  // Their fill is the warning colour, not a plain tile's.
  const fills = await page.$$eval('[data-testid="player-sheet"] polygon.tile', (els) => [...new Set(els.map((e) => getComputedStyle(e).fill))]);
  assert.ok(fills.length >= 2, `tiles drawn in ${fills}`);
  assert.ok((await screenshot(browser, page, 'graded-overlap')) > 20);
  assert.deepEqual(problems(page), []);
});
