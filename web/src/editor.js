// The live design panel: a slider per shape parameter of the family (default ± max(0.5,
// |default|)), a kerf slider (logarithmic, 1e-4…0.2 of the mean edge length) and a joint
// editor drawn as the closed unit cell, where clicking an edge (or Enter/Space on it) cycles
// its joint none → A → B → both (welded) → none. Every change composes a spec string
// FAMILY:PARAMS:CELL:JOINTS and calls `onChange(spec, kerf)`; the design page deploys it.
// In static mode the controls are shown disabled with the reason.
//
// Shape-aware sliders (with `shape`, server mode): the design's shape class is shown over the
// sliders. A special design keeps one degree of freedom only on some shapes, so moving one
// of its sliders asks the server to follow (shape.js's FollowQueue) and sets every slider to
// the answer before deploying; pinned parameters' sliders are disabled with the reason. A
// "move freely" box restores the plain behaviour (which breaks such a design's motion).

import * as d3 from 'd3';
import { fmt, h } from './dom.js';
import { FollowQueue, pinnedSet, shapeStatusText, shouldFollow } from './shape.js';

const CYCLE = { '-': 'a', a: 'b', b: 'x', x: '-' };
const JOINT_NAMES = { '-': 'no joint', a: 'joint at end A', b: 'joint at end B', x: 'joints at both ends (welded)' };
const KERF_MIN = -4;
const KERF_MAX = Math.log10(0.2);

/** The spec string of a design. */
export function composeSpec({ family, params, cell, joints }) {
  return `${family}:${params.map((p) => String(p)).join(',')}:${cell[0]}x${cell[1]}:${joints}`;
}

/** Slider range of a parameter with default `d`. */
export function paramRange(d) {
  const half = Math.max(0.5, Math.abs(d));
  return [d - half, d + half];
}

/** Kerf from the log slider's position, rounded to 3 significant digits. */
export function kerfFromSlider(s) {
  return Number((10 ** s).toPrecision(3));
}

export function createEditor(container, { live, onChange, reason, shape = null }) {
  let design = null; // {family, params, cell, joints}
  let kerf = 0.01;
  let info = null; // FamilyInfo
  let geometry = null;
  let tilesClosed = null;
  let shapeInfo = null; // GET /api/shape of the design, or {error}
  let classified = null; // the spec shapeInfo belongs to (or is being fetched for)
  let classifying = null; // AbortController of the running classification
  let free = false; // move sliders freely, ignoring the shape constraints
  let inputs = [];
  let outputs = [];

  const fire = () => onChange(composeSpec(design), kerf);

  const shapeStatus = h('p', { class: 'help shape-status', testid: 'shape-status', 'aria-live': 'polite' });
  const freeBox = h('input', {
    type: 'checkbox',
    id: 'shape-free',
    testid: 'shape-free',
    onchange: (e) => {
      free = e.target.checked;
      queue.clear();
      showShape();
    },
  });
  const freeLabel = h(
    'label',
    { class: 'shape-free', for: 'shape-free', hidden: true },
    freeBox,
    ' move sliders freely (a special design stops moving)',
  );

  const queue = new FollowQueue((k, value) => shape.follow(composeSpec(design), k, value), {
    onAnswer: (answer) => {
      design.params = [...answer.params];
      classified = composeSpec(design); // same class along the constraints
      showParams();
      const moved = answer.adjusted.filter((x) => Math.abs(x) > 1e-9).length;
      shapeStatus.textContent = `${shapeStatusText(shapeInfo)} (${moved} parameter${moved === 1 ? '' : 's'} moved)`;
      fire();
    },
    onError: (e) => {
      // Back to the last design that moves; say why.
      showParams();
      shapeStatus.textContent = `${e.message}${e.hint ? ` — ${e.hint}` : ''}`;
    },
  });

  /** Sliders and their numbers from `design.params` (after a follow or a refusal). */
  function showParams() {
    design.params.forEach((value, k) => {
      const input = inputs[k];
      if (!input) return;
      input.min = String(Math.min(Number(input.min), value));
      input.max = String(Math.max(Number(input.max), value));
      input.value = String(value);
      outputs[k].textContent = fmt(value);
      outputs[k].title = String(value);
    });
  }

  /** Class words, pinned sliders and the free box from `shapeInfo`. */
  function showShape() {
    shapeStatus.textContent = shapeStatusText(shapeInfo, { free });
    // Shown for a special design, and kept while ticked (a free move may have made the design
    // rigid, so it is no longer special, and the user must be able to untick it).
    freeLabel.hidden = !(free || (shapeInfo && shapeInfo.class === 'special'));
    const pinned = pinnedSet(shapeInfo, { free });
    inputs.forEach((input, k) => {
      input.disabled = !live || pinned.has(k);
      input.title = pinned.has(k)
        ? `v${k} is pinned: no change of it keeps this sheet moving (tick "move sliders freely" to move it anyway)`
        : '';
    });
  }

  /** Classifies the design being edited unless it already is (server mode only). */
  async function classify() {
    if (!shape || !live || !design || !design.params.length) {
      shapeInfo = null;
      showShape();
      return;
    }
    const spec = composeSpec(design);
    if (spec === classified) return;
    classified = spec;
    if (classifying) classifying.abort();
    const controller = new AbortController();
    classifying = controller;
    try {
      const answer = await shape.classify(spec, controller.signal);
      if (classified !== spec) return;
      shapeInfo = answer;
    } catch (e) {
      if (e.name === 'AbortError' || classified !== spec) return;
      shapeInfo = { error: e.message };
    }
    showShape();
  }

  const sliders = h('div', { class: 'sliders' });
  const kerfBox = h('div', { class: 'slider' });
  const cellBox = h('div', { class: 'joint-editor', testid: 'joint-editor' });
  const jointsText = h('code', { class: 'joints', testid: 'joints' });
  container.replaceChildren(
    ...(live ? [] : [h('p', { class: 'notice notice-static', testid: 'live-unavailable' }, reason)]),
    h('h3', {}, 'Shape parameters'),
    shapeStatus,
    freeLabel,
    sliders,
    h('h3', {}, 'Kerf'),
    kerfBox,
    h('h3', {}, 'Joints ', jointsText),
    h('p', { class: 'help' }, 'Click an edge of the cell (or focus it and press Enter) to cycle: none → A → B → both → none.'),
    cellBox,
  );

  function renderSliders() {
    const defaults = info ? info.default_params : design.params;
    inputs = [];
    outputs = [];
    sliders.replaceChildren(
      ...design.params.map((value, k) => {
        const [lo, hi] = paramRange(defaults[k] ?? value);
        const min = Math.min(lo, value);
        const max = Math.max(hi, value);
        const id = `param-v${k}`;
        const out = h('output', { for: id, testid: `param-v${k}-value`, title: String(value) }, fmt(value));
        const input = h('input', {
          type: 'range',
          id,
          min: String(min),
          max: String(max),
          step: String((max - min) / 400),
          value: String(value),
          disabled: !live,
          testid: `param-v${k}`,
          oninput: (e) => {
            const target = Number(Number(e.target.value).toFixed(4));
            out.textContent = fmt(target);
            out.title = String(target);
            if (shouldFollow(shapeInfo, { free })) {
              queue.move(k, target);
              return;
            }
            design.params[k] = target;
            fire();
            classifySoon();
          },
        });
        inputs.push(input);
        outputs.push(out);
        return h('div', { class: 'slider' }, h('label', { for: id }, `v${k}`), input, out);
      }),
    );
    if (!design.params.length) sliders.append(h('p', { class: 'help' }, 'This family has no shape parameters.'));
    const out = h('output', { for: 'kerf', testid: 'kerf-value' }, String(kerf));
    kerfBox.replaceChildren(
      h('label', { for: 'kerf' }, 'kerf / edge'),
      h('input', {
        type: 'range',
        id: 'kerf',
        min: String(KERF_MIN),
        max: String(KERF_MAX),
        step: '0.01',
        value: String(Math.log10(kerf)),
        disabled: !live,
        testid: 'kerf',
        oninput: (e) => {
          kerf = kerfFromSlider(Number(e.target.value));
          out.textContent = String(kerf);
          fire();
        },
      }),
      out,
    );
  }

  let classifyTimer = null;
  /** Classifies again shortly after the topology or a freely moved shape changed. */
  function classifySoon() {
    clearTimeout(classifyTimer);
    classifyTimer = setTimeout(classify, 250);
  }

  function renderCell() {
    jointsText.textContent = design.joints;
    if (!geometry) return;
    const pts = tilesClosed.flat().concat(geometry.edges.flatMap((e) => [e.a, e.b]));
    const [x0, x1] = d3.extent(pts, (p) => p[0]);
    const [y0, y1] = d3.extent(pts, (p) => p[1]);
    const pad = 0.08 * Math.max(x1 - x0, y1 - y0);
    const svg = d3
      .create('svg')
      .attr('viewBox', `${x0 - pad} ${-y1 - pad} ${x1 - x0 + 2 * pad} ${y1 - y0 + 2 * pad}`)
      .attr('role', 'group')
      .attr('aria-label', 'joint editor: the unit cell in the closed state, one button per edge');
    const g = svg.append('g').attr('transform', 'scale(1,-1)');
    const width = Math.max(x1 - x0, y1 - y0);
    g.selectAll('polygon')
      .data(tilesClosed)
      .join('polygon')
      .attr('class', 'tile')
      .attr('points', (poly) => poly.map((p) => p.join(',')).join(' '));
    const edges = g
      .selectAll('g.edge')
      .data(geometry.edges.map((e, i) => ({ ...e, i })))
      .join('g')
      .attr('class', (e) => `edge joint-${design.joints[e.i] === '-' ? 'none' : design.joints[e.i]}`)
      .attr('tabindex', live ? 0 : -1)
      .attr('role', 'button')
      .attr('data-testid', (e) => `edge-${e.i}`)
      .attr('aria-label', (e) => `edge ${e.i}: ${JOINT_NAMES[design.joints[e.i]] ?? design.joints[e.i]}`)
      .attr('aria-disabled', live ? null : 'true');
    edges
      .append('line')
      .attr('class', 'hit')
      .attr('stroke-width', width * 0.06)
      .attr('x1', (e) => e.a[0])
      .attr('y1', (e) => e.a[1])
      .attr('x2', (e) => e.b[0])
      .attr('y2', (e) => e.b[1]);
    edges
      .append('line')
      .attr('class', 'seg')
      .attr('stroke-width', width * 0.012)
      .attr('x1', (e) => e.a[0])
      .attr('y1', (e) => e.a[1])
      .attr('x2', (e) => e.b[0])
      .attr('y2', (e) => e.b[1]);
    edges.each(function pins(e) {
      const c = design.joints[e.i];
      const ends = c === 'a' ? [e.a] : c === 'b' ? [e.b] : c === 'x' ? [e.a, e.b] : [];
      for (const p of ends) {
        const pull = 0.12; // pin drawn slightly inside the edge so that coincident corners stay apart
        const q = [p[0] + pull * ((e.a[0] + e.b[0]) / 2 - p[0]), p[1] + pull * ((e.a[1] + e.b[1]) / 2 - p[1])];
        d3.select(this).append('circle').attr('class', 'pin').attr('r', width * 0.022).attr('cx', q[0]).attr('cy', q[1]);
      }
    });
    const cycle = (e) => {
      if (!live) return;
      const chars = [...design.joints];
      chars[e.i] = CYCLE[chars[e.i]] ?? '-';
      design.joints = chars.join('');
      renderCell();
      classifySoon();
      const again = cellBox.querySelector(`[data-testid="edge-${e.i}"]`);
      if (again) again.focus();
      fire();
    };
    edges.on('click', (event, e) => cycle(e));
    edges.on('keydown', (event, e) => {
      if (event.key === 'Enter' || event.key === ' ') {
        event.preventDefault();
        cycle(e);
      }
    });
    cellBox.replaceChildren(svg.node());
  }

  function takeGeometry(view) {
    geometry = view.geometry;
    tilesClosed = geometry.tiles.map((poly, k) => {
      const pose = view.report.frames[0].tiles[k];
      const c = Math.cos(pose.theta);
      const s = Math.sin(pose.theta);
      return poly.map((p) => [pose.x + c * p[0] - s * p[1], pose.y + s * p[0] + c * p[1]]);
    });
  }

  return {
    /** Takes the design of a view (on load and after each successful deployment). */
    sync(view, families) {
      const g = view.geometry;
      info = families.find((f) => f.name === g.family) || null;
      const joints = g.edges.map((e) => e.joint).join('');
      design = { family: g.family, params: [...g.params], cell: [...g.cell], joints };
      kerf = Number(view.report.kerf.toPrecision(3));
      takeGeometry(view);
      renderSliders();
      renderCell();
      classified = null;
      shapeInfo = null;
      showShape();
      classify();
    },
    /** Redraws the cell of a fresh deployment of the design being edited, leaving the sliders
     * alone (the user may still be dragging one). */
    showGeometry(view) {
      takeGeometry(view);
      renderCell();
    },
    /** The shape classification shown (GET /api/shape), or null. */
    shapeClass() {
      return shapeInfo;
    },
    /** The design as edited. */
    current() {
      return design ? { spec: composeSpec(design), kerf } : null;
    },
  };
}
