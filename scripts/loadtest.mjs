#!/usr/bin/env node
// Loopback load test of `isogami serve` (node ≥ 18, no dependencies):
//
//   node scripts/loadtest.mjs --base http://127.0.0.1:8080 [--seconds 60] [--browsers 50]
//        [--sliders 10] [--max-requests 200000] [--timeout 10] [--think 1] [--slider-interval 0.1]
//
// Clients behave like people: a browsing client reads each page for --think seconds (random
// 0.5–1.5×) before the next, a slider client moves again --slider-interval seconds after the
// answer (the live panel's debounce). `--think 0 --slider-interval 0` is a stress test instead:
// every client fires back to back, so latencies then measure queueing at saturation.
//
// `--browsers` clients browse the catalogue: a page of designs under random filters, sorts
// and pages, its facets, sometimes a scatter, thumbnails of a few rows and one design view.
// `--sliders` clients move shape sliders: each picks a stored design with shape parameters,
// nudges one parameter by a small random step and POSTs /api/deploy, as the live design
// panel does. Bounded in time (--seconds) and in count (--max-requests over all clients).
//
// Prints p50/p99/max latency per category and the error count, and exits 1 on any error:
// a network failure, a timeout, a 5xx, or a 4xx other than a refused slider move (422 with
// kind bad_design, rigid or ill_shaped: a shape the user may legitimately reach, counted
// apart). A deployment that runs out of time (kind "timeout") counts as an error.

const args = process.argv.slice(2);
function opt(name, fallback) {
  const i = args.indexOf(`--${name}`);
  if (i < 0) return fallback;
  const v = args[i + 1];
  if (v === undefined) usage(`--${name} needs a value`);
  return v;
}
function usage(message) {
  console.error(`error: ${message}\nusage: node scripts/loadtest.mjs --base URL [--seconds 60] [--browsers 50] [--sliders 10] [--max-requests N] [--timeout S] [--think S] [--slider-interval S]`);
  process.exit(2);
}
function positive(name, fallback) {
  const v = Number(opt(name, fallback));
  if (!Number.isFinite(v) || v < 0) usage(`--${name} must be a non-negative number`);
  return v;
}

const base = String(opt('base', '')).replace(/\/$/, '');
if (!/^https?:\/\//.test(base)) usage('--base http://HOST:PORT is required');
const seconds = positive('seconds', 60);
const browsers = Math.floor(positive('browsers', 50));
const sliders = Math.floor(positive('sliders', 10));
const maxRequests = Math.floor(positive('max-requests', 200000));
const timeoutMs = positive('timeout', 10) * 1000;
const thinkMs = positive('think', 1) * 1000;
const sliderMs = positive('slider-interval', 0.1) * 1000;
const sleep = (ms) => new Promise((ok) => setTimeout(ok, ms));

const MEASURES = ['max_expansion', 'min_expansion', 'max_area_ratio', 'max_tile_rotation', 'poisson_min', 'poisson_max', 'steps'];
const REFUSED = new Set(['bad_design', 'rigid', 'ill_shaped']);
const deadline = Date.now() + seconds * 1000;
const latencies = new Map(); // category → ms[]
const errors = [];
let refused = 0;
let sent = 0;

const pick = (list) => list[Math.floor(Math.random() * list.length)];
const live = () => Date.now() < deadline && sent < maxRequests;

async function timed(category, url, init = {}) {
  sent += 1;
  const start = performance.now();
  let res;
  let body;
  try {
    res = await fetch(url, { ...init, signal: AbortSignal.timeout(timeoutMs) });
    body = Buffer.from(await res.arrayBuffer());
  } catch (e) {
    errors.push(`${category}: ${e.name === 'TimeoutError' ? 'timed out' : e.message} (${url})`);
    return null;
  }
  const ms = performance.now() - start;
  if (!latencies.has(category)) latencies.set(category, []);
  latencies.get(category).push(ms);
  if (res.ok) return { res, body };
  let kind = '';
  try {
    kind = JSON.parse(body.toString()).kind ?? '';
  } catch {
    kind = '';
  }
  if (category === 'deploy' && res.status === 422 && REFUSED.has(kind)) {
    refused += 1;
    return null;
  }
  errors.push(`${category}: ${res.status} ${kind} ${body.toString().slice(0, 200)} (${url})`);
  return null;
}

const json = (r) => (r ? JSON.parse(r.body.toString()) : null);

async function setup() {
  const families = json(await timed('setup', `${base}/api/families`));
  const facets = json(await timed('setup', `${base}/api/facets`));
  const rows = [];
  for (;;) {
    const page = json(await timed('setup', `${base}/api/designs?limit=500&offset=${rows.length}`));
    if (!page || !page.rows.length) break;
    rows.push(...page.rows);
    if (rows.length >= page.total) break;
  }
  if (!families || !facets || !rows.length) throw new Error('cannot read the catalogue to load-test it');
  return { families, facets, rows };
}

function randomQuery({ facets, rows }) {
  const p = new URLSearchParams();
  if (Math.random() < 0.4) p.append('family', pick(facets.family).value);
  if (Math.random() < 0.2) p.append('behaviour', pick(facets.behaviour).value ?? 'none');
  if (Math.random() < 0.2) {
    const c = pick(facets.cell).value;
    p.append('cell', `${c[0]}x${c[1]}`);
  }
  if (Math.random() < 0.3) {
    const m = pick(MEASURES.slice(0, 4));
    const v = pick(rows)[m];
    p.append('range', Math.random() < 0.5 ? `${m}:${v}:` : `${m}::${v}`);
  }
  if (Math.random() < 0.7) p.set('sort', `${Math.random() < 0.5 ? '-' : ''}${pick([...MEASURES, 'spec', 'family', 'cell', 'behaviour'])}`);
  p.set('limit', String(pick([10, 25, 50, 100])));
  p.set('offset', String(pick([0, 0, 0, 10, 50])));
  return p;
}

async function browser(ctx) {
  // People arrive spread over one think time, not all in the same millisecond.
  await sleep(thinkMs * Math.random());
  while (live()) {
    const q = randomQuery(ctx);
    const [page] = await Promise.all([
      timed('designs', `${base}/api/designs?${q}`).then(json),
      timed('facets', `${base}/api/facets?${q}`),
      Math.random() < 0.3 ? timed('scatter', `${base}/api/scatter?x=${pick(MEASURES)}&y=${pick(MEASURES)}&${q}`) : null,
    ]);
    const shown = page ? page.rows.slice(0, 4) : [];
    await Promise.all(shown.map((r) => live() && timed('thumbnail', `${base}/api/thumbnail?spec=${encodeURIComponent(r.spec)}`)));
    if (live()) {
      const r = pick(shown.length ? shown : ctx.rows);
      await timed('design', `${base}/api/design?spec=${encodeURIComponent(r.spec)}`);
    }
    if (thinkMs > 0 && live()) await sleep(thinkMs * (0.5 + Math.random()));
  }
}

async function slider(ctx) {
  const candidates = ctx.rows.filter((r) => r.params.length > 0 && r.dof === 1);
  if (!candidates.length) return;
  while (live()) {
    const r = pick(candidates);
    const info = ctx.families.find((f) => f.name === r.family);
    const params = [...r.params];
    const k = Math.floor(Math.random() * params.length);
    const d = info ? info.default_params[k] ?? params[k] : params[k];
    const half = Math.max(0.5, Math.abs(d));
    params[k] = Number((params[k] + (Math.random() - 0.5) * 0.05 * half).toFixed(4));
    const spec = `${r.family}:${params.join(',')}:${r.cell[0]}x${r.cell[1]}:${r.joints}`;
    await timed('deploy', `${base}/api/deploy`, {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify({ design: spec, kerf: r.kerf }),
    });
    if (sliderMs > 0 && live()) await sleep(sliderMs);
  }
}

function quantile(sorted, q) {
  if (!sorted.length) return NaN;
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
}

const ctx = await setup();
const t0 = performance.now();
await Promise.all([...Array(browsers)].map(() => browser(ctx)).concat([...Array(sliders)].map(() => slider(ctx))));
const wall = (performance.now() - t0) / 1000;

console.log(`load test of ${base}: ${browsers} browsing + ${sliders} slider clients, think ${thinkMs / 1000} s, slider interval ${sliderMs / 1000} s, ${wall.toFixed(1)} s, ${sent} requests (${(sent / wall).toFixed(0)}/s)`);
console.log('category      count     p50 ms     p99 ms     max ms');
for (const [cat, ms] of [...latencies.entries()].sort()) {
  ms.sort((a, b) => a - b);
  const f = (v) => v.toFixed(1).padStart(10);
  console.log(`${cat.padEnd(10)} ${String(ms.length).padStart(8)} ${f(quantile(ms, 0.5))} ${f(quantile(ms, 0.99))} ${f(ms[ms.length - 1])}`);
}
console.log(`refused slider moves (422 bad_design/rigid/ill_shaped): ${refused}`);
console.log(`errors: ${errors.length}`);
for (const e of errors.slice(0, 20)) console.log(`  ${e}`);
process.exit(errors.length ? 1 : 0);
