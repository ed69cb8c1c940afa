// Buildability (issue 40): which designs have a one-DOF finite sheet, in the browser. The
// catalogue keeps a range on finite_covered from its URL (it used to drop it and list every
// design), shows the measure as a table column and a badge on cards and rows, and filters on it
// (the "only designs with a one-DOF finite sheet" box); the design page's badge says it; the
// export panel of a design without a sheet chooses the raw rectangle and says why before
// Download (it used to leave the completed sheet chosen and fail with 422 after the click); the
// graded page says before Grade that the region has no one-DOF sheet, with what to do instead.
// The static site does the same from its files. Designs are chosen by rule from the API: the
// first without a sheet (finite_covered null) whose 3×3 region the finite-sheet check refuses,
// and the first with one whose 3×3 region it does not.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  allApiRows, buildSite, byTestId, catalogueTotal, getJson, launchBrowser, newPage, pollUntil, problems, screenshot,
  serveFolder, startServer,
} from './harness.mjs';
import { isBuildable } from '../src/buildable.js';

let server;
let browser;
let site;
let files;
let rows;
let noSheet; // a catalogue row without a one-DOF sheet
let withSheet; // a catalogue row with one

const sheetAt = (spec, region) =>
  getJson(`${server.base}/api/sheet?design=${encodeURIComponent(spec)}&region=${region}`);

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  rows = await allApiRows(server.base);
  for (const row of rows) {
    if (noSheet && withSheet) break;
    if (row.origin !== 'explored' || row.finite_raw_dof === null) continue;
    const none = row.finite_covered === null;
    if (none ? noSheet : withSheet) continue;
    const refused = (await sheetAt(row.spec, '3x3')).refused !== null;
    if (none && refused) noSheet = row;
    if (!none && !refused) withSheet = row;
  }
  assert.ok(noSheet, 'the test database has a design without a one-DOF sheet');
  assert.ok(withSheet, 'the test database has a design with one');
  site = await buildSite();
  files = await serveFolder(site.dir, '/sub');
});

after(async () => {
  await browser?.close();
  await files?.stop();
  await server?.stop();
  await site?.remove();
});

/** The badge of a card or row of `spec` on the catalogue page. */
const badgeOf = (page, kind, spec) => page.locator(`[data-testid="${kind}"][data-spec="${spec}"] [data-testid="sheet-badge"]`);

async function catalogueKeepsTheRange(base, label) {
  const page = await newPage(browser);
  await page.goto(`${base}/index.html?range=finite_covered:0.9:&view=table&limit=200`);
  const total = await catalogueTotal(page);
  // In the page's order (largest area ratio first).
  const api = await getJson(`${server.base}/api/designs?range=finite_covered:0.9:&sort=-max_area_ratio&lead=buildable&limit=200`);
  assert.equal(total, api.total, `${label}: the range filters (the API's total)`);
  assert.ok(api.total > 0 && api.total < rows.length, `${label}: the range excludes some designs (${api.total} of ${rows.length})`);
  const search = new URLSearchParams(new URL(page.url()).search);
  assert.deepEqual(search.getAll('range'), ['finite_covered:0.9:'], `${label}: the range stays in the URL`);
  assert.equal(await byTestId(page, 'range-min-finite_covered').inputValue(), '0.9');
  assert.ok(await byTestId(page, 'buildable-only').isChecked());
  // The table has the measure's column, sortable; every row's badge agrees with the API.
  assert.equal(await byTestId(page, 'sort-finite_covered').count(), 1);
  assert.equal(await byTestId(page, 'sort-finite_raw_dof').count(), 1);
  const shown = await byTestId(page, 'design-row').evaluateAll((trs) =>
    trs.map((tr) => [tr.dataset.spec, tr.querySelector('[data-testid="sheet-badge"]').dataset.sheet]),
  );
  assert.deepEqual(shown, api.rows.map((r) => [r.spec, 'sheet']));
  assert.deepEqual(problems(page), []);
  await page.context().close();
}

test('the catalogue keeps ?range=finite_covered:0.9: and shows the measure as a column and badges', async () => {
  await catalogueKeepsTheRange(server.base, 'server');
});

async function firstPageLeadsWithBuildable(base, label) {
  const page = await newPage(browser);
  await page.goto(`${base}/index.html?view=grid&limit=25`);
  await catalogueTotal(page);
  await page.waitForSelector('[data-testid="design-card"]');
  const shown = await page.$$eval('[data-testid="design-card"]', (els) => els.map((e) => e.dataset.spec));
  const bySpec = new Map(rows.map((r) => [r.spec, r]));
  const buildable = rows.filter(isBuildable).length;
  assert.ok(buildable > 0 && buildable < rows.length, `${label}: the database has both kinds (${buildable} of ${rows.length})`);
  // The default order: every buildable design before any other, largest area ratio first in each.
  const want = Math.min(buildable, shown.length);
  shown.forEach((spec, k) => assert.equal(isBuildable(bySpec.get(spec)), k < want, `${label}: card ${k} ${spec}`));
  const areas = shown.slice(0, want).map((spec) => bySpec.get(spec).max_area_ratio);
  assert.deepEqual(areas, [...areas].sort((a, b) => b - a), `${label}: largest area ratio first`);
  // A special design says so on its card.
  const special = shown.filter((spec) => bySpec.get(spec).shape_tolerance === 0);
  for (const spec of special) {
    assert.equal(await badgeOf(page, 'design-card', spec).count(), 1);
    assert.equal(await page.locator(`[data-testid="design-card"][data-spec="${spec}"] [data-testid="shape-badge"]`).getAttribute('data-shape'), 'special');
  }
  // Unticking "buildable designs first" gives the plain order (and says so in the URL).
  await byTestId(page, 'lead-buildable').uncheck();
  await page.waitForFunction(() => new URL(location.href).searchParams.get('lead') === 'all');
  const api = await getJson(`${server.base}/api/designs?sort=-max_area_ratio&limit=25`);
  await page.waitForFunction(
    (w) => JSON.stringify([...document.querySelectorAll('[data-testid="design-card"]')].map((e) => e.dataset.spec)) === JSON.stringify(w),
    api.rows.map((r) => r.spec),
  );
  assert.deepEqual(problems(page), []);
  await page.context().close();
}

test('the default order leads with buildable designs; special designs say so; the lead can be turned off', async () => {
  await firstPageLeadsWithBuildable(server.base, 'server');
  await firstPageLeadsWithBuildable(files.base, 'static site');
});

test('cards and rows carry the badge; the buildable box filters to the designs with a sheet', async () => {
  const page = await newPage(browser);
  for (const row of [noSheet, withSheet]) {
    await page.goto(`${server.base}/index.html?view=grid&limit=200&family=${row.family}`);
    await catalogueTotal(page);
    const badge = badgeOf(page, 'design-card', row.spec);
    await badge.waitFor();
    if (row === noSheet) {
      assert.equal(await badge.getAttribute('data-sheet'), 'none');
      assert.match(await badge.innerText(), /^no one-DOF sheet/);
      assert.match(await badge.getAttribute('title'), new RegExp(`${row.finite_raw_dof} DOF.*--raw`));
    } else {
      assert.equal(await badge.getAttribute('data-sheet'), 'sheet');
      assert.match(await badge.innerText(), new RegExp(`^one-DOF sheet · ${Math.round(row.finite_covered * 100)} % kept`));
    }
    // The explanation is read out with the badge.
    assert.match(await badge.textContent(), /6×6-cell patch/);
  }
  await page.goto(`${server.base}/index.html?view=table&limit=200&family=${noSheet.family}`);
  await catalogueTotal(page);
  const cell = badgeOf(page, 'design-row', noSheet.spec);
  assert.equal(await cell.innerText(), 'none');
  assert.equal(await cell.getAttribute('data-sheet'), 'none');

  await page.goto(`${server.base}/index.html?view=grid`);
  await catalogueTotal(page);
  await byTestId(page, 'buildable-only').check();
  const having = rows.filter((r) => r.finite_covered !== null).length;
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), having);
  assert.deepEqual(new URLSearchParams(new URL(page.url()).search).getAll('range'), ['finite_covered:0:']);
  const badges = await byTestId(page, 'sheet-badge').evaluateAll((bs) => bs.map((b) => b.dataset.sheet));
  assert.ok(badges.length > 0 && badges.every((k) => k === 'sheet'), badges.join());
  await byTestId(page, 'buildable-only').uncheck();
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), rows.length);
  assert.deepEqual(problems(page), []);
  await page.context().close();
});

async function openDesign(page, base, spec) {
  await page.goto(`${base}/design.html?spec=${encodeURIComponent(spec)}`);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  await page.waitForFunction(() => document.querySelectorAll('[data-testid="export-format"] option').length > 0);
}

test('a design without a one-DOF sheet: the badge says so and the export panel chooses the raw rectangle before Download', async () => {
  const page = await newPage(browser);
  await openDesign(page, server.base, noSheet.spec);
  const badge = byTestId(page, 'sheet-badge');
  assert.equal(await badge.getAttribute('data-sheet'), 'none');
  assert.match(await badge.innerText(), /^no one-DOF sheet/);
  // Before any click: the raw rectangle chosen, the reason and what to do beside the choice.
  assert.ok(await byTestId(page, 'export-sheet-raw').isChecked(), 'the raw rectangle is chosen');
  const note = byTestId(page, 'export-sheet-note');
  assert.ok(await note.isVisible());
  assert.match(await note.innerText(), new RegExp(`no one-DOF sheet: its 6×6-cell patch as cut has ${noSheet.finite_raw_dof} DOF`));
  assert.match(await note.innerText(), /The raw rectangle is chosen/);
  assert.match(await note.innerText(), /another region/);
  assert.ok(await byTestId(page, 'export-sheet-completed-none').isVisible());
  // What to do: a design of the same family with a sheet (named when the catalogue has one).
  await pollUntil(() => note.innerText(), (t) => /the designs that have one/.test(t));
  const family = rows.filter((r) => r.family === noSheet.family && r.finite_covered !== null);
  const neighbour = byTestId(page, 'export-sheet-neighbour');
  if (family.length) {
    const spec = await neighbour.getAttribute('data-spec');
    const shown = rows.find((r) => r.spec === spec);
    assert.equal(shown.family, noSheet.family);
    assert.equal(shown.finite_covered, Math.max(...family.map((r) => r.finite_covered)), `${spec}: the largest sheet of the family`);
  } else assert.equal(await neighbour.count(), 0);
  assert.match(await byTestId(page, 'export-command').textContent(), / --raw( |$)/);
  // Download saves the raw rectangle: no 422.
  const [dl] = await Promise.all([page.waitForEvent('download'), byTestId(page, 'export-download').click()]);
  assert.ok(dl.suggestedFilename().endsWith('-4x4.svg'), dl.suggestedFilename());
  assert.ok(await byTestId(page, 'export-error').isHidden());
  await pollUntil(() => byTestId(page, 'export-status').textContent(), (t) => /^saved /.test(t));
  assert.match(await byTestId(page, 'export-status').textContent(), /warning: .*degrees of freedom/);
  assert.ok((await screenshot(browser, page, 'buildable-export-no-sheet')) > 50);
  assert.deepEqual(problems(page), []);
  await page.context().close();
});

test('a design with a one-DOF sheet: the badge gives the kept fraction and the completed sheet stays the default', async () => {
  const page = await newPage(browser);
  await openDesign(page, server.base, withSheet.spec);
  const badge = byTestId(page, 'sheet-badge');
  assert.equal(await badge.getAttribute('data-sheet'), 'sheet');
  assert.match(await badge.innerText(), new RegExp(`^one-DOF sheet · ${Math.round(withSheet.finite_covered * 100)} % kept`));
  assert.ok(await byTestId(page, 'export-sheet-completed').isChecked());
  assert.ok(await byTestId(page, 'export-sheet-note').isHidden());
  assert.doesNotMatch(await byTestId(page, 'export-command').textContent(), /--raw/);
  assert.deepEqual(problems(page), []);
  await page.context().close();
});

test('the graded page says before Grade that the design’s region has no one-DOF sheet, and what to do', async () => {
  const page = await newPage(browser);
  let posted = 0;
  page.on('request', (r) => {
    if (r.method() === 'POST' && r.url().endsWith('/api/graded')) posted += 1;
  });
  await page.goto(`${server.base}/graded.html?design=${encodeURIComponent(noSheet.spec)}`);
  await page.waitForFunction(() => document.body.dataset.ready === 'true');
  assert.equal(await byTestId(page, 'rows').inputValue(), '3');
  const line = byTestId(page, 'design-sheet');
  await page.waitForFunction(() => document.querySelector('[data-testid="design-sheet"]').dataset.sheet === 'none');
  assert.ok(await line.isVisible());
  const refused = (await sheetAt(noSheet.spec, '3x3')).refused;
  const text = await line.innerText();
  assert.match(text, /^No one-DOF sheet in this 3×3 region, so Grade would fail/);
  assert.ok(text.includes(refused.replace(/^no one-DOF sheet in this region:\s*/, '')), text);
  assert.match(text, /every finite sheet flops/.test(refused) ? /No region of this design has one/ : /larger region/);
  assert.equal(posted, 0, 'nothing was graded');
  // A design of the same family with a sheet, one click away (when the catalogue has one).
  await pollUntil(() => line.innerText(), (t) => /one-DOF sheet\.$|instead/.test(t));
  const use = byTestId(page, 'design-sheet-neighbour');
  if (await use.count()) {
    const spec = await use.getAttribute('data-spec');
    assert.notEqual(rows.find((r) => r.spec === spec).finite_covered, null);
    await use.click();
    assert.equal(await byTestId(page, 'design').inputValue(), spec);
    await page.waitForFunction(() => document.querySelector('[data-testid="design-sheet"]').dataset.sheet !== 'checking');
  }
  // A design whose region has a sheet: no line.
  await byTestId(page, 'design').fill(withSheet.spec);
  await page.waitForFunction(() => document.querySelector('[data-testid="design-sheet"]').dataset.sheet === 'ok');
  assert.ok(await line.isHidden());
  // Back to the design without one, by typing: the line comes back.
  await byTestId(page, 'design').fill(noSheet.spec);
  await page.waitForFunction(() => document.querySelector('[data-testid="design-sheet"]').dataset.sheet === 'none');
  assert.ok((await screenshot(browser, page, 'buildable-graded-no-sheet')) > 50);
  assert.equal(posted, 0);
  assert.deepEqual(problems(page), []);
  await page.context().close();
});

test('the static site: the range, the column, the badges and the export panel’s advice from its files', async () => {
  await catalogueKeepsTheRange(files.base, 'static site');
  const page = await newPage(browser);
  await openDesign(page, files.base, noSheet.spec);
  assert.equal(await page.evaluate(() => document.body.dataset.mode), 'static');
  assert.equal(await byTestId(page, 'sheet-badge').getAttribute('data-sheet'), 'none');
  assert.ok(await byTestId(page, 'export-sheet-raw').isChecked());
  assert.ok(await byTestId(page, 'export-sheet-note').isVisible());
  assert.match(await byTestId(page, 'export-command').textContent(), / --raw( |$)/);
  await openDesign(page, files.base, withSheet.spec);
  assert.equal(await byTestId(page, 'sheet-badge').getAttribute('data-sheet'), 'sheet');
  assert.ok(await byTestId(page, 'export-sheet-completed').isChecked());
  assert.deepEqual(problems(page), []);
  await page.context().close();
});
