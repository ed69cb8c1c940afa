// Shape-aware sliders (issue 13, item 6) in real headless Chromium over `isogami serve`: a
// special design's slider move is followed on the server (the other constrained slider moves
// with it) and the sheet still deploys, where moving the slider freely makes it rigid; a
// pinned slider is disabled and says why; a generic design's slider moves alone.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  byTestId, moveSlider, newPage, openDesign as openHarnessDesign, problems, readOnlySession,
} from './harness.mjs';

// These designs are not in the database: the page deploys them live.

// One DOF only where v2 = v3.
const SPECIAL = 'IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-';
// Special, its only parameter pinned.
const PINNED = 'IH16:0.216506350946:1x1:-a-a-aaaa';
// One DOF at every nearby shape.
const GENERIC = 'IH28:0.588675134594,0.35:1x1:a--a-b-bbb';

let server;
let browser;
readOnlySession((s, b) => {
  server = s;
  browser = b;
});

const openDesign = (page, spec) => openHarnessDesign(page, server.base, spec);

const deployments = (page) => page.evaluate(() => Number(document.body.dataset.deployments || 0));
const paramsOf = (spec) => spec.split(':')[1].split(',').map(Number);

/** Presses `key` `times` on slider `id` and waits for the edit to settle (moveSlider): the
 * answer to the last deployment asked for, its body already read, and the count of
 * deployments shown before the presses. */
async function press(page, id, key, times) {
  const count = await deployments(page);
  const res = await moveSlider(page, id, key, times);
  return { res, count };
}

test('a special design follows its constraint and keeps deploying; moved freely it goes rigid', async () => {
  const page = await newPage(browser);
  const follows = [];
  page.on('request', (r) => {
    if (r.url().endsWith('/api/shape/follow')) follows.push(JSON.parse(r.postData()));
  });
  await openDesign(page, SPECIAL);
  const status = byTestId(page, 'shape-status');
  await page.waitForFunction(() => /special/.test(document.querySelector('[data-testid="shape-status"]').textContent));
  assert.match(await status.textContent(), /1 shape constraint; the sliders follow it/);
  const v3Before = await byTestId(page, 'param-v3').inputValue();

  const { res, count } = await press(page, 'param-v2', 'ArrowRight', 6);
  assert.equal(res.status(), 200, 'the followed design deploys');
  await page.waitForFunction((n) => Number(document.body.dataset.deployments) > n, count);
  assert.ok(follows.length >= 1, 'the move went through POST /api/shape/follow');
  assert.ok(follows.every((f) => f.index === 2));
  // Six key presses can start more than one follow-and-deploy; once the network is idle, the
  // header's spec and the slider's exact value are read together, in the one evaluation that
  // finds them agreeing (a later answer landing between two separate reads made CI see one
  // state's spec beside the next state's value).
  await page.waitForLoadState('networkidle');
  const agreed = await page.waitForFunction(() => {
    const spec = document.querySelector('[data-testid="spec"]').textContent;
    const v3 = Number(document.querySelector('[data-testid="param-v3-value"]').getAttribute('title'));
    return Number(spec.split(':')[1].split(',')[3]) === v3 && { spec, v3 };
  });
  const { spec, v3 } = await agreed.jsonValue();
  const p = paramsOf(spec);
  assert.ok(p[2] > 0.2254, `v2 moved right: ${spec}`);
  assert.ok(Math.abs(p[2] - p[3]) < 1e-6, `v3 followed v2: ${spec}`);
  assert.notEqual(await byTestId(page, 'param-v3').inputValue(), v3Before, 'the v3 slider moved by itself');
  // The number beside it is exact (a range input snaps to its step).
  assert.equal(v3, p[3]);
  const body = await res.json();
  assert.ok(body.report.frames.length >= 2 && body.report.max_expansion > 0.01, 'the sheet opens');
  assert.equal(await page.locator('.notice[data-kind="rigid"]').count(), 0);
  assert.match(await status.textContent(), /2 parameters moved/);

  // Moving freely breaks it: the same kind of move on v2 alone is rigid, explained in place.
  await byTestId(page, 'shape-free').check();
  assert.match(await status.textContent(), /moving freely/);
  const sent = follows.length;
  const free = await press(page, 'param-v2', 'ArrowRight', 4);
  assert.equal(free.res.status(), 422);
  assert.equal((await free.res.json()).kind, 'rigid');
  await page.locator('.notice[data-kind="rigid"]').waitFor({ state: 'visible' });
  assert.equal(follows.length, sent, 'no follow request while moving freely');
  // The rigid design is no longer special, yet the box stays to be unticked.
  await page.waitForFunction(() => /degrees of freedom/.test(document.querySelector('[data-testid="shape-status"]').textContent));
  assert.equal(await byTestId(page, 'shape-free').isVisible(), true);
  assert.deepEqual(problems(page, [/^422 POST \S+\/api\/deploy$/, /^422 GET \S+\/api\/shape\?/]), []);
});

test('a pinned slider is disabled and says why', async () => {
  const page = await newPage(browser);
  await openDesign(page, PINNED);
  await page.waitForFunction(() => /special/.test(document.querySelector('[data-testid="shape-status"]').textContent));
  const slider = byTestId(page, 'param-v0');
  assert.equal(await slider.isDisabled(), true);
  assert.match(await slider.getAttribute('title'), /pinned/);
  // Moving freely enables it again.
  await byTestId(page, 'shape-free').check();
  assert.equal(await slider.isDisabled(), false);
  assert.deepEqual(problems(page), []);
});

test('a generic design says so and its slider moves alone, without following', async () => {
  const page = await newPage(browser);
  let follows = 0;
  page.on('request', (r) => {
    if (r.url().endsWith('/api/shape/follow')) follows += 1;
  });
  await openDesign(page, GENERIC);
  await page.waitForFunction(() => /generic/.test(document.querySelector('[data-testid="shape-status"]').textContent));
  assert.equal(await byTestId(page, 'shape-free').isVisible(), false, 'nothing to free');
  let moved = null;
  for (const key of ['ArrowRight', 'ArrowLeft']) {
    const { res, count } = await press(page, 'param-v1', key, 4);
    if (res.status() !== 200) continue;
    await page.waitForFunction((n) => Number(document.body.dataset.deployments) > n, count);
    moved = await byTestId(page, 'spec').textContent();
    break;
  }
  assert.ok(moved, 'a move of v1 deployed');
  const p = paramsOf(moved);
  assert.equal(p[0], 0.588675134594, `v0 untouched: ${moved}`);
  assert.notEqual(p[1], 0.35);
  assert.equal(follows, 0);
  assert.deepEqual(problems(page, [/^422 POST \S+\/api\/deploy$/]), []);
});
