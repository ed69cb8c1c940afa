// The inverse-design page (inverse.html): a target with its syntax and example chips, the
// search sizes within the server's caps, Run and Stop; while a job runs, its stage (announced
// to screen readers when it changes), a progress bar, the leaders (each leading topology's
// best design so far) and the best objective over evaluations, polled from the server; at
// the end the results (screened → refined objective, spec, measures) with a link opening each
// refined design on the design page, and "save all". Errors are the server's one-line
// messages. The job is the server's: the URL names it (?job=ID, with the form), so a reload or
// a copied link shows it again, running or finished, with the form and command that started it
// (echoed by the server); a page opened while a job runs shows that job, and Run while the one
// job of the server runs shows it too instead of an error. On a static site nothing runs: the
// page composes the `isogami inverse …` command.
// Request building and table rows are in inverse-request.js.

import { openData } from './data.js';
import { h, fmt, showNotice, clearNotice } from './dom.js';
import { createLinePlot } from './plots.js';
import { designHref } from './url.js';
import {
  EXAMPLES, NUMBER_FIELDS, cliCommand, emptyForm, formFromJob, formFromSearch, formProblem, formSearch, historyPoints, inverseBody,
  leaderRows, progressLine, resultRows, sameSearch,
} from './inverse-request.js';

const $ = (id) => document.getElementById(id);
const POLL_MS = 250;

const STAGES = {
  confirm: 'Re-deploying the best pre-screened designs',
  sample: 'Deploying fresh shape samples',
  triage: 'Refining every screened design briefly',
  refine: 'Refining the best topologies',
  verify: 'Re-deploying and checking the refined designs',
};

let data;
let settings = null;
let jobId = null;
let timer = null;
let plot = null;
let lastStage = '';
let lastLeaders = '';
/** What the first view of the attached job does to the form: `restore` it from the job's
 * request, then `overlay` the URL's own fields (edits made after the job, kept by a reload);
 * `notStarted`: the form whose Run was refused because this job runs. */
let pending = null;

function form() {
  return {
    target: $('target').value,
    top: $('top').value,
    budget: $('budget').value,
    confirm: $('confirm').value,
    triage: $('triage').value,
    samples: $('samples').value,
    kerf: $('kerf').value,
    refineKerf: $('refine-kerf').checked,
  };
}

function showError(e) {
  showNotice($('notice'), { message: e.message, hint: e.hint || '', kind: e.kind || 'error' });
}

/** The command line of the form; `keep` (an edit, not the page's first fill) also keeps the
 * form in the URL. */
function updateCommand(keep = true) {
  const f = form();
  $('command').textContent = String(f.target).trim() ? cliCommand(f, settings?.database) : '';
  // The form lives in the URL, and the job shown: a reload or a shared link keeps the target,
  // the command and the run.
  if (!keep) return;
  keepUrl(f);
}

/** Writes form `f` and the job shown to the URL. */
function keepUrl(f = form()) {
  const q = new URLSearchParams(formSearch(f));
  if (jobId !== null) q.set('job', String(jobId));
  const search = q.toString() ? `?${q}` : '';
  if (search !== location.search) history.replaceState(null, '', `${location.pathname}${search}`);
}

/** Fills the form with `f`'s fields. */
function fillForm(f) {
  for (const [field, value] of Object.entries(f)) {
    if (field === 'refineKerf') $('refine-kerf').checked = Boolean(value);
    else $(field).value = value;
  }
}

/** Fills the form from the URL's query (`?target=…`, as formSearch writes it). */
function formFromUrl() {
  fillForm(formFromSearch(location.search));
}

async function main() {
  data = await openData();
  document.body.dataset.mode = data.mode;
  $('mode').textContent = data.mode === 'static' ? 'static site (read-only)' : 'live server';
  plot = createLinePlot($('history-plot'), {
    xLabel: 'evaluations',
    yLabel: 'best objective',
    height: 180,
    xAuto: true,
    steps: true,
    marker: false,
    yLog: true,
  });
  try {
    settings = await data.inverseSettings();
  } catch (e) {
    showError(e);
    return;
  }
  const initial = emptyForm(settings);
  for (const key of ['top', 'budget']) $(key).value = initial[key];
  // The server's caps; the command line has only the library's.
  for (const f of NUMBER_FIELDS) {
    const cap = data.live ? settings.limits?.[f.cap] : undefined;
    if (cap !== undefined) {
      $(f.key).max = String(cap);
      $(`${f.key}-cap`).textContent = `at most ${cap}`;
    }
  }
  $('examples').replaceChildren(
    ...EXAMPLES.map((x) =>
      h('button', {
        type: 'button',
        class: 'chip',
        testid: 'example',
        'data-target': x.target,
        title: x.target,
        onclick: () => {
          $('target').value = x.target;
          updateCommand();
          $('target').focus();
        },
      }, x.label),
    ),
  );
  formFromUrl();
  $('inverse-form').addEventListener('input', updateCommand);
  $('inverse-form').addEventListener('change', updateCommand);
  $('inverse-form').addEventListener('submit', (event) => {
    event.preventDefault();
    run();
  });
  $('stop').addEventListener('click', stop);
  $('save-all').addEventListener('click', saveAll);
  updateCommand(false);
  if (!data.live) {
    $('run').disabled = true;
    $('progress-section').hidden = true;
    $('run-note').textContent = 'Running needs `isogami serve`: run the command below instead.';
    return;
  }
  // The job the URL names, else the one running: shown with the form that started it.
  const named = new URLSearchParams(location.search).get('job');
  if (named !== null) attach(named, { restore: true, overlay: true });
  else if (settings.running) attach(settings.running, { restore: true });
}

function setRunning(running) {
  $('run').disabled = running;
  $('stop').disabled = !running;
  document.body.dataset.inverseState = running ? 'running' : document.body.dataset.inverseState;
}

async function run() {
  const f = form();
  const problem = formProblem(f, settings);
  if (problem) {
    showNotice($('notice'), { message: problem, hint: 'fix the form and run again', kind: 'bad_parameter' });
    return;
  }
  clearNotice($('notice'));
  $('run').disabled = true;
  // The server runs one job at a time: while one runs (another tab's, say) it is shown
  // rather than asked for a second and refused.
  const busy = await runningJob();
  if (busy !== null) {
    attach(busy, { restore: true, notStarted: f });
    return;
  }
  try {
    const started = await data.startInverse(inverseBody(f));
    attach(started.id);
  } catch (e) {
    // One started in the meantime: shown rather than the refusal.
    const running = e.status === 409 && e.kind === 'busy' ? await runningJob() : null;
    if (running !== null) {
      attach(running, { restore: true, notStarted: f });
      return;
    }
    $('run').disabled = false;
    showError(e);
  }
}

/** The id of the job running on the server, or null. */
async function runningJob() {
  try {
    return (await data.inverseSettings()).running ?? null;
  } catch {
    return null;
  }
}

function attach(id, how = {}) {
  jobId = String(id);
  pending = how;
  keepUrl();
  lastStage = '';
  lastLeaders = '';
  document.body.dataset.jobId = String(id);
  document.body.dataset.leaderUpdates = '0';
  document.body.dataset.polls = '0';
  $('results-section').hidden = true;
  $('save-status').textContent = '';
  $('stage-line').textContent = 'Starting…';
  setRunning(true);
  clearTimeout(timer);
  poll();
}

async function poll() {
  const id = jobId;
  let job;
  try {
    job = await data.inverseJob(id);
  } catch (e) {
    if (id !== jobId) return;
    // An unknown or forgotten job (a link kept too long): the server's message says so.
    pending = null;
    setRunning(false);
    document.body.dataset.inverseState = 'lost';
    showError(e);
    return;
  }
  if (id !== jobId) return;
  document.body.dataset.polls = String(Number(document.body.dataset.polls || 0) + 1);
  if (pending) firstView(job);
  render(job);
  if (job.state === 'running') timer = setTimeout(poll, POLL_MS);
  else finish(job);
}

/** The attached job's first view: the form that started it (and the URL's edits since, on a
 * reload); a Run refused for it says what was not started. */
function firstView(job) {
  const how = pending;
  pending = null;
  if (how.restore) {
    fillForm(formFromJob(job.request, settings));
    if (how.overlay) formFromUrl();
    updateCommand();
  }
  if (how.notStarted && !sameSearch(how.notStarted, form())) {
    const target = String(how.notStarted.target).trim();
    showNotice($('notice'), {
      message: `This server runs one inverse design at a time: job ${job.id}, shown here, is running. Your search for '${target}' was not started.`,
      hint: 'run it again once this one ends (or stop this one)',
      kind: 'busy',
    });
  }
}

function render(job) {
  const p = job.progress;
  $('progress-line').textContent = progressLine(job);
  const bar = $('progress-bar');
  bar.max = Math.max(1, p?.total ?? 1);
  bar.value = Math.min(bar.max, p?.done ?? 0);
  const stage = job.state === 'running'
    ? `${job.stopping ? 'Stopping… ' : ''}${p ? STAGES[p.stage] ?? p.stage : 'Starting'}`
    : '';
  if (stage && stage !== lastStage) {
    lastStage = stage;
    $('stage-line').textContent = `${stage}.`;
  }
  const leaders = leaderRows(p);
  const key = JSON.stringify(leaders);
  if (key !== lastLeaders) {
    lastLeaders = key;
    drawLeaders(leaders);
    document.body.dataset.leaderUpdates = String(Number(document.body.dataset.leaderUpdates || 0) + 1);
  }
  const points = historyPoints(job);
  plot.update(points.length ? [{ name: 'best objective', className: 'best', points }] : []);
}

/** A link opening `spec` (deployed with `kerf`) on the design page. */
function openLink(spec, kerf, label, ariaLabel) {
  return h('a', { href: designHref(spec, { kerf }), testid: 'open', 'aria-label': ariaLabel, title: 'open on the design page' }, label);
}

function drawLeaders(rows) {
  const table = $('leaders');
  if (!rows.length) {
    table.replaceChildren(h('tbody', {}, h('tr', {}, h('td', { class: 'empty' }, 'No valid design yet.'))));
    return;
  }
  table.replaceChildren(
    h('thead', {}, h('tr', {},
      h('th', { scope: 'col' }, '#'), h('th', { scope: 'col' }, 'design'), h('th', { scope: 'col' }, 'objective'),
      h('th', { scope: 'col' }, 'found in'), h('th', { scope: 'col' }, 'spec'))),
    h('tbody', {}, rows.map((r) => h('tr', { testid: 'leader' },
      h('td', { class: 'num' }, r.rank),
      h('td', {}, openLink(r.spec, r.kerf, r.design, `open leader ${r.rank}, ${r.design}`)),
      h('td', { class: 'num', testid: 'leader-objective' }, fmt(r.objective)),
      h('td', {}, r.stage),
      h('td', { class: 'spec' }, h('code', {}, r.spec))))),
  );
}

function finish(job) {
  clearTimeout(timer);
  setRunning(false);
  document.body.dataset.inverseState = job.state;
  const words = { done: 'Done', failed: 'Failed', stopped: 'Stopped' };
  $('stage-line').textContent = `${words[job.state] ?? job.state} after ${job.evaluations} evaluations in ${job.elapsed.toFixed(1)} s.`;
  if (job.state === 'done') {
    showResults(job);
  } else if (job.error) {
    showNotice($('notice'), { message: job.error.error, hint: job.error.hint, kind: job.error.kind });
  }
}

function showResults(job) {
  const result = job.result;
  const rows = resultRows(result);
  $('results-summary').textContent =
    `${result.target}: ${result.candidates} candidates, ${result.admitted} pass the constraints, ` +
    `${result.confirmed} re-deployed (${result.confirmed_valid} valid), ${result.triaged} triaged; ` +
    `${result.evaluations} deployments in ${result.seconds.toFixed(1)} s.`;
  // Whether the best design meets the target (goals naming a value, within tolerance).
  const verdict = result.results[0]?.verdict;
  $('results-verdict').textContent = verdict ? `Best design: ${verdict.summary}` : '';
  $('results-verdict').dataset.met = String(result.met);
  const head = ['#', 'design', 'objective before → after', 'spec (refined)', 'kerf', 'area ratio',
    'principal expansions', 'Poisson range', 'end state', 'evaluations'];
  $('results').replaceChildren(
    h('thead', {}, h('tr', {}, head.map((t) => h('th', { scope: 'col' }, t)))),
    h('tbody', {}, rows.map((r) => h('tr', { testid: 'result', class: r.improved ? 'improved' : '' },
      h('td', { class: 'num' }, r.rank),
      h('td', {}, openLink(r.spec, r.kerf, `open ${r.design}`, `open result ${r.rank}, ${r.design}`)),
      h('td', { class: 'num after' }, `${fmt(r.before)} → ${fmt(r.after)}${r.improved ? '' : ' (not improved)'}`),
      h('td', { class: 'spec' }, h('code', { testid: 'result-spec' }, r.spec)),
      h('td', { class: 'num' }, fmt(r.kerf)),
      h('td', { class: 'num' }, fmt(r.area)),
      h('td', {}, r.expansions),
      h('td', {}, r.poisson),
      h('td', {}, r.end),
      h('td', { class: 'num' }, r.evaluations)))),
  );
  $('results-section').hidden = false;
  $('save-all').hidden = !settings.save;
  $('save-all').disabled = false;
}

async function stop() {
  if (jobId === null) return;
  $('stop').disabled = true;
  try {
    render(await data.stopInverse(jobId));
  } catch (e) {
    showError(e);
  }
}

async function saveAll() {
  $('save-all').disabled = true;
  $('save-status').textContent = 'saving…';
  try {
    const { saved } = await data.saveInverse(jobId);
    const stored = saved.filter((s) => s.saved).length;
    const kept = saved.length - stored;
    $('save-status').textContent =
      `saved ${stored} design${stored === 1 ? '' : 's'}${kept ? `; ${kept} already in the database` : ''}.`;
  } catch (e) {
    $('save-status').textContent = '';
    $('save-all').disabled = false;
    showError(e);
  }
}

main();
