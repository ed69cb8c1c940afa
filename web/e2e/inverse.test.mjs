// The inverse-design page over a read-only `isogami serve`, in real headless Chromium: reached
// from the catalogue's navigation, a target entered from the keyboard runs; the stage,
// progress bar and leaders show and update while it runs; the results table lists the
// server's result, which is what the command shown under the form prints (run here with the
// binary); "open" shows the first refined design deploying on the design page. A bad target
// shows the server's message and starts nothing; every example target is one the server
// reads; Stop ends a run; "save all" stores the refined designs on a writable server. On the
// static site nothing runs and the page shows the command.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { basename, dirname } from 'node:path';
import { promisify } from 'node:util';
import {
  buildSite, byTestId, canvasColours, canvasPixels, copyDb, env, getJson, newPage, nextAnswer, problems, readOnlySession, screenshot, serveFolder, startServer,
} from './harness.mjs';
import { EXAMPLES } from '../src/inverse-request.js';
import { shellSplit } from '../test/shell.mjs';

let server;
let browser;
readOnlySession((s, b) => {
  server = s;
  browser = b;
});

async function openPanel(page) {
  await page.goto(`${server.base}/index.html`);
  await byTestId(page, 'nav-inverse').click();
  await page.waitForURL(/inverse\.html$/);
  // The defaults and caps come from the server.
  await page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');
}

const state = (page) => page.evaluate(() => document.body.dataset.inverseState ?? '');

/** POSTs a body to /api/inverse from node; status and JSON. */
async function postInverse(body) {
  const res = await fetch(`${server.base}/api/inverse`, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(body),
  });
  return { status: res.status, json: await res.json() };
}

test('a run shows its progress and leaders, ends with the CLI’s result, and opens a design', async () => {
  const page = await newPage(browser);
  await openPanel(page);
  // Every field has a label; the caps are shown.
  const unlabelled = await page.$$eval('#inverse-form input, #inverse-form select', (els) =>
    els.filter((e) => e.labels.length === 0).map((e) => e.id || e.name),
  );
  assert.deepEqual(unlabelled, []);
  const settings = await getJson(`${server.base}/api/inverse`);
  assert.equal(await byTestId(page, 'budget').getAttribute('max'), String(settings.limits.budget));
  assert.equal(await byTestId(page, 'top').inputValue(), String(settings.defaults.top));

  // An example chip from the keyboard, then Enter in the target field runs it.
  const chip = byTestId(page, 'example').first();
  await chip.focus();
  await page.keyboard.press('Enter');
  assert.equal(await byTestId(page, 'target').inputValue(), EXAMPLES[0].target);
  await byTestId(page, 'target').fill('area');
  const command = await byTestId(page, 'inverse-command').textContent();
  assert.equal(command, `isogami inverse --target 'area' --db ${basename(env().db)} --top 3 --budget 80 --json`);
  const started = page.waitForResponse((r) => r.url().endsWith('/api/inverse') && r.request().method() === 'POST');
  await byTestId(page, 'target').press('Enter');
  assert.equal((await started).status(), 202);

  // While it runs: a stage, a progress bar moving, leaders with objectives — read in the one
  // evaluation that sees it running (the run lasts seconds; a later read may find it done).
  const running = await (await page.waitForFunction(() => {
    const q = (id) => document.querySelector(`[data-testid="${id}"]`);
    return document.body.dataset.inverseState === 'running' &&
      document.querySelectorAll('[data-testid="leader"]').length > 0 &&
      Number(q('progress-bar').value) > 0 && {
      runDisabled: q('run').disabled,
      stopDisabled: q('stop').disabled,
      stage: q('stage-line').textContent,
      progress: q('progress-line').textContent,
    };
  })).jsonValue();
  assert.ok(running.runDisabled, 'Run is disabled while it runs');
  assert.ok(!running.stopDisabled, 'Stop is enabled while it runs');
  assert.match(running.stage, /\w/);
  assert.match(running.progress, /evaluations · best objective -?\d/);
  assert.ok((await screenshot(browser, page, 'inverse-running')) > 30);

  await page.waitForFunction(() => document.body.dataset.inverseState !== 'running', null, { timeout: 300000 });
  assert.equal(await state(page), 'done');
  // The leaders changed while it ran (they appeared, then improved).
  const updates = await page.evaluate(() => Number(document.body.dataset.leaderUpdates));
  assert.ok(updates >= 2, `${updates} leader updates`);
  assert.ok(Number(await page.evaluate(() => document.body.dataset.polls)) >= 2);

  // The results are the server's, and the command prints the same.
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const job = await getJson(`${server.base}/api/inverse/${id}`);
  const results = job.result.results;
  assert.ok(results.length >= 1 && results.length <= 3);
  assert.equal(await byTestId(page, 'result').count(), results.length);
  const shown = await byTestId(page, 'result-spec').allTextContents();
  assert.deepEqual(shown, results.map((r) => r.after.spec));
  // The verdict of the best design: 'area' asks for the most, so nothing to meet.
  assert.equal(job.result.met, null);
  assert.equal(await byTestId(page, 'results-verdict').textContent(), `Best design: ${results[0].verdict.summary}`);
  assert.match(results[0].verdict.summary, /^no value to meet; area asks for the most/);
  assert.ok(await byTestId(page, 'save-all').isHidden(), 'no saving on a read-only server');
  // End reasons in words, as the library says them, never the internal key.
  const table = await page.$eval('[data-testid="results"]', (t) => t.textContent).catch(() => '');
  const rowsText = (await byTestId(page, 'result').allTextContents()).join(' ') + table;
  assert.doesNotMatch(rowsText, /contact_limit|[a-z]_[a-z]/, 'no internal names in the results');
  for (const r of results) assert.ok(rowsText.includes(r.after.measures.end_label), r.after.measures.end_label);
  const words = shellSplit(command);
  const { stdout } = await promisify(execFile)(env().bin, words.slice(1), { cwd: dirname(env().db), maxBuffer: 64 << 20 });
  const cli = JSON.parse(stdout);
  delete cli.seconds;
  const api = { ...job.result };
  delete api.seconds;
  assert.deepEqual(api, cli, 'the page’s result is what `isogami inverse --json` prints');
  assert.ok((await screenshot(browser, page, 'inverse-results')) > 30);
  assert.deepEqual(problems(page), []);

  // Open the first refined design: the design page deploys that spec.
  await byTestId(page, 'result').first().locator('[data-testid="open"]').click();
  await page.waitForURL(/design\.html\?spec=/);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1, null, { timeout: 60000 });
  assert.equal(await byTestId(page, 'spec').textContent(), results[0].after.spec);
  assert.ok(canvasColours(await canvasPixels(page, '[data-testid="sheet"]')) > 2, 'the sheet is drawn');
  // A refined design is not in the database: the design page deploys it live, and no
  // request fails on the way.
  assert.deepEqual(problems(page), []);
});

test('the best objective of a value goal is drawn on a log scale with its legend above the lines', async () => {
  const page = await newPage(browser);
  await openPanel(page);
  await byTestId(page, 'target').fill('area(1.6)');
  await byTestId(page, 'budget').fill('30');
  await byTestId(page, 'target').press('Enter');
  await page.waitForFunction(() => document.body.dataset.inverseState && document.body.dataset.inverseState !== 'running', null, { timeout: 300000 });
  const id = await page.evaluate(() => document.body.dataset.jobId);
  const job = await getJson(`${server.base}/api/inverse/${id}`);
  const values = job.history.map(([, v]) => v);
  assert.ok(values.length >= 2, 'a history of best objectives');
  const svg = page.locator('[data-testid="history-plot"] svg');
  const positive = values.every((v) => v > 0);
  assert.equal(await svg.getAttribute('data-scale'), positive ? 'log' : 'linear', `history ${values.slice(0, 5)}…`);
  if (positive) {
    assert.match(await svg.getAttribute('aria-label'), /log scale/);
    // Tick labels are decades, readable (no run of digits).
    const ticks = (await page.$$eval('[data-testid="history-plot"] .y-axis .tick text', (ts) => ts.map((t) => t.textContent))).filter(Boolean);
    assert.ok(ticks.length >= 1, `labelled ticks ${ticks}`);
    for (const t of ticks) assert.match(t, /^(\d+(\.\d+)?|\d(\.\d+)?e[-+]\d+)$/, t);
  }
  // The legend sits above the plot area (the top of the y axis), so no line runs under it.
  const legend = await page.locator('[data-testid="legend-best"]').boundingBox();
  const axis = await page.locator('[data-testid="history-plot"] .y-axis path.domain').boundingBox();
  assert.ok(legend.y + legend.height <= axis.y + 1, `legend bottom ${legend.y + legend.height} above the plot area ${axis.y}`);
  const line = await page.locator('[data-testid="series-best"]').boundingBox();
  assert.ok(legend.y + legend.height <= line.y + 1, 'and above the line');
  assert.deepEqual(problems(page), []);
});

test('a bad target shows the server’s message and starts nothing; the examples are all readable', async () => {
  const page = await newPage(browser);
  await openPanel(page);
  await byTestId(page, 'target').fill('aera + isotropic');
  const response = nextAnswer(page, (r) => r.url().endsWith('/api/inverse') && r.method() === 'POST');
  await byTestId(page, 'run').click();
  const res = await response;
  assert.equal(res.status(), 400);
  const notice = byTestId(page, 'notice');
  await notice.waitFor({ state: 'visible' });
  assert.equal(await notice.locator('strong').textContent(), (await res.json()).error);
  assert.match(await notice.textContent(), /unknown goal 'aera'/);
  assert.equal(await state(page), '');
  assert.ok(await byTestId(page, 'run').isEnabled());
  assert.equal((await getJson(`${server.base}/api/inverse`)).running, null);
  assert.deepEqual(problems(page, [/^400 POST \S+\/api\/inverse$/]), []);

  // Each example is read by the server (it then refuses top 0, so nothing runs).
  for (const x of EXAMPLES) {
    const { status, json } = await postInverse({ target: x.target, top: 0 });
    assert.equal(status, 400);
    assert.equal(json.kind, 'bad_parameter', `${x.target}: ${json.error}`);
    assert.match(json.error, /top 0/);
  }
});

test('Stop ends a run', async () => {
  const page = await newPage(browser);
  await openPanel(page);
  await byTestId(page, 'target').fill('isotropic + 0.5*uniform');
  await byTestId(page, 'top').fill('5');
  await byTestId(page, 'budget').fill('200');
  await byTestId(page, 'run').click();
  await page.waitForFunction(() => document.querySelectorAll('[data-testid="leader"]').length > 0);
  assert.equal(await state(page), 'running');
  await byTestId(page, 'stop').click();
  await page.waitForFunction(() => document.body.dataset.inverseState === 'stopped');
  const notice = byTestId(page, 'notice');
  await notice.waitFor({ state: 'visible' });
  assert.match(await notice.textContent(), /stopped by request/);
  assert.match(await byTestId(page, 'stage-line').textContent(), /^Stopped after \d+ evaluations/);
  assert.ok(await byTestId(page, 'run').isEnabled());
  assert.ok(await byTestId(page, 'results-section').isHidden());
  assert.equal((await getJson(`${server.base}/api/inverse`)).running, null);
  assert.deepEqual(problems(page), []);
});

test('save all stores the refined designs on a writable server', async () => {
  const copy = await copyDb();
  const writable = await startServer({ db: copy.file });
  try {
    const page = await newPage(browser);
    await page.goto(`${writable.base}/inverse.html`);
    await page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');
    await byTestId(page, 'target').fill('area');
    await byTestId(page, 'top').fill('2');
    await byTestId(page, 'budget').fill('8');
    await byTestId(page, 'run').click();
    await page.waitForFunction(() => document.body.dataset.inverseState === 'done', null, { timeout: 300000 });
    const specs = await byTestId(page, 'result-spec').allTextContents();
    assert.ok(specs.length >= 1);
    // Refined designs are new; one that refinement did not move is already stored.
    const stored = async (spec) => (await fetch(`${writable.base}/api/design?spec=${encodeURIComponent(spec)}`)).status === 200;
    const fresh = [];
    for (const spec of specs) if (!(await stored(spec))) fresh.push(spec);
    assert.ok(fresh.length >= 1, 'refinement found a new design');
    await byTestId(page, 'save-all').click();
    await page.waitForFunction(() => /^saved/.test(document.querySelector('[data-testid="save-status"]').textContent));
    const kept = specs.length - fresh.length;
    assert.equal(
      await byTestId(page, 'save-status').textContent(),
      `saved ${fresh.length} design${fresh.length === 1 ? '' : 's'}${kept ? `; ${kept} already in the database` : ''}.`,
    );
    assert.ok(await byTestId(page, 'save-all').isDisabled(), 'saved once');
    for (const spec of fresh) {
      const view = await getJson(`${writable.base}/api/design?spec=${encodeURIComponent(spec)}`);
      assert.equal(view.origin, 'user');
    }
    assert.deepEqual(problems(page), []);
  } finally {
    await writable.stop();
    await copy.remove();
  }
});

test('Ctrl-C stops the server promptly while a job runs', async () => {
  const own = await startServer({ args: ['--read-only'] });
  try {
    const res = await fetch(`${own.base}/api/inverse`, {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify({ target: 'isotropic + 0.5*uniform', top: 5, budget: 200 }),
    });
    assert.equal(res.status, 202);
    const { id } = await res.json();
    await new Promise((ok) => setTimeout(ok, 300));
    assert.equal((await getJson(`${own.base}/api/inverse/${id}`)).state, 'running');
    const t0 = Date.now();
    const code = await own.interrupt(8000); // the run alone takes about 20 s here
    assert.notEqual(code, null, 'the server exited');
    assert.ok(Date.now() - t0 < 8000);
  } finally {
    await own.stop();
  }
});

test('on the static site the page shows the command instead of running', async () => {
  const site = await buildSite();
  const files = await serveFolder(site.dir, '/sub');
  try {
    const page = await newPage(browser);
    await page.goto(`${files.base}/index.html`);
    await byTestId(page, 'nav-inverse').click();
    await page.waitForURL(/inverse\.html$/);
    await page.waitForFunction(() => document.body.dataset.mode === 'static');
    await page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');
    assert.ok(await byTestId(page, 'run').isDisabled());
    assert.match(await byTestId(page, 'run-note').textContent(), /isogami serve/);
    // The command line has no server caps.
    assert.equal(await byTestId(page, 'budget').getAttribute('max'), null);
    assert.ok(await page.locator('#progress-section').isHidden());
    await byTestId(page, 'example').nth(2).click();
    await byTestId(page, 'budget').fill('20');
    assert.equal(
      await byTestId(page, 'inverse-command').textContent(),
      `isogami inverse --target '${EXAMPLES[2].target}' --db ${basename(env().db)} --top 3 --budget 20 --json`,
    );
    assert.ok((await screenshot(browser, page, 'inverse-static')) > 20);
    assert.deepEqual(problems(page), []);
  } finally {
    await files.stop();
    await site.remove();
  }
});

test('inverse.html?target= fills the form and its command; an edited form survives a reload (issue 42 item 16)', async () => {
  // Every example target, given in the URL as a link from elsewhere would give it.
  const page = await newPage(browser);
  for (const x of EXAMPLES) {
    await page.goto(`${server.base}/inverse.html?target=${encodeURIComponent(x.target)}&budget=60`);
    await page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');
    assert.equal(await byTestId(page, 'target').inputValue(), x.target);
    assert.equal(await byTestId(page, 'budget').inputValue(), '60');
    const command = await byTestId(page, 'inverse-command').textContent();
    assert.ok(command.includes('--budget 60'), command);
    assert.ok(shellSplit(command).includes(x.target), command);
  }
  // A target typed in, then a reload: the same target and command.
  await byTestId(page, 'target').fill('area(1.5)');
  const typed = await byTestId(page, 'inverse-command').textContent();
  await page.reload();
  await page.waitForFunction(() => document.querySelector('[data-testid="top"]').value !== '');
  assert.equal(await byTestId(page, 'target').inputValue(), 'area(1.5)');
  assert.equal(await byTestId(page, 'inverse-command').textContent(), typed);
  assert.deepEqual(problems(page), []);
});
