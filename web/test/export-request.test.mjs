// The export panel's request builders: the query of GET /api/export and the CLI command say
// the same thing (the command, split as a shell splits it, gives back every query pair as a
// flag); settings only of the groups a format uses; file names as the server gives them.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  attachmentName, cliCommand, exportFileName, exportPairs, exportParams, fieldsOf, patchProblem, shellWord, usesState,
} from '../src/export-request.js';
import { shellSplit } from './shell.mjs';

// A catalogue of the shape GET /api/export/formats serves.
const catalog = {
  formats: [
    { name: 'svg', description: 'laser', extension: 'svg', settings: ['laser'], uses_state: false },
    { name: 'fold', description: 'FOLD', extension: 'fold', settings: [], uses_state: true },
    { name: 'kirigami-sim', description: 'files', extension: null, settings: [] },
  ],
  settings: [
    {
      name: 'laser',
      label: 'Laser cutting',
      fields: [
        { name: 'material', kind: 'choice', default: null, choices: [{ value: 'card', sets: { hinge_mm: 1 } }] },
        { name: 'hinge_mm', kind: 'number', default: 1.5 },
        { name: 'cut_colour', kind: 'colour', default: '#000000' },
        { name: 'labels', kind: 'flag', default: false },
      ],
    },
  ],
  defaults: { rows: 6, cols: 6, edge_mm: 20, t: 0, kerf: 0.01, frames: 11 },
  limits: { max_patch: 40, max_frames: 100, max_tiles: 1800 },
};

const form = (extra = {}) => ({
  spec: 'IH1:0.12,0.5:2x1:--bbb-',
  kerf: 0.01,
  t: 0.123456,
  format: 'svg',
  rows: 2,
  cols: 3,
  scale: 'edge',
  mm: 15,
  state: 'current',
  settings: {},
  ...extra,
});

/** The query pairs a command line stands for (flags back to keys; --out dropped). */
function pairsOfCommand(line) {
  const words = shellSplit(line);
  assert.deepEqual(words.slice(0, 2), ['isogami', 'export']);
  const pairs = [];
  for (let i = 2; i < words.length; i += 1) {
    const key = words[i].replace(/^--/, '').replace(/-/g, '_');
    if (key === 'out') {
      i += 1;
      continue;
    }
    if (key === 'labels' || key === 'raw') pairs.push([key, 'true']);
    else {
      pairs.push([key, words[i + 1]]);
      i += 1;
    }
  }
  return pairs;
}

test('the CLI command carries exactly the query of the download', () => {
  const cases = [
    form(),
    form({ state: 'open', scale: 'width', mm: 300, kerf: 0.02 }),
    form({ state: 'closed', settings: { laser: { material: 'card', hinge_mm: '0.8', labels: true, cut_colour: '#ff00ff' } } }),
    form({ spec: "{\"family\": \"it's\"}", format: 'fold', settings: { laser: { hinge_mm: '9' } } }),
    form({ sheet: 'raw', format: 'fold' }),
    form({ sheet: 'completed', state: 'closed' }),
  ];
  for (const f of cases) {
    const pairs = exportPairs(f, catalog);
    assert.deepEqual(pairsOfCommand(cliCommand(f, catalog)), pairs, JSON.stringify(f));
    assert.deepEqual([...exportParams(f, catalog)], pairs);
  }
});

test('the query holds the state, the scale and only the settings the format uses', () => {
  const get = (f, key) => new Map(exportPairs(f, catalog)).get(key);
  const fold = (extra) => form({ format: 'fold', ...extra });
  assert.equal(get(fold(), 't'), '0.123');
  assert.equal(get(fold({ state: 'open' }), 't'), 'open');
  assert.equal(get(fold({ state: 'closed' }), 't'), '0');
  assert.equal(get(form(), 'patch'), '2x3');
  assert.equal(get(form(), 'edge_mm'), '15');
  assert.equal(get(form({ scale: 'width' }), 'width_mm'), '15');
  assert.equal(get(form({ scale: 'width' }), 'edge_mm'), undefined);
  // The default kerf is left out, another one is sent.
  assert.equal(get(form(), 'kerf'), undefined);
  assert.equal(get(form({ kerf: 0.05 }), 'kerf'), '0.05');
  const laser = { laser: { hinge_mm: '2', labels: true } };
  assert.equal(get(form({ settings: laser }), 'hinge_mm'), '2');
  assert.equal(get(form({ settings: laser }), 'labels'), 'true');
  assert.equal(get(form({ format: 'fold', settings: laser }), 'hinge_mm'), undefined);
  assert.equal(get(form({ settings: { laser: { labels: false } } }), 'labels'), undefined);
  // Values of a group the format does not use are never sent, even under a shared key.
  const shared = {
    ...catalog,
    formats: [...catalog.formats, { name: 'stl', extension: 'stl', settings: ['print'] }],
    settings: [...catalog.settings, { name: 'print', fields: [{ name: 'hinge_mm', kind: 'number', default: 1 }] }],
  };
  const both = { laser: { hinge_mm: '2' }, print: { hinge_mm: '3' } };
  assert.equal(new Map(exportPairs(form({ format: 'stl', settings: both }), shared)).get('hinge_mm'), '3');
  assert.equal(new Map(exportPairs(form({ format: 'svg', settings: both }), shared)).get('hinge_mm'), '2');
  assert.deepEqual(fieldsOf(catalog, 'fold'), []);
  assert.deepEqual(fieldsOf(catalog, 'svg').map((f) => f.name), ['material', 'hinge_mm', 'cut_colour', 'labels']);
});

test('the completed sheet is the default; the raw rectangle is raw=true and --raw', () => {
  const get = (f, key) => new Map(exportPairs(f, catalog)).get(key);
  // Nothing is sent for the completed sheet: the server's and the CLI's default.
  assert.equal(get(form(), 'raw'), undefined);
  assert.equal(get(form({ sheet: 'completed' }), 'raw'), undefined);
  assert.equal(get(form(), 'complete'), undefined);
  assert.equal(get(form({ sheet: 'raw' }), 'raw'), 'true');
  const words = shellSplit(cliCommand(form({ sheet: 'raw' }), catalog));
  assert.ok(words.includes('--raw'));
  // A bare flag: the next word is another flag.
  assert.match(words[words.indexOf('--raw') + 1], /^--/);
  assert.ok(!shellSplit(cliCommand(form(), catalog)).some((w) => w === '--raw' || w === '--complete'));
});

test('file names are the server’s, and the CLI writes a folder format to a folder', () => {
  const [svg, , sim] = catalog.formats;
  assert.equal(exportFileName('IH1:0.12,0.5:2x1:--bbb-', 2, 3, svg), 'IH1_0.12~0.5_2x1_--bbb--2x3.svg');
  assert.equal(exportFileName('IH1:0.5:1x1:a', 4, 4, sim), 'IH1_0.5_1x1_a-4x4.kirigami-sim.zip');
  const line = cliCommand(form({ format: 'kirigami-sim' }), catalog);
  assert.match(line, / --out IH1_0\.12~0\.5_2x1_--bbb--2x3\.kirigami-sim$/);
});

test('Content-Disposition names are read, never as paths', () => {
  assert.equal(attachmentName('attachment; filename="a-2x3.svg"'), 'a-2x3.svg');
  assert.equal(attachmentName('attachment; filename=b.fold'), 'b.fold');
  assert.equal(attachmentName('attachment; filename="../../x"'), '.._.._x');
  assert.equal(attachmentName(''), null);
  assert.equal(attachmentName(null), null);
});

test('shell words: bare when safe, quoted otherwise', () => {
  assert.equal(shellWord('6x6'), '6x6');
  assert.equal(shellWord('#ff0000'), "'#ff0000'");
  assert.equal(shellWord("it's"), "'it'\\''s'");
  assert.equal(shellWord('-x'), "'-x'");
  assert.equal(shellWord('~x'), "'~x'");
  assert.equal(shellWord('a~b'), 'a~b');
  assert.deepEqual(shellSplit(`a ${shellWord("it's")} b`), ['a', "it's", 'b']);
});

test('a laser file has no state: neither the query nor the command names a t', () => {
  assert.equal(usesState(catalog, 'svg'), false);
  assert.equal(usesState(catalog, 'fold'), true);
  assert.equal(usesState(catalog, 'kirigami-sim'), true, 'a catalogue without the flag: the state counts');
  for (const state of ['closed', 'current', 'open']) {
    const laser = form({ state });
    assert.equal(exportParams(laser, catalog).get('t'), null, state);
    assert.ok(!shellSplit(cliCommand(laser, catalog)).includes('--t'), state);
    assert.equal(cliCommand(laser, catalog), cliCommand(form({ state: 'closed' }), catalog), 'the same command whatever the radio says');
  }
  assert.equal(exportParams(form({ format: 'fold', state: 'open' }), catalog).get('t'), 'open');
  assert.equal(exportParams(form({ format: 'fold', state: 'current' }), catalog).get('t'), '0.123');
});

test('rows × columns are checked against the catalogue limits before any request', () => {
  assert.equal(patchProblem(form(), catalog, 4), null);
  assert.equal(patchProblem(form({ rows: 40, cols: 1 }), catalog, 45), null, '1800 tiles is allowed');
  const big = patchProblem(form({ rows: 999 }), catalog, 4);
  assert.equal(big.field, 'rows');
  assert.match(big.message, /1 to 40/);
  assert.equal(patchProblem(form({ cols: 0 }), catalog, 4).field, 'cols');
  assert.equal(patchProblem(form({ cols: 2.5 }), catalog, 4).field, 'cols');
  assert.equal(patchProblem(form({ rows: Number('') }), catalog, 4).field, 'rows', 'an empty field');
  const many = patchProblem(form({ rows: 40, cols: 40 }), catalog, 6);
  assert.equal(many.field, 'patch');
  assert.equal(many.serverOnly, true);
  assert.match(many.message, /9600 tiles/);
  assert.match(many.message, /at most 1800/);
});
