// Cell twins (issue 40): a design found again on another cell of its family (same shape and
// path) is stored once. On its design page the other cells' specs are named; opening a twin's
// own spec shows the design it is stored with, naming the twin. The test makes its own small
// database: IH1 on its 1×2 and 2×1 cells (rotated cells of one family, where twins arise),
// and checks the page against the API for every twin the file holds.

import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { mkdtemp, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { promisify } from 'node:util';
import { allApiRows, byTestId, env, getJson, launchBrowser, newPage, openDesign, problems, startServer } from './harness.mjs';

let dir;
let server;
let browser;
let twins; // [{twin, kept}]

before(async () => {
  dir = await mkdtemp(join(tmpdir(), 'isogami-twins-'));
  const db = join(dir, 'twins.db');
  await promisify(execFile)(env().bin, ['explore', '--families', 'IH1', '--cells', '1x2,2x1', '--samples', '4', '--db', db]);
  server = await startServer({ db, args: ['--read-only'] });
  browser = await launchBrowser();
  const stats = await getJson(`${server.base}/api/stats`);
  assert.ok(stats.cell_twins > 0, 'the database folds twins');
  twins = [];
  for (const row of await allApiRows(server.base)) {
    const view = await getJson(`${server.base}/api/design?spec=${encodeURIComponent(row.spec)}`);
    for (const twin of view.other_cells) twins.push({ twin, kept: row.spec });
  }
  assert.equal(twins.length, stats.cell_twins, 'every folded spec is listed by its design');
});

after(async () => {
  await browser?.close();
  await server?.stop();
  if (dir) await rm(dir, { recursive: true, force: true });
});

test('a design page names its other cells, and a twin spec opens the design it is stored with', async () => {
  const page = await newPage(browser);
  for (const { twin, kept } of twins) {
    await openDesign(page, server.base, kept);
    const line = byTestId(page, 'other-cells');
    assert.equal(await line.isVisible(), true, kept);
    const text = await line.textContent();
    assert.ok(text.includes(twin), `${kept}: ${text}`);
    assert.ok(text.includes(twin.split(':')[2].replace('x', '×')), text);

    await openDesign(page, server.base, twin);
    assert.equal(await byTestId(page, 'spec').textContent(), kept);
    assert.ok((await byTestId(page, 'other-cells').textContent()).includes(twin));
  }
  // A design without twins shows no such line.
  const alone = (await allApiRows(server.base)).find((r) => !twins.some((t) => t.kept === r.spec));
  if (alone) {
    await openDesign(page, server.base, alone.spec);
    assert.equal(await byTestId(page, 'other-cells').isVisible(), false);
  }
  assert.deepEqual(problems(page), []);
});
