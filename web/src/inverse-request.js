// What the inverse-design page asks for and shows, as data: the example targets, the body of
// POST /api/inverse, the equivalent `isogami inverse …` command, the numbers checked against
// the server's caps, and the rows of the leaders and results tables. Pure functions over a
// form state, the server's settings (GET /api/inverse, or a static site's data/site.json
// `inverse`) and the job's JSON; inverse.js draws the page.
//
// Form state: { target, top, budget, confirm, triage, samples, kerf, refineKerf } where every
// number is the text of its field ('' means the CLI's default).

import { shellWord } from './export-request.js';

/** Example targets for the chips: a label and the target text (the README's syntax). */
export const EXAMPLES = [
  { label: 'largest area', target: 'area' },
  { label: 'opens to 1.6× its area', target: 'area(1.6)' },
  { label: 'isotropic', target: 'isotropic' },
  { label: 'isotropic, uniform, ≤ 4 tiles', target: 'isotropic + 0.5*uniform; tiles<=4' },
  { label: 'most uniform opening', target: 'uniform' },
  { label: 'locks at +10 % / +30 %', target: 'lock(0.1,0.3)' },
  { label: 'expansion path', target: 'path(0.5:0.05:0.1, 1:0.1:0.3)' },
];

/** The numeric fields: form key, body and CLI name, lowest value, cap key (null: no cap). */
export const NUMBER_FIELDS = [
  { key: 'top', name: 'top', min: 1, cap: 'top' },
  { key: 'budget', name: 'budget', min: 0, cap: 'budget' },
  { key: 'confirm', name: 'confirm', min: 1, cap: 'confirm' },
  { key: 'triage', name: 'triage', min: 1, cap: 'triage' },
  { key: 'samples', name: 'samples', min: 0, cap: 'samples' },
];

/** A blank form with the server's defaults for top and budget. */
export function emptyForm(settings) {
  const d = settings?.defaults ?? {};
  return {
    target: '',
    top: String(d.top ?? 3),
    budget: String(d.budget ?? 80),
    confirm: '',
    triage: '',
    samples: '',
    kerf: '',
    refineKerf: false,
  };
}

/** The form's problem as one line (a number that is not a whole number in range, no
 * target), or null. The server checks everything again; this only saves a round trip. */
export function formProblem(form, settings) {
  if (!String(form.target ?? '').trim()) return 'target: no goal given (e.g. \'area\', \'isotropic\', \'lock(0.1,0.3)\')';
  const limits = settings?.limits ?? {};
  for (const f of NUMBER_FIELDS) {
    const text = String(form[f.key] ?? '').trim();
    if (text === '') continue;
    const v = Number(text);
    if (!Number.isInteger(v) || v < f.min) return `${f.name} must be a whole number of at least ${f.min}`;
    const cap = limits[f.cap];
    if (cap !== undefined && v > cap) return `${f.name} ${v} is above this server's limit of ${cap}`;
  }
  const kerf = String(form.kerf ?? '').trim();
  if (kerf !== '' && !(Number(kerf) > 0)) return 'kerf must be a positive number';
  return null;
}

/** The numbers of the form that differ from an empty field, as [name, number] pairs in a
 * fixed order (top, budget, confirm, triage, samples, kerf). */
function numbers(form) {
  const out = [];
  for (const f of NUMBER_FIELDS) {
    const text = String(form[f.key] ?? '').trim();
    if (text !== '') out.push([f.name, Number(text)]);
  }
  const kerf = String(form.kerf ?? '').trim();
  if (kerf !== '') out.push(['kerf', Number(kerf)]);
  return out;
}

/** The JSON body of POST /api/inverse. */
export function inverseBody(form) {
  const body = { target: String(form.target).trim() };
  for (const [name, v] of numbers(form)) body[name] = v;
  if (form.refineKerf) body.refine_kerf = true;
  return body;
}

/** The `isogami inverse …` command that runs the same search (`database`: the database's
 * file name, run from its folder). */
export function cliCommand(form, database) {
  const words = ['isogami', 'inverse', '--target', `'${String(form.target).trim().replace(/'/g, `'\\''`)}'`];
  words.push('--db', shellWord(database || 'isogami.db'));
  for (const [name, v] of numbers(form)) words.push(`--${name}`, shellWord(String(v)));
  if (form.refineKerf) words.push('--refine-kerf');
  words.push('--json');
  return words.join(' ');
}

/** "IH28 2×1" of a spec (family and cell), or the spec's first field. */
export function familyCell(spec) {
  const parts = String(spec).split(':');
  return parts.length >= 3 ? `${parts[0]} ${parts[2].replace('x', '×')}` : parts[0];
}

/** Rows of the leaders table from a progress report. */
export function leaderRows(progress) {
  return (progress?.leaders ?? []).map((l, i) => ({
    rank: i + 1,
    design: familyCell(l.spec),
    spec: l.spec,
    kerf: l.kerf,
    objective: l.objective,
    stage: l.stage,
  }));
}

/** A [min, max] pair as "[a, b]" with 4 significant digits, or "–". */
export function pair(v) {
  if (!Array.isArray(v) || v.length !== 2) return '–';
  const f = (x) => String(Number(Number(x).toPrecision(4)));
  return `[${f(v[0])}, ${f(v[1])}]`;
}

/** A supercell as "2×1": the JSON's [a, b] (or "2x1" text). */
export function cellText(cell) {
  return Array.isArray(cell) ? cell.join('×') : String(cell).replace('x', '×');
}

/** Why a deployment ended, in words: the library's `end_label` ("contact limit"); a result
 * saved before it had one gets its key with spaces. */
export function endWords(m) {
  return m.end_label ?? String(m.end_reason ?? '').replace(/_/g, ' ');
}

/** Rows of the results table from a finished job's result (`isogami inverse --json`). */
export function resultRows(result) {
  return (result?.results ?? []).map((r) => {
    const m = r.after.measures;
    return {
      rank: r.rank,
      design: `${r.family} ${cellText(r.cell)}`,
      before: r.before.objective,
      after: r.after.objective,
      improved: r.improved,
      spec: r.after.spec,
      kerf: r.after.kerf,
      area: m.max_area_ratio,
      expansions: pair([m.min_expansion, m.max_expansion]),
      poisson: pair(m.poisson),
      end: `${endWords(m)} at ${pair(m.end_expansions)}`,
      evaluations: r.evaluations,
    };
  });
}

/** One line of progress: "triage · 12 / 40 evaluations · best −0.98", for the live region. */
export function progressLine(job) {
  const p = job?.progress;
  if (!p) return job?.state === 'running' ? 'starting…' : '';
  const best = p.best === null || p.best === undefined ? '–' : String(Number(p.best.toPrecision(4)));
  return `${p.stage} · ${p.done} / ${p.total} evaluations · best objective ${best} · ${job.evaluations} in all`;
}

/** The best-objective line's points from the job's history, extended to the evaluations so
 * far (a step function drawn as a line). */
export function historyPoints(job) {
  const h = job?.history ?? [];
  if (!h.length) return [];
  const points = h.map(([n, v]) => [n, v]);
  const last = h[h.length - 1];
  if ((job.evaluations ?? 0) > last[0]) points.push([job.evaluations, last[1]]);
  return points;
}

/** The form's fields that the page's URL keeps (query key → form key). */
const URL_FIELDS = [
  ['target', 'target'], ['top', 'top'], ['budget', 'budget'], ['confirm', 'confirm'],
  ['triage', 'triage'], ['samples', 'samples'], ['kerf', 'kerf'],
];

/** The form values a URL's query string sets (`?target=area&budget=80&refine-kerf=1`): only
 * the keys present, as text; `refineKerf` true for `refine-kerf=1`. */
export function formFromSearch(search) {
  const q = new URLSearchParams(search);
  const out = {};
  for (const [key, field] of URL_FIELDS) if (q.has(key)) out[field] = q.get(key);
  if (q.has('refine-kerf')) out.refineKerf = q.get('refine-kerf') === '1';
  return out;
}

/** The query string that keeps form `f` in the URL: every non-empty field, so a reload or a
 * shared link shows the same form (formFromSearch reads it back). */
export function formSearch(f) {
  const q = new URLSearchParams();
  for (const [key, field] of URL_FIELDS) {
    const v = String(f[field] ?? '').trim();
    if (v) q.set(key, v);
  }
  if (f.refineKerf) q.set('refine-kerf', '1');
  const s = q.toString();
  return s ? `?${s}` : '';
}

/** The form that started a job, from the request its view echoes (`GET /api/inverse/{id}`'s
 * `request.body`: the body as posted, a field left out null): what a page attaching to a
 * running or finished job shows, so that its command line is the job's. A job without the
 * echo of its body (an older server) gives the resolved request's target. */
export function formFromJob(request, settings) {
  const f = emptyForm(settings);
  const b = request?.body ?? {};
  const target = b.target ?? request?.target ?? '';
  f.target = typeof target === 'string' ? target : JSON.stringify(target);
  for (const { key } of NUMBER_FIELDS) if (b[key] !== null && b[key] !== undefined) f[key] = String(b[key]);
  if (b.kerf !== null && b.kerf !== undefined) f.kerf = String(b.kerf);
  f.refineKerf = b.refine_kerf === true;
  return f;
}

/** Whether two forms ask for the same search (the same body of POST /api/inverse). */
export function sameSearch(a, b) {
  return JSON.stringify(inverseBody(a)) === JSON.stringify(inverseBody(b));
}
