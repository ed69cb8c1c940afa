// Catalogue page over `isogami serve` in real headless Chromium: it opens and is not blank;
// filtering by family and by a range changes the count to the API's total; the view state
// survives a reload; a scatter point opens its design page; sorting by a column either way
// agrees with the API; the CSV and JSON downloads hold every filtered row.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  allApiRows, byTestId, canvasColours, canvasPixels, catalogueTotal, downloadText, getJson,
  launchBrowser, newPage, parseCsv, problems, screenshot, startServer,
} from './harness.mjs';

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

test('the catalogue opens with every design, thumbnails and a scatter', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/?view=grid`);
  const total = await catalogueTotal(page);
  const api = await getJson(`${server.base}/api/designs?limit=1`);
  assert.ok(api.total > 0, 'the test database has designs');
  assert.equal(total, api.total);
  const stats = await getJson(`${server.base}/api/stats`);
  assert.match(await byTestId(page, 'stats').textContent(), new RegExp(`^${stats.designs} designs`));
  assert.equal(await byTestId(page, 'design-card').count(), Math.min(50, total));
  await page.waitForFunction(() => {
    const img = document.querySelector('[data-testid="design-card"] img');
    return img && img.complete && img.naturalWidth > 0;
  });
  // Thumbnails load lazily: scroll through the grid, then every one must have loaded.
  await page.evaluate(() => window.scrollTo(0, document.body.scrollHeight));
  await page.waitForFunction(() =>
    [...document.querySelectorAll('[data-testid="design-card"] img')].every((img) => img.complete && img.naturalWidth > 0),
  );
  await page.evaluate(() => window.scrollTo(0, 0));
  const pixels = await canvasPixels(page, '[data-testid="scatter-canvas"]');
  assert.ok(canvasColours(pixels) > 2, 'the scatter shows points');
  assert.ok((await screenshot(browser, page, 'catalogue')) > 50, 'the catalogue screenshot is not blank');
  await byTestId(page, 'view-table').click();
  await page.waitForSelector('[data-testid="design-row"]');
  assert.ok((await screenshot(browser, page, 'catalogue-table')) > 30);
  assert.deepEqual(problems(page), []);
});

test('filtering by a range and by a family changes the count to the API total, and survives a reload', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/`);
  const total = await catalogueTotal(page);

  // A range: max expansion at least the median of every design's.
  const values = (await getJson(`${server.base}/api/scatter?x=max_expansion&y=max_area_ratio`)).map((p) => p.x).sort((a, b) => a - b);
  const median = values[Math.floor(values.length / 2)];
  await byTestId(page, 'range-min-max_expansion').fill(String(median));
  await byTestId(page, 'range-min-max_expansion').press('Enter');
  const ranged = (await getJson(`${server.base}/api/designs?range=max_expansion:${median}:&limit=1`)).total;
  assert.ok(ranged > 0 && ranged < total, `the range keeps some designs (${ranged} of ${total})`);
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), ranged);

  // A family: the most frequent one under the range, ticked in the facet list.
  const facets = await getJson(`${server.base}/api/facets?range=max_expansion:${median}:`);
  const family = facets.family[0];
  await byTestId(page, `facet-family-${family.value}`).check();
  const both = (await getJson(`${server.base}/api/designs?family=${family.value}&range=max_expansion:${median}:&limit=1`)).total;
  assert.equal(both, family.count, 'the facet count is what ticking it gives');
  await page.waitForFunction((n) => document.querySelector('[data-testid="total"]').textContent === String(n), both);

  const url = new URL(page.url());
  assert.deepEqual(url.searchParams.getAll('family'), [family.value]);
  assert.deepEqual(url.searchParams.getAll('range'), [`max_expansion:${median}:`]);
  await page.reload();
  assert.equal(await catalogueTotal(page), both);
  assert.ok(await byTestId(page, `facet-family-${family.value}`).isChecked());
  assert.equal(await byTestId(page, 'range-min-max_expansion').inputValue(), String(median));
  assert.deepEqual(problems(page), []);
});

test('hovering a scatter point shows the design; clicking opens its design page', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/`);
  await catalogueTotal(page);
  const canvas = byTestId(page, 'scatter-canvas');
  await canvas.waitFor();
  // A drawn stack of one design (stacks of several list theirs: scatter.test.mjs).
  await page.waitForFunction(() => document.getElementById('scatter').scatterDrawn?.designs > 0);
  const spot = await page.evaluate(() => document.getElementById('scatter').scatterDrawn.stacks.find((s) => s.count === 1));
  assert.ok(spot, 'the scatter has a single design');
  const box = await canvas.boundingBox();
  await page.mouse.move(box.x + spot.px, box.y + spot.py);
  const tip = byTestId(page, 'scatter-tooltip');
  await tip.waitFor({ state: 'visible' });
  const spec = (await tip.locator('code').textContent()).trim();
  assert.match(spec, /^IH\d+:/);
  await page.mouse.click(box.x + spot.px, box.y + spot.py);
  await page.waitForURL(/design\.html\?spec=/);
  await page.waitForFunction((s) => document.querySelector('[data-testid="spec"]').textContent === s, spec);
  assert.equal(new URL(page.url()).searchParams.get('spec'), spec);
  assert.deepEqual(problems(page), []);
});

test('sorting by a column either way agrees with the API', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/?view=table&limit=10&sort=steps`);
  await catalogueTotal(page);
  const firstSpecs = () => page.$$eval('[data-testid="design-row"]', (rows) => rows.map((r) => r.dataset.spec));
  // The first click sorts ascending, the second flips to descending.
  for (const sort of ['max_area_ratio', '-max_area_ratio']) {
    const before = page.url();
    await byTestId(page, 'sort-max_area_ratio').click();
    await page.waitForFunction((u) => location.href !== u, before);
    const api = await getJson(`${server.base}/api/designs?sort=${sort}&lead=buildable&limit=10`);
    const want = api.rows.map((r) => r.spec);
    await page.waitForFunction((w) => {
      const got = [...document.querySelectorAll('[data-testid="design-row"]')].map((r) => r.dataset.spec);
      return JSON.stringify(got) === JSON.stringify(w);
    }, want);
    assert.deepEqual(await firstSpecs(), want);
    // Largest area ratio first is the catalogue's default order: left out of the URL.
    assert.equal(new URL(page.url()).searchParams.get('sort'), sort === '-max_area_ratio' ? null : sort);
  }
  assert.deepEqual(problems(page), []);
});

test('CSV and JSON downloads hold every filtered row with the dictionary and provenance', async () => {
  const facets = await getJson(`${server.base}/api/facets`);
  const family = facets.family[0].value;
  const page = await newPage(browser);
  await page.goto(`${server.base}/?family=${family}&limit=10`);
  const total = await catalogueTotal(page);
  const want = await allApiRows(server.base, `family=${family}`);
  assert.equal(want.length, total);

  const csv = await downloadText(page, () => byTestId(page, 'download-csv').click());
  const table = parseCsv(csv.text);
  const [header, ...rows] = table;
  assert.equal(rows.length, total, 'one CSV row per filtered design, not one page');
  for (const col of ['spec', 'family', 'cell', 'tile_count', 'behaviour', 'max_expansion', 'max_area_ratio', 'v0']) {
    assert.ok(header.includes(col), `CSV column ${col}`);
  }
  assert.ok(rows.every((r) => r.length === header.length), 'every row has every column');
  const specCol = header.indexOf('spec');
  assert.deepEqual(new Set(rows.map((r) => r[specCol])), new Set(want.map((r) => r.spec)));
  const famCol = header.indexOf('family');
  assert.ok(rows.every((r) => r[famCol] === family));
  const maxCol = header.indexOf('max_expansion');
  const bySpec = new Map(want.map((r) => [r.spec, r]));
  assert.ok(rows.every((r) => Number(r[maxCol]) === bySpec.get(r[specCol]).max_expansion), 'numbers round-trip');

  const json = JSON.parse((await downloadText(page, () => byTestId(page, 'download-json').click())).text);
  const stats = await getJson(`${server.base}/api/stats`);
  const dictionary = await getJson(`${server.base}/api/dictionary`);
  assert.equal(json.designs.length, total);
  assert.equal(json.total, total);
  assert.equal(json.tool_version, stats.tool_version);
  assert.deepEqual(json.settings, stats.settings);
  assert.deepEqual(json.dictionary, dictionary);
  assert.deepEqual(json.query.family, [family]);

  const dict = parseCsv((await downloadText(page, () => byTestId(page, 'download-dictionary').click())).text);
  assert.deepEqual(dict[0], ['field', 'type', 'unit', 'meaning']);
  assert.deepEqual(dict.slice(1).map((r) => r[0]), header, 'the dictionary lists every CSV column in order');
  assert.deepEqual(problems(page), []);
});

test('the table keeps the sorted column in view and the spec column beside it (issue 24 item 8)', async () => {
  const page = await newPage(browser);
  await page.setViewportSize({ width: 700, height: 900 });
  await page.goto(`${server.base}/?view=table`);
  await page.waitForSelector('[data-testid="design-row"]');
  const wrap = page.locator('.table-wrap');
  assert.ok(
    await wrap.evaluate((w) => w.scrollWidth > w.clientWidth + 200),
    'at 700 px the table is wider than its box (the test needs a sideways scroll)',
  );
  // Scroll to the far right and sort by the last numeric column there.
  await wrap.evaluate((w) => {
    w.scrollLeft = w.scrollWidth;
  });
  const before = await page.$$eval('[data-testid="design-row"]', (rows) => rows.map((r) => r.dataset.spec).join());
  await byTestId(page, 'sort-poisson_max').click();
  await page.waitForFunction(
    (old) => [...document.querySelectorAll('[data-testid="design-row"]')].map((r) => r.dataset.spec).join() !== old,
    before,
  );
  const seen = await page.evaluate(() => {
    const w = document.querySelector('.table-wrap');
    const box = w.getBoundingClientRect();
    const th = document.querySelector('th[aria-sort]:not([aria-sort="none"])');
    const spec = document.querySelector('[data-testid="design-row"] td:first-child');
    const r = th.getBoundingClientRect();
    const s = spec.getBoundingClientRect();
    return {
      label: th.textContent,
      inside: r.left >= box.left - 0.5 && r.right <= box.right + 0.5,
      specInside: s.left >= box.left - 0.5 && s.right <= box.right + 0.5,
      clear: s.right <= r.left + 0.5,
      tinted: document.querySelectorAll('td.sorted').length,
    };
  });
  assert.match(seen.label, /ν max/);
  assert.ok(seen.inside, 'the sorted column is inside the table box');
  assert.ok(seen.specInside && seen.clear, 'the spec column stays visible and does not cover it');
  assert.ok(seen.tinted > 0, 'the sorted column is marked');
  assert.deepEqual(problems(page), []);
});

/** The table's layout as the page leaves it: the spec column's box, every column's header
 * box, the sorted column's index and the box of the table's scrolling frame. */
async function tableLayout(page) {
  return page.evaluate(() => {
    const wrap = document.querySelector('.table-wrap');
    const box = (el) => {
      const r = el.getBoundingClientRect();
      return { left: r.left, right: r.right };
    };
    const heads = [...wrap.querySelectorAll('thead th')];
    const rows = [...wrap.querySelectorAll('[data-testid="design-row"]')];
    return {
      wrap: { ...box(wrap), width: wrap.clientWidth },
      spec: box(heads[0]),
      columns: heads.map((th) => ({ label: th.textContent, ...box(th) })),
      sorted: heads.findIndex((th) => th.classList.contains('sorted')),
      specsWhole: rows.every((r) => r.querySelector('td').textContent === r.dataset.spec),
    };
  });
}

test('the sticky spec column cuts no column and leaves room for the others (issue 42 item 13)', async () => {
  // At every common laptop width, the table as the page leaves it (default sort, scrolled to
  // show the sorted column): no column is partly hidden under the spec column, the spec
  // column takes at most a third of the table's width and holds every spec whole, and the
  // sorted column is in view. At 1440 px every column up to the sorted one is in view.
  for (const width of [1440, 1280, 1024]) {
    const page = await newPage(browser);
    await page.setViewportSize({ width, height: 900 });
    await page.goto(`${server.base}/?view=table`);
    await page.waitForSelector('[data-testid="design-row"]');
    await page.waitForLoadState('networkidle');
    const t = await tableLayout(page);
    const edge = t.spec.right;
    const cut = t.columns.slice(1).filter((c) => c.left < edge - 0.5 && c.right > edge + 0.5 && c.left < t.wrap.right);
    assert.deepEqual(cut.map((c) => c.label), [], `${width} px: columns partly under the spec column (its right edge at ${edge})`);
    assert.ok(t.spec.right - t.spec.left <= t.wrap.width / 3 + 0.5, `${width} px: spec column ${t.spec.right - t.spec.left} px of ${t.wrap.width}`);
    assert.ok(t.specsWhole, `${width} px: every spec is shown whole`);
    assert.ok(t.sorted > 0, 'the default view is sorted by a column other than spec');
    const sorted = t.columns[t.sorted];
    assert.ok(sorted.left >= edge - 0.5 && sorted.right <= t.wrap.right + 0.5, `${width} px: the sorted column ${sorted.label} is in view`);
    if (width === 1440) {
      const hidden = t.columns.slice(1, t.sorted).filter((c) => c.left < edge - 0.5);
      assert.deepEqual(hidden.map((c) => c.label), [], '1440 px: every column up to the sorted one is in view');
    }
    assert.deepEqual(problems(page), []);
    await page.close();
  }
});

test('a newcomer finds an introduction and a glossary; on a phone the scatter comes before the filters (issue 42 item 18)', async () => {
  const page = await newPage(browser);
  await page.goto(`${server.base}/`);
  await catalogueTotal(page);
  // Every word the catalogue's columns, facets and axes use without explaining it.
  const intro = byTestId(page, 'intro');
  await intro.locator('summary').click();
  const terms = await byTestId(page, 'glossary').locator('dt').allTextContents();
  for (const word of [/IH famil/, /area ratio/, /ε/, /Poisson-like ratio ν/, /behaviour/, /linkages/, /joints/]) {
    assert.ok(terms.some((t) => word.test(t)), `the glossary explains ${word}: ${terms.join(' | ')}`);
  }
  const text = await byTestId(page, 'glossary').textContent();
  for (const b of ['isotropic auxetic', 'anisotropic auxetic', 'orthotropic positive Poisson']) assert.ok(text.includes(b), b);
  // A phone (390 × 844): the scatter starts within the first screen, before the filters.
  await page.setViewportSize({ width: 390, height: 844 });
  await page.reload();
  await catalogueTotal(page);
  const tops = await page.evaluate(() => ({
    scatter: document.querySelector('[data-testid="scatter"]').getBoundingClientRect().top + scrollY,
    filters: document.querySelector('.filters').getBoundingClientRect().top + scrollY,
  }));
  assert.ok(tops.scatter < 844, `the scatter starts ${tops.scatter} px down`);
  assert.ok(tops.scatter < tops.filters, 'the scatter comes before the filters');
  assert.deepEqual(problems(page), []);
});

test('long facet lists show their first values until opened; the keyboard reaches a design in few Tabs (issue 42 item 18)', async () => {
  const page = await newPage(browser);
  await page.setViewportSize({ width: 1440, height: 900 });
  await page.goto(`${server.base}/?view=grid`);
  await catalogueTotal(page);
  await page.waitForSelector('[data-testid="design-card"]');
  const facets = await getJson(`${server.base}/api/facets`);
  const long = Object.entries(facets).filter(([, values]) => Array.isArray(values) && values.length > 9);
  assert.ok(long.length >= 1, 'the quick database has a facet with more than 9 values');
  for (const [name, values] of long) {
    const boxes = byTestId(page, `facet-${name}`).locator('input[type="checkbox"]');
    assert.ok((await boxes.count()) <= 8, `${name}: at most 8 values shown of ${values.length}`);
    await byTestId(page, `facet-more-${name}`).click();
    assert.equal(await boxes.count(), values.length, `${name}: every value once opened`);
    await byTestId(page, `facet-more-${name}`).click();
  }
  // Without the skip link: Tab from the top of the page to the first design card. Every stop
  // before it is counted; a facet list adds at most 9 (8 values and its button).
  await page.goto(`${server.base}/?view=grid`);
  await page.waitForSelector('[data-testid="design-card"]');
  let tabs = 0;
  for (; tabs < 200; ) {
    await page.keyboard.press('Tab');
    tabs += 1;
    if (await page.evaluate(() => Boolean(document.activeElement?.closest('[data-testid="design-card"]')))) break;
  }
  const facetStops = await page.$$eval('#facets fieldset', (sets) => sets.map((f) => f.querySelectorAll('input, button').length));
  assert.ok(facetStops.every((n) => n <= 9), `stops per facet: ${facetStops}`);
  // The header, the introduction, the scatter's controls and the toolbar take about 35 stops;
  // the filters, their lists shortened, the rest (two checkboxes of buildability among them).
  assert.ok(tabs <= 65, `${tabs} Tabs to the first design`);
  assert.deepEqual(problems(page), []);
});
