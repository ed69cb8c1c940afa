// The design page's "Export / make it" panel over a read-only `isogami serve`, in real
// headless Chromium: a catalogue design downloads as a laser SVG in mm with a cut group
// (parsed in node by an XML parser), and the command line shown under the form writes the
// same bytes; a changed patch and format (FOLD, 2×3) shows in the downloaded file's faces,
// cells and frames; an edited design exports the edited shape; a hinge too wide is explained
// in the panel and nothing is downloaded.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { DOMParser } from '@xmldom/xmldom';
import { allApiRows, byTestId, env, getJson, launchBrowser, newPage, problems, screenshot, startServer } from './harness.mjs';
import { slug } from '../src/schema.js';

let server;
let browser;
let designs;

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  designs = (await allApiRows(server.base)).filter((r) => r.params.length > 0 && r.dof === 1);
  assert.ok(designs.length > 0, 'the test database has a design with shape parameters');
});

after(async () => {
  await browser?.close();
  await server?.stop();
});

async function openDesign(page, spec) {
  await page.goto(`${server.base}/design.html?spec=${encodeURIComponent(spec)}`);
  await page.waitForFunction(() => Number(document.body.dataset.deployments || 0) >= 1);
  await page.waitForFunction(() => document.querySelectorAll('[data-testid="export-format"] option').length > 0);
}

/** Clicks Download and returns the file's name and bytes. */
async function downloadExport(page) {
  const [dl] = await Promise.all([page.waitForEvent('download'), byTestId(page, 'export-download').click()]);
  return { name: dl.suggestedFilename(), bytes: await readFile(await dl.path()) };
}

const mm = (text) => {
  const m = /^(\d+(?:\.\d+)?)mm$/.exec(text ?? '');
  assert.ok(m, `${text} is a length in mm`);
  return Number(m[1]);
};

test('a catalogue design downloads as a laser SVG in mm, and the CLI command writes the same file', async () => {
  const page = await newPage(browser);
  const spec = designs[0].spec;
  await openDesign(page, spec);
  assert.equal(await byTestId(page, 'export-format').inputValue(), 'svg');
  assert.match(await byTestId(page, 'export-format-help').textContent(), /laser/);
  await byTestId(page, 'export-laser-hinge_mm').waitFor({ state: 'visible' });
  const file = await downloadExport(page);
  assert.equal(file.name, `${slug(spec)}-4x4.svg`);

  const doc = new DOMParser().parseFromString(file.bytes.toString('utf8'), 'image/svg+xml');
  const svg = doc.documentElement;
  assert.equal(svg.tagName, 'svg');
  const [width, height] = [mm(svg.getAttribute('width')), mm(svg.getAttribute('height'))];
  const box = svg.getAttribute('viewBox').split(/\s+/).map(Number);
  assert.equal(box.length, 4);
  assert.ok(Math.abs(box[2] - width) < 1e-6 && Math.abs(box[3] - height) < 1e-6, 'one user unit is 1 mm');
  assert.ok(width > 20 && height > 20, `${width} × ${height} mm`);
  const groups = Array.from(svg.getElementsByTagName('g'));
  const cut = groups.find((g) => g.getAttribute('id') === 'cut');
  assert.ok(cut, 'a cut group');
  const paths = Array.from(cut.getElementsByTagName('path'));
  assert.ok(paths.length > 16, `${paths.length} cut paths`);
  for (const p of paths) assert.match(p.getAttribute('d'), /^M[-\d.]+ [-\d.]+ L/);
  const desc = svg.getElementsByTagName('desc')[0].textContent;
  assert.ok(desc.includes(spec), 'the metadata names the design');

  // The command shown under the form writes the same bytes.
  const command = await byTestId(page, 'export-command').textContent();
  assert.ok(command.startsWith(`isogami export --design '${spec}' --format svg --patch 4x4`), command);
  const dir = await mkdtemp(join(tmpdir(), 'isogami-export-'));
  try {
    await promisify(execFile)('bash', ['-c', `"$ISOGAMI_BIN" ${command.slice('isogami '.length)}`], {
      cwd: dir,
      env: { ...process.env, ISOGAMI_BIN: env().bin },
    });
    assert.ok((await readFile(join(dir, file.name))).equals(file.bytes), 'the CLI wrote the same file');
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
  // Every field of the panel has a label.
  const unlabelled = await page.$$eval('#export-panel input, #export-panel select', (els) =>
    els.filter((e) => e.labels.length === 0).map((e) => e.id || e.name),
  );
  assert.deepEqual(unlabelled, []);
  assert.ok((await screenshot(browser, page, 'design-export')) > 50);
  assert.deepEqual(problems(page), []);
});

test('a 2×3 FOLD download has the patch’s faces, cells and frames', async () => {
  const page = await newPage(browser);
  const spec = designs[0].spec;
  await openDesign(page, spec);
  const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(spec)}`);
  const catalog = await getJson(`${server.base}/api/export/formats`);
  const tiles = view.geometry.tiles;
  await byTestId(page, 'export-format').selectOption('fold');
  assert.ok(await byTestId(page, 'export-group-laser').isHidden(), 'laser settings hidden for FOLD');
  await byTestId(page, 'export-rows').fill('2');
  await byTestId(page, 'export-cols').fill('3');
  await byTestId(page, 'export-state-open').check();
  assert.match(await byTestId(page, 'export-command').textContent(), /--format fold --patch 2x3 .*--t open/);
  const file = await downloadExport(page);
  assert.equal(file.name, `${slug(spec)}-2x3.fold`);
  const fold = JSON.parse(file.bytes.toString('utf8'));
  assert.equal(fold.faces_vertices.length, 2 * 3 * tiles.length);
  const cells = new Set(fold['faces_isogami:tile'].map(([i, j]) => `${i},${j}`));
  assert.deepEqual([...cells].sort(), ['0,0', '0,1', '1,0', '1,1', '2,0', '2,1']);
  const vertices = 2 * 3 * tiles.reduce((n, poly) => n + poly.length, 0);
  assert.equal(fold.vertices_coords.length, vertices);
  assert.equal(fold.file_frames.length, catalog.defaults.frames);
  for (const f of fold.file_frames) assert.equal(f.vertices_coords.length, vertices);
  // "open" is the state of largest area ratio: the last frame's t or before it.
  assert.ok(fold['isogami:t'] > 0, `t = ${fold['isogami:t']}`);
  assert.equal(fold.frame_unit, 'mm');
  assert.deepEqual(problems(page), []);
});

/** Moves the first shape slider until the server deploys a new shape; the new spec, or null. */
async function editShape(page) {
  for (const key of ['ArrowRight', 'ArrowLeft']) {
    const slider = byTestId(page, 'param-v0');
    await slider.focus();
    // Every live deployment the key presses start; the page shows the last one to answer, so
    // the edited design is the one the last request asked for, once the page has taken it.
    const responses = [];
    const listener = (r) => {
      if (r.url().endsWith('/api/deploy') && r.request().method() === 'POST') responses.push(r);
    };
    page.on('response', listener);
    const first = page.waitForResponse((r) => r.url().endsWith('/api/deploy') && r.request().method() === 'POST');
    for (let k = 0; k < 6; k += 1) await slider.press(key);
    await first;
    // Settled: no new deployment for a second.
    let seen = -1;
    while (seen !== responses.length) {
      seen = responses.length;
      await page.waitForTimeout(1000);
    }
    page.off('response', listener);
    const last = responses[responses.length - 1];
    if (last.status() !== 200) continue;
    const spec = (await last.json()).spec;
    await page.waitForFunction((s) => document.title === `${s} · isogami`, spec);
    return spec;
  }
  return null;
}

test('an edited design exports the edited shape', async () => {
  const page = await newPage(browser);
  let done = false;
  for (const design of designs.slice(0, 5)) {
    await openDesign(page, design.spec);
    await byTestId(page, 'export-format').selectOption('fold');
    const before = JSON.parse((await downloadExport(page)).bytes.toString('utf8'));
    assert.equal(before['isogami:design'], design.spec);
    const edited = await editShape(page);
    if (!edited) continue;
    assert.notEqual(edited, design.spec);
    const request = page.waitForRequest((r) => r.url().includes('/api/export?'));
    const file = await downloadExport(page);
    assert.equal(new URL((await request).url()).searchParams.get('design'), edited);
    assert.equal(file.name, `${slug(edited)}-4x4.fold`);
    const after = JSON.parse(file.bytes.toString('utf8'));
    assert.equal(after['isogami:design'], edited);
    assert.equal(after.faces_vertices.length, before.faces_vertices.length);
    assert.notDeepEqual(after.vertices_coords, before.vertices_coords, 'the edited shape differs');
    assert.match(await byTestId(page, 'export-command').textContent(), new RegExp(`--design '${edited.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}'`));
    done = true;
    break;
  }
  assert.ok(done, 'a slider move on one of five designs was deployed');
  assert.deepEqual(problems(page, [/^422 POST \S+\/api\/deploy$/]), []);
});

test('a hinge too wide is explained in the panel and nothing is downloaded', async () => {
  const page = await newPage(browser);
  await openDesign(page, designs[0].spec);
  let downloads = 0;
  page.on('download', () => {
    downloads += 1;
  });
  await byTestId(page, 'export-format').selectOption('svg');
  await byTestId(page, 'export-laser-hinge_mm').fill('1000');
  assert.match(await byTestId(page, 'export-command').textContent(), / --hinge-mm 1000 /);
  const response = page.waitForResponse((r) => r.url().includes('/api/export?'));
  await byTestId(page, 'export-download').click();
  const res = await response;
  assert.equal(res.status(), 400);
  const error = byTestId(page, 'export-error');
  await error.waitFor({ state: 'visible' });
  assert.equal(await error.locator('strong').textContent(), (await res.json()).error);
  assert.match(await error.textContent(), /hinge 1000 mm does not fit/);
  // The keyboard reaches the button: Enter on it asks again, with the same answer.
  const again = page.waitForResponse((r) => r.url().includes('/api/export?'));
  await byTestId(page, 'export-download').focus();
  await page.keyboard.press('Enter');
  assert.equal((await again).status(), 400);
  await error.waitFor({ state: 'visible' });
  await page.waitForTimeout(300);
  assert.equal(downloads, 0, 'no file was saved');
  assert.deepEqual(problems(page, [/^400 GET \S+\/api\/export\?/]), []);
});
