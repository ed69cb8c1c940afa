// Linkages drawn as loops (issue 24, item 5) in real headless Chromium over `isogami serve`:
// the design page draws every linkage as a loop through its joints in its own colour by default
// (the paper's Fig. 6), the legend's entries carry those colours, tiles shared by several
// linkages are not coloured as one of them, and the frame SVG download draws the same loops.
// Reproducer: IH16:0.21650635094600001:1x1:-a-a-aaaa, three 4-bar linkages through every tile
// (before, the sheet showed one colour: every tile "linkage 0", loops only on demand).
// The same page's numbers (item 8): values that are zero up to rounding (IH16's closed state
// has ε = ±2.2e-16) print 0, and a sheet that ends smaller than it started (IH90::1x1:aaa opens
// to ε = 1, then closes past its start to ε = −0.004 at the contact limit) says so in words.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DOMParser } from '@xmldom/xmldom';
import {
  allApiRows, byTestId, downloadText, getJson, newPage, openDesign as openHarnessDesign, problems, readOnlySession, screenshot,
} from './harness.mjs';

const IH16 = 'IH16:0.21650635094600001:1x1:-a-a-aaaa';

let server;
let browser;
readOnlySession((s, b) => {
  server = s;
  browser = b;
});

const openDesign = (page, spec) => openHarnessDesign(page, server.base, spec);

const rgb = (hex) => [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
const near = (a, b, tol = 12) => a.every((v, i) => Math.abs(v - b[i]) <= tol);

/** The loops the canvas says it drew, and for each the share of its segments whose midpoint
 * pixel has the loop's colour. */
async function drawnLoops(page) {
  return page.$eval('[data-testid="sheet"]', (c) => {
    const loops = JSON.parse(c.dataset.linkageLoops || '[]');
    const ratio = c.width / c.clientWidth;
    const ctx = c.getContext('2d');
    const pixel = ([x, y]) => Array.from(ctx.getImageData(Math.round(x * ratio), Math.round(y * ratio), 1, 1).data).slice(0, 3);
    return loops.map((l) => ({
      ...l,
      midpoints: l.points.map((p, i) => {
        const q = l.points[(i + 1) % l.points.length];
        return pixel([(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]);
      }),
    }));
  });
}

test('the IH16 reproducer draws its three loops in three colours, as its legend says', async () => {
  const page = await newPage(browser);
  await openDesign(page, IH16);
  const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(IH16)}`);
  assert.equal(view.linkages.linkages.length, 3, 'three linkages');
  assert.ok(view.tile_linkages.every((set) => set.length === 3), 'every tile is in all three');
  assert.equal(await byTestId(page, 'show-links').isChecked(), true, 'loops are drawn by default');

  const loops = await drawnLoops(page);
  const indices = [...new Set(loops.map((l) => l.index))].sort();
  assert.deepEqual(indices, [0, 1, 2], 'a loop of every linkage is drawn');
  const colours = [...new Set(loops.map((l) => l.colour))];
  assert.equal(colours.length, 3, `three distinct loop colours: ${colours}`);
  for (const index of indices) {
    const mine = loops.filter((l) => l.index === index);
    assert.equal(new Set(mine.map((l) => l.colour)).size, 1, `linkage ${index} has one colour`);
    assert.ok(mine.every((l) => l.points.length === view.linkages.linkages[index].bars), 'a loop passes each joint');
    const mids = mine.flatMap((l) => l.midpoints);
    const hits = mids.filter((p) => near(p, rgb(mine[0].colour))).length;
    assert.ok(hits >= mids.length / 2, `linkage ${index}: ${hits} of ${mids.length} segment midpoints are its colour on the canvas`);
  }

  const legend = await page.$$eval('[data-testid="legend-linkage"]', (items) =>
    items.map((li) => ({ colour: li.dataset.colour, swatch: getComputedStyle(li.querySelector('.swatch')).backgroundColor, text: li.textContent })),
  );
  assert.equal(legend.length, 3, 'three legend entries');
  for (const [i, item] of legend.entries()) {
    const loopColour = loops.find((l) => l.index === i).colour;
    assert.equal(item.colour, loopColour, `legend entry ${i + 1} has its loop's colour`);
    assert.equal(item.swatch, `rgb(${rgb(loopColour).join(', ')})`, 'and its swatch shows it');
    assert.match(item.text, /4-bar/);
  }
  // At t = 0 the measures are 0, not rounding noise like 2.220e-16.
  const atT = await byTestId(page, 'measures-at-t').textContent();
  assert.doesNotMatch(atT, /\de-(1[3-9]|[2-9]\d)/, `no rounding noise printed: ${atT}`);
  assert.match(atT, /min \/ max expansion\s*0 \/ 0/);
  const fills = await byTestId(page, 'legend-fills').textContent();
  assert.match(fills, /shared by several linkages/, 'the legend says what a grey tile means');
  assert.doesNotMatch(fills, /one linkage only/, 'no tile is in only one linkage here');
  assert.ok((await screenshot(browser, page, 'linkages-ih16')) > 20);

  const { text } = await downloadText(page, () => byTestId(page, 'download-svg').click());
  const svg = new DOMParser().parseFromString(text, 'image/svg+xml');
  const strokes = Array.from(svg.getElementsByTagName('polygon')).filter((p) => p.getAttribute('data-linkage') !== null);
  assert.deepEqual(
    [...new Set(strokes.map((p) => p.getAttribute('data-linkage')))].sort(),
    ['0', '1', '2'],
    'the frame SVG draws the same loops',
  );
  for (const p of strokes) {
    const drawn = loops.find((l) => String(l.index) === p.getAttribute('data-linkage'));
    assert.equal(p.getAttribute('stroke'), drawn.colour, 'in the same colours');
  }
  assert.deepEqual(problems(page), []);
});

test('every design with linkages draws each of them; unticking hides them', async () => {
  const page = await newPage(browser);
  const rows = (await allApiRows(server.base)).filter((r) => r.linkage_signature && r.linkage_signature !== 'none');
  assert.ok(rows.length >= 6, 'the quick exploration has designs with linkages');
  const step = Math.max(1, Math.floor(rows.length / 6));
  for (const row of rows.filter((_, i) => i % step === 0).slice(0, 6)) {
    await openDesign(page, row.spec);
    const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(row.spec)}`);
    const loops = await drawnLoops(page);
    const want = view.linkages.linkages.map((_, i) => i);
    assert.deepEqual([...new Set(loops.map((l) => l.index))].sort((a, b) => a - b), want, `${row.spec}: every linkage drawn`);
    for (const [i, set] of view.tile_linkages.entries()) {
      for (const k of set) assert.ok(view.linkages.linkages[k].nodes.some((n) => n[0] === i), `${row.spec}: tile ${i} in linkage ${k}`);
    }
    assert.equal(await byTestId(page, 'legend-linkage').count(), want.length, `${row.spec}: one legend entry per linkage`);
  }
  await byTestId(page, 'show-links').uncheck();
  assert.deepEqual(await drawnLoops(page), [], 'no loops once unticked');
  await page.waitForFunction(() => new URL(location.href).searchParams.get('links') === '0');
  assert.deepEqual(problems(page), []);
});

test('a sheet that ends smaller than closed says by how much and where', async () => {
  const page = await newPage(browser);
  const spec = 'IH90::1x1:aaa';
  await openDesign(page, spec);
  const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(spec)}`);
  const r = view.report;
  assert.ok(r.max_expansion > 0.99 && r.min_expansion < -0.001, 'the reproducer opens to 1 and ends contracted');
  const last = r.frames[r.frames.length - 1];
  assert.ok(last.measures.min_expansion <= r.min_expansion + 1e-9 && last.measures.area_ratio < 1, 'real: the last state is smaller than the closed sheet');
  const summary = await byTestId(page, 'measures').textContent();
  const pct = Number((-100 * r.min_expansion).toPrecision(2));
  assert.ok(summary.includes(`(contracts ${pct} % at t = 1)`), summary);
  assert.deepEqual(problems(page), []);
});
