// The catalogue's mechanisms view and navigation (issue 24 items 2, 6 and three of item 8), in
// real headless Chromium over `isogami serve` and over a static site written by `isogami site`:
// one card per distinct motion in the API's order (largest area ratio first by default) with
// counts and ranges over the matching designs, variants expanding in place (aria-expanded,
// keyboard); the static site's query.js gives the same groups as GET /api/motions; a facet
// with one value is a one-line fact; the first card is reached in at most 10 Tab presses;
// "back to the catalogue" restores the filters, sort and view; "same motion elsewhere" shows
// each linked design's own area ratio and thumbnail, sorted by family number. Expected values
// come from the API, never from constants.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { join } from 'node:path';
import {
  allApiRows, buildSite, byTestId, catalogueTotal, getJson, launchBrowser, newPage, problems, screenshot,
  serveFolder, startServer,
} from './harness.mjs';
import { isBuildable } from '../src/buildable.js';
import { motionGroups } from '../src/query.js';
import { parseCatalogueState } from '../src/url.js';

let server;
let browser;
let site;
let files;

before(async () => {
  site = await buildSite();
  files = await serveFolder(site.dir, '/sub');
  server = await startServer();
  browser = await launchBrowser();
});

after(async () => {
  await browser?.close();
  await server?.stop();
  await files?.stop();
  await site?.remove();
});

const cards = (page) =>
  page.$$eval('[data-testid="motion-card"]', (els) =>
    els.map((e) => ({ representative: e.dataset.representative, designs: Number(e.dataset.designs), best: e.dataset.best })),
  );

const expectedCards = (answer) =>
  [...answer.groups, ...(answer.unclassified ? [answer.unclassified] : [])].map((g) => ({
    representative: g.representative ?? '',
    designs: g.designs,
    best: g.members[0].spec,
  }));

async function waitCards(page, want) {
  await page.waitForFunction(
    (w) => JSON.stringify([...document.querySelectorAll('[data-testid="motion-card"]')].map((e) => e.dataset.best)) === JSON.stringify(w),
    want.map((c) => c.best),
  );
}

test('the default view: one card per distinct motion, largest area ratio first, variants expand in place', async () => {
  const answer = await getJson(`${server.base}/api/motions?sort=-max_area_ratio&lead=buildable`);
  const all = await getJson(`${server.base}/api/designs?limit=1`);
  assert.equal(answer.total, all.total, 'every design is in a card');
  assert.ok(answer.groups.length > 1 && answer.groups.length < answer.total, 'grouping merges designs');
  // The first card's example is the buildable design of largest area ratio (buildable designs
  // lead the default order), and every card's example is buildable when one of its designs is.
  const best = (await getJson(`${server.base}/api/designs?sort=-max_area_ratio&lead=buildable&limit=1`)).rows[0];
  assert.equal(answer.groups[0].members[0].spec, best.spec);
  const rows = new Map((await allApiRows(server.base)).map((r) => [r.spec, r]));
  assert.ok(isBuildable(best), 'the quick database has buildable designs');
  for (const g of answer.groups) {
    const any = g.members.some((m) => isBuildable(rows.get(m.spec)));
    assert.equal(isBuildable(rows.get(g.members[0].spec)), any, `the example of ${g.representative}`);
  }
  const page = await newPage(browser);
  await page.goto(`${server.base}/`);
  assert.equal(await catalogueTotal(page), all.total);
  await waitCards(page, expectedCards(answer));
  assert.deepEqual(await cards(page), expectedCards(answer));
  assert.match(await byTestId(page, 'mechanism-count').textContent(), new RegExp(`${answer.groups.length} distinct motion`));
  const first = page.locator('[data-testid="motion-card"]').first();
  const g = answer.groups[0];
  const area = (await first.locator('[data-testid="motion-area"]').textContent()).trim();
  assert.ok(area.length > 0 && !/e-|0000/.test(area), `a readable range: ${area}`);
  const listText = await byTestId(page, 'list').textContent();
  assert.doesNotMatch(listText, /\bnull\b|undefined|NaN/, 'no placeholder text in the cards');
  assert.doesNotMatch(listText, /\d–-/, 'negative ranges are not written with a dash before a minus');
  // A card with several designs expands with the keyboard, and collapses again.
  const k = answer.groups.findIndex((x) => x.designs > 1);
  assert.ok(k >= 0, 'a class with several designs');
  const card = page.locator('[data-testid="motion-card"]').nth(k);
  const toggle = card.locator('[data-testid="motion-expand"]');
  assert.equal(await toggle.getAttribute('aria-expanded'), 'false');
  assert.ok(await card.locator('[data-testid="card-variants"]').isHidden());
  await toggle.focus();
  await page.keyboard.press('Enter');
  assert.equal(await toggle.getAttribute('aria-expanded'), 'true');
  const variants = card.locator('[data-testid="card-variant"]');
  await variants.first().waitFor();
  const specs = await variants.evaluateAll((els) => els.map((e) => [e.dataset.spec, Number(e.dataset.area)]));
  assert.deepEqual(specs, answer.groups[k].members.map((m) => [m.spec, m.max_area_ratio]));
  await card.locator('[data-testid="card-variant"] img').first().evaluate((img) => img.decode());
  assert.ok((await screenshot(browser, page, 'catalogue-mechanisms')) > 50);
  await page.keyboard.press('Space');
  assert.equal(await toggle.getAttribute('aria-expanded'), 'false');
  assert.ok(g.members.length === g.designs);
  assert.deepEqual(problems(page), []);
});

test('filters apply to the cards: a class is listed when one of its designs matches, ranges over those', async () => {
  const facets = await getJson(`${server.base}/api/facets`);
  const family = facets.family.find((f) => f.count > 1) ?? facets.family[0];
  const q = `family=${family.value}&sort=spec`;
  const answer = await getJson(`${server.base}/api/motions?${q}`);
  assert.equal(answer.total, family.count);
  for (const g of answer.groups) assert.ok(g.members.every((m) => m.family === family.value));
  const page = await newPage(browser);
  await page.goto(`${server.base}/?${q}`);
  await waitCards(page, expectedCards(answer));
  assert.deepEqual(await cards(page), expectedCards(answer));
  // Switching to the grid lists designs, and back.
  await byTestId(page, 'view-grid').click();
  await page.waitForSelector('[data-testid="design-card"]:not([data-testid="motion-card"] *)');
  assert.equal(new URL(page.url()).searchParams.get('view'), 'grid');
  await byTestId(page, 'view-mechanisms').click();
  await waitCards(page, expectedCards(answer));
  assert.equal(new URL(page.url()).searchParams.get('view'), null);
  assert.deepEqual(problems(page), []);
});

test('the static site groups exactly as the server does, and shows the same cards', async () => {
  const rows = JSON.parse(await readFile(join(site.dir, 'data', 'designs.json'), 'utf8'));
  const motions = JSON.parse(await readFile(join(site.dir, 'data', 'motions.json'), 'utf8'));
  const facets = await getJson(`${server.base}/api/facets`);
  const searches = [
    '',
    `?family=${facets.family[0].value}`,
    '?sort=spec',
    '?range=max_area_ratio:1.05:&sort=-max_expansion',
    `?behaviour=${facets.behaviour[0].value ?? 'none'}&sort=family`,
  ];
  for (const search of searches) {
    const state = parseCatalogueState(search);
    const p = new URLSearchParams(search);
    p.set('sort', `${state.sort.desc ? '-' : ''}${state.sort.key}`);
    if (state.lead === 'buildable') p.set('lead', 'buildable');
    const server_ = await getJson(`${server.base}/api/motions?${p}`);
    assert.deepEqual(motionGroups(rows, motions, state), server_, search);
  }
  const page = await newPage(browser);
  await page.goto(`${files.base}/`);
  const answer = await getJson(`${server.base}/api/motions?sort=-max_area_ratio&lead=buildable`);
  await waitCards(page, expectedCards(answer));
  assert.deepEqual(await cards(page), expectedCards(answer));
  assert.deepEqual(problems(page), []);
});

test('a facet with one value is a one-line fact, not a checkbox list', async () => {
  const facets = await getJson(`${server.base}/api/facets`);
  // The family with the fewest designs narrows at least one other facet to a single value.
  const family = [...facets.family].sort((a, b) => a.count - b.count)[0].value;
  const narrowed = await getJson(`${server.base}/api/facets?family=${family}`);
  const single = Object.entries(narrowed).filter(([name, values]) => name !== 'family' && values.length === 1);
  assert.ok(single.length > 0, 'some facet has one value');
  const several = Object.entries(narrowed).filter(([, values]) => values.length > 1);
  const page = await newPage(browser);
  await page.goto(`${server.base}/?family=${family}`);
  await catalogueTotal(page);
  for (const [name] of single) {
    const fact = byTestId(page, `facet-fact-${name}`);
    await fact.waitFor();
    assert.match(await fact.textContent(), /all \d+ shown/);
    assert.equal(await byTestId(page, `facet-${name}`).count(), 0, `${name} has no checkbox list`);
  }
  for (const [name] of several) assert.equal(await byTestId(page, `facet-${name}`).count(), 1, `${name} stays a filter`);
  // The ticked family stays a checkbox (to untick it) even with one value left.
  assert.ok(await byTestId(page, `facet-family-${family}`).isChecked());
  assert.deepEqual(problems(page), []);
});

test('the keyboard reaches the first card in at most 10 Tab presses', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/`);
  await page.waitForSelector('[data-testid="motion-card"]');
  let tabs = 0;
  const where = () =>
    page.evaluate(() => {
      const a = document.activeElement;
      return { skip: a?.dataset?.testid === 'skip-to-results', card: Boolean(a?.closest('[data-testid="motion-card"]')) };
    });
  for (; tabs < 10; ) {
    await page.keyboard.press('Tab');
    tabs += 1;
    const at = await where();
    if (at.card) break;
    if (at.skip) await page.keyboard.press('Enter');
  }
  const at = await where();
  assert.ok(at.card, `a card has the focus after ${tabs} Tab presses`);
  assert.ok(tabs <= 10, `${tabs} Tab presses`);
  const focused = await page.evaluate(() => document.activeElement.closest('[data-testid="motion-card"]').dataset.best);
  const first = await page.$eval('[data-testid="motion-card"]', (e) => e.dataset.best);
  assert.equal(focused, first, 'the first card');
  assert.deepEqual(problems(page), []);
});

for (const mode of ['server', 'static']) {
  test(`"back to the catalogue" restores the filters, sort and view (${mode})`, async () => {
    const base = mode === 'server' ? server.base : files.base;
    const facets = await getJson(`${server.base}/api/facets`);
    const family = facets.family[0].value;
    const search = `?family=${family}&range=max_expansion:0.01:&sort=steps&view=table`;
    const page = await newPage(browser);
    await page.goto(`${base}/${search}`);
    await page.waitForSelector('[data-testid="design-row"] a');
    const url = new URL(page.url());
    await page.locator('[data-testid="design-row"] a').first().click();
    await page.waitForURL(/design\.html\?spec=/);
    const back = byTestId(page, 'back-link');
    await back.waitFor();
    await page.waitForFunction(() => document.querySelector('[data-testid="back-link"]').getAttribute('href') !== './index.html');
    await back.click();
    await page.waitForURL(/index\.html/);
    await page.waitForSelector('[data-testid="design-row"]');
    const now = new URL(page.url());
    assert.deepEqual([...now.searchParams.entries()], [...url.searchParams.entries()]);
    assert.ok(await byTestId(page, `facet-family-${family}`).isChecked());
    assert.deepEqual(problems(page, [/\/api\/(sheet|shape)/]), []);
  });
}

test('"same motion elsewhere": honest wording, each linked design\'s own area ratio and thumbnail, sorted by family number', async () => {
  const answer = await getJson(`${server.base}/api/motions?sort=-max_area_ratio&lead=buildable`);
  const group = answer.groups.find((g) => g.topologies > 1);
  assert.ok(group, 'a motion shared by several topologies');
  const spec = group.members[0].spec;
  const motion = await getJson(`${server.base}/api/motion?spec=${encodeURIComponent(spec)}`);
  const others = motion.class.variants.filter((v) => v.topology !== motion.topology);
  const num = (f) => Number(f.replace('IH', ''));
  const page = await newPage(browser);
  await page.goto(`${server.base}/design.html?spec=${encodeURIComponent(spec)}`);
  const section = byTestId(page, 'motion-section');
  await section.waitFor();
  await page.waitForSelector('[data-testid="motion-variant"], [data-testid="motion-show-all"]');
  const text = await section.textContent();
  assert.doesNotMatch(text, /exactly/);
  assert.match(text, /own area ratio/);
  assert.match(text, new RegExp(`this design opens to`));
  if (await byTestId(page, 'motion-show-all').count()) await byTestId(page, 'motion-show-all').click();
  const rows = await page.$$eval('[data-testid="motion-variant"]', (els) =>
    els.map((e) => ({ spec: e.dataset.spec, area: Number(e.dataset.area), img: Boolean(e.querySelector('img')), text: e.textContent })),
  );
  assert.equal(rows.length, others.length);
  const bySpec = new Map(others.map((v) => [v.example, v]));
  for (const r of rows) {
    const v = bySpec.get(r.spec);
    assert.ok(v, `${r.spec} is a variant's example`);
    assert.equal(r.area, v.example_area_ratio);
    assert.ok(r.img, 'a thumbnail');
    assert.match(r.text, /opens to \d/);
  }
  const fam = rows.map((r) => num(bySpec.get(r.spec).family));
  assert.deepEqual(fam, [...fam].sort((a, b) => a - b), 'by family number');
  assert.deepEqual(problems(page, [/\/api\/(sheet|shape)/]), []);
});
