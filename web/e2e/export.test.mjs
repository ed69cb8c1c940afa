// The design page's "Export / make it" panel over a read-only `isogami serve`, in real
// headless Chromium: a catalogue design downloads as a laser SVG in mm with a cut group
// (parsed in node by an XML parser), and the command line shown under the form writes the
// same bytes; by default the file is the rectangle's completion to one DOF (the tiles of
// GET /api/sheet's completion), and "raw rectangle" writes every tile of the rows × columns,
// each with a command that writes the same bytes; a rectangle without a completion is
// refused in the panel with the library's reason; a changed patch and format (FOLD, 2×3)
// shows in the downloaded file's faces, cells and frames; an edited design exports the edited
// shape; a hinge too wide is explained in the panel and nothing is downloaded.
//
// The CLI's default sheet: the page writes commands for `isogami export` whose default is the
// completed sheet and whose `--raw` writes the rectangle. A binary from before that change
// (default raw, `--complete` to complete, no `--raw`) is detected from its --help, and the
// shown command is then translated (`--complete` added for the completed sheet, `--raw`
// dropped) before it is run; `cliRuns` says which.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { DOMParser } from '@xmldom/xmldom';
import {
  allApiRows, byTestId, env, getJson, launchBrowser, moveSlider, newPage, nextAnswer, problems, screenshot, startServer,
} from './harness.mjs';
import { slug } from '../src/schema.js';

let server;
let browser;
let designs;
let catalog;
/** A design whose 4×4 rectangle completes to a sheet other than the rectangle, with the API's
 * completion; and one whose 4×4 rectangle has no completion (or null). */
let completes = null;
let noCompletion = null;
/** Whether the CLI binary writes the completed sheet by default and takes --raw. */
let newCli = false;

/** The 4×4 finite sheet of a catalogue row, as GET /api/sheet answers (no deployment). */
async function sheetOf(row, region = '4x4') {
  const kerf = Math.abs(row.kerf - catalog.defaults.kerf) > 1e-12 ? `&kerf=${row.kerf}` : '';
  const res = await fetch(`${server.base}/api/sheet?design=${encodeURIComponent(row.spec)}&region=${region}${kerf}`);
  return res.status === 200 ? res.json() : null;
}

before(async () => {
  server = await startServer({ args: ['--read-only'] });
  browser = await launchBrowser();
  catalog = await getJson(`${server.base}/api/export/formats`);
  const all = await allApiRows(server.base);
  designs = all.filter((r) => r.params.length > 0 && r.dof === 1);
  assert.ok(designs.length > 0, 'the test database has a design with shape parameters');
  for (const row of all.filter((r) => r.dof === 1).slice(0, 60)) {
    if (completes && noCompletion) break;
    const a = await sheetOf(row);
    if (!a) continue;
    const c = a.analysis.completion;
    // The catalogue says it has a one-DOF sheet: its panel leaves the completed sheet chosen.
    if (!completes && row.finite_covered !== null && c && c.report.removed.length + c.report.added.length > 0) completes = { row, sheet: a };
    if (!noCompletion && a.refused) noCompletion = { row, sheet: a };
  }
  assert.ok(completes, 'the test database has a design whose 4×4 rectangle completes to another sheet');
  const { stdout } = await promisify(execFile)(env().bin, ['export', '--help']);
  newCli = /--raw\b/.test(stdout);
});

/** The shown command as the CLI binary under test reads it (see the header). */
function cliRuns(command) {
  if (newCli) return command;
  return / --raw( |$)/.test(command) ? command.replace(/ --raw( |$)/, '$1') : `${command} --complete`;
}

/** Runs the command the page shows in a scratch folder; the bytes of `name` it wrote. */
async function runShown(command, name) {
  const dir = await mkdtemp(join(tmpdir(), 'isogami-export-'));
  try {
    await promisify(execFile)('bash', ['-c', `"$ISOGAMI_BIN" ${cliRuns(command).slice('isogami '.length)}`], {
      cwd: dir,
      env: { ...process.env, ISOGAMI_BIN: env().bin },
    });
    return await readFile(join(dir, name));
  } finally {
    await rm(dir, { recursive: true, force: true });
  }
}

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
  const spec = completes.row.spec;
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
  assert.ok((await runShown(command, file.name)).equals(file.bytes), `the CLI wrote the same file (${cliRuns(command)})`);
  // Every field of the panel has a label.
  const unlabelled = await page.$$eval('#export-panel input, #export-panel select', (els) =>
    els.filter((e) => e.labels.length === 0).map((e) => e.id || e.name),
  );
  assert.deepEqual(unlabelled, []);
  assert.ok((await screenshot(browser, page, 'design-export')) > 50);
  assert.deepEqual(problems(page), []);
});

test('the download is the completed sheet by default and the rectangle when raw is chosen; both commands write the same bytes', async () => {
  const page = await newPage(browser);
  const { row, sheet } = completes;
  await openDesign(page, row.spec);
  const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(row.spec)}`);
  const tiles = view.geometry.tiles.length;
  await byTestId(page, 'export-format').selectOption('fold');
  assert.ok(await byTestId(page, 'export-sheet-completed').isChecked(), 'the completed sheet is the default');
  const key = (t) => `${t[0]},${t[1]}#${t[2]}`;
  const completed = await downloadExport(page);
  const commandCompleted = await byTestId(page, 'export-command').textContent();
  assert.doesNotMatch(commandCompleted, /--raw|--complete/);
  const fold = JSON.parse(completed.bytes.toString('utf8'));
  const want = sheet.analysis.completion.sheet.tiles.map((t) => key([t.cell[0], t.cell[1], t.tile])).sort();
  assert.deepEqual(fold['faces_isogami:tile'].map(key).sort(), want, 'the file holds the API’s completed sheet');
  assert.notEqual(fold.faces_vertices.length, 16 * tiles);
  assert.doesNotMatch(await byTestId(page, 'export-status').textContent(), /warning/);

  await byTestId(page, 'export-sheet-raw').check();
  const commandRaw = await byTestId(page, 'export-command').textContent();
  assert.match(commandRaw, / --raw( |$)/);
  const raw = await downloadExport(page);
  assert.equal(raw.name, completed.name);
  const rect = JSON.parse(raw.bytes.toString('utf8'));
  // The raw rectangle's DOF, as the finite-sheet analysis counts it, in the library's warning.
  const dof = sheet.analysis.raw_mobility.dof;
  if (dof !== 1) assert.match(await byTestId(page, 'export-status').textContent(), new RegExp(`warning: .*\\b${dof} degrees of freedom`));
  assert.equal(rect.faces_vertices.length, 16 * tiles);
  const cells = new Set(rect['faces_isogami:tile'].map(([i, j]) => `${i},${j}`));
  assert.equal(cells.size, 16);
  for (const c of cells) assert.match(c, /^[0-3],[0-3]$/);

  assert.ok((await runShown(commandCompleted, completed.name)).equals(completed.bytes), `the completed sheet's command (${cliRuns(commandCompleted)})`);
  assert.ok((await runShown(commandRaw, raw.name)).equals(raw.bytes), `the raw rectangle's command (${cliRuns(commandRaw)})`);
  assert.deepEqual(problems(page), []);
});

test('a rectangle without a one-DOF completion is refused in the panel with the library’s reason; raw downloads', async (t) => {
  if (!noCompletion) {
    t.skip('no design of the test database refuses its 4×4 completion');
    return;
  }
  const page = await newPage(browser);
  await openDesign(page, noCompletion.row.spec);
  await byTestId(page, 'export-format').selectOption('fold');
  let downloads = 0;
  page.on('download', () => {
    downloads += 1;
  });
  // A design the catalogue knows has no one-DOF sheet gets the raw rectangle chosen before any
  // click (buildable.test.mjs); the completed sheet, chosen anyway, is refused with the reason.
  await byTestId(page, 'export-sheet-completed').check();
  const response = nextAnswer(page, (r) => r.url().includes('/api/export?'));
  await byTestId(page, 'export-download').click();
  const res = await response;
  assert.equal(res.status(), 422);
  const body = await res.json();
  assert.equal(body.kind, 'no_one_dof_sheet');
  // The same reason as the finite-sheet analysis of that rectangle.
  assert.ok(body.error.includes(noCompletion.sheet.refused.replace(/^no one-DOF sheet in this region: /, '')), `${body.error} / ${noCompletion.sheet.refused}`);
  const error = byTestId(page, 'export-error');
  await error.waitFor({ state: 'visible' });
  assert.equal(await error.locator('strong').textContent(), body.error);
  assert.match(await error.textContent(), /raw/);
  await page.waitForTimeout(300);
  assert.equal(downloads, 0);
  await byTestId(page, 'export-sheet-raw').check();
  const file = await downloadExport(page);
  assert.ok(JSON.parse(file.bytes.toString('utf8')).faces_vertices.length > 0);
  assert.ok(await error.isHidden());
  assert.deepEqual(problems(page, [/^422 GET \S+\/api\/export\?/]), []);
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
  // The rectangle as it is (the completed sheet is the test above).
  await byTestId(page, 'export-sheet-raw').check();
  await byTestId(page, 'export-rows').fill('2');
  await byTestId(page, 'export-cols').fill('3');
  await byTestId(page, 'export-state-open').check();
  assert.match(await byTestId(page, 'export-command').textContent(), /--format fold --patch 2x3 .*--t open.* --raw/);
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
    // The key presses may start more than one live deployment; once the edit has settled the
    // page shows the last one asked for, which is the edited design.
    const last = await moveSlider(page, 'param-v0', key, 6);
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
    // The rectangle: an edit may change which tiles a completion keeps.
    await byTestId(page, 'export-sheet-raw').check();
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
  const response = nextAnswer(page, (r) => r.url().includes('/api/export?'));
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

test('a laser file is the closed sheet: the state is disabled with the reason, the command has no --t, and formats that use it keep it', async () => {
  const page = await newPage(browser);
  const spec = completes.row.spec;
  await openDesign(page, spec);
  const command = () => byTestId(page, 'export-command').textContent();
  assert.equal(await byTestId(page, 'export-format').inputValue(), 'svg');
  const fieldsetDisabled = () => byTestId(page, 'export-state').evaluate((f) => f.disabled);
  assert.equal(await fieldsetDisabled(), true, 'the state fieldset is disabled for SVG');
  for (const s of ['closed', 'current', 'open']) assert.equal(await byTestId(page, `export-state-${s}`).isDisabled(), true);
  assert.match(await byTestId(page, 'export-state-note').textContent(), /closed/);
  assert.equal(await byTestId(page, 'export-state-note').isVisible(), true);
  assert.doesNotMatch(await command(), / --t /, 'no state in the laser command');

  await byTestId(page, 'export-format').selectOption('fold');
  assert.equal(await fieldsetDisabled(), false, 'FOLD uses the state');
  assert.equal(await byTestId(page, 'export-state-note').isVisible(), false);
  await byTestId(page, 'export-state-open').check();
  assert.match(await command(), / --t open /);
  await byTestId(page, 'export-format').selectOption('dxf');
  assert.doesNotMatch(await command(), / --t /, 'DXF: no state either');

  // The download asks for no state, and the command shown writes the same bytes.
  const asked = [];
  page.on('request', (r) => r.url().includes('/api/export?') && asked.push(new URL(r.url()).searchParams));
  const file = await downloadExport(page);
  assert.equal(asked.length, 1);
  assert.equal(asked[0].get('t'), null);
  assert.ok((await runShown(await command(), file.name)).equals(file.bytes), 'the CLI wrote the same DXF');
  assert.deepEqual(problems(page), []);
});

test('rows × columns beyond the server’s limits are refused beside the field before any request', async () => {
  const page = await newPage(browser);
  const spec = completes.row.spec;
  await openDesign(page, spec);
  const asked = [];
  page.on('request', (r) => r.url().includes('/api/export?') && asked.push(r.url()));
  const error = byTestId(page, 'export-patch-error');
  assert.equal(await error.isVisible(), false);
  await byTestId(page, 'export-rows').fill('999');
  assert.equal(await error.isVisible(), true);
  assert.match(await error.textContent(), new RegExp(`rows: a whole number from 1 to ${catalog.limits.max_patch}`));
  assert.equal(await byTestId(page, 'export-download').isDisabled(), true, 'Download is disabled');
  assert.equal(await byTestId(page, 'export-rows').getAttribute('aria-invalid'), 'true');
  // Beside the field: just under the rows × columns row.
  // Both boxes in one layout (two separate reads straddled a late layout shift once: the
  // message 67 px below a field read before the shift).
  const [field, box] = await page.evaluate(() =>
    ['export-rows', 'export-patch-error'].map((id) => {
      const r = document.querySelector(`[data-testid="${id}"]`).getBoundingClientRect();
      return { y: r.y, height: r.height };
    }),
  );
  assert.ok(box.y >= field.y && box.y - (field.y + field.height) < 40, `the message is beside the field (${box.y} vs ${field.y})`);

  // Within the library's limit but over the server's tile cap.
  const tiles = (await getJson(`${server.base}/api/design?spec=${encodeURIComponent(spec)}`)).geometry.tiles.length;
  const max = catalog.limits.max_patch;
  if (max * max * tiles > catalog.limits.max_tiles) {
    await byTestId(page, 'export-rows').fill(String(max));
    await byTestId(page, 'export-cols').fill(String(max));
    assert.match(await error.textContent(), new RegExp(`${max * max * tiles} tiles: the server exports at most ${catalog.limits.max_tiles}`));
    assert.equal(await byTestId(page, 'export-download').isDisabled(), true);
    // The server agrees: it refuses that rectangle.
    const res = await fetch(`${server.base}/api/export?design=${encodeURIComponent(spec)}&format=svg&patch=${max}x${max}`);
    assert.equal(res.status, 422);
  }
  const over = await fetch(`${server.base}/api/export?design=${encodeURIComponent(spec)}&format=svg&patch=999x4`);
  assert.equal(over.status, 400, 'and the server refuses 999 rows, as the page said');
  await byTestId(page, 'export-rows').fill('2');
  await byTestId(page, 'export-cols').fill('3');
  assert.equal(await error.isVisible(), false);
  assert.equal(await byTestId(page, 'export-download').isDisabled(), false);
  assert.deepEqual(asked, [], 'nothing was asked of the server');
  assert.deepEqual(problems(page), []);
});
