// "Same motion elsewhere" on the design page (issue 13 item 5, issue 24 item 6) in real headless Chromium over
// `isogami serve`: a stored design whose motion appears in other cells or families lists them,
// each link opens a design of that topology whose panel lists the first one back; a design
// found only once shows no panel.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import {
  allApiRows, byTestId, getJson, launchBrowser, newPage, nextAnswer, openDesign as openHarnessDesign, problems, startServer,
} from './harness.mjs';
import { SHOWN, variantRows } from '../src/motion-panel.js';

let server;
let browser;
let shared = null; // {row, klass}
let alone = null;

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  for (const row of await allApiRows(server.base)) {
    const answer = await getJson(`${server.base}/api/motion?spec=${encodeURIComponent(row.spec)}`);
    assert.ok(answer.class, `every explored design has a class: ${row.spec}`);
    const n = answer.class.variants.length;
    if (n > 1 && !shared) shared = { row, klass: answer.class, topology: answer.topology };
    if (n === 1 && !alone) alone = row;
    if (shared && alone) break;
  }
  assert.ok(shared, 'the quick exploration has a motion found in several cells or families');
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

const openDesign = (page, spec) => openHarnessDesign(page, server.base, spec);

test('a shared motion lists its other cells and families, and the links lead back', async () => {
  const page = await newPage(browser);
  await openDesign(page, shared.row.spec);
  const section = byTestId(page, 'motion-section');
  await section.waitFor({ state: 'visible' });
  const items = page.locator('[data-testid="motion-variant"]');
  // Sorted by family number, cell, then area ratio; long lists collapsed behind "show all".
  const others = variantRows(shared.klass, shared.topology);
  assert.equal(await items.count(), Math.min(others.length, SHOWN));
  for (let i = 0; i < Math.min(others.length, SHOWN); i += 1) {
    assert.match(await items.nth(i).textContent(), new RegExp(`^${others[i].label}`));
  }
  // Follow the first link: a stored design of that topology, whose panel names the first back.
  await Promise.all([page.waitForNavigation(), items.first().locator('a').click()]);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  assert.equal(await byTestId(page, 'spec').textContent(), others[0].spec);
  await byTestId(page, 'motion-section').waitFor({ state: 'visible' });
  const me = shared.klass.variants.find((v) => v.topology === shared.topology);
  const label = `${me.family} ${me.cell.replace('x', '×')}`;
  if (await byTestId(page, 'motion-show-all').count()) await byTestId(page, 'motion-show-all').click();
  const all = await page.locator('[data-testid="motion-variant"]').allTextContents();
  assert.ok(all.some((t) => t.startsWith(label)), all.join(' | '));
  assert.deepEqual(problems(page), []);
});

test('a motion found only once shows no panel', async (t) => {
  if (!alone) {
    t.skip('every motion of this database is shared');
    return;
  }
  const page = await newPage(browser);
  const answered = nextAnswer(page, (r) => r.url().includes('/api/motion?'));
  await openDesign(page, alone.spec);
  assert.equal((await (await answered).json()).class.variants.length, 1);
  await page.waitForTimeout(100); // the answer renders (or here: leaves the panel hidden)
  assert.equal(await byTestId(page, 'motion-section').isVisible(), false);
  assert.deepEqual(problems(page), []);
});
