// The design page's "Finite sheet" panel: what a sheet cut to a region of the design does,
// beside the periodic figures. A region (R×C cells, or a rectangle or disc in mm), the DOF
// badge of the sheet shown ("1 DOF ✓" or "N DOF: these tiles flop", the floppy tiles
// highlighted), the raw region or its completion to a one-DOF sheet (removed tiles ghosted,
// added tiles marked), the refusal when there is none, and the completed sheet's finite
// deployment animated by the page's t and Play. One GET /api/sheet per design and region
// (debounced, the previous request aborted); on a static site the panel says it needs the
// server and asks nothing.

import { h, fmt } from './dom.js';
import { FIT, attachZoom, zoomedTransform } from './zoom-pan.js';
import {
  dofBadge, finiteFrameAt, latticeOf, placePolygon, poseOutside, sheetCommand, sheetKerfDiffers, sheetLayers, sheetParams,
} from './sheet-request.js';

const FILL = { plain: '#c9d6e3', kept: '#c9d6e3', floppy: '#e4572e', added: '#7bc96f', removed: 'rgba(120, 120, 120, 0.12)' };
const STROKE = { plain: '#333333', kept: '#333333', floppy: '#7a1f08', added: '#1e6b14', removed: '#9a9a9a' };
const MAX_CELLS = 12;

/** Draws the panel into `container`. `current()` gives {spec, kerf} of the design on screen
 * (null before one is shown); `defaultKerf()` the library's default kerf (left out of the
 * request and command when equal). */
export function createFinitePanel(container, { data, current, defaultKerf = () => null }) {
  const el = {};
  let answer = null;
  let inflight = null;
  let timer = null;
  let asked = '';
  let lastT = 0;
  let bounds = null;
  let zoom = FIT; // the canvas's zoom and pan (zoom-pan.js)

  if (!data.live) {
    container.replaceChildren(
      h(
        'p',
        { class: 'notice', testid: 'finite-unavailable' },
        'The finite sheet needs `isogami serve`: this static copy has no simulation. Run `isogami sheet --design SPEC --region 6x6 --deploy` from the command line, or `isogami serve --db FILE` and open the design there.',
      ),
    );
    return { show() {}, render() {} };
  }

  const form = () => {
    const now = current();
    if (!now) return null;
    return {
      spec: now.spec,
      kerf: now.kerf,
      shape: el.shape.value,
      rows: el.rows.value,
      cols: el.cols.value,
      width: el.width.value,
      height: el.height.value,
      radius: el.radius.value,
    };
  };

  function numberInput(id, attrs) {
    return h('input', { id, testid: id, type: 'number', inputmode: 'decimal', ...attrs, oninput: changed, onchange: changed });
  }

  function build() {
    el.shape = h(
      'select',
      { id: 'finite-shape', testid: 'finite-shape', onchange: changed },
      h('option', { value: 'cells' }, 'rows × columns of cells'),
      h('option', { value: 'rect' }, 'rectangle (mm)'),
      h('option', { value: 'disc' }, 'disc (mm)'),
    );
    el.rows = numberInput('finite-rows', { min: 1, max: MAX_CELLS, step: 1, value: 4 });
    el.cols = numberInput('finite-cols', { min: 1, max: MAX_CELLS, step: 1, value: 4 });
    el.width = numberInput('finite-width', { min: 1, step: 'any', value: 100 });
    el.height = numberInput('finite-height', { min: 1, step: 'any', value: 80 });
    el.radius = numberInput('finite-radius', { min: 1, step: 'any', value: 50 });
    el.cellsRow = h('span', { class: 'finite-sizes' }, h('label', { for: 'finite-rows' }, 'rows'), el.rows, h('label', { for: 'finite-cols' }, 'columns'), el.cols);
    el.rectRow = h('span', { class: 'finite-sizes', hidden: true }, h('label', { for: 'finite-width' }, 'width'), el.width, h('label', { for: 'finite-height' }, 'height'), el.height, ' mm');
    el.discRow = h('span', { class: 'finite-sizes', hidden: true }, h('label', { for: 'finite-radius' }, 'radius'), el.radius, ' mm');
    const radio = (value, label) =>
      h('label', { class: 'radio' }, h('input', { type: 'radio', name: 'finite-view', value, testid: `finite-view-${value}`, checked: value === 'completed', onchange: () => render(lastT) }), ' ', label);
    el.badge = h('span', { class: 'dof-badge', testid: 'finite-dof', 'aria-live': 'polite' });
    el.summary = h('p', { class: 'finite-summary', testid: 'finite-summary' });
    el.refusal = h('p', { class: 'notice notice-refused', testid: 'finite-refusal', hidden: true });
    el.singular = h('p', { class: 'notice notice-refused', testid: 'finite-singular', hidden: true });
    el.error = h('div', { class: 'notice notice-error', role: 'alert', testid: 'finite-error', hidden: true });
    el.canvas = h('canvas', { id: 'finite-canvas', testid: 'finite-canvas', role: 'img', 'aria-label': 'the finite sheet' });
    attachZoom(el.canvas, () => zoom, (z) => {
      zoom = z;
      render(lastT);
    });
    el.motion = h('p', { class: 'muted finite-motion', testid: 'finite-motion' });
    el.status = h('span', { class: 'muted', testid: 'finite-status', 'aria-live': 'polite' });
    el.command = h('code', { testid: 'finite-command' });
    el.kerfNote = h('span', { class: 'muted' });
    el.legend = h(
      'ul',
      { class: 'legend finite-legend' },
      [['floppy', 'flops (raw region)'], ['removed', 'removed by completion'], ['added', 'added by completion']].map(([role, text]) =>
        h('li', {}, h('span', { class: 'swatch', style: `background:${FILL[role]};border-color:${STROKE[role]}` }), text),
      ),
    );
    container.replaceChildren(
      h('div', { class: 'controls' }, h('label', { for: 'finite-shape' }, 'region'), el.shape, el.cellsRow, el.rectRow, el.discRow, el.status),
      h('div', { class: 'controls' }, h('fieldset', { class: 'finite-view' }, h('legend', {}, 'show'), radio('completed', 'completed sheet'), radio('raw', 'raw region')), el.badge),
      el.summary,
      el.refusal,
      el.singular,
      el.error,
      el.canvas,
      el.motion,
      el.legend,
      h('p', { class: 'help' }, 'The same from the command line: ', el.command, el.kerfNote),
    );
    new ResizeObserver(() => render(lastT)).observe(el.canvas);
  }

  function changed() {
    const shape = el.shape.value;
    el.cellsRow.hidden = shape !== 'cells';
    el.rectRow.hidden = shape !== 'rect';
    el.discRow.hidden = shape !== 'disc';
    show();
  }

  /** Asks for the sheet of the design on screen and the region chosen (debounced). */
  function show() {
    const f = form();
    if (!f) return;
    const options = { defaultKerf: defaultKerf() };
    el.command.textContent = sheetCommand(f, options);
    el.kerfNote.textContent = sheetKerfDiffers(f, options) ? ` (at the default kerf: this design's kerf ${f.kerf} is not a flag of \`isogami sheet\`)` : '';
    const params = sheetParams(f, options);
    if (!params) {
      el.status.textContent = 'give the region a size';
      return;
    }
    const key = params.toString();
    if (key === asked) return;
    asked = key;
    clearTimeout(timer);
    // The answer in flight is for what was asked before: dropped now, not shown (and the panel
    // said ready) during the wait for this one.
    if (inflight) {
      inflight.abort();
      inflight = null;
    }
    el.status.textContent = 'analysing…';
    container.dataset.state = 'loading';
    timer = setTimeout(() => fetchSheet(params), 150);
  }

  async function fetchSheet(params) {
    if (inflight) inflight.abort();
    const controller = new AbortController();
    inflight = controller;
    try {
      const a = await data.sheet(params, controller.signal);
      if (inflight !== controller) return;
      answer = a;
      bounds = null;
      el.error.hidden = true;
      el.status.textContent = '';
      describe();
      container.dataset.state = 'ready';
      container.dataset.answers = String(Number(container.dataset.answers || 0) + 1);
      render(lastT);
    } catch (e) {
      if (e.name === 'AbortError' || inflight !== controller) return;
      answer = null;
      el.status.textContent = '';
      el.error.replaceChildren(h('strong', {}, e.message), e.hint ? h('p', { class: 'hint' }, e.hint) : null);
      el.error.dataset.kind = e.kind || 'error';
      el.error.hidden = false;
      el.badge.textContent = '';
      el.summary.textContent = '';
      el.refusal.hidden = true;
      el.motion.textContent = '';
      container.dataset.state = 'error';
      clear();
    } finally {
      if (inflight === controller) inflight = null;
    }
  }

  /** The words about the answer that do not change with t. */
  function describe() {
    const a = answer.analysis;
    const completed = container.querySelector('[data-testid="finite-view-completed"]');
    completed.disabled = !a.completion;
    el.refusal.hidden = !answer.refused;
    el.refusal.textContent = answer.refused ? `${answer.refused}. The raw region is shown; the export can still write it (raw rectangle).` : '';
    const states = singularStates(answer.deployment);
    el.singular.hidden = states.length === 0;
    el.singular.textContent = states.length
      ? `Singular states: ${states.join('; ')}. A sheet pulled through one can branch off the periodic motion there and parts of it drift away: stop short of it or guide the sheet.`
      : '';
    const raw = `${a.raw.tiles.length} tiles, ${a.raw.joints.length} pins; raw ${a.raw_mobility.dof} DOF opened (t = ${a.t.toFixed(3)}), ${a.raw_closed_dof} closed`;
    if (a.completion) {
      const r = a.completion.report;
      el.summary.textContent = `${raw}. Completed: ${r.kept} of ${r.requested} tiles kept, ${r.removed.length} removed, ${r.added.length} added, ${(100 * r.covered_fraction).toFixed(1)} % of the region covered.`;
    } else el.summary.textContent = `${raw}.`;
  }

  /** The singular states of a finite deployment's paths (the sheet's, the periodic sheet's),
   * in words: where, and how many extra first-order motions. */
  function singularStates(d) {
    if (!d) return [];
    const words = (what) => (s) =>
      `t = ${s.t.toFixed(3)} of ${what} path (${s.extra_motions} extra first-order motion${s.extra_motions === 1 ? '' : 's'})`;
    return [...(d.singular ?? []).map(words('this sheet’s')), ...(d.periodic_singular ?? []).map(words('the periodic sheet’s'))];
  }

  function view() {
    const chosen = container.querySelector('input[name="finite-view"]:checked')?.value ?? 'completed';
    return chosen === 'completed' && answer?.analysis.completion ? 'completed' : 'raw';
  }

  function clear() {
    const ctx = el.canvas.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, el.canvas.width, el.canvas.height);
    for (const k of ['view', 'floppy', 'removed', 'added', 'tiles', 'frame', 't']) delete el.canvas.dataset[k];
  }

  /** The tiles to draw at t: [{tile, cell, role, pose}] and the finite frame (or null). */
  function tilesAt(t) {
    const shown = view();
    const layers = sheetLayers(answer, shown);
    const deployment = answer.deployment;
    if (shown !== 'completed' || !deployment) return { layers, frame: null, tiles: layers.tiles };
    const frame = finiteFrameAt(deployment, t);
    const sheet = answer.analysis.completion.sheet.tiles;
    const lattice = latticeOf(sheet, frame.poses);
    // Kept and added tiles come first, in the deployed sheet's order (its frames' poses).
    const tiles = layers.tiles.map((tile, n) =>
      tile.role === 'removed' ? { ...tile, pose: poseOutside(tile, sheet, frame.poses, lattice) } : { ...tile, pose: frame.poses[n] },
    );
    return { layers, frame, tiles: tiles.filter((tile) => tile.pose) };
  }

  /** Bounds over the whole finite motion (or the closed sheet), so the sheet visibly opens. */
  function motionBounds() {
    let b = [Infinity, Infinity, -Infinity, -Infinity];
    const ts = answer.deployment ? answer.deployment.frames.map((f) => f.t) : [0];
    for (const t of ts) {
      for (const tile of tilesAt(t).tiles) {
        for (const [x, y] of placePolygon(answer.drawing.tiles[tile.tile], tile.pose)) b = [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)];
      }
    }
    return b;
  }

  /** Draws the sheet shown at t (the finite deployment's own t, from the page's slider). */
  function render(t) {
    lastT = t;
    if (!answer || !el.canvas) return;
    const shown = view();
    const layers = sheetLayers(answer, shown);
    const badge = dofBadge(layers.mobility);
    el.badge.textContent = badge.text;
    el.badge.dataset.ok = String(badge.ok);
    const key = `${shown}`;
    if (!bounds || bounds.key !== key) bounds = { key, box: motionBounds() };
    const { frame, tiles } = tilesAt(t);
    const canvas = el.canvas;
    const ratio = window.devicePixelRatio || 1;
    const width = canvas.clientWidth || 360;
    const height = canvas.clientHeight || 300;
    if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
      canvas.width = Math.round(width * ratio);
      canvas.height = Math.round(height * ratio);
    }
    const ctx = canvas.getContext('2d');
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    const [x0, y0, x1, y1] = bounds.box;
    const pad = 10;
    const s = Math.min((width - 2 * pad) / Math.max(1e-9, x1 - x0), (height - 2 * pad) / Math.max(1e-9, y1 - y0));
    // The scale fits the whole motion; the sheet as it is at t is centred (a thin sheet that
    // turns as it opens would otherwise sit in a corner of its motion's box).
    const [cx, cy] = centreOf(tiles) ?? [(x0 + x1) / 2, (y0 + y1) / 2];
    ctx.setTransform(...zoomedTransform(zoom, width, height, ratio, [s, width / 2 - s * cx, height / 2 + s * cy]));
    canvas.dataset.zoom = `${zoom.k},${zoom.x},${zoom.y}`;
    const px = 1 / (s * zoom.k);
    ctx.lineJoin = 'round';
    const count = { floppy: 0, removed: 0, added: 0, solid: 0 };
    // Ghosts first, under the sheet.
    const order = [...tiles].sort((a, b) => (a.role === 'removed' ? 0 : 1) - (b.role === 'removed' ? 0 : 1));
    for (const tile of order) {
      const points = placePolygon(answer.drawing.tiles[tile.tile], tile.pose);
      ctx.beginPath();
      points.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      ctx.closePath();
      ctx.fillStyle = FILL[tile.role];
      ctx.fill();
      ctx.strokeStyle = STROKE[tile.role];
      ctx.lineWidth = (tile.role === 'floppy' || tile.role === 'added' ? 2 : 1) * px;
      ctx.setLineDash(tile.role === 'removed' ? [4 * px, 3 * px] : []);
      ctx.stroke();
      if (tile.role === 'removed') count.removed += 1;
      else count.solid += 1;
      if (tile.role === 'floppy') count.floppy += 1;
      if (tile.role === 'added') count.added += 1;
    }
    ctx.setLineDash([]);
    Object.assign(canvas.dataset, {
      view: shown,
      floppy: String(count.floppy),
      removed: String(count.removed),
      added: String(count.added),
      tiles: String(count.solid),
      frame: frame ? String(frame.index) : '',
      t: frame ? t.toFixed(3) : '',
    });
    el.motion.textContent = motionWords(shown, frame);
  }

  /** Centre of the bounding box of `tiles` as drawn, or null for none. */
  function centreOf(tiles) {
    let b = [Infinity, Infinity, -Infinity, -Infinity];
    for (const tile of tiles) {
      for (const [x, y] of placePolygon(answer.drawing.tiles[tile.tile], tile.pose)) b = [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)];
    }
    return Number.isFinite(b[0]) ? [(b[0] + b[2]) / 2, (b[1] + b[3]) / 2] : null;
  }

  function motionWords(shown, frame) {
    const d = answer.deployment;
    if (shown === 'raw') return 'The raw region as cut (closed). Highlighted tiles move in extra modes: the sheet does not follow the design’s one motion.';
    if (!frame) return answer.not_deployed ? `Not deployed: ${answer.not_deployed}` : 'The completed sheet, closed.';
    const end = typeof d.end_reason === 'object' ? d.end_reason.kind.replace(/_/g, ' ') : String(d.end_reason);
    return `Finite deployment at t = ${frame.t.toFixed(3)} (frame ${frame.index + 1} of ${d.frames.length}): hull area ×${fmt(frame.measures.hull_area_ratio)}; ends at ${end} after ${d.steps} states (largest hull area ×${fmt(d.max_hull_area_ratio)}); the periodic sheet's ${d.periodic.steps} states reach ×${fmt(d.periodic.measures.hull_area_ratio)} on these tiles.`;
  }

  build();
  return {
    /** Asks for the sheet of the design now on screen. */
    show,
    /** Draws the finite sheet at the page's t. */
    render,
  };
}
