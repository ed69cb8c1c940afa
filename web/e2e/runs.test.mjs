// Runs that outlive the page, over `isogami serve` in real headless Chromium: a graded-sheet
// or inverse-design job is the server's, and any page shows it from there. A reload in the
// middle of a run, or a second tab, shows the running job with the form holding its
// parameters and the command line the job's; a finished run's results come back after a
// reload; the page's URL names the run (?job=ID), so a copied link opens it, and an unknown
// id says so on the page; a second tab that presses Run while the one inverse design runs is
// shown that run instead of an error.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  byTestId, getJson, newPage, problems, readOnlySession,
} from './harness.mjs';

let server;
let browser;
readOnlySession((s, b) => {
  server = s;
  browser = b;
});

/** Stops every running job of `kind` (graded or inverse) and waits for it to end. */
async function stopAll(kind) {
  const running = (await getJson(`${server.base}/api/${kind}`)).running;
  for (const id of [running ?? []].flat()) {
    await fetch(`${server.base}/api/${kind}/${id}`, { method: 'DELETE' });
    while ((await getJson(`${server.base}/api/${kind}/${id}`)).state === 'running') await new Promise((ok) => setTimeout(ok, 50));
  }
}

const gradedReady = (page) => page.waitForFunction(() => document.body.dataset.ready === 'true');
const inverseReady = (page) => page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');

/** What the graded form shows: its fields, the target chosen, the command. */
function gradedForm(page) {
  return page.evaluate(() => {
    const v = (id) => document.querySelector(`[data-testid="${id}"]`).value;
    return {
      design: v('design'),
      rows: v('rows'),
      cols: v('cols'),
      iterations: v('iterations'),
      outline: document.querySelector('input[name="outline"]:checked')?.value,
      corners: document.querySelector('[data-testid="draw-pad"]').dataset.points,
      command: document.querySelector('[data-testid="graded-command"]').textContent,
    };
  });
}

/** What the inverse form shows: its fields and the command. */
function inverseForm(page) {
  return page.evaluate(() => {
    const v = (id) => document.querySelector(`[data-testid="${id}"]`).value;
    return {
      target: v('target'),
      top: v('top'),
      budget: v('budget'),
      confirm: v('confirm'),
      command: document.querySelector('[data-testid="inverse-command"]').textContent,
    };
  });
}

test('graded: a reload mid-run and a second tab show the running job, its form and command; the URL names it', async () => {
  await stopAll('graded');
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await gradedReady(page);
  // A polygon, 800 iterations, 6x6 cells: a run of most of a minute here.
  await byTestId(page, 'rows').fill('6');
  await byTestId(page, 'cols').fill('6');
  await byTestId(page, 'iterations').fill('800');
  await byTestId(page, 'pad-corners').fill('0,1; -0.9,-0.6; 0.9,-0.6');
  await page.waitForFunction(() => document.querySelector('[data-testid="draw-pad"]').dataset.checked === 'true');
  const asked = await gradedForm(page);
  assert.equal(asked.outline, 'polygon');
  assert.match(asked.command, /--target 'polygon:0,1;-0\.9,-0\.6;0\.9,-0\.6' --iterations 800/);
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => document.body.dataset.gradedState === 'running');
  const id = await page.evaluate(() => document.body.dataset.jobId);
  // The URL names the run.
  await page.waitForFunction((i) => new URLSearchParams(location.search).get('job') === i, id);

  // A reload in the middle of the run: the same job, the same form, the same command.
  await page.reload();
  await gradedReady(page);
  await page.waitForFunction((i) => document.body.dataset.jobId === i && document.body.dataset.gradedState === 'running', id);
  await page.waitForFunction((c) => document.querySelector('[data-testid="graded-command"]').textContent === c, asked.command, { timeout: 5000 })
    .catch(() => {});
  assert.deepEqual(await gradedForm(page), asked, 'the form after a reload is the running job’s');
  assert.ok(await byTestId(page, 'run').isDisabled());
  assert.ok(await byTestId(page, 'stop').isEnabled());

  // A second tab on the bare page: the running job, its form and command.
  const second = await newPage(browser);
  await second.goto(`${server.base}/graded.html`);
  await gradedReady(second);
  await second.waitForFunction((i) => document.body.dataset.jobId === i && document.body.dataset.gradedState === 'running', id);
  await second.waitForFunction((c) => document.querySelector('[data-testid="graded-command"]').textContent === c, asked.command, { timeout: 5000 })
    .catch(() => {});
  assert.deepEqual(await gradedForm(second), asked, 'the second tab’s form is the running job’s');
  // Its live view follows the job.
  await second.waitForFunction(() => Number(document.querySelector('[data-testid="live-sheet"]').dataset.iteration) > 0, null, { timeout: 30000 });
  assert.match(new URL(second.url()).search, new RegExp(`[?&]job=${id}(&|$)`));

  await byTestId(second, 'stop').click();
  await page.waitForFunction(() => document.body.dataset.gradedState === 'stopped', null, { timeout: 30000 });
  await second.waitForFunction(() => document.body.dataset.gradedState === 'stopped', null, { timeout: 30000 });
  assert.deepEqual(problems(page), []);
  assert.deepEqual(problems(second), []);
});

test('graded: a finished run stays after a reload, and a copied link opens it; an unknown id says so', async () => {
  await stopAll('graded');
  const page = await newPage(browser);
  await page.goto(`${server.base}/graded.html`);
  await gradedReady(page);
  await byTestId(page, 'rows').fill('2');
  await byTestId(page, 'cols').fill('2');
  await byTestId(page, 'iterations').fill('40');
  await byTestId(page, 'outline-ellipse').check();
  await byTestId(page, 'aspect').fill('1.2');
  const asked = await gradedForm(page);
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => ['done', 'failed', 'stopped'].includes(document.body.dataset.gradedState), null, { timeout: 60000 });
  assert.equal(await page.evaluate(() => document.body.dataset.gradedState), 'done');
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const report = await byTestId(page, 'report').textContent();

  await page.reload();
  await gradedReady(page);
  await page.waitForFunction(() => document.body.dataset.gradedState === 'done', null, { timeout: 10000 });
  assert.ok(await page.locator('#results-section').isVisible(), 'the results are shown again');
  assert.equal(await byTestId(page, 'report').textContent(), report);
  assert.deepEqual(await gradedForm(page), asked);
  assert.equal(await byTestId(page, 'download').getAttribute('href'), `./api/graded/${id}/sheet`);

  // The link, opened in another tab.
  const link = page.url();
  const other = await newPage(browser);
  await other.goto(link);
  await other.waitForFunction(() => document.body.dataset.gradedState === 'done', null, { timeout: 10000 });
  assert.equal(await byTestId(other, 'report').textContent(), report);
  assert.deepEqual(await gradedForm(other), asked);

  // An unknown run: the server's message on the page.
  const lost = await newPage(browser);
  await lost.goto(`${server.base}/graded.html?job=99999`);
  await gradedReady(lost);
  const notice = byTestId(lost, 'notice');
  await notice.waitFor({ state: 'visible' });
  assert.match(await notice.textContent(), /no graded-sheet job "99999" on this server/);
  assert.match(await notice.textContent(), /forgotten \d+ minutes after they end/);
  assert.ok(await byTestId(lost, 'run').isEnabled(), 'a new run can start');
  assert.deepEqual(problems(page), []);
  assert.deepEqual(problems(other), []);
  assert.deepEqual(problems(lost, [/^404 GET \S+\/api\/graded\/99999$/]), []);
});

test('inverse: a reload mid-run and a second tab show the running job, its form and command', async () => {
  await stopAll('inverse');
  // A second tab opened before the run starts.
  const second = await newPage(browser);
  await second.goto(`${server.base}/inverse.html`);
  await inverseReady(second);

  const page = await newPage(browser);
  await page.goto(`${server.base}/inverse.html`);
  await inverseReady(page);
  await byTestId(page, 'target').fill('isotropic + 0.5*uniform');
  await byTestId(page, 'top').fill('5');
  await byTestId(page, 'budget').fill('200');
  await page.locator('details.more summary').click();
  await byTestId(page, 'confirm').fill('60');
  const asked = await inverseForm(page);
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => document.body.dataset.inverseState === 'running');
  const id = await page.evaluate(() => document.body.dataset.jobId);
  await page.waitForFunction((i) => new URLSearchParams(location.search).get('job') === i, id);

  // A reload mid-run: the same job, form and command.
  await page.reload();
  await inverseReady(page);
  await page.waitForFunction((i) => document.body.dataset.jobId === i && document.body.dataset.inverseState === 'running', id);
  await page.waitForFunction((c) => document.querySelector('[data-testid="inverse-command"]').textContent === c, asked.command, { timeout: 5000 })
    .catch(() => {});
  assert.deepEqual(await inverseForm(page), asked, 'the form after a reload is the running job’s');

  // The tab opened before: Run with another target is shown the running job, not an error.
  await byTestId(second, 'target').fill('area');
  await byTestId(second, 'run').click();
  await second.waitForFunction((i) => document.body.dataset.jobId === i && document.body.dataset.inverseState === 'running', id, { timeout: 10000 });
  await second.waitForFunction((c) => document.querySelector('[data-testid="inverse-command"]').textContent === c, asked.command, { timeout: 5000 })
    .catch(() => {});
  assert.deepEqual(await inverseForm(second), asked, 'the second tab’s form is the running job’s');
  const said = await byTestId(second, 'notice').textContent();
  assert.doesNotMatch(said, /already running|DELETE/, said);
  assert.match(said, /'area' was not started/);
  await second.waitForFunction(() => document.querySelectorAll('[data-testid="leader"]').length > 0, null, { timeout: 60000 });

  // A third tab on the bare page attaches too.
  const third = await newPage(browser);
  await third.goto(`${server.base}/inverse.html`);
  await inverseReady(third);
  await third.waitForFunction((i) => document.body.dataset.jobId === i, id);
  await third.waitForFunction((c) => document.querySelector('[data-testid="inverse-command"]').textContent === c, asked.command, { timeout: 5000 })
    .catch(() => {});
  assert.deepEqual(await inverseForm(third), asked);

  await byTestId(third, 'stop').click();
  for (const p of [page, second, third]) await p.waitForFunction(() => document.body.dataset.inverseState === 'stopped', null, { timeout: 30000 });
  assert.deepEqual(problems(page), []);
  assert.deepEqual(problems(second), []);
  assert.deepEqual(problems(third), []);
});

test('inverse: a finished run stays after a reload, and a copied link opens it; an unknown id says so', async () => {
  await stopAll('inverse');
  const page = await newPage(browser);
  await page.goto(`${server.base}/inverse.html`);
  await inverseReady(page);
  await byTestId(page, 'target').fill('area');
  await byTestId(page, 'top').fill('2');
  await byTestId(page, 'budget').fill('8');
  const asked = await inverseForm(page);
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => document.body.dataset.inverseState === 'done', null, { timeout: 300000 });
  const specs = await byTestId(page, 'result-spec').allTextContents();
  assert.ok(specs.length >= 1);
  const link = page.url();
  assert.match(new URL(link).search, /[?&]job=\d+/);

  await page.reload();
  await inverseReady(page);
  await page.waitForFunction(() => document.body.dataset.inverseState === 'done', null, { timeout: 10000 });
  assert.deepEqual(await byTestId(page, 'result-spec').allTextContents(), specs, 'the results are shown again');
  assert.deepEqual(await inverseForm(page), asked);

  const other = await newPage(browser);
  await other.goto(link);
  await other.waitForFunction(() => document.body.dataset.inverseState === 'done', null, { timeout: 10000 });
  assert.deepEqual(await byTestId(other, 'result-spec').allTextContents(), specs);
  assert.deepEqual(await inverseForm(other), asked);

  const lost = await newPage(browser);
  await lost.goto(`${server.base}/inverse.html?job=99999`);
  await inverseReady(lost);
  const notice = byTestId(lost, 'notice');
  await notice.waitFor({ state: 'visible' });
  assert.match(await notice.textContent(), /no inverse-design job "99999" on this server/);
  assert.ok(await byTestId(lost, 'run').isEnabled(), 'a new run can start');
  assert.deepEqual(problems(page), []);
  assert.deepEqual(problems(other), []);
  assert.deepEqual(problems(lost, [/^404 GET \S+\/api\/inverse\/99999$/]), []);
});
