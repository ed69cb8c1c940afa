// The design page (design.html?spec=…&R=4&C=4&kerf=…&colour=linkage|rotation&t=…): the
// deployment of an R×C patch on a canvas with a t slider, play/pause and speed; colouring by
// linkage or rotation; the unit cell and lattice vectors and the linkage loops on demand;
// min/max principal expansion versus t and the polar stretch profile following t; every
// measure; the spec with a copy button; downloads; and, over `isogami serve`, live design
// (editor.js): each change is deployed on the server while the control moves (live-queue.js:
// at most one request per interval, the latest value winning, the request in flight aborted)
// and a refusal is explained next to the control that caused it, while every panel still
// showing the last valid design is marked stale (dimmed, a badge, `data-stale`) until a valid
// design is shown again. A design not in the database is deployed live; the view state is
// kept in the URL. On wide screens the sheet stays in view (sticky) beside the controls. Beside the periodic figures, the finite-sheet panel
// (finite-panel.js): what a sheet cut to a region does, animated by the same t and Play.

import { openData } from './data.js';
import { h, fmt, fmtExpansion, showNotice, clearNotice, debounce } from './dom.js';
import { createLinePlot, createPolarPlot } from './plots.js';
import {
  frameAt,
  motionBounds,
  linkageColour,
  linkageFill,
  tileLinkageKinds,
  NO_LINKAGE_COLOUR,
  SHARED_LINKAGE_COLOUR,
} from './patch.js';
import { drawSheet } from './sheet.js';
import { FIT, attachZoom } from './zoom-pan.js';
import { createEditor } from './editor.js';
import { LatestThrottle } from './live-queue.js';
import { catalogueHref, designSearch, parseDesignState } from './url.js';
import { download, fileStem, frameSvg, trajectoryCsv } from './export.js';
import { facetLabel } from './schema.js';
import { sheetStatus } from './buildable.js';
import { createExportPanel } from './export-panel.js';
import { createMotionPanel } from './motion-panel.js';
import { createFinitePanel } from './finite-panel.js';

const $ = (id) => document.getElementById(id);
const PLAY_SECONDS = 4; // t from 0 to 1 at speed 1

let data;
let state;
let view = null;
let families = [];
let bounds = null;
let editor = null;
let playing = false;
let live = null; // LatestThrottle of live deployments
let rangesRequest = null; // AbortController of the running GET /api/shape/ranges
// Whether the design shown is well-shaped at its shape (every parameter inside its well-shaped
// band, GET /api/shape/ranges): true, false, or null until that answer is in. Save waits for true.
let wellShaped = null;
let sheetZoom = FIT; // the sheet canvas's zoom and pan (zoom-pan.js)
let exportPanel = null;
let finitePanel = null;

async function main() {
  $('back-link').href = catalogueHref(); // the filters, sort and view the catalogue last had
  data = await openData();
  document.body.dataset.mode = data.mode;
  state = parseDesignState(location.search);
  setupControls();
  const expansion = createLinePlot($('expansion-plot'), { xLabel: 't', yLabel: 'principal expansion' });
  const polar = createPolarPlot($('polar-plot'));
  plots = { expansion, polar };
  if (!state.spec) {
    showNotice($('notice'), {
      message: 'No design given.',
      hint: 'open a design from the catalogue, or add ?spec=FAMILY:PARAMS:CELL:JOINTS to the address',
      kind: 'bad_design',
    });
    return;
  }
  try {
    families = await data.families();
  } catch (e) {
    families = [];
  }
  try {
    defaultKerf = (await data.exportCatalog()).defaults.kerf;
  } catch {
    defaultKerf = null;
  }
  exportPanel = createExportPanel($('export-panel'), {
    data,
    current: () => (view
      ? { spec: view.spec, kerf: view.report.kerf, t: state.t, tiles: view.geometry.tiles.length, family: view.geometry.family, summary: view.summary ?? null }
      : null),
    initial: { rows: state.rows, cols: state.cols },
  });
  finitePanel = createFinitePanel($('finite-panel'), {
    data,
    current: () => (view ? { spec: view.spec, kerf: view.report.kerf } : null),
    defaultKerf: () => defaultKerf,
  });
  motionPanel = createMotionPanel($('motion-section'), $('motion-variants'), { data });
  editor = createEditor($('editor'), {
    live: data.live,
    // Static copies have no shape analysis: the sliders then say nothing about it.
    shape: data.live
      ? { classify: (spec, signal) => data.shape(spec, signal), follow: (spec, i, v) => data.followShape(spec, i, v) }
      : null,
    reason: 'Live design needs `isogami serve`: this is a static copy of the catalogue. Run `isogami serve --db FILE` to tune designs.',
    onChange: (spec, kerf, source) => requestDeploy(spec, kerf, source),
  });
  await load();
}

let plots;
let motionPanel;
let defaultKerf = null;

/** The stored design, or (on a server) a live deployment when it is not stored or another
 * kerf is asked: one request, which the server answers either way. */
async function load() {
  setStatus('loading…');
  let v = null;
  try {
    v = data.live ? await data.designView(state.spec, state.kerf) : await data.design(state.spec);
  } catch (e) {
    fail(e);
    return;
  }
  showView(v, { fromEditor: false });
}

function deployBody(spec, kerf) {
  const body = { design: spec };
  if (kerf !== null && kerf !== undefined) body.kerf = kerf;
  return body;
}

function fail(e) {
  setStatus('');
  showNotice($('notice'), {
    message: e.message,
    hint: e.hint || (e.kind === 'network' ? 'check that the server is running' : ''),
    kind: e.kind,
  });
}

function setStatus(text) {
  $('status').textContent = text;
}

/** Live deployments of edited designs: sent while the control moves, latest value wins. */
function liveQueue() {
  if (live) return live;
  live = new LatestThrottle(({ spec, kerf }, signal) => data.deploy(deployBody(spec, kerf), signal), {
    onResult: (v, asked, ms, requestMs) => {
      const t0 = performance.now();
      showView(v, { fromEditor: true, source: asked.source });
      const drawn = performance.now();
      // Input → drawn (and its parts), for the live-design benchmark (e2e/bench-live.mjs).
      (window.isogamiLive ??= []).push({ ms: ms + (drawn - t0), requestMs, drawMs: drawn - t0, spec: v.spec });
      settled();
    },
    onError: (e, asked) => {
      setStatus('');
      refuse(e, asked.source);
      settled();
    },
  });
  return live;
}

/** Once a drag's last answer is in: the panels that ask the server for more (the finite
 * sheet, the sliders' ranges) catch up, having waited so as not to compete with the drag's
 * deployments for the server. */
let followUps = false;
function settled() {
  if (live.busy()) return;
  document.body.classList.remove('simulating');
  if (followUps && view) {
    followUps = false;
    editor.showGeometry(view);
    motionPanel.show(view.spec, view.origin !== null && view.origin !== undefined, view.summary?.max_area_ratio ?? null);
    finitePanel.show();
    rangesSoon(view.spec, view.report.kerf);
  }
}

function requestDeploy(spec, kerf, source) {
  setStatus('re-simulating…');
  document.body.classList.add('simulating');
  liveQueue().push({ spec, kerf, source });
}

/** A refused edit: its reason next to the control, and every panel marked stale. */
function refuse(e, source) {
  const notice = { message: e.message, hint: e.hint, kind: e.kind };
  if (source) editor.showNotice(source, notice);
  else showNotice($('notice'), notice);
  markStale(true, e.kind);
}

/** Panels that show the current design; marked stale while an edit is refused. */
const STALE_PANELS = ['.viewer', '.charts', '.measures', '.finite', '.export', '.downloads', '.spec-line'];

function markStale(stale, kind = '') {
  const badge = $('stale-badge');
  if (stale) {
    document.body.dataset.stale = 'true';
    badge.hidden = false;
    badge.textContent = `stale: the edit was refused${kind ? ` (${kind.replace(/_/g, ' ')})` : ''}; every panel shows the last valid design, ${view ? view.spec : ''}`;
  } else {
    delete document.body.dataset.stale;
    badge.hidden = true;
    badge.textContent = '';
  }
  for (const sel of STALE_PANELS) {
    for (const el of document.querySelectorAll(sel)) {
      if (stale) {
        el.dataset.stale = 'true';
        el.setAttribute('aria-describedby', 'stale-badge');
      } else {
        delete el.dataset.stale;
        el.removeAttribute('aria-describedby');
      }
    }
  }
  updateSave();
}

/** Save: enabled for a live design shown (not stale, not stored) once it is known to be
 * well-shaped; a design that is not says why beside the button. */
function updateSave() {
  const stale = document.body.dataset.stale === 'true';
  const status = $('save-status');
  $('save').disabled = stale || !data.live || !view || view.origin !== null || wellShaped !== true;
  const reason = data.live && view && view.origin === null && wellShaped === false
    ? 'not saved: the tile is not well-shaped at this shape (degenerate or self-touching); move the sliders back into the green band'
    : '';
  if (reason) {
    status.textContent = reason;
    status.dataset.reason = 'ill-shaped';
  } else if (status.dataset.reason) {
    status.textContent = '';
    delete status.dataset.reason;
  }
}

/** Asks for each shape parameter's valid range at the design shown (server mode). */
const rangesSoon = debounce(async (spec, kerf) => {
  if (!data.live || !data.shapeRanges) return;
  if (rangesRequest) rangesRequest.abort();
  const controller = new AbortController();
  rangesRequest = controller;
  try {
    const answer = await data.shapeRanges(spec, kerf, controller.signal);
    if (rangesRequest !== controller || !view || view.spec !== spec) return;
    editor.setRanges(answer);
    wellShaped = answer.ranges.every((r) => r.well_shaped !== null);
    updateSave();
  } catch (e) {
    // No ranges: the sliders keep their default span (the server still refuses bad shapes);
    // a design that does not build (422) is not saved.
    if (e?.name !== 'AbortError' && rangesRequest === controller && view?.spec === spec) {
      wellShaped = e?.status === 422 ? false : null;
      updateSave();
    }
  }
}, 120);

/** Shows a DesignView: canvas, plots, measures, editor; its notice (multi-DOF, locked) if any. */
function showView(v, { fromEditor, source = null }) {
  if (v.spec !== view?.spec) wellShaped = null;
  view = v;
  state.spec = v.spec;
  state.kerf = fromEditor ? v.report.kerf : state.kerf;
  markStale(false);
  // A remark on an edited design (several DOF, locked) goes next to the control that made it.
  const notice = v.notice ? { message: v.notice.message, hint: v.notice.hint, kind: v.notice.kind } : null;
  if (fromEditor && source) {
    clearNotice($('notice'));
    if (notice) editor.showNotice(source, notice);
    else editor.clearNotices();
  } else if (notice) showNotice($('notice'), notice);
  else clearNotice($('notice'));
  $('spec').textContent = v.spec;
  $('grade-link').href = `./graded.html?design=${encodeURIComponent(v.spec)}`;
  const origin = v.origin ?? 'live';
  $('origin').textContent = origin === 'live' ? 'live (not in the database)' : `${origin} design`;
  $('origin').dataset.origin = origin;
  showSheetBadge(v);
  showOtherCells(v);
  updateSave();
  const dragging = fromEditor && live && live.busy();
  if (dragging) followUps = true;
  else rangesSoon(v.spec, v.report.kerf);
  $('download-gif').hidden = !data.live || v.origin === null;
  bounds = motionBounds(v, state.rows, state.cols);
  const frames = v.report.frames;
  plots.expansion.update([
    { name: 'max expansion', className: 'max', points: frames.map((f) => [f.t, f.measures.max_expansion]) },
    { name: 'min expansion', className: 'min', points: frames.map((f) => [f.t, f.measures.min_expansion]) },
  ]);
  let rMax = 1;
  for (const f of frames) rMax = Math.max(rMax, 1 + f.measures.max_expansion, 1 + f.measures.min_expansion);
  plots.polar.setMaxRadius(rMax);
  renderSummary();
  renderLegend();
  // During a drag the joint editor's cell is redrawn once the drag's last answer is in.
  if (!fromEditor) editor.sync(v, families);
  else if (!dragging) editor.showGeometry(v);
  if (!dragging) motionPanel.show(v.spec, v.origin !== null && v.origin !== undefined, v.summary?.max_area_ratio ?? null);
  document.title = `${v.spec} · isogami`;
  setStatus(fromEditor ? `re-simulated: ${frames.length} frames, ${v.report.steps} steps` : '');
  document.body.dataset.deployments = String(Number(document.body.dataset.deployments || 0) + 1);
  if (!dragging) finitePanel.show();
  renderFrame();
}

/** The badge of the design's finite sheet (buildable.js) from its catalogue row: "no one-DOF
 * sheet" or the fraction its sheet keeps; a live design (no row) has none. */
function showSheetBadge(v) {
  const badge = $('sheet-badge');
  const s = sheetStatus(v.summary);
  badge.hidden = !v.summary;
  badge.dataset.sheet = s.kind;
  badge.title = s.title;
  badge.replaceChildren(s.text, Object.assign(document.createElement('span'), { className: 'visually-hidden', textContent: `: ${s.title}` }));
}

/** The specs of the same design on other cells of its family, stored with this one (cell
 * twins): the catalogue lists it once, so the page names the others. */
function showOtherCells(v) {
  const line = $('other-cells');
  const others = v.other_cells ?? [];
  line.hidden = others.length === 0;
  if (line.hidden) return;
  const cells = others.map((s) => s.split(':')[2]?.replace('x', '×') ?? s);
  line.replaceChildren(
    `The same design (shape and motion) is also found on the ${cells.join(', ')} cell${others.length > 1 ? 's' : ''}, stored once as this one: `,
    ...others.flatMap((s, i) => [i > 0 ? ', ' : '', Object.assign(document.createElement('code'), { textContent: s })]),
  );
}

function renderFrame() {
  if (!view) return;
  const frame = frameAt(view.report, state.t);
  drawSheet($('sheet'), view, frame, { rows: state.rows, cols: state.cols, colour: state.colour, cell: state.cell, links: state.links, bounds, zoom: sheetZoom });
  plots.expansion.setMarker(state.t);
  plots.polar.update(frame.F);
  $('t').value = String(state.t);
  $('t-value').textContent = state.t.toFixed(3);
  renderFrameMeasures(frame);
  finitePanel?.render(state.t);
  exportPanel?.update();
  saveUrl();
}

const saveUrl = debounce(() => {
  history.replaceState(null, '', `${location.pathname}${designSearch(state)}`);
}, 150);

function setupControls() {
  $('t').addEventListener('input', () => {
    state.t = Number($('t').value);
    renderFrame();
  });
  $('play').addEventListener('click', () => (playing ? stop() : play()));
  for (let n = 1; n <= 8; n += 1) {
    $('rows').append(h('option', { value: n }, String(n)));
    $('cols').append(h('option', { value: n }, String(n)));
  }
  $('rows').value = String(state.rows);
  $('cols').value = String(state.cols);
  $('colour').value = state.colour;
  $('show-cell').checked = state.cell;
  $('show-links').checked = state.links;
  const patch = () => {
    state.rows = Number($('rows').value);
    state.cols = Number($('cols').value);
    if (view) bounds = motionBounds(view, state.rows, state.cols);
    renderFrame();
  };
  $('rows').addEventListener('change', patch);
  $('cols').addEventListener('change', patch);
  $('colour').addEventListener('change', () => {
    state.colour = $('colour').value;
    renderLegend();
    renderFrame();
  });
  $('show-cell').addEventListener('change', () => {
    state.cell = $('show-cell').checked;
    renderFrame();
  });
  $('show-links').addEventListener('change', () => {
    state.links = $('show-links').checked;
    renderLegend();
    renderFrame();
  });
  $('copy').addEventListener('click', async () => {
    try {
      await navigator.clipboard.writeText($('spec').textContent);
      $('copy-status').textContent = 'copied';
    } catch {
      const range = document.createRange();
      range.selectNodeContents($('spec'));
      getSelection().removeAllRanges();
      getSelection().addRange(range);
      $('copy-status').textContent = 'selected: press Ctrl+C';
    }
  });
  $('save').addEventListener('click', save);
  $('download-json').addEventListener('click', () => view && download(`${fileStem(view.spec)}.trajectory.json`, JSON.stringify(view.report, null, 1), 'application/json'));
  $('download-csv').addEventListener('click', () => view && download(`${fileStem(view.spec)}.trajectory.csv`, trajectoryCsv(view.report), 'text/csv'));
  $('download-svg').addEventListener('click', () => {
    if (!view) return;
    const frame = frameAt(view.report, state.t);
    const svg = frameSvg(view, frame, { rows: state.rows, cols: state.cols, colour: state.colour, bounds, links: state.links });
    download(`${fileStem(view.spec)}.t${state.t.toFixed(3)}.svg`, svg, 'image/svg+xml');
  });
  $('download-gif').addEventListener('click', () => {
    if (view && data.gifUrl(view.spec)) {
      const a = h('a', { href: data.gifUrl(view.spec), download: `${fileStem(view.spec)}.gif` });
      document.body.append(a);
      a.click();
      a.remove();
    }
  });
  if (!data.live) {
    $('save').disabled = true;
    $('download-gif').hidden = true;
    $('gif-note').textContent = 'GIF: needs `isogami serve`.';
  }
  attachZoom($('sheet'), () => sheetZoom, (z) => {
    sheetZoom = z;
    renderFrame();
  });
  new ResizeObserver(() => renderFrame()).observe($('sheet'));
}

function play() {
  playing = true;
  $('play').textContent = 'Pause';
  $('play').setAttribute('aria-pressed', 'true');
  let last = performance.now();
  const tick = (now) => {
    if (!playing) return;
    const speed = Number($('speed').value) || 1;
    state.t += ((now - last) / 1000 / PLAY_SECONDS) * speed;
    last = now;
    if (state.t > 1) state.t = 0;
    renderFrame();
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
}

function stop() {
  playing = false;
  $('play').textContent = 'Play';
  $('play').setAttribute('aria-pressed', 'false');
}

async function save() {
  const current = editor.current();
  if (!current) return;
  $('save').disabled = true;
  try {
    const res = await data.save({ design: view.spec, kerf: view.report.kerf });
    $('save-status').textContent = `saved as a user design: ${res.spec}`;
    view.origin = 'user';
    $('origin').textContent = 'user design';
    $('origin').dataset.origin = 'user';
    $('download-gif').hidden = false;
  } catch (e) {
    $('save').disabled = e.status === 409;
    $('save-status').textContent = e.status === 409 ? 'already in the database' : '';
    if (e.status !== 409) showNotice($('notice'), { message: e.message, hint: e.hint, kind: e.kind });
  }
}

function row(label, value, unit = '') {
  return h('tr', {}, h('th', { scope: 'row' }, label), h('td', { class: 'num' }, value), h('td', { class: 'unit' }, unit));
}

/** The smallest principal expansion over the motion; when the sheet contracts (ε < 0 beyond
 * rounding: IH90::1x1:aaa opens to ε = 1, then closes past its start to −0.004 at the contact
 * limit), by how much and at which t (the frame where it is smallest). */
function minExpansionText(r) {
  const text = fmtExpansion(r.min_expansion);
  if (!text.includes('contracts')) return text;
  let at = null;
  for (const f of r.frames) if (at === null || f.measures.min_expansion < at.measures.min_expansion) at = f;
  return at ? text.replace(/\)$/, ` at t = ${fmt(at.t)})`) : text;
}

function renderSummary() {
  const r = view.report;
  const l = view.linkages;
  const hist = l ? Object.entries(l.degree_histogram).map(([d, n]) => `${n}×deg ${d}`).join(', ') : '–';
  const s = view.summary;
  // The report's own range (live deployments too); the catalogue row's for reports stored before it.
  const poisson = r.poisson_range ?? (s && s.poisson_min !== null ? [s.poisson_min, s.poisson_max] : null);
  $('summary').replaceChildren(
    h('caption', {}, 'Whole deployment'),
    h(
      'tbody',
      {},
      row('family / cell', `${view.geometry.family} · ${view.geometry.cell.join('×')}`),
      row('tiles in cell', String(view.geometry.tiles.length)),
      row('behaviour', facetLabel('behaviour', r.behaviour ?? null)),
      row('linkages', l ? l.signature : '–'),
      row('tile degrees', hist),
      row('degrees of freedom', String(r.dof)),
      row('method', r.method),
      row('end reason', typeof r.end_reason === 'object' ? r.end_reason.kind.replace(/_/g, ' ') : String(r.end_reason)),
      row('max expansion', fmt(r.max_expansion)),
      row('min expansion', minExpansionText(r)),
      row('max area ratio', fmt(r.max_area_ratio)),
      row('max tile rotation', fmt(r.max_tile_rotation), 'rad'),
      row('Poisson-like ratio', poisson ? `${fmt(poisson[0])} … ${fmt(poisson[1])}` : '–'),
      row('kerf', fmt(r.kerf), '× L'),
      row('mean edge length L', fmt(r.length_scale), 'tiling units'),
      row('steps / attempts', `${r.steps} / ${r.attempts}`),
      row('arc length', fmt(r.arc_length)),
      row('max joint residual', fmt(r.max_joint_residual), '× L'),
      row('min clearance', fmt(r.min_clearance), '× L'),
    ),
  );
}

function renderFrameMeasures(frame) {
  const f = view.report.frames[frame.index];
  const m = f.measures;
  const F = frame.F;
  $('at-t').replaceChildren(
    h('caption', {}, `At t = ${state.t.toFixed(3)} (nearest frame ${frame.index}, t = ${f.t.toFixed(3)})`),
    h(
      'tbody',
      {},
      row('F', `[${fmt(F[0][0])} ${fmt(F[0][1])}; ${fmt(F[1][0])} ${fmt(F[1][1])}]`),
      row('area ratio det F', fmt(F[0][0] * F[1][1] - F[0][1] * F[1][0])),
      row('min / max expansion', `${fmt(m.min_expansion)} / ${fmt(m.max_expansion)}`),
      row('principal angle', fmt(m.principal_angle), 'rad'),
      row('lattice rotation', fmt(m.lattice_rotation), 'rad'),
      row('max tile rotation', fmt(m.max_tile_rotation), 'rad'),
      row('joint residual', fmt(f.joint_residual), '× L'),
      row('min clearance', fmt(f.min_clearance), '× L'),
    ),
  );
}

/** The legend: one entry per linkage with its loop colour (a line swatch, as drawn), then what
 * the tile fill means — by linkage only the kinds present (one linkage, shared, none), or the
 * rotation ramp. */
function renderLegend() {
  if (!view) return;
  const l = view.linkages ? view.linkages.linkages : [];
  const tilesOf = (i) => (view.tile_linkages || []).filter((set) => set.length === 1 && set[0] === i).length;
  const colouring = state.colour !== 'rotation';
  const loops = l.map((k, i) =>
    h(
      'li',
      { 'data-testid': 'legend-linkage', 'data-colour': linkageColour(i) },
      h('span', { class: 'swatch loop', style: `background:${linkageColour(i)}` }),
      `linkage ${i + 1}: ${k.bars}-bar loop`,
      colouring && tilesOf(i) ? [' ', h('span', { class: 'swatch', style: `background:${linkageFill(i)}` }), `its own tiles`] : null,
    ),
  );
  if (!l.length) loops.push(h('li', {}, 'no linkages (no closed loop of pinned tiles)'));
  else if (!state.links) loops.push(h('li', { class: 'muted' }, 'loops hidden: tick “linkage loops” to draw them'));
  let fills;
  if (state.colour === 'rotation') {
    const m = view.report.max_tile_rotation;
    fills = [
      h('span', { class: 'ramp' }),
      ` tile rotation: −${fmt(m)} rad (clockwise, blue) through 0 (white) to +${fmt(m)} rad (counter-clockwise, red)`,
    ];
  } else {
    const kinds = tileLinkageKinds(view);
    const item = (colour, text) => h('li', {}, h('span', { class: 'swatch', style: `background:${colour}` }), text);
    const list = [];
    if (kinds.single) list.push(h('li', {}, 'tile in one linkage only: that loop’s colour, pale'));
    if (kinds.shared) list.push(item(SHARED_LINKAGE_COLOUR, 'tile shared by several linkages (the loops tell them apart)'));
    if (kinds.none) list.push(item(NO_LINKAGE_COLOUR, 'tile in no linkage'));
    fills = [h('ul', { 'data-testid': 'legend-fills' }, list)];
  }
  $('legend').replaceChildren(h('ul', { 'data-testid': 'legend-loops' }, loops), ...fills);
}

main().catch((e) => fail(e));
