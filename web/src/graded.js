// The graded-sheet page (graded.html): a design (pre-filled from ?design=), a region checked
// against the server's caps as typed, a target (disc, ellipse, a polygon clicked point by point
// on a pad, checked by the library through GET /api/graded/outline and its one-line error shown
// beside the pad; an uploaded SVG file, read by the library through POST /api/graded/svg, its
// error shown the same way; or an area-ratio field: from, to, direction); Grade starts a job (POST /api/graded) that the page
// polls: iteration, cost, stage, a progress bar and the opened sheet as it stands drawn over
// the target; at the end the report, a player through the path check's states (closed ↔
// opened, the tiles placed from each state's poses, the fitted target at the opened end) and
// the sheet's JSON as `isogami graded --out` writes it; the library's verdict in its own words
// (opens along one motion or not, meets the target within the tolerance or misses it, how deep
// tiles overlap, whether the target asked was given up for the nearest sheet that opens), the
// outline's fit figures, the worst boundary stretch marked on the opened sheet beside the target
// and the deepest overlap's two tiles filled with their depth in mm (the player jumps to its
// state); a field's cells in a table (asked and
// achieved area ratio) and coloured by their error at the opened end; laser and print files of
// the graded sheet (GET /api/graded/{id}/export, as `isogami export --sheet`). The polygon's corners are
// also a text field bound both ways with the pad, and a corner focused on the pad moves with the arrow keys
// and goes with Delete (the keyboard's ways to add, move and remove them). The job
// is the server's: the URL names it (?job=ID), so a reload or a copied link shows it again, running or
// finished, with the form and command that started it (echoed by the server); a page opened while a job
// runs shows that job. The tolerance and whether to fall back to the nearest sheet that opens
// are the CLI's `--tolerance` and `--no-fallback`. On a static site nothing runs: the page shows the command. Before Grade, the
// design and region are checked for a one-DOF sheet (GET /api/sheet: the same library check the
// job starts with); when there is none the page says so, why, and what to do instead (a larger
// region, or a design of the same family that has one). Pure logic is in graded-model.js and
// buildable.js.

import { ApiError, openData } from './data.js';
import { showNotice, clearNotice, debounce } from './dom.js';
import { designHref } from './url.js';
import { familyOfSpec, findNeighbour, neighbourHref, percentText, refusalReason, sheetCheckQuery } from './buildable.js';
import {
  DEFAULTS, EXPORTS, aspectProblem, bounds, cliCommand, cornersText, deepestOverlapIndex, edgeProblem, emptyForm, errorColour, exportCommand,
  exportParams, fieldProblem, fieldRows, fitFigures, formFromJob, gradedBody, hullArea, iterationsProblem, outlineAtArea, outlineText,
  overlapAnchor, overlapMark, parseCorners, playerStates, posedPolygons, progressLine, regionProblem, reportLines, starProblem, svgProblem,
  toleranceProblem, verdictView, worstPoint,
} from './graded-model.js';

const $ = (id) => document.getElementById(id);
const SVG = 'http://www.w3.org/2000/svg';
const POLL_MS = 250;
/** States per second while playing. */
const PLAY_RATE = 8;

let data;
let settings = { defaults: DEFAULTS, limits: {} };
let points = [];
let jobId = null;
let timer = null;
let outlineAsked = 0;
let serverOutlineError = '';
let outlineChecked = false; // the library's answer for the drawn points is in (the pad's data-checked)
let svgFile = null; // { name, text, points } of the chosen SVG file, read by the library
let svgError = '';
let svgAsked = 0;
let cornersError = ''; // the corners field's text is not corners: why
let focusedCorner = null; // the corner last moved from the keyboard (kept focused when redrawn)
let extra = { states: '', t: '' }; // a restored job's states and t (the page has no fields for them)
let restorePending = false; // the attached job's first view fills the form
let live = null; // { frame, target, count, done }
let player = null; // { result, states, all, deepest, worst, frame, playing, timer }
let sheetAsk = null; // the one-DOF sheet check in flight (AbortController)

/** An SVG element. */
function s(tag, attrs = {}) {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== null && v !== undefined) el.setAttribute(k, v);
  return el;
}

const pointsAttr = (poly) => poly.map(([x, y]) => `${+x.toFixed(6)},${+y.toFixed(6)}`).join(' ');

async function getJson(url, options) {
  let res;
  try {
    res = await fetch(url, options);
  } catch (e) {
    throw new ApiError(`cannot reach ${url}: ${e.message}`, 'network', 'is `isogami serve` still running?');
  }
  let body = null;
  try {
    body = await res.json();
  } catch {
    body = null;
  }
  if (res.ok && body !== null) return body;
  if (body && typeof body.error === 'string') throw new ApiError(body.error, body.kind || 'error', body.hint || '', res.status);
  throw new ApiError(`${res.status} ${res.statusText} for ${url}`, 'http', '', res.status);
}

function form() {
  return {
    design: $('design').value,
    rows: $('rows').value,
    cols: $('cols').value,
    outline: document.querySelector('input[name="outline"]:checked')?.value ?? 'disc',
    aspect: $('aspect').value,
    points,
    from: $('field-from').value,
    to: $('field-to').value,
    degrees: $('field-degrees').value,
    svg: svgFile,
    iterations: $('iterations').value,
    states: extra.states,
    t: extra.t,
    tolerance: $('tolerance').value,
    fallBack: $('fall-back').checked,
  };
}

function showError(e) {
  showNotice($('notice'), { message: e.message, hint: e.hint || '', kind: e.kind || 'error' });
}

/** Every check of the form, shown beside its control; true when nothing is wrong. */
function check() {
  const f = form();
  const limits = settings.limits ?? {};
  const region = regionProblem(f, limits);
  $('region-error').textContent = region;
  const iterations = iterationsProblem(f, limits);
  $('iterations-error').textContent = iterations;
  const tolerance = toleranceProblem(f);
  $('tolerance-error').textContent = tolerance;
  const outline = outlineProblem(f);
  $('outline-error').textContent = outline;
  $('command').textContent = cliCommand(f);
  return !region && !iterations && !tolerance && !outline;
}

/** An element with children (graded.js builds few: no dom.js `h` here). */
function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  e.append(...children.filter((c) => c !== null && c !== undefined));
  return e;
}

/** Whether the design and region have a one-DOF sheet, asked of GET /api/sheet as the form
 * changes: when not, the line under the design says so before Grade, with the library's reason
 * and what to do (a larger region; a design of the same family with a sheet; the catalogue's
 * list of designs with one). `data-sheet` on the line: checking, ok, none or unknown. */
async function checkSheet() {
  const box = $('design-sheet');
  sheetAsk?.abort();
  sheetAsk = null;
  const f = form();
  const query = data?.live ? sheetCheckQuery(f, (x) => regionProblem(x, settings.limits ?? {})) : null;
  if (!query) {
    box.hidden = true;
    box.dataset.sheet = 'unknown';
    return;
  }
  const controller = new AbortController();
  sheetAsk = controller;
  box.dataset.sheet = 'checking';
  let answer = null;
  try {
    answer = await getJson(`./api/sheet?${query}`, { signal: controller.signal });
  } catch {
    answer = null;
  }
  if (sheetAsk !== controller || controller.signal.aborted) return;
  if (!answer || !answer.refused) {
    box.hidden = true;
    box.dataset.sheet = answer ? 'ok' : 'unknown';
    return;
  }
  const design = f.design.trim();
  const region = `${Number(f.rows)}×${Number(f.cols)}`;
  const neighbours = el('span', { 'data-testid': 'design-sheet-neighbours' });
  box.replaceChildren(
    el('strong', {}, `No one-DOF sheet in this ${region} region, so Grade would fail: `),
    `${refusalReason(answer.refused)}. Grading starts from the design’s own finite sheet completed to one degree of freedom. `,
    // An isostatic cell (the library says every finite sheet flops) has none in any region.
    /every finite sheet flops/.test(answer.refused)
      ? 'No region of this design has one: grade a design that has one: '
      : 'Try a larger region, or grade a design that has one: ',
    neighbours,
  );
  box.hidden = false;
  box.dataset.sheet = 'none';
  const all = el('a', { href: neighbourHref(null), 'data-testid': 'design-sheet-all' }, 'the catalogue’s designs with a one-DOF sheet');
  let found = null;
  try {
    found = await findNeighbour(data, familyOfSpec(design), design);
  } catch {
    found = null;
  }
  if (sheetAsk !== controller) return;
  if (found) {
    const use = el('button', { type: 'button', 'data-testid': 'design-sheet-neighbour', 'data-spec': found.spec }, `grade ${found.spec} instead`);
    use.addEventListener('click', () => {
      $('design').value = found.spec;
      check();
      checkSheet();
    });
    neighbours.replaceChildren(
      'the same family’s ', el('a', { href: designHref(found.spec) }, el('code', {}, found.spec)),
      ` (its 6×6 sheet keeps ${percentText(found.finite_covered)} %) `, use, ', or ', all, '.',
    );
  } else neighbours.replaceChildren(all, '.');
}

const checkSheetSoon = debounce(checkSheet, 300);

/** The outline's problem: the ellipse's ratio, or a drawn polygon's (the server's message
 * when it answered for these points, else the same rule checked here). */
function outlineProblem(f) {
  if (f.outline === 'ellipse') return aspectProblem(f);
  if (f.outline === 'field') return fieldProblem(f);
  if (f.outline === 'svg') return svgError || svgProblem(f);
  if (f.outline !== 'polygon') return '';
  if (cornersError) return cornersError;
  if (points.length < 3) return '';
  return serverOutlineError || starProblem(points);
}

/** Asks the library about the drawn polygon (debounced; stale answers dropped). */
const askOutline = debounce(async () => {
  if (!data.live || form().outline !== 'polygon' || points.length < 3) return;
  const text = outlineText(form());
  const asked = ++outlineAsked;
  try {
    await getJson(`./api/graded/outline?outline=${encodeURIComponent(text)}`);
    if (asked === outlineAsked) serverOutlineError = '';
  } catch (e) {
    if (asked !== outlineAsked) return;
    serverOutlineError = e.kind === 'bad_target' ? e.message : '';
  }
  if (asked === outlineAsked) {
    outlineChecked = true;
    check();
    drawPad();
  }
}, 120);

/** The points changed (`typed`: from the corners field, which then keeps its text). */
function pointsChanged(typed = false) {
  if (!typed) {
    cornersError = '';
    $('corners').value = cornersText(points);
  }
  serverOutlineError = '';
  outlineChecked = false;
  outlineAsked += 1;
  $('outline-status').textContent = points.length
    ? `${points.length} point${points.length === 1 ? '' : 's'}${points.length < 3 ? ': at least 3 make an outline' : ''}`
    : '';
  check();
  drawPad();
  askOutline();
}

function drawPad() {
  const pad = $('pad');
  const f = form();
  const g = s('g', { transform: 'scale(1,-1)' });
  g.append(s('line', { class: 'axis', x1: -1.25, y1: 0, x2: 1.25, y2: 0 }), s('line', { class: 'axis', x1: 0, y1: -1.25, x2: 0, y2: 1.25 }));
  const bad = Boolean(outlineProblem(f));
  if (f.outline === 'disc') g.append(s('circle', { class: 'outline', cx: 0, cy: 0, r: 1, 'data-outline': 'disc' }));
  else if (f.outline === 'ellipse') {
    const a = Number(f.aspect);
    const ok = Number.isFinite(a) && a > 0;
    const k = ok ? Math.max(a, 1) : 1;
    g.append(s('ellipse', { class: `outline${ok ? '' : ' bad'}`, cx: 0, cy: 0, rx: ok ? a / k : 1, ry: 1 / k, 'data-outline': 'ellipse' }));
  } else if (f.outline === 'svg') {
    const p = svgFile?.points;
    if (p?.length) {
      const r = Math.max(...p.map(([x, y]) => Math.hypot(x, y))) || 1;
      g.append(s('polygon', { class: 'outline', points: pointsAttr(p.map(([x, y]) => [x / r, y / r])), 'data-outline': 'svg' }));
    }
  } else if (f.outline === 'field') {
    // The ramp: an arrow along its direction, from the "from" end to the "to" end.
    const a = (Number(f.degrees) || 0) * Math.PI / 180;
    const [c, sn] = [Math.cos(a), Math.sin(a)];
    g.append(s('line', { class: 'outline', x1: -c, y1: -sn, x2: c, y2: sn, 'data-outline': 'field' }));
    g.append(s('polygon', { class: 'outline', points: pointsAttr([[c, sn], [0.8 * c - 0.1 * sn, 0.8 * sn + 0.1 * c], [0.8 * c + 0.1 * sn, 0.8 * sn - 0.1 * c]]) }));
  } else {
    if (points.length >= 2) {
      g.append(s(points.length >= 3 ? 'polygon' : 'polyline', {
        class: `outline${bad ? ' bad' : ''}`, points: pointsAttr(points), 'data-outline': 'polygon',
      }));
    }
    // Each corner takes the keyboard (padKey): focused, the arrows move it, Delete removes it.
    points.forEach(([x, y], k) => g.append(s('circle', {
      class: 'corner', cx: x, cy: y, r: 0.035, tabindex: 0, 'data-corner': k,
      'aria-label': `corner ${k + 1} of ${points.length} at ${cornersText([[x, y]]).replace(',', ', ')}: arrow keys move it, Delete removes it`,
    })));
  }
  // A corner moved or removed from the keyboard keeps the focus (its element is redrawn).
  const refocus = pad.contains(document.activeElement) && focusedCorner !== null;
  pad.replaceChildren(g);
  if (refocus) pad.querySelector(`[data-corner="${Math.min(focusedCorner, points.length - 1)}"]`)?.focus();
  pad.dataset.outline = f.outline;
  pad.dataset.points = String(points.length);
  pad.dataset.bad = String(bad);
  // Whether what the pad and the error beside it say about the drawn points is the library's
  // answer for them (until it comes, the same rule checked here).
  pad.dataset.checked = String(outlineChecked);
}

/** Reads the chosen SVG file and asks the library for its outline (POST /api/graded/svg): the
 * outline drawn on the pad, or the library's one-line error beside it. */
async function svgChosen() {
  const file = $('svg-file').files?.[0];
  const asked = ++svgAsked;
  document.querySelector('input[name="outline"][value="svg"]').checked = true;
  svgFile = null;
  svgError = '';
  if (!file) {
    check();
    drawPad();
    return;
  }
  const text = await file.text();
  if (asked !== svgAsked) return;
  if (!data.live) {
    // A static site cannot read it; the command shown names the file.
    svgFile = { name: file.name, text, points: null };
  } else {
    try {
      const v = await getJson(`./api/graded/svg?name=${encodeURIComponent(file.name)}`, {
        method: 'POST', headers: { 'content-type': 'image/svg+xml' }, body: text,
      });
      if (asked !== svgAsked) return;
      svgFile = { name: file.name, text, points: v.points };
      $('outline-status').textContent = `${file.name}: an outline of ${v.points.length} corners`;
    } catch (e) {
      if (asked !== svgAsked) return;
      svgError = e.message;
      $('outline-status').textContent = '';
    }
  }
  document.body.dataset.svgChecks = String(Number(document.body.dataset.svgChecks || 0) + 1);
  check();
  drawPad();
}

/** The corners field edited: its corners are the polygon's (choosing the polygon outline), or
 * the reason it is not corners shown beside the pad. */
function cornersTyped() {
  const parsed = parseCorners($('corners').value);
  document.querySelector('input[name="outline"][value="polygon"]').checked = true;
  cornersError = parsed.error ?? '';
  if (!parsed.error) points = parsed.points;
  pointsChanged(true);
}

/** A key on a focused corner of the pad: the arrows move it (0.05; with Shift 0.01), Delete
 * or Backspace removes it. */
function padKey(event) {
  const k = Number(event.target.dataset?.corner);
  if (!Number.isInteger(k) || k >= points.length) return;
  const step = event.shiftKey ? 0.01 : 0.05;
  const moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
  if (moves[event.key]) {
    const [dx, dy] = moves[event.key];
    const round = (v) => Math.round(v * 1e4) / 1e4;
    points = points.map((p, i) => (i === k ? [round(p[0] + dx), round(p[1] + dy)] : p));
  } else if (event.key === 'Delete' || event.key === 'Backspace') {
    points = points.filter((_, i) => i !== k);
  } else {
    return;
  }
  event.preventDefault();
  focusedCorner = points.length ? k : null;
  pointsChanged();
}

/** Adds a corner where the pad was clicked (choosing the polygon outline). */
function padClick(event) {
  const pad = $('pad');
  const g = pad.firstElementChild;
  const ctm = g?.getScreenCTM();
  if (!ctm) return;
  const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(ctm.inverse());
  const polygon = document.querySelector('input[name="outline"][value="polygon"]');
  if (!polygon.checked) {
    polygon.checked = true;
    points = [];
  }
  points = [...points, [Math.round(p.x * 1e4) / 1e4, Math.round(p.y * 1e4) / 1e4]];
  focusedCorner = null;
  pointsChanged();
}

/** Draws `polygons` (and the target) into `svg` framed by `frame` [minX, minY, maxX, maxY],
 * y up; `overlap` (overlapMark) fills two tiles and labels them with their depth; `worst`
 * marks the worst boundary point ([x, y]). Labels are drawn upright, outside the flipped group. */
function drawSheet(svg, polygons, { frame, target = null, overlap = null, worst = null, cells = null }) {
  const [x0, y0, x1, y1] = frame;
  const size = Math.max(x1 - x0, y1 - y0) || 1;
  const m = 0.05 * size;
  const cx = (x0 + x1) / 2;
  const cy = (y0 + y1) / 2;
  const half = size / 2 + m;
  svg.setAttribute('viewBox', `${cx - half} ${-cy - half} ${2 * half} ${2 * half}`);
  const g = s('g', { transform: 'scale(1,-1)' });
  const labels = s('g', { class: 'labels', 'font-size': +(0.035 * size).toFixed(6), 'stroke-width': +(0.008 * size).toFixed(6) });
  polygons.forEach((poly, i) => {
    const hit = overlap && overlap.tiles.includes(i);
    g.append(s('polygon', {
      class: `tile${hit ? ' overlap' : ''}${hit && overlap.deepest ? ' deepest' : ''}`, points: pointsAttr(poly), 'data-tile': i, 'data-overlap': hit ? '' : null,
    }));
  });
  if (overlap && overlap.tiles.every((t) => polygons[t])) {
    const [x, y] = overlapAnchor(polygons, overlap.tiles);
    labels.append(s('text', {
      class: 'overlap-label', x: +x.toFixed(6), y: +(-y).toFixed(6), 'text-anchor': 'middle', 'data-overlap-label': '',
    }));
    labels.lastChild.textContent = overlap.mm === null ? 'overlap' : `${overlap.mm.toFixed(3)} mm`;
  }
  for (const c of cells ?? []) {
    g.append(s('polygon', {
      class: 'field-cell', points: pointsAttr(c.opened), fill: errorColour(c.error), 'data-cell': c.cell, 'data-error': c.error.toFixed(6),
    }));
  }
  if (target?.length) g.append(s('polygon', { class: 'target', points: pointsAttr(target), 'data-target': '' }));
  if (worst) {
    const r = 0.02 * size;
    g.append(s('circle', { class: 'worst', cx: +worst[0].toFixed(6), cy: +worst[1].toFixed(6), r: +r.toFixed(6), 'data-worst': '' }));
    labels.append(s('text', { class: 'worst-label', x: +(worst[0] + 1.4 * r).toFixed(6), y: +(-worst[1] - 1.4 * r).toFixed(6), 'data-worst-label': '' }));
    labels.lastChild.textContent = 'worst';
  }
  svg.replaceChildren(g, labels);
}

async function main() {
  data = await openData();
  document.body.dataset.mode = data.mode;
  $('mode').textContent = data.mode === 'static' ? 'static site (read-only)' : 'live server';
  if (data.live) {
    try {
      settings = await getJson('./api/graded');
    } catch (e) {
      showError(e);
    }
  }
  const initial = emptyForm(settings, window.location.search);
  for (const key of ['design', 'rows', 'cols', 'iterations']) $(key).value = initial[key];
  // Left empty, the tolerance is the library's default, which the placeholder shows.
  $('tolerance').placeholder = String(settings.defaults?.tolerance ?? DEFAULTS.tolerance);
  const limits = settings.limits ?? {};
  if (limits.side !== undefined) {
    for (const key of ['rows', 'cols']) $(key).max = String(limits.side);
    $('iterations').max = String(limits.iterations);
    $('region-cap').textContent = `This server grades at most ${limits.side} cells each way, ${limits.cells} cells and ${limits.tiles} tiles in all, ${limits.iterations} iterations.`;
  }
  $('graded-form').addEventListener('input', (e) => {
    if (e.target.id === 'corners') {
      cornersTyped();
      return;
    }
    check();
    drawPad();
    if (['design', 'rows', 'cols'].includes(e.target.id)) checkSheetSoon();
  });
  $('graded-form').addEventListener('change', (e) => {
    if (e.target.name === 'outline') pointsChanged();
    if (e.target.id === 'svg-file') svgChosen();
  });
  for (const { format, label } of EXPORTS) {
    const b = document.createElement('button');
    b.type = 'button';
    b.textContent = label;
    b.dataset.testid = `export-${format}`;
    b.dataset.format = format;
    b.addEventListener('click', () => exportFile(format));
    $('export-buttons').append(b);
  }
  $('export-edge').addEventListener('input', exportChanged);
  $('graded-form').addEventListener('submit', (event) => {
    event.preventDefault();
    run();
  });
  $('pad').addEventListener('click', padClick);
  $('pad').addEventListener('keydown', padKey);
  $('undo-point').addEventListener('click', () => {
    points = points.slice(0, -1);
    pointsChanged();
  });
  $('clear-points').addEventListener('click', () => {
    points = [];
    pointsChanged();
  });
  $('stop').addEventListener('click', stop);
  $('state-slider').addEventListener('input', () => {
    pause();
    showState(Number($('state-slider').value));
  });
  $('play').addEventListener('click', () => (player?.playing ? pause() : play()));
  $('show-overlap').addEventListener('click', showDeepestOverlap);
  check();
  drawPad();
  document.body.dataset.ready = 'true';
  if (!data.live) {
    $('run').disabled = true;
    $('progress-section').hidden = true;
    $('run-note').textContent = 'The optimiser needs `isogami serve`: run the command below instead, or open this page from `isogami serve`.';
    return;
  }
  checkSheet();
  // The job the URL names, else one running: shown with the form that started it.
  const named = new URLSearchParams(window.location.search).get('job');
  if (named !== null) attach(named, { restore: true });
  else if (settings.running?.length) attach(settings.running[0], { restore: true });
}

/** Fills the form with the request that started a job (its view's echo). */
function restoreForm(request) {
  const f = formFromJob(request, settings);
  for (const key of ['design', 'rows', 'cols', 'iterations', 'aspect', 'tolerance']) $(key).value = f[key];
  $('fall-back').checked = f.fallBack;
  $('field-from').value = f.from;
  $('field-to').value = f.to;
  $('field-degrees').value = f.degrees;
  document.querySelector(`input[name="outline"][value="${f.outline}"]`).checked = true;
  extra = { states: f.states, t: f.t };
  points = f.points;
  if (f.outline === 'svg') {
    svgFile = f.svg;
    svgError = '';
  }
  pointsChanged();
  checkSheetSoon();
  if (f.outline === 'svg') $('outline-status').textContent = `${f.svg.name}: choose the file again to grade it again`;
}

function setRunning(running) {
  $('run').disabled = running;
  $('stop').disabled = !running;
}

async function run() {
  if (!check()) {
    showNotice($('notice'), { message: 'fix the form first: see the message beside the control', hint: '', kind: 'bad_parameter' });
    return;
  }
  const f = form();
  if (f.outline === 'polygon' && points.length < 3) {
    $('outline-error').textContent = 'bad target: an outline needs at least three finite points';
    return;
  }
  if (f.outline === 'svg' && (!svgFile?.text || svgError)) {
    $('outline-error').textContent = svgError || (svgFile ? `choose ${svgFile.name} again: the page has the file's outline, not its text` : svgProblem(f));
    return;
  }
  clearNotice($('notice'));
  $('run').disabled = true;
  try {
    const started = await getJson('./api/graded', {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(gradedBody(f)),
    });
    attach(started.id);
  } catch (e) {
    $('run').disabled = false;
    showError(e);
  }
}

function attach(id, { restore = false } = {}) {
  jobId = String(id);
  restorePending = restore;
  // The URL names the run: a reload or a copied link shows it again.
  const q = new URLSearchParams(window.location.search);
  q.delete('design');
  q.set('job', jobId);
  history.replaceState(null, '', `${window.location.pathname}?${q}`);
  live = null;
  pause();
  player = null;
  document.body.dataset.jobId = String(id);
  document.body.dataset.gradedState = 'running';
  $('results-section').hidden = true;
  $('live-sheet').replaceChildren();
  // An SVG element has no `hidden` property: the attribute itself.
  $('live-sheet').setAttribute('hidden', '');
  $('stage-line').textContent = 'Starting: the design’s own finite sheet, opened…';
  // The job's first view is not here yet: the line and bar say so rather than keep the last
  // job's (or nothing) until the first poll answers.
  $('progress-line').textContent = progressLine({ state: 'running' });
  $('progress-bar').value = 0;
  setRunning(true);
  clearTimeout(timer);
  poll();
}

async function poll() {
  const id = jobId;
  let job;
  try {
    job = await getJson(`./api/graded/${encodeURIComponent(id)}`);
  } catch (e) {
    if (id !== jobId) return;
    restorePending = false;
    setRunning(false);
    document.body.dataset.gradedState = 'lost';
    showError(e);
    return;
  }
  if (id !== jobId) return;
  if (restorePending) {
    restorePending = false;
    restoreForm(job.request);
  }
  render(job);
  if (job.state === 'running') timer = setTimeout(poll, POLL_MS);
  else finish(job);
}

function render(job) {
  const p = job.progress;
  $('progress-line').textContent = progressLine(job);
  const bar = $('progress-bar');
  bar.max = Math.max(1, p?.max_iterations ?? 1);
  bar.value = job.state === 'done' ? bar.max : Math.min(bar.max, p?.iteration ?? 0);
  if (job.state === 'running') {
    $('stage-line').textContent = job.stopping
      ? 'Stopping…'
      : p
        ? `Fitting the shapes: stage ${p.stage + 1} of ${p.stages} (the pins stiffened at each stage); then the pins are closed and the path checked.`
        : 'Starting: the design’s own finite sheet, opened…';
  }
  drawSnapshot(job);
}

/** Draws the job's snapshot when it is a new one, and once more when the job is done (over the
 * fitted target), whether or not a poll while it ran already had its last snapshot. */
function drawSnapshot(job) {
  const snap = job.snapshot;
  const done = job.state === 'done' && Boolean(job.result);
  if (!snap || (live && live.count === snap.count && (live.done || !done))) return;
  if (!live) {
    // The target sized to the sheet's area at its first snapshot (the library sizes it to the
    // start's); the report's fitted outline replaces it at the end.
    const target = outlineAtArea(job.request.outline_points, hullArea(snap.polygons));
    live = { target, frame: bounds(snap.polygons, [target]), count: 0, done: false };
    $('live-target-note').textContent = job.request.field ? '(none: a field target)' : '(sized to the sheet’s area at the start)';
  }
  let target = live.target;
  let worst = null;
  if (done && !job.request.field) {
    target = job.result.report.target;
    worst = worstPoint(job.result);
    $('live-target-note').textContent = '(at the fitted scale)';
  }
  const b = bounds(snap.polygons, [target]);
  live.frame = [Math.min(live.frame[0], b[0]), Math.min(live.frame[1], b[1]), Math.max(live.frame[2], b[2]), Math.max(live.frame[3], b[3])];
  live.count = snap.count;
  live.done = done;
  drawSheet($('live-sheet'), snap.polygons, { frame: live.frame, target, worst });
  $('live-sheet').removeAttribute('hidden');
  $('live-sheet').dataset.iteration = String(snap.iteration);
}

function finish(job) {
  clearTimeout(timer);
  setRunning(false);
  const words = { done: 'Done', failed: 'Failed', stopped: 'Stopped' };
  const iterations = job.progress ? ` after ${job.progress.iteration} iterations` : '';
  $('stage-line').textContent = `${words[job.state] ?? job.state}${iterations} in ${job.elapsed.toFixed(1)} s.`;
  if (job.state === 'done') showResult(job);
  else if (job.error) showNotice($('notice'), { message: job.error.error, hint: job.error.hint, kind: job.error.kind });
  document.body.dataset.gradedState = job.state;
}

/** The library's verdict, in its own words, and the outline's fit figures. */
function showVerdict(result) {
  const v = verdictView(result);
  const box = $('verdict');
  box.textContent = v.text ?? 'This result has no verdict (written before the library gave one): see the report below.';
  box.dataset.level = v.level;
  box.dataset.opens = String(v.opens);
  box.dataset.meets = String(v.meets);
  const figures = fitFigures(result);
  $('fit-figures').hidden = figures.length === 0;
  $('fit-list').replaceChildren(...figures.map((f) => el('div', { 'data-key': f.key }, el('dt', {}, f.label), el('dd', {}, f.text))));
}

function showResult(job) {
  const result = job.result;
  showVerdict(result);
  $('report').replaceChildren(...reportLines(result).map((l) => {
    const li = document.createElement('li');
    li.dataset.key = l.key;
    li.dataset.testid = `report-${l.key}`;
    if (l.key === 'path') li.dataset.reached = String(verdictView(result).opens);
    li.textContent = l.text;
    return li;
  }));
  const states = playerStates(result);
  const all = states.map((st) => posedPolygons(result.sheet, st.poses));
  const cells = fieldRows(result);
  const worst = worstPoint(result);
  player = {
    job,
    result,
    states,
    all,
    cells,
    deepest: deepestOverlapIndex(result),
    worst,
    frame: bounds(...all, [result.report.target], cells.map((c) => c.opened), worst ? [[worst]] : []),
    playing: false,
    timer: 0,
  };
  $('show-overlap').hidden = player.deepest === null;
  const slider = $('state-slider');
  slider.max = String(states.length - 1);
  slider.value = String(states.length - 1);
  showState(states.length - 1);
  $('download').href = `./api/graded/${encodeURIComponent(job.id)}/sheet`;
  $('download').setAttribute('download', `graded-${job.request.rows}x${job.request.cols}.json`);
  showField(player.cells);
  exportChanged();
  $('export-status').textContent = '';
  $('results-section').hidden = false;
}

/** The field's cells in the table (a field target only). */
function showField(cells) {
  $('field-result').hidden = cells.length === 0;
  $('field-table').tBodies[0].replaceChildren(...cells.map((c) => {
    const tr = document.createElement('tr');
    tr.dataset.cell = String(c.cell);
    for (const v of [String(c.cell), c.target.toFixed(4), c.ratio.toFixed(4), `${c.error >= 0 ? '+' : '−'}${Math.abs(c.error).toFixed(4)}`]) {
      const td = document.createElement('td');
      td.textContent = v;
      tr.append(td);
    }
    tr.lastChild.style.background = errorColour(c.error);
    return tr;
  }));
}

/** The export command for the current edge length; the edge's problem shown. */
function exportChanged() {
  const edge = $('export-edge').value;
  const problem = edgeProblem(edge);
  for (const b of $('export-buttons').children) b.disabled = Boolean(problem) || !player;
  $('export-status').textContent = problem;
  const r = player?.job.request;
  $('export-command').textContent = r ? exportCommand('svg', edge, r.rows, r.cols) : '';
}

/** Downloads the graded sheet in `format` (the server's export of the finished job), or shows
 * the server's one-line reason. */
async function exportFile(format) {
  if (!player || edgeProblem($('export-edge').value)) return;
  const job = player.job;
  const url = `./api/graded/${encodeURIComponent(job.id)}/export?${exportParams(format, $('export-edge').value)}`;
  $('export-status').textContent = `exporting ${format.toUpperCase()}…`;
  $('export-command').textContent = exportCommand(format, $('export-edge').value, job.request.rows, job.request.cols);
  let res;
  try {
    res = await fetch(url);
  } catch (e) {
    $('export-status').textContent = `cannot reach the server: ${e.message}`;
    return;
  }
  if (!res.ok) {
    let message = `${res.status} ${res.statusText}`;
    try {
      const body = await res.json();
      if (typeof body.error === 'string') message = body.error;
    } catch {
      // not JSON: the status says it
    }
    $('export-status').textContent = message;
    return;
  }
  const blob = await res.blob();
  const disposition = res.headers.get('content-disposition') || '';
  const name = /filename="([^"]+)"/.exec(disposition)?.[1] ?? `graded.${format}`;
  const href = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = href;
  a.download = name;
  a.hidden = true;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(href), 60000);
  const warning = res.headers.get('x-isogami-warning');
  $('export-status').textContent = `saved ${name} (${blob.size} bytes)${warning ? `; warning: ${decodeURIComponent(warning.replace(/\+/g, ' '))}` : ''}`;
}

/** Shows player state `k` (0 closed … n − 1 the optimised opened state). */
function showState(k) {
  if (!player) return;
  const n = player.states.length;
  const st = player.states[k];
  const opened = k === n - 1;
  const mark = overlapMark(player.result, k, player.deepest);
  drawSheet($('player-sheet'), player.all[k], {
    frame: player.frame,
    target: opened ? player.result.report.target : null,
    overlap: mark,
    worst: opened ? player.worst : null,
    cells: opened ? player.cells : null,
  });
  $('player-sheet').dataset.state = String(k);
  $('state-value').textContent = `${(100 * st.opening).toFixed(0)} % open${st.dof === null || st.dof === undefined ? '' : ` · DOF ${st.dof}`}${mark ? ` · ${mark.label}` : ''}`;
}

/** Moves the player to the state of the path's deepest overlap. */
function showDeepestOverlap() {
  if (player?.deepest === null || player?.deepest === undefined) return;
  pause();
  $('state-slider').value = String(player.deepest);
  showState(player.deepest);
}

function play() {
  if (!player || player.states.length < 2) return;
  player.playing = true;
  $('play').textContent = 'Pause';
  $('play').setAttribute('aria-pressed', 'true');
  const n = player.states.length;
  // Ping-pong over 0 … n − 1 from where the slider is, heading for the other end. A timer,
  // not animation frames: those stop while the page is hidden, a timer only slows.
  const period = 2 * (n - 1);
  const from = Number($('state-slider').value);
  let t = from === n - 1 ? n - 1 : from;
  clearInterval(player.timer);
  player.timer = setInterval(() => {
    t = (t + 1) % period;
    const k = t < n ? t : period - t;
    $('state-slider').value = String(k);
    showState(k);
  }, 1000 / PLAY_RATE);
}

function pause() {
  if (!player) return;
  player.playing = false;
  clearInterval(player.timer);
  $('play').textContent = 'Play';
  $('play').setAttribute('aria-pressed', 'false');
}

async function stop() {
  if (jobId === null) return;
  $('stop').disabled = true;
  try {
    render(await getJson(`./api/graded/${encodeURIComponent(jobId)}`, { method: 'DELETE' }));
  } catch (e) {
    showError(e);
  }
}

main();
