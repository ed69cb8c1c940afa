// The live design panel: a slider per shape parameter of the family, labelled with what the
// parameter does to the tile (the library's `param_effects`, from /api/families) and limited
// to the parameter's valid range at the current shape (the library's `param_ranges`, GET
// /api/shape/ranges, given by the page through `setRanges`; default ± max(0.5, |default|)
// until it arrives), with the well-shaped part shaded; a kerf slider (logarithmic, 1e-4…0.2
// of the mean edge length) and a joint editor drawn as the closed unit cell, where clicking
// an edge (or Enter/Space on it) cycles its joint none → A → B → both (welded) → none, with a
// legend of its marks and pins spread apart where corners coincide. Every change composes a
// spec string FAMILY:PARAMS:CELL:JOINTS and calls `onChange(spec, kerf, source)` (source:
// 'shape', 'kerf' or 'joints'); the design page deploys it and shows a refusal next to the
// control that caused it (`showNotice(source, …)`). In static mode the controls are shown
// disabled with the reason.
//
// Shape-aware sliders (with `shape`, server mode): the design's shape class is shown over the
// sliders. A special design keeps one degree of freedom only on some shapes, so moving one
// of its sliders asks the server to follow (shape.js's FollowQueue) and sets every slider to
// the answer before deploying; pinned parameters' sliders are disabled with the reason. A
// "move freely" box restores the plain behaviour (which breaks such a design's motion).

import * as d3 from 'd3';
import { fmt, h, showNotice as showNoticeIn, clearNotice } from './dom.js';
import { FollowQueue, pinnedSet, shapeStatusText, shouldFollow } from './shape.js';

const CYCLE = { '-': 'a', a: 'b', b: 'x', x: '-' };
const JOINT_NAMES = { '-': 'no joint', a: 'joint at end A', b: 'joint at end B', x: 'joints at both ends (welded)' };
const KERF_MIN = -4;
const KERF_MAX = Math.log10(0.2);

/** The spec string of a design. */
export function composeSpec({ family, params, cell, joints }) {
  return `${family}:${params.map((p) => String(p)).join(',')}:${cell[0]}x${cell[1]}:${joints}`;
}

/** Slider range of a parameter with default `d` (before its valid range is known). */
export function paramRange(d) {
  const half = Math.max(0.5, Math.abs(d));
  return [d - half, d + half];
}

/** The span of a shape slider from its range `r` (GET /api/shape/ranges): the valid interval
 * where the tile is well-shaped at the value; where it is not, that interval joined with the
 * family's default span around `d` (paramRange), so the slider can go back. */
export function sliderSpan(r, d) {
  if (r.well_shaped || d === undefined || !Number.isFinite(d)) return [r.lo, r.hi];
  const [lo, hi] = paramRange(d);
  return [Math.min(r.lo, lo), Math.max(r.hi, hi)];
}

/** A slider value rounded to 4 decimals, kept inside [min, max] (rounding must not leave
 * the valid range); at an end, exactly that end. */
export function sliderValue(raw, min, max) {
  const x = Number(raw);
  if (x >= max) return max; // at an end: exactly the end of the valid range
  if (x <= min) return min;
  const v = Number(x.toFixed(4));
  return Math.min(max, Math.max(min, v));
}

/**
 * Pin positions on the joint editor: each pin sits on its edge, `r`·2.2 from its end, and
 * pins that would overlap (edges meeting at a small angle at one corner) are pushed further
 * along their edges (at most 45 % of the edge) until no two are closer than 2.1·r.
 * `pins`: [{end: [x, y], other: [x, y]}] (the pinned end and the edge's other end).
 */
export function spreadPins(pins, r) {
  const len = pins.map((p) => Math.hypot(p.other[0] - p.end[0], p.other[1] - p.end[1]));
  const dist = pins.map((_, i) => Math.min(2.2 * r, 0.45 * len[i]));
  const at = (i) => {
    const p = pins[i];
    const u = len[i] > 0 ? dist[i] / len[i] : 0;
    return [p.end[0] + u * (p.other[0] - p.end[0]), p.end[1] + u * (p.other[1] - p.end[1])];
  };
  for (let round = 0; round < 200; round += 1) {
    let moved = false;
    for (let i = 0; i < pins.length; i += 1) {
      for (let j = i + 1; j < pins.length; j += 1) {
        const a = at(i);
        const b = at(j);
        if (Math.hypot(a[0] - b[0], a[1] - b[1]) >= 2.1 * r) continue;
        // Stagger: the pin already further out moves on (the other keeps its place), or
        // the other one when that one is at its limit.
        const order = dist[j] >= dist[i] ? [j, i] : [i, j];
        for (const k of order) {
          const next = Math.min(dist[k] + 0.5 * r, 0.45 * len[k]);
          if (next > dist[k]) {
            dist[k] = next;
            moved = true;
            break;
          }
        }
      }
    }
    if (!moved) break;
  }
  return pins.map((_, i) => at(i));
}

/** Kerf from the log slider's position, rounded to 3 significant digits. */
export function kerfFromSlider(s) {
  return Number((10 ** s).toPrecision(3));
}

/** The joint editor's legend: what its lines, dots and letters mean. */
function jointLegend() {
  const sample = (cls, pins) => {
    const svg = d3.create('svg').attr('viewBox', '0 0 40 12').attr('width', 40).attr('height', 12).attr('aria-hidden', 'true');
    svg.append('line').attr('class', cls).attr('x1', 3).attr('y1', 6).attr('x2', 37).attr('y2', 6).attr('stroke-width', 2.5);
    for (const x of pins) svg.append('circle').attr('class', 'pin').attr('cx', x).attr('cy', 6).attr('r', 3.2);
    return svg.node();
  };
  return h(
    'ul',
    { class: 'joint-legend', testid: 'joint-legend' },
    h('li', {}, sample('seg cut', []), 'grey: cut, no joint'),
    h('li', {}, sample('seg joined', [9]), 'black with a red pin: a hinge at that end (A or B)'),
    h('li', {}, sample('seg joined', [9, 31]), 'two pins: both ends, welded'),
    h('li', {}, h('span', { class: 'end-key' }, 'A B'), 'hover or focus an edge to see its ends A and B'),
    h('li', {}, h('span', { class: 'corner-key' }, '0 1 2'), "tile 0's corners, as the shape sliders name them (edge k runs from corner k to k + 1)"),
  );
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
  let bands = [];
  let ranges = null; // GET /api/shape/ranges answer for the design being edited

  const fire = (source) => onChange(composeSpec(design), kerf, source);

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
      fire('shape');
    },
    onError: (e) => {
      // Back to the last design that moves; say why.
      showParams();
      shapeStatus.textContent = `${e.message}${e.hint ? ` — ${e.hint}` : ''}`;
      showNoticeIn(notices.shape, { message: e.message, hint: e.hint, kind: e.kind });
    },
  });

  /** Marks the editor `data-following` while follow requests are in flight or waiting (`done`:
   * the queue's promise, settled once it is empty). The last answer's deployment is asked for
   * before the mark goes, so a live edit is over once neither the mark nor the page's
   * deployment in flight is there. */
  function following(done) {
    container.dataset.following = 'true';
    done.finally(() => {
      if (!queue.busy()) delete container.dataset.following;
    });
  }

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
  // One notice box per control group: a refusal is shown next to what caused it.
  const notices = {
    shape: h('div', { class: 'notice-box local', testid: 'notice-shape', 'aria-live': 'assertive', hidden: true }),
    kerf: h('div', { class: 'notice-box local', testid: 'notice-kerf', 'aria-live': 'assertive', hidden: true }),
    joints: h('div', { class: 'notice-box local', testid: 'notice-joints', 'aria-live': 'assertive', hidden: true }),
  };
  container.replaceChildren(
    ...(live ? [] : [h('p', { class: 'notice notice-static', testid: 'live-unavailable' }, reason)]),
    h('h3', {}, 'Shape parameters'),
    shapeStatus,
    freeLabel,
    sliders,
    notices.shape,
    h('h3', {}, 'Kerf'),
    kerfBox,
    notices.kerf,
    h('h3', {}, 'Joints ', jointsText),
    h('p', { class: 'help' }, 'Click an edge of the cell (or focus it and press Enter) to cycle: none → A → B → both → none.'),
    jointLegend(),
    notices.joints,
    cellBox,
  );

  function renderSliders() {
    const defaults = info ? info.default_params : design.params;
    inputs = [];
    outputs = [];
    bands = [];
    sliders.replaceChildren(
      ...design.params.map((value, k) => {
        const [lo, hi] = paramRange(defaults[k] ?? value);
        const min = Math.min(lo, value);
        const max = Math.max(hi, value);
        const id = `param-v${k}`;
        const doc = info?.param_effects?.[k]?.description ?? '';
        const out = h('output', { for: id, testid: `param-v${k}-value`, title: String(value) }, fmt(value));
        const band = h('div', { class: 'range-band', testid: `param-v${k}-band`, 'aria-hidden': 'true' }, h('span', { class: 'well' }));
        const input = h('input', {
          type: 'range',
          id,
          min: String(min),
          max: String(max),
          step: String((max - min) / 400),
          value: String(value),
          disabled: !live,
          testid: `param-v${k}`,
          'aria-describedby': doc ? `${id}-doc` : null,
          oninput: (e) => {
            const target = sliderValue(e.target.value, Number(e.target.min), Number(e.target.max));
            out.textContent = fmt(target);
            out.title = String(target);
            if (shouldFollow(shapeInfo, { free })) {
              following(queue.move(k, target));
              return;
            }
            design.params[k] = target;
            fire('shape');
            classifySoon();
          },
        });
        inputs.push(input);
        outputs.push(out);
        bands.push(band);
        return h(
          'div',
          { class: 'slider param' },
          h('label', { for: id }, `v${k}`),
          h('div', { class: 'track' }, input, band),
          out,
          doc ? h('p', { class: 'param-doc', id: `${id}-doc`, testid: `param-v${k}-doc` }, `v${k} ${doc}`) : null,
          h('p', { class: 'param-range', testid: `param-v${k}-range` }),
        );
      }),
    );
    showRanges();
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
          fire('kerf');
        },
      }),
      out,
    );
  }

  /** Slider limits, the shaded well-shaped band and the range text from `ranges`. */
  function showRanges() {
    if (!ranges || !design || ranges.ranges.length !== design.params.length) return;
    for (const r of ranges.ranges) {
      const input = inputs[r.index];
      if (!input) continue;
      // Not well-shaped here (the tile is degenerate at this shape): the valid interval, searched
      // only near the value, would trap the slider there; it reaches back to the family's
      // default span too.
      const [min, max] = sliderSpan(r, info?.default_params?.[r.index]);
      input.min = String(min);
      input.max = String(max);
      input.step = String((max - min) / 400);
      input.value = String(design.params[r.index]);
      input.dataset.lo = String(r.lo);
      input.dataset.hi = String(r.hi);
      const well = bands[r.index].firstChild;
      const span = max - min;
      if (r.well_shaped && span > 0) {
        const [a, b] = r.well_shaped;
        well.style.left = `${(100 * (a - min)) / span}%`;
        well.style.width = `${(100 * (b - a)) / span}%`;
        well.hidden = false;
        bands[r.index].dataset.well = `${a},${b}`;
      } else {
        well.hidden = true;
        delete bands[r.index].dataset.well;
      }
      const text = sliders.querySelector(`[data-testid="param-v${r.index}-range"]`);
      if (text) {
        const open = [r.lo_open ? 'below' : null, r.hi_open ? 'above' : null].filter(Boolean).join(' and ');
        text.textContent = `valid ${fmt(r.lo)} … ${fmt(r.hi)} with the others fixed` +
          (open ? ` (valid ${open} too: searched no further)` : '') +
          (r.well_shaped
            ? `; well-shaped ${fmt(r.well_shaped[0])} … ${fmt(r.well_shaped[1])} (shaded green)`
            : `; the tile is not well-shaped here (the slider reaches back to ${fmt(min)} … ${fmt(max)})`);
      }
    }
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
    // Tile 0's corners numbered as the shape sliders' descriptions name them.
    const t0 = tilesClosed[0] ?? [];
    const [cx, cy] = t0.reduce((acc, p) => [acc[0] + p[0] / t0.length, acc[1] + p[1] / t0.length], [0, 0]);
    const corners = g.append('g').attr('class', 'corners').attr('data-testid', 'tile0-corners').attr('pointer-events', 'none');
    t0.forEach((p, k) => {
      const x = p[0] + 0.16 * (cx - p[0]);
      const y = p[1] + 0.16 * (cy - p[1]);
      corners.append('text').attr('class', 'corner-label')
        .attr('transform', `translate(${x},${y}) scale(1,-1)`)
        .attr('font-size', width * 0.04).attr('text-anchor', 'middle').attr('dy', '0.35em').text(String(k));
    });
    // End markers A and B, shown on the hovered or focused edge.
    const r = width * 0.018;
    edges.each(function ends(e) {
      for (const [name, p, q] of [['A', e.a, e.b], ['B', e.b, e.a]]) {
        const u = 0.22;
        const x = p[0] + u * (q[0] - p[0]);
        const y = p[1] + u * (q[1] - p[1]);
        d3.select(this).append('text').attr('class', 'end-label')
          .attr('transform', `translate(${x},${y}) scale(1,-1)`)
          .attr('font-size', width * 0.05).attr('text-anchor', 'middle').attr('dy', '0.35em').text(name);
      }
    });
    // Pins: on their edge near the pinned end, spread where several meet at one corner.
    const wanted = [];
    geometry.edges.forEach((e, i) => {
      const c = design.joints[i];
      if (c === 'a' || c === 'x') wanted.push({ i, end: e.a, other: e.b });
      if (c === 'b' || c === 'x') wanted.push({ i, end: e.b, other: e.a });
    });
    const spots = spreadPins(wanted, r);
    const pinLayer = g.append('g').attr('class', 'pins').attr('pointer-events', 'none');
    wanted.forEach((p, k) => {
      pinLayer.append('line').attr('class', 'pin-lead').attr('stroke-width', width * 0.006)
        .attr('x1', p.end[0]).attr('y1', p.end[1]).attr('x2', spots[k][0]).attr('y2', spots[k][1]);
      pinLayer.append('circle').attr('class', 'pin').attr('data-edge', p.i)
        .attr('r', r).attr('cx', spots[k][0]).attr('cy', spots[k][1]);
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
      fire('joints');
    };
    edges.on('click', (event, e) => cycle(e));
    edges.on('keydown', (event, e) => {
      if (event.key === 'Enter' || event.key === ' ') {
        event.preventDefault();
        cycle(e);
      }
    });
    // Keep the keyboard focus on its edge when an answer redraws the cell.
    const focused = cellBox.contains(document.activeElement) ? document.activeElement.dataset?.testid : null;
    cellBox.replaceChildren(svg.node());
    if (focused) cellBox.querySelector(`[data-testid="${focused}"]`)?.focus();
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
      ranges = null;
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
    /** Takes each parameter's valid range (GET /api/shape/ranges) of the design shown. */
    setRanges(answer) {
      ranges = answer;
      showRanges();
    },
    /** Shows a refusal next to the control group that caused it ('shape', 'kerf', 'joints'). */
    showNotice(source, notice) {
      for (const [k, box] of Object.entries(notices)) {
        if (k === source) showNoticeIn(box, notice);
        else clearNotice(box);
      }
    },
    /** Clears the notices next to the controls. */
    clearNotices() {
      for (const box of Object.values(notices)) clearNotice(box);
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
