// The static site written by `isogami site`, served by a plain file server under a sub-path:
// it shows the same catalogue as the server (count, filtered count), opens a design from a
// card with live design shown as unavailable, the export panel's command line instead of
// downloads and the finite-sheet panel saying it needs the server; and the JS query engine of the static site
// answers like the server's API on the same database (totals, page order, facet counts).

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import {
  buildSite, byTestId, canvasColours, canvasPixels, catalogueTotal, getJson, launchBrowser, newPage,
  problems, screenshot, serveFolder, startServer,
} from './harness.mjs';
import { facetCounts, page as queryPage, scatter } from '../src/query.js';
import { pageParams, parseCatalogueState, filterParams } from '../src/url.js';
import { slug } from '../src/schema.js';

let site;
let files;
let server;
let browser;
let rows;

before(async () => {
  site = await buildSite();
  files = await serveFolder(site.dir, '/some/sub/path');
  server = await startServer();
  browser = await launchBrowser();
  rows = JSON.parse(await readFile(join(site.dir, 'data', 'designs.json'), 'utf8'));
});

after(async () => {
  await browser?.close();
  await files?.stop();
  await server?.stop();
  await site?.remove();
});

test('the static site shows the same catalogue and opens a design', async () => {
  const page = await newPage(browser);
  await page.goto(`${files.base}/`);
  const total = await catalogueTotal(page);
  assert.equal(total, (await getJson(`${server.base}/api/designs?limit=1`)).total);
  assert.match(await byTestId(page, 'mode').textContent(), /static/);
  await page.waitForFunction(() => {
    const img = document.querySelector('[data-testid="design-card"] img');
    return img && img.complete && img.naturalWidth > 0;
  });
  assert.ok((await screenshot(browser, page, 'static-catalogue')) > 50);

  const facets = await getJson(`${server.base}/api/facets`);
  const family = facets.family[facets.family.length - 1];
  // The last family of a long list is shown once the list is opened.
  if (await byTestId(page, 'facet-more-family').count()) await byTestId(page, 'facet-more-family').click();
  await byTestId(page, `facet-family-${family.value}`).check();
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), family.count);

  const card = byTestId(page, 'design-card').first();
  const spec = await card.getAttribute('data-spec');
  await card.click();
  await page.waitForURL(/design\.html\?spec=/);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  assert.equal(await byTestId(page, 'spec').textContent(), spec);
  assert.ok(canvasColours(await canvasPixels(page, '[data-testid="sheet"]')) > 3, 'the patch is drawn');
  await byTestId(page, 'live-unavailable').waitFor({ state: 'visible' });
  assert.match(await byTestId(page, 'live-unavailable').textContent(), /isogami serve/);
  assert.ok(await byTestId(page, 'param-v0').count() === 0 || (await byTestId(page, 'param-v0').isDisabled()));
  assert.ok(await byTestId(page, 'kerf').isDisabled());
  assert.ok(await byTestId(page, 'download-gif').isHidden());
  // The export panel offers the command line instead of downloads.
  const command = byTestId(page, 'export-command');
  await page.waitForFunction(() => /isogami export/.test(document.querySelector('[data-testid="export-command"]')?.textContent ?? ''));
  assert.ok((await command.textContent()).startsWith(`isogami export --design '${spec}' --format svg --patch 4x4 `));
  await byTestId(page, 'export-format').selectOption('kirigami-sim');
  assert.match(await command.textContent(), / --format kirigami-sim .* --out \S+-4x4\.kirigami-sim$/);
  assert.match(await byTestId(page, 'export-panel').textContent(), /Downloads need `isogami serve`/);
  assert.ok(await byTestId(page, 'export-download').isDisabled());
  // The finite-sheet panel says it needs the server and asks nothing.
  await byTestId(page, 'finite-unavailable').waitFor({ state: 'visible' });
  assert.match(await byTestId(page, 'finite-unavailable').textContent(), /needs `isogami serve`/);
  assert.equal(await byTestId(page, 'finite-canvas').count(), 0);
  assert.ok((await screenshot(browser, page, 'static-design')) > 50);
  assert.deepEqual(problems(page), []);
});

test('a design not in the static site is explained, not blank', async () => {
  const page = await newPage(browser);
  await page.goto(`${files.base}/design.html?spec=${encodeURIComponent('rotating-squares')}`);
  const notice = page.locator('.notice[data-kind="not_found"]');
  await notice.waitFor({ state: 'visible' });
  assert.match(await notice.textContent(), /isogami serve/);
});

test('every design of the catalogue has its static page and thumbnail', async () => {
  const total = (await getJson(`${server.base}/api/designs?limit=1`)).total;
  assert.equal(rows.length, total);
  for (const r of rows.slice(0, 20)) {
    const view = await getJson(`${files.base}/data/design/${slug(r.spec)}.json`);
    assert.equal(view.spec, r.spec);
    const thumb = await fetch(`${files.base}/thumbs/${slug(r.spec)}.svg`);
    assert.equal(thumb.status, 200);
  }
});

test('the static query engine answers like the server on the same database', async () => {
  const facets = await getJson(`${server.base}/api/facets`);
  const fam = facets.family.map((f) => f.value);
  const cells = facets.cell.map((c) => `${c.value[0]}x${c.value[1]}`);
  const values = rows.map((r) => r.max_expansion).sort((a, b) => a - b);
  const mid = values[Math.floor(values.length / 2)];
  const queries = [
    '',
    `family=${fam[0]}`,
    `family=${fam[0]}&family=${fam[fam.length - 1]}&cell=${cells[0]}`,
    `range=max_expansion:${mid}:`,
    `range=poisson_min::0&sort=-poisson_min`,
    `behaviour=none&behaviour=isotropic_auxetic`,
    `sort=-family&limit=7&offset=3`,
    `sort=cell`,
    `sort=behaviour`,
    `sort=-linkage_signature&range=v0:0:`,
    `sort=max_tile_rotation&tiles=${facets.tile_count[0].value}`,
    `sort=-steps&origin=explored`,
  ];
  for (const query of queries) {
    const state = parseCatalogueState(`?${query}`);
    const api = await getJson(`${server.base}/api/designs?${pageParams(state)}`);
    const js = queryPage(rows, state);
    assert.equal(js.total, api.total, `total of ${query}`);
    assert.deepEqual(js.rows.map((r) => r.spec), api.rows.map((r) => r.spec), `order of ${query}`);
    const apiFacets = await getJson(`${server.base}/api/facets?${filterParams(state)}`);
    const jsFacets = facetCounts(rows, state);
    for (const name of Object.keys(jsFacets)) {
      assert.deepEqual(jsFacets[name], apiFacets[name], `facet ${name} of ${query}`);
    }
    const apiPoints = await getJson(`${server.base}/api/scatter?x=steps&y=poisson_max&${filterParams(state)}`);
    assert.deepEqual(scatter(rows, state, 'steps', 'poisson_max'), apiPoints, `scatter of ${query}`);
  }
});
