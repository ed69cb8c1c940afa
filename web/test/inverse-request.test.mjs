// The inverse-design page's request builders and table rows: the POST body and the CLI
// command say the same thing (the command, split as a shell splits it, gives back every
// field of the body as a flag); left-out fields stay out; the form check against the
// server's caps; the example targets; rows of the leaders and results tables.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  EXAMPLES, cellText, cliCommand, emptyForm, familyCell, formFromJob, formFromSearch, formProblem, formSearch, historyPoints, inverseBody,
  leaderRows, pair, progressLine, resultRows, sameSearch,
} from '../src/inverse-request.js';
import { shellSplit } from './shell.mjs';

const settings = {
  defaults: { top: 3, budget: 80, samples: 0, kerf: 0.01, refine_kerf: false },
  limits: { top: 5, budget: 200, confirm: 200, triage: 80, samples: 20 },
  save: true,
  database: 'q.db',
};

const form = (extra = {}) => ({ ...emptyForm(settings), target: 'area', ...extra });

/** The body a command line stands for (flags back to fields; --db and --json checked). */
function bodyOfCommand(line) {
  const words = shellSplit(line);
  assert.deepEqual(words.slice(0, 2), ['isogami', 'inverse']);
  assert.equal(words.at(-1), '--json');
  const body = {};
  for (let i = 2; i < words.length - 1; i += 1) {
    const key = words[i].replace(/^--/, '').replace(/-/g, '_');
    if (key === 'refine_kerf') body.refine_kerf = true;
    else if (key === 'db') {
      assert.equal(words[i + 1], 'q.db');
      i += 1;
    } else {
      body[key] = key === 'target' ? words[i + 1] : Number(words[i + 1]);
      i += 1;
    }
  }
  return body;
}

test('the CLI command carries exactly the body of the request', () => {
  const cases = [
    form(),
    form({ target: '  isotropic + 0.5*uniform; tiles<=4 ', top: '2', budget: '6' }),
    form({ target: "lock(0.1,0.3); families=IH28", confirm: '7', triage: '9', samples: '3', kerf: '0.02', refineKerf: true }),
    form({ target: "it's", top: '', budget: '' }),
  ];
  for (const f of cases) {
    const body = inverseBody(f);
    assert.deepEqual(bodyOfCommand(cliCommand(f, 'q.db')), body, JSON.stringify(f));
  }
  assert.deepEqual(inverseBody(cases[1]), { target: 'isotropic + 0.5*uniform; tiles<=4', top: 2, budget: 6 });
  assert.deepEqual(inverseBody(cases[2]), {
    target: 'lock(0.1,0.3); families=IH28', top: 3, budget: 80, confirm: 7, triage: 9, samples: 3, kerf: 0.02, refine_kerf: true,
  });
  // Fields left empty are left out: the CLI's and the server's defaults apply.
  assert.deepEqual(inverseBody(cases[3]), { target: "it's" });
  assert.equal(cliCommand(form({ top: '2', budget: '6' }), 'q.db'), "isogami inverse --target 'area' --db q.db --top 2 --budget 6 --json");
  assert.match(cliCommand(form(), null), / --db isogami\.db /);
});

test('the form is checked against the server’s caps before a round trip', () => {
  assert.equal(formProblem(form(), settings), null);
  assert.match(formProblem(form({ target: '  ' }), settings), /^target: no goal given/);
  assert.equal(formProblem(form({ budget: '201' }), settings), "budget 201 is above this server's limit of 200");
  assert.equal(formProblem(form({ top: '0' }), settings), 'top must be a whole number of at least 1');
  assert.equal(formProblem(form({ top: '1.5' }), settings), 'top must be a whole number of at least 1');
  assert.equal(formProblem(form({ triage: '81' }), settings), "triage 81 is above this server's limit of 80");
  assert.equal(formProblem(form({ budget: '0', samples: '20' }), settings), null);
  assert.equal(formProblem(form({ kerf: '-1' }), settings), 'kerf must be a positive number');
  // Without caps (an older static site) only the lower bounds apply.
  assert.equal(formProblem(form({ budget: '5000' }), {}), null);
  assert.deepEqual(emptyForm(null), { target: '', top: '3', budget: '80', confirm: '', triage: '', samples: '', kerf: '', refineKerf: false });
});

test('the examples cover the kinds of goal, each a target of the README’s syntax', () => {
  const targets = EXAMPLES.map((x) => x.target);
  for (const goal of ['area', 'isotropic', 'lock(', 'path(']) {
    assert.ok(targets.some((t) => t.startsWith(goal)), goal);
  }
  assert.ok(targets.some((t) => t.includes(';')), 'one example has a constraint');
  assert.equal(new Set(EXAMPLES.map((x) => x.label)).size, EXAMPLES.length);
  for (const t of targets) assert.equal(formProblem(form({ target: t }), settings), null, t);
});

const scored = (spec, objective, extra = {}) => ({
  spec,
  kerf: 0.01,
  objective,
  measures: {
    max_area_ratio: 1.5, max_expansion: 0.3, min_expansion: 0.1, poisson: [-1.02, -0.98], end_reason: 'contact_limit',
    end_label: 'contact limit', end_expansions: [0.1, 0.25], ...extra,
  },
});

test('table rows: leaders in their order, results with before, after and measures', () => {
  const progress = {
    stage: 'refine',
    done: 3,
    total: 10,
    best: -1.5,
    leaders: [
      { topology: 'IH28:1,2:1x1:ab', spec: 'IH28:1.1,2:1x1:ab', kerf: 0.01, objective: -1.5, stage: 'refine' },
      { topology: 'IH1:1:2x1:a', spec: 'IH1:0.9:2x1:a', kerf: 0.02, objective: -1.2, stage: 'confirm' },
    ],
  };
  assert.deepEqual(leaderRows(progress).map((r) => [r.rank, r.design, r.objective, r.stage, r.kerf]), [
    [1, 'IH28 1×1', -1.5, 'refine', 0.01],
    [2, 'IH1 2×1', -1.2, 'confirm', 0.02],
  ]);
  assert.deepEqual(leaderRows(null), []);
  assert.equal(familyCell('rotating-squares'), 'rotating-squares');
  const job = { state: 'running', progress, evaluations: 42, history: [[1, -1], [5, -1.5]] };
  assert.equal(progressLine(job), 'refine · 3 / 10 evaluations · best objective -1.5 · 42 in all');
  assert.equal(progressLine({ state: 'running', progress: null }), 'starting…');
  assert.deepEqual(historyPoints(job), [[1, -1], [5, -1.5], [42, -1.5]]);
  assert.deepEqual(historyPoints({ history: [] }), []);

  const result = {
    results: [
      { rank: 1, family: 'IH28', cell: [2, 1], improved: true, evaluations: 12, before: scored('A', -1), after: scored('B', -1.5) },
      { rank: 2, family: 'IH1', cell: [1, 1], improved: false, evaluations: 6, before: scored('C', -0.5), after: scored('C', -0.5, { poisson: null }) },
    ],
  };
  const rows = resultRows(result);
  assert.deepEqual(rows.map((r) => [r.rank, r.design, r.before, r.after, r.spec, r.improved]), [
    [1, 'IH28 2×1', -1, -1.5, 'B', true],
    [2, 'IH1 1×1', -0.5, -0.5, 'C', false],
  ]);
  assert.equal(rows[0].expansions, '[0.1, 0.3]');
  assert.equal(rows[0].poisson, '[-1.02, -0.98]');
  assert.equal(rows[1].poisson, '–');
  assert.equal(rows[0].end, 'contact limit at [0.1, 0.25]', 'the library’s words, not the key');
  const older = resultRows({ results: [{ ...result.results[0], after: scored('B', -1.5, { end_label: undefined, end_reason: 'max_steps' }) }] });
  assert.equal(older[0].end, 'max steps at [0.1, 0.25]', 'a result without end_label: the key in words');
  assert.equal(pair([1 / 3, 2]), '[0.3333, 2]');
  assert.equal(cellText('3x2'), '3×2');
});

test('the form round-trips through the URL: every example target, with and without options', () => {
  for (const x of EXAMPLES) {
    for (const extra of [{}, { top: '5', budget: '120', kerf: '0.02', refineKerf: true }]) {
      const f = { target: x.target, top: '', budget: '', confirm: '', triage: '', samples: '', kerf: '', refineKerf: false, ...extra };
      const back = formFromSearch(formSearch(f));
      assert.equal(back.target, x.target);
      for (const [k, v] of Object.entries(extra)) assert.equal(back[k], v, `${k} of ${x.target}`);
      assert.ok(!('samples' in back), 'empty fields stay out of the URL');
    }
  }
  assert.deepEqual(formFromSearch(''), {});
  assert.equal(formSearch({ target: '  ' }), '');
});

test('a job’s echoed body gives back the form and command that started it', () => {
  const settings = { defaults: { top: 3, budget: 80 } };
  const base = emptyForm(settings);
  const forms = [
    { ...base, target: 'area' },
    { ...base, target: 'isotropic + 0.5*uniform; tiles<=4', top: '5', budget: '200', confirm: '60' },
    { ...base, target: 'lock(0.1,0.3)', triage: '9', samples: '2', kerf: '0.02', refineKerf: true },
  ];
  for (const f of forms) {
    // The server echoes the body as posted, a field left out null.
    const b = inverseBody(f);
    const body = { target: b.target, top: null, budget: null, confirm: null, triage: null, samples: null, kerf: null, refine_kerf: null, ...b };
    const restored = formFromJob({ target: 'canonical text', body }, settings);
    assert.equal(cliCommand(restored, 'x.db'), cliCommand(f, 'x.db'));
    assert.ok(sameSearch(restored, f));
  }
  assert.ok(!sameSearch({ ...base, target: 'area' }, { ...base, target: 'area(1.6)' }));
  // A target posted as JSON comes back as its JSON text; a view without the body, the
  // resolved target.
  const json = { terms: [{ goal: { kind: 'area' } }] };
  assert.equal(formFromJob({ target: '1*area', body: { target: json } }, settings).target, JSON.stringify(json));
  assert.equal(formFromJob({ target: '1*area' }, settings).target, '1*area');
});
