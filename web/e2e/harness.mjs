// Test harness for the end-to-end tests: starts `isogami serve` on a free port (binary from
// ISOGAMI_BIN, database from ISOGAMI_DB), writes a static site with `isogami site` and serves
// it with a small node:http file server, launches the system's Chromium through
// playwright-core (never downloads a browser), and checks screenshots and canvases for
// blankness. Everything started here is stopped by the returned handles.

import { spawn, execFile } from 'node:child_process';
import { createServer } from 'node:http';
import { copyFile, mkdir, mkdtemp, readFile, rm, stat } from 'node:fs/promises';
import { createInterface } from 'node:readline';
import { tmpdir } from 'node:os';
import { dirname, extname, join, normalize, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { promisify } from 'node:util';
import { after, before } from 'node:test';
import { chromium } from 'playwright-core';

const here = dirname(fileURLToPath(import.meta.url));
export const ARTIFACTS = join(here, 'artifacts');

/** ISOGAMI_BIN and ISOGAMI_DB, or a clear failure (the e2e tests need both). */
export function env() {
  const bin = process.env.ISOGAMI_BIN;
  const db = process.env.ISOGAMI_DB;
  if (!bin || !db) {
    throw new Error('set ISOGAMI_BIN (the isogami binary) and ISOGAMI_DB (a design database) to run the e2e tests');
  }
  return { bin: resolve(bin), db: resolve(db) };
}

/** A private copy of the database (for tests that write to it, e.g. saving a design). */
export async function copyDb() {
  const { db } = env();
  const dir = await mkdtemp(join(tmpdir(), 'isogami-db-'));
  const file = join(dir, 'copy.db');
  await copyFile(db, file);
  return { file, remove: () => rm(dir, { recursive: true, force: true }) };
}

/** Starts `isogami serve` on 127.0.0.1:0 (on `db`, ISOGAMI_DB by default) and waits for its
 * `listening on http://…` line. */
export async function startServer({ db = env().db, args: extraArgs = [] } = {}) {
  const { bin } = env();
  const child = spawn(bin, ['serve', '--db', db, '--addr', '127.0.0.1:0', ...extraArgs], {
    stdio: ['ignore', 'pipe', 'pipe'],
  });
  let stderr = '';
  child.stderr.on('data', (d) => {
    stderr += d;
  });
  const base = await new Promise((ok, fail) => {
    const timer = setTimeout(() => fail(new Error(`isogami serve did not report its address in 120 s\n${stderr}`)), 120000);
    const lines = createInterface({ input: child.stdout });
    lines.on('line', (line) => {
      const m = /listening on (http:\/\/\S+)/.exec(line);
      if (m) {
        clearTimeout(timer);
        ok(m[1].replace(/\/$/, ''));
      }
    });
    child.on('exit', (code) => {
      clearTimeout(timer);
      fail(new Error(`isogami serve exited with ${code}\n${stderr}`));
    });
  });
  child.stdout.resume();
  return {
    base,
    stderr: () => stderr,
    async stop() {
      if (child.exitCode === null) {
        const gone = new Promise((ok) => child.once('exit', ok));
        child.kill('SIGTERM');
        await gone;
      }
    },
    /** Sends SIGINT (Ctrl-C: a graceful shutdown) and resolves with the exit code, or null
     * when the server is still running after `ms`. */
    async interrupt(ms) {
      if (child.exitCode !== null) return child.exitCode;
      const gone = new Promise((ok) => child.once('exit', (code) => ok(code)));
      child.kill('SIGINT');
      return Promise.race([gone, new Promise((ok) => setTimeout(() => ok(null), ms))]);
    },
  };
}

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.svg': 'image/svg+xml',
  '.gif': 'image/gif',
  '.png': 'image/png',
  '.csv': 'text/csv',
};

/** Registers a test file's hooks for a read-only `isogami serve` and a browser: `use(server,
 * browser)` is called once both are up; both are stopped after the file's tests. */
export function readOnlySession(use) {
  let server;
  let browser;
  before(async () => {
    server = await startServer({ args: ['--read-only'] });
    browser = await launchBrowser();
    use(server, browser);
  });
  after(async () => {
    await browser?.close();
    await server?.stop();
  });
}

/** A plain static file server over `root` on a free port (GET only, no listing). */
export async function serveFolder(root, prefix = '') {
  const top = resolve(root);
  const server = createServer(async (req, res) => {
    try {
      let path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
      if (!path.startsWith(`${prefix}/`)) throw new Error('outside');
      path = path.slice(prefix.length);
      if (path.endsWith('/')) path += 'index.html';
      const file = normalize(join(top, path));
      if (file !== top && !file.startsWith(top + sep)) throw new Error('outside');
      if (!(await stat(file)).isFile()) throw new Error('not a file');
      const body = await readFile(file);
      res.writeHead(200, { 'content-type': TYPES[extname(file)] || 'application/octet-stream' });
      res.end(body);
    } catch {
      res.writeHead(404, { 'content-type': 'text/plain' });
      res.end('not found');
    }
  });
  await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
  return {
    base: `http://127.0.0.1:${server.address().port}${prefix}`,
    stop: () => new Promise((ok) => server.close(ok)),
  };
}

/** Runs `isogami site --db $ISOGAMI_DB --out <tmp>` and returns the folder. */
export async function buildSite() {
  const { bin, db } = env();
  const out = await mkdtemp(join(tmpdir(), 'isogami-site-'));
  await promisify(execFile)(bin, ['site', '--db', db, '--out', out], { maxBuffer: 64 << 20 });
  return { dir: out, remove: () => rm(out, { recursive: true, force: true }) };
}

/** Chromium from the system (CHROMIUM or /usr/bin/chromium), headless. */
export async function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--headless', '--no-sandbox'],
  });
}

/** A page that records script errors, console errors and HTTP error responses (tests assert
 * on them with `problems`). The browser's own "Failed to load resource" console lines are left
 * to the response records, which name the URL. */
export async function newPage(browser) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 1000 }, acceptDownloads: true });
  const page = await context.newPage();
  page.errors = [];
  page.on('pageerror', (e) => page.errors.push(`pageerror: ${e.message}`));
  page.on('console', (m) => {
    if (m.type() === 'error' && !m.text().startsWith('Failed to load resource')) page.errors.push(`console: ${m.text()}`);
  });
  page.on('response', (r) => {
    if (r.status() >= 400) page.errors.push(`${r.status()} ${r.request().method()} ${r.url()}`);
  });
  page.on('requestfailed', (r) => {
    const why = r.failure()?.errorText ?? '';
    if (!/ERR_ABORTED/.test(why)) page.errors.push(`failed ${r.url()}: ${why}`);
  });
  return page;
}

/** The errors of `page` that no pattern of `expected` matches. (Every page first fetches
 * ./data/site.json to learn its mode; the server answers it too, so it is no 404 there.) */
export function problems(page, expected = []) {
  return page.errors.filter((e) => !expected.some((re) => re.test(e)));
}

/** JSON of a URL (for comparing the page against the API). */
export async function getJson(url) {
  const res = await fetch(url);
  if (!res.ok) throw new Error(`${res.status} for ${url}: ${await res.text()}`);
  return res.json();
}

/** Number of distinct colours in a PNG, decoded by the browser. */
export async function distinctColours(browser, png) {
  const page = await browser.newPage();
  try {
    return await page.evaluate(async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(img, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      const seen = new Set();
      for (let i = 0; i < d.length; i += 4) seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
      return seen.size;
    }, png.toString('base64'));
  } finally {
    await page.close();
  }
}

/** Saves a full-page screenshot to artifacts/<name>.png and returns its distinct colour count. */
export async function screenshot(browser, page, name) {
  await mkdir(ARTIFACTS, { recursive: true });
  const png = await page.screenshot({ fullPage: true, path: join(ARTIFACTS, `${name}.png`) });
  return distinctColours(browser, png);
}

/** The RGBA pixels of a canvas on the page, as a plain array. */
export async function canvasPixels(page, selector) {
  return page.$eval(selector, (c) => Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data));
}

/** How many pixels differ between two RGBA arrays of the same canvas. */
export function pixelsChanged(a, b) {
  if (a.length !== b.length) return Math.max(a.length, b.length) / 4;
  let n = 0;
  for (let i = 0; i < a.length; i += 4) {
    if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2] || a[i + 3] !== b[i + 3]) n += 1;
  }
  return n;
}

/** The number of distinct colours among a canvas's pixels. */
export function canvasColours(pixels) {
  const seen = new Set();
  for (let i = 0; i < pixels.length; i += 4) seen.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
  return seen.size;
}

/** A page's text content of `[data-testid=…]`. */
export function byTestId(page, id) {
  return page.locator(`[data-testid="${id}"]`);
}

/** Waits until the catalogue shows a number in its total. */
export async function catalogueTotal(page) {
  await page.waitForFunction(() => /^\d+$/.test(document.querySelector('[data-testid="total"]')?.textContent ?? ''));
  return Number(await byTestId(page, 'total').textContent());
}

/** Parses CSV text (RFC 4180: quoted fields with doubled quotes, commas and line breaks). */
export function parseCsv(text) {
  const rows = [];
  let row = [];
  let field = '';
  let quoted = false;
  for (let i = 0; i < text.length; i += 1) {
    const c = text[i];
    if (quoted) {
      if (c === '"' && text[i + 1] === '"') {
        field += '"';
        i += 1;
      } else if (c === '"') quoted = false;
      else field += c;
    } else if (c === '"') quoted = true;
    else if (c === ',') {
      row.push(field);
      field = '';
    } else if (c === '\n') {
      row.push(field);
      rows.push(row);
      row = [];
      field = '';
    } else if (c !== '\r') field += c;
  }
  if (field !== '' || row.length) {
    row.push(field);
    rows.push(row);
  }
  return rows;
}

/** Every row of /api/designs under a query string, paging through the API. */
export async function allApiRows(base, query = '') {
  const rows = [];
  for (;;) {
    const sep = query ? '&' : '';
    const page = await getJson(`${base}/api/designs?${query}${sep}limit=500&offset=${rows.length}`);
    rows.push(...page.rows);
    if (!page.rows.length || rows.length >= page.total) return rows;
  }
}

/** Text of a download triggered by `click()`. */
export async function downloadText(page, click) {
  const [dl] = await Promise.all([page.waitForEvent('download'), click()]);
  const path = await dl.path();
  return { name: dl.suggestedFilename(), text: await readFile(path, 'utf8') };
}

/** Opens the design page of `spec` on the server at `base` and waits for its first
 * deployment to be shown. */
export async function openDesign(page, base, spec, extra = '') {
  await page.goto(`${base}/design.html?spec=${encodeURIComponent(spec)}${extra}`);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
}

/** Waits until a live edit on the design page is over: no shape-follow request in flight or
 * waiting (the editor's `data-following`) and no deployment in flight or waiting (the body's
 * `simulating` class), so the page shows — or refuses — the last design asked for. */
export async function liveSettled(page, timeout = 60000) {
  await page.waitForFunction(
    () => !document.body.classList.contains('simulating') && document.getElementById('editor')?.dataset.following !== 'true',
    null,
    { timeout },
  );
}

/** A response whose body was read the moment it finished loading: `status()` and `json()`
 * like a playwright Response, but usable after the page has moved on. (A Response's body is
 * fetched from the browser on demand; once the page aborts that request — a live queue
 * superseding it — or navigates, the body is gone, and a test that reads it after its next
 * interaction fails now and then: "Response body is not available …".) */
function readAnswer(status, url, text) {
  return {
    status: () => status,
    url: () => url,
    text: async () => text,
    json: async () => JSON.parse(text),
  };
}

/** The next request of `page` that matches `match(request)` and finishes loading (an aborted
 * or failed one does not count), with its body read at once (readAnswer). Call it before the
 * interaction that sends the request. `status` (optional) also filters on the response's
 * status. */
export function nextAnswer(page, match, { status = null, timeout = 60000 } = {}) {
  return new Promise((ok, fail) => {
    let done = false;
    const stop = () => {
      done = true;
      page.off('requestfinished', listener);
      clearTimeout(timer);
    };
    const timer = setTimeout(() => {
      stop();
      fail(new Error(`no finished request matched in ${timeout} ms`));
    }, timeout);
    const listener = async (req) => {
      if (done || !match(req)) return;
      try {
        const res = await req.response();
        if (!res || done || (status !== null && res.status() !== status)) return;
        const text = (await res.body()).toString('utf8');
        if (done) return;
        stop();
        ok(readAnswer(res.status(), req.url(), text));
      } catch (e) {
        if (!done) {
          stop();
          fail(e);
        }
      }
    };
    page.on('requestfinished', listener);
  });
}

/** Records every finished request of `page` matching `match`, bodies read at once; returns
 * `{ answerOf, stop }`: `answerOf(request)` waits (up to 10 s) for that request's answer
 * (readAnswer), or null when it never finished (aborted or failed: the page never used it). */
export function recordAnswers(page, match) {
  const reads = new Map();
  const listener = (req) => {
    if (!match(req)) return;
    reads.set(req, (async () => {
      const res = await req.response();
      return res && readAnswer(res.status(), req.url(), (await res.body()).toString('utf8'));
    })().catch(() => null));
  };
  page.on('requestfinished', listener);
  return {
    async answerOf(req) {
      const res = await req.response().catch(() => null);
      if (res) await res.finished();
      else return null;
      const end = Date.now() + 10000;
      while (!reads.has(req) && Date.now() < end) await new Promise((ok) => setTimeout(ok, 20));
      return reads.get(req) ?? null;
    },
    stop: () => page.off('requestfinished', listener),
  };
}

const isDeploy = (r) => r.url().endsWith('/api/deploy') && r.method() === 'POST';

/** Presses `key` `times` on the design page's slider `testid`, waits for the first deployment
 * the presses start to finish and then for the edit to settle (liveSettled); the answer
 * (readAnswer) to the last deployment asked for, the one the page now shows (200) or refuses.
 * Every body is read as its request finishes: an earlier deployment aborted by a later one
 * has none. */
export async function moveSlider(page, testid, key, times) {
  const asked = [];
  const onRequest = (r) => {
    if (isDeploy(r)) asked.push(r);
  };
  page.on('request', onRequest);
  const record = recordAnswers(page, isDeploy);
  try {
    const first = nextAnswer(page, isDeploy);
    const slider = byTestId(page, testid);
    await slider.focus();
    for (let k = 0; k < times; k += 1) await slider.press(key);
    await first;
    await liveSettled(page);
    const last = asked[asked.length - 1];
    const answer = await record.answerOf(last);
    if (!answer) throw new Error(`the last deployment asked for (${asked.length} asked) did not finish`);
    return answer;
  } finally {
    page.off('request', onRequest);
    record.stop();
  }
}

/** Retries `read()` (every `every` ms) until `ok(value)` or `timeout` ms have passed; the last
 * value read (the caller asserts on it, so a timeout fails with the caller's message). */
export async function pollUntil(read, ok, { timeout = 10000, every = 50 } = {}) {
  const end = Date.now() + timeout;
  let value = await read();
  while (!ok(value) && Date.now() < end) {
    await new Promise((done) => setTimeout(done, every));
    value = await read();
  }
  return value;
}
