// The catalogue's scatter of two measures. Designs that fall on one spot are drawn as one
// stack (a disc whose size grows with its count, the count written inside, slices coloured by
// behaviour or family), on a <canvas> so that 10^4 designs stay smooth; axes, the brush and the
// zoom live in an SVG on top. Dragging a rectangle reports it as two ranges (the catalogue
// filters by them), the wheel or the buttons zoom (shift-drag pans), hovering a stack shows its
// count and designs, clicking opens its design or pins its list. The plot is focusable: arrow
// keys move between stacks, Enter opens, Escape closes; the focused stack is announced. The
// stacks drawn are exposed as `container.scatterDrawn` (what tests check). Fetches no data.

import * as d3 from 'd3';
import { h, fmt } from './dom.js';
import {
  axisTicks, colourKey, fittingTicks, nearestInDirection, pickStack, roundedRange, stackPoints, stackQuantum,
  stackRadius, stackSlices,
} from './scatter-model.js';

const MARGIN = { top: 14, right: 18, bottom: 44, left: 64 };
const LIST = 8;

/** The data extent widened so that `inset` px of the `length` px axis lie beyond it on each
 * side (room for the largest disc); an empty extent is widened by 5 % of its value. */
function padDomain([lo, hi], length, inset) {
  if (lo === undefined || hi === undefined) return [0, 1];
  if (lo === hi) {
    const d = Math.abs(lo) * 0.05 || 0.5;
    return [lo - d, hi + d];
  }
  const pad = ((hi - lo) * inset) / Math.max(1, length - 2 * inset);
  return [lo - pad, hi + pad];
}

/** "0.4142" or "0.4142 – 0.4143" for the values of a stack along one axis. */
function valueText(values) {
  const lo = fmt(d3.min(values));
  const hi = fmt(d3.max(values));
  return lo === hi ? lo : `${lo} – ${hi}`;
}

/**
 * `createScatter(container, options)`. Options: `onOpen(spec)`, `onBrush({x: [min, max], y:
 * [min, max]})`, `href(spec)` (a design's link), `thumbnailUrl(spec)`, `countEl` (the element
 * that gets "N designs at M positions"), `height`. Returns `{update(points, xLabel, yLabel,
 * colourBy), setColour(by), zoomBy(k), resetZoom()}`.
 */
export function createScatter(container, options) {
  const { onOpen, onBrush, href, thumbnailUrl, countEl, height = 360 } = options;
  container.classList.add('plot', 'scatter');
  const stage = h('div', { class: 'scatter-stage' });
  const canvas = h('canvas', { 'aria-hidden': 'true', testid: 'scatter-canvas' });
  stage.append(canvas);
  const svgEl = d3.select(stage).append('svg').attr('aria-hidden', 'true');
  const axes = svgEl.append('g');
  const brushG = svgEl.append('g').attr('class', 'brush');
  const tip = h('div', { class: 'tooltip', hidden: true, testid: 'scatter-tooltip' });
  const live = h('div', { class: 'visually-hidden', 'aria-live': 'polite', testid: 'scatter-live' });
  stage.append(tip);
  const zoomButtons = h(
    'div',
    { class: 'scatter-zoom', role: 'group', 'aria-label': 'zoom' },
    h('button', { type: 'button', testid: 'scatter-zoom-in', 'aria-label': 'zoom in', onclick: () => zoomBy(2) }, '+'),
    h('button', { type: 'button', testid: 'scatter-zoom-out', 'aria-label': 'zoom out', onclick: () => zoomBy(0.5) }, '−'),
    h('button', { type: 'button', testid: 'scatter-zoom-reset', onclick: () => resetZoom() }, 'reset zoom'),
  );
  // Out of the Tab order: in the focused plot the keys +, − and 0 do the same (its label says
  // so), and the catalogue's cards stay a few Tabs away.
  for (const b of zoomButtons.querySelectorAll('button')) b.tabIndex = -1;
  const legend = h('div', { class: 'scatter-legend', testid: 'scatter-legend' });
  stage.tabIndex = 0;
  stage.setAttribute('role', 'application');
  stage.setAttribute('aria-roledescription', 'scatter plot');
  stage.dataset.testid = 'scatter-stage';
  container.append(zoomButtons, stage, legend, live);

  let points = [];
  let labels = { x: '', y: '' };
  let colourBy = 'behaviour';
  let key = colourKey([], colourBy);
  let base = null; // unzoomed scales
  let view = null; // {sx, sy, stacks (drawn, top-most last), width, h}
  let transform = d3.zoomIdentity;
  let hovered = null;
  let focused = null;
  let pinned = null;
  let stackCache = { qx: NaN, qy: NaN, stacks: [] };

  const zoom = d3
    .zoom()
    .scaleExtent([1, 1e4])
    .filter((e) => e.type === 'wheel' || e.type === 'dblclick' || (e.type === 'mousedown' && e.shiftKey))
    .on('zoom', (e) => {
      transform = e.transform;
      hideTip();
      draw();
    });
  svgEl.call(zoom);

  const brush = d3
    .brush()
    .filter((e) => !e.ctrlKey && !e.shiftKey && !e.button)
    .on('end', (e) => {
      if (!e.sourceEvent) return;
      if (!e.selection) {
        // A click without a drag: the stack under the pointer.
        const [px, py] = d3.pointer(e.sourceEvent, stage);
        const s = stackAt(px, py);
        if (s) activate(s);
        else unpin();
        return;
      }
      const [[x0, y0], [x1, y1]] = e.selection;
      brushG.call(brush.move, null);
      if (Math.abs(x1 - x0) < 3 && Math.abs(y1 - y0) < 3) return;
      onBrush({
        x: Object.values(roundedRange(view.sx.invert(x0), view.sx.invert(x1))),
        y: Object.values(roundedRange(view.sy.invert(y1), view.sy.invert(y0))),
      });
    });

  /** The stacks at grid steps (qx, qy); when the grid changes (a zoom), the hovered, focused
   * and pinned stacks become the new stacks holding their first design. */
  function stacksFor(qx, qy) {
    if (stackCache.qx !== qx || stackCache.qy !== qy || stackCache.points !== points) {
      const stacks = stackPoints(points, qx, qy);
      if (stackCache.points === points) {
        const home = new Map();
        for (const st of stacks) for (const p of st.points) home.set(p, st);
        const follow = (st) => (st ? home.get(st.points[0]) ?? null : null);
        hovered = follow(hovered);
        focused = follow(focused);
        pinned = follow(pinned);
      }
      stackCache = { qx, qy, points, stacks };
    }
    return stackCache.stacks;
  }

  function draw() {
    const width = Math.max(260, Math.floor(container.clientWidth || 480));
    const hgt = height;
    const x0 = MARGIN.left;
    const x1 = width - MARGIN.right;
    const y0 = hgt - MARGIN.bottom;
    const y1 = MARGIN.top;
    const extentX = d3.extent(points, (p) => p.x);
    const extentY = d3.extent(points, (p) => p.y);
    const inset = stackRadius(points.length) + 3;
    base = {
      sx: d3.scaleLinear().domain(padDomain(extentX, x1 - x0, inset)).range([x0, x1]),
      sy: d3.scaleLinear().domain(padDomain(extentY, y0 - y1, inset)).range([y0, y1]),
    };
    const sx = transform.rescaleX(base.sx);
    const sy = transform.rescaleY(base.sy);
    const [dx0, dx1] = sx.domain();
    const [dy0, dy1] = sy.domain();
    const stacks = stacksFor(stackQuantum(dx1 - dx0), stackQuantum(dy1 - dy0));
    const drawn = [];
    for (const s of stacks) {
      const px = sx(s.x);
      const py = sy(s.y);
      const r = stackRadius(s.points.length);
      if (px < x0 - 1 || px > x1 + 1 || py > y0 + 1 || py < y1 - 1) continue;
      drawn.push({ stack: s, px, py, r, count: s.points.length });
    }
    // Largest first, so that small stacks are drawn on top of large ones.
    drawn.sort((a, b) => b.count - a.count);
    view = { sx, sy, drawn, width, hgt };

    zoom.extent([[x0, y1], [x1, y0]]).translateExtent([[x0, y1], [x1, y0]]);
    svgEl.attr('width', width).attr('height', hgt).attr('viewBox', `0 0 ${width} ${hgt}`);
    drawAxes(width, hgt, sx, sy, extentX, extentY);
    const brushArea = `${x0},${y1},${x1},${y0}`;
    if (brushG.attr('data-area') !== brushArea) {
      // Only when the plot area changes: a hover redraw must not touch a brush being dragged.
      brush.extent([[x0, y1], [x1, y0]]);
      brushG.attr('data-area', brushArea).call(brush);
    }

    const ratio = window.devicePixelRatio || 1;
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(hgt * ratio);
    canvas.style.width = `${width}px`;
    canvas.style.height = `${hgt}px`;
    const ctx = canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, hgt);
    ctx.save();
    ctx.beginPath();
    ctx.rect(x0, y1, x1 - x0, y0 - y1);
    ctx.clip();
    for (const d of drawn) drawStack(ctx, d);
    drawCounts(ctx, drawn);
    for (const [s, colour, extra] of [[hovered, '#1f5fa8', 3], [pinned, '#1b1f24', 3], [focused, '#1b1f24', 5]]) {
      const d = s && drawn.find((x) => x.stack === s);
      if (!d) continue;
      ctx.lineWidth = 2;
      ctx.strokeStyle = '#fff';
      ring(ctx, d.px, d.py, d.r + extra + 1.5);
      ctx.strokeStyle = colour;
      ring(ctx, d.px, d.py, d.r + extra);
    }
    ctx.restore();

    const inView = d3.sum(drawn, (d) => d.count);
    const zoomed = transform.k !== 1 || transform.x !== 0 || transform.y !== 0;
    const summary = `${points.length} ${points.length === 1 ? 'design' : 'designs'} at ${stacks.length} ${stacks.length === 1 ? 'position' : 'positions'}${zoomed ? ` · ${inView} in view` : ''}`;
    if (countEl) countEl.textContent = summary;
    stage.setAttribute(
      'aria-label',
      `${labels.y} against ${labels.x}: ${summary}. Arrow keys move between stacks, Enter opens a design or lists a stack, plus and minus zoom, 0 resets the zoom, Escape closes the list.`,
    );
    container.dataset.stacks = String(drawn.length);
    container.dataset.designs = String(inView);
    container.dataset.xDomain = `${dx0},${dx1}`;
    container.dataset.yDomain = `${dy0},${dy1}`;
    const plain = (d) => d && { px: d.px, py: d.py, r: d.r, count: d.count, specs: d.stack.points.map((p) => p.spec) };
    container.scatterDrawn = {
      stacks: drawn.map(plain),
      focused: plain(focused && drawn.find((d) => d.stack === focused)) || null,
      pinned: plain(pinned && drawn.find((d) => d.stack === pinned)) || null,
      positions: stacks.length,
      designs: points.length,
      xDomain: [dx0, dx1],
      yDomain: [dy0, dy1],
    };
  }

  function ring(ctx, x, y, r) {
    ctx.beginPath();
    ctx.arc(x, y, r, 0, 2 * Math.PI);
    ctx.stroke();
  }

  function drawStack(ctx, d) {
    const slices = stackSlices(d.stack, key);
    let a = -Math.PI / 2;
    ctx.globalAlpha = d.count > 1 ? 0.85 : 0.9;
    for (const s of slices) {
      const b = a + (2 * Math.PI * s.count) / d.count;
      ctx.beginPath();
      if (slices.length > 1) ctx.moveTo(d.px, d.py);
      ctx.arc(d.px, d.py, d.r, a, b);
      ctx.closePath();
      ctx.fillStyle = s.colour;
      ctx.fill();
      a = b;
    }
    ctx.globalAlpha = 1;
    ctx.lineWidth = 1;
    ctx.strokeStyle = d.count > 1 ? '#1b1f24' : 'rgba(27, 31, 36, 0.7)';
    ring(ctx, d.px, d.py, d.r);
  }

  /** The counts of stacks large enough to hold them, largest first, each left out where it
   * would cover a count already written. */
  function drawCounts(ctx, drawn) {
    const placed = [];
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    for (const d of drawn) {
      if (d.r < 8) continue;
      const text = String(d.count);
      ctx.font = `${d.r >= 14 ? 12 : 10}px system-ui, sans-serif`;
      const w = ctx.measureText(text).width / 2 + 2;
      const box = [d.px - w, d.py - 8, d.px + w, d.py + 8];
      if (placed.some((b) => b[0] < box[2] && box[0] < b[2] && b[1] < box[3] && box[1] < b[3])) continue;
      placed.push(box);
      ctx.lineWidth = 3;
      ctx.strokeStyle = '#fff';
      ctx.strokeText(text, d.px, d.py);
      ctx.fillStyle = '#1b1f24';
      ctx.fillText(text, d.px, d.py);
    }
  }

  function drawAxes(width, hgt, sx, sy, extentX, extentY) {
    axes.selectAll('*').remove();
    const allEqual = (e) => e[0] !== undefined && e[0] === e[1] && transform.k === 1;
    const xt = allEqual(extentX)
      ? axisTicks([extentX[0], extentX[0]], 1)
      : fittingTicks(sx.domain(), width - MARGIN.left - MARGIN.right, Math.max(2, Math.floor(width / 90)));
    const yt = allEqual(extentY)
      ? axisTicks([extentY[0], extentY[0]], 1)
      : fittingTicks(sy.domain(), hgt - MARGIN.top - MARGIN.bottom, 6, { vertical: true, gap: 14 });
    axes
      .append('g')
      .attr('class', 'x-axis')
      .attr('data-testid', 'scatter-x-axis')
      .attr('transform', `translate(0,${hgt - MARGIN.bottom})`)
      .call(d3.axisBottom(sx).tickValues(xt.values).tickFormat((_, i) => xt.labels[i]));
    axes
      .append('g')
      .attr('class', 'y-axis')
      .attr('data-testid', 'scatter-y-axis')
      .attr('transform', `translate(${MARGIN.left},0)`)
      .call(d3.axisLeft(sy).tickValues(yt.values).tickFormat((_, i) => yt.labels[i]));
    const xTitle = xt.offset ? `${labels.x} (ticks: ${xt.offset.label} + value)` : labels.x;
    const yTitle = yt.offset ? `${labels.y} (ticks: ${yt.offset.label} + value)` : labels.y;
    axes
      .append('text')
      .attr('class', 'axis-label')
      .attr('data-testid', 'scatter-x-label')
      .attr('x', (MARGIN.left + width - MARGIN.right) / 2)
      .attr('y', hgt - 8)
      .attr('text-anchor', 'middle')
      .text(xTitle);
    axes
      .append('text')
      .attr('class', 'axis-label')
      .attr('data-testid', 'scatter-y-label')
      .attr('transform', `translate(14,${(MARGIN.top + hgt - MARGIN.bottom) / 2}) rotate(-90)`)
      .attr('text-anchor', 'middle')
      .text(yTitle);
  }

  /** The top-most drawn stack whose disc (plus 3 px) holds the pixel. */
  function stackAt(px, py) {
    if (!view) return null;
    const i = pickStack(view.drawn, px, py);
    return i < 0 ? null : view.drawn[i].stack;
  }

  function drawnOf(stack) {
    return view?.drawn.find((d) => d.stack === stack) ?? null;
  }

  function describe(stack, withLinks) {
    const n = stack.points.length;
    const rows = [
      h('strong', { class: 'tip-count', testid: 'scatter-tip-count' }, n === 1 ? '1 design' : `${n} designs here`),
      h('div', {}, `${labels.x}: ${valueText(stack.points.map((p) => p.x))}`),
      h('div', {}, `${labels.y}: ${valueText(stack.points.map((p) => p.y))}`),
    ];
    if (n === 1) rows.push(h('img', { src: thumbnailUrl(stack.points[0].spec), alt: '', width: 96, height: 48 }));
    const shown = stack.points.slice(0, LIST);
    rows.push(
      h(
        'ul',
        { class: 'tip-list' },
        shown.map((p) =>
          h(
            'li',
            {},
            h('span', { class: 'swatch', style: `background:${key.colourOf(p)}`, 'aria-hidden': 'true' }),
            withLinks ? h('a', { href: href(p.spec) }, h('code', {}, p.spec)) : h('code', {}, p.spec),
          ),
        ),
      ),
    );
    if (n > LIST) rows.push(h('div', { class: 'muted' }, `and ${n - LIST} more`));
    if (withLinks && n > 1) {
      rows.push(
        h(
          'div',
          { class: 'tip-actions' },
          h(
            'button',
            {
              type: 'button',
              testid: 'scatter-list-stack',
              onclick: () => {
                const xs = d3.extent(stack.points, (p) => p.x);
                const ys = d3.extent(stack.points, (p) => p.y);
                unpin();
                onBrush({ x: xs, y: ys });
              },
            },
            `show these ${n} in the list`,
          ),
          h('button', { type: 'button', testid: 'scatter-tip-close', onclick: () => unpin() }, 'close'),
        ),
      );
    } else if (!withLinks && n > 1) {
      rows.push(h('div', { class: 'muted' }, 'click for the list'));
    }
    tip.replaceChildren(...rows);
  }

  function place(stack) {
    const d = drawnOf(stack);
    if (!d) return;
    tip.hidden = false;
    const w = tip.offsetWidth || 230;
    const left = d.px + d.r + 10 + w > view.width ? d.px - d.r - 10 - w : d.px + d.r + 10;
    tip.style.left = `${Math.max(0, left)}px`;
    tip.style.top = `${Math.max(0, Math.min(d.py - 20, view.hgt - tip.offsetHeight))}px`;
  }

  function hideTip() {
    if (pinned) {
      pinned = null;
      tip.classList.remove('pinned');
    }
    tip.hidden = true;
  }

  function unpin() {
    pinned = null;
    tip.classList.remove('pinned');
    tip.hidden = true;
    draw();
  }

  /** Enter or a click on a stack: one design opens, several are listed in a pinned tooltip. */
  function activate(stack) {
    if (stack.points.length === 1) {
      onOpen(stack.points[0].spec);
      return;
    }
    pinned = stack;
    tip.classList.add('pinned');
    describe(stack, true);
    place(stack);
    live.textContent = `${stack.points.length} designs listed: ${stack.points.slice(0, 3).map((p) => p.spec).join(', ')}${stack.points.length > 3 ? ' and more' : ''}. Tab to reach their links.`;
    draw();
  }

  stage.addEventListener('mousemove', (event) => {
    if (pinned) return;
    const [px, py] = d3.pointer(event, stage);
    const s = stackAt(px, py);
    if (s !== hovered) {
      hovered = s;
      draw();
    }
    if (s) {
      describe(s, false);
      place(s);
    } else if (!focused) tip.hidden = true;
  });
  stage.addEventListener('mouseleave', () => {
    if (pinned) return;
    if (hovered) {
      hovered = null;
      draw();
    }
    tip.hidden = true;
  });

  stage.addEventListener('keydown', (event) => {
    if (!view || event.target !== stage) return;
    const k = event.key;
    if (k.startsWith('Arrow')) {
      event.preventDefault();
      const list = view.drawn;
      if (!list.length) return;
      const from = focused && drawnOf(focused);
      let next;
      if (!from) {
        // Start at the stack nearest the plot's centre.
        const cx = (MARGIN.left + view.width - MARGIN.right) / 2;
        const cy = (MARGIN.top + view.hgt - MARGIN.bottom) / 2;
        next = d3.least(list, (d) => Math.hypot(d.px - cx, d.py - cy));
      } else {
        const i = nearestInDirection(list, from, k);
        if (i < 0) return;
        next = list[i];
      }
      setFocus(next.stack);
    } else if ((k === 'Enter' || k === ' ') && focused) {
      event.preventDefault();
      activate(focused);
    } else if (k === 'Escape') {
      if (pinned) unpin();
      else setFocus(null);
    } else if (k === '+' || k === '=') {
      zoomBy(2);
    } else if (k === '-') {
      zoomBy(0.5);
    } else if (k === '0') {
      resetZoom();
    }
  });
  stage.addEventListener('blur', () => {
    if (!pinned && focused) {
      focused = null;
      tip.hidden = true;
      draw();
    }
  });

  function setFocus(stack) {
    focused = stack;
    if (pinned && pinned !== stack) {
      pinned = null;
      tip.classList.remove('pinned');
    }
    draw();
    if (!stack) {
      tip.hidden = true;
      return;
    }
    describe(stack, false);
    place(stack);
    const n = stack.points.length;
    const what = n === 1 ? `1 design, ${stack.points[0].spec}` : `${n} designs`;
    live.textContent = `${what} at ${labels.x} ${valueText(stack.points.map((p) => p.x))}, ${labels.y} ${valueText(stack.points.map((p) => p.y))}. Enter ${n === 1 ? 'opens it' : 'lists them'}.`;
  }

  function zoomBy(k) {
    const centre = focused && drawnOf(focused);
    const p = centre ? [centre.px, centre.py] : undefined;
    zoom.scaleBy(svgEl, k, p);
  }

  function resetZoom() {
    zoom.transform(svgEl, d3.zoomIdentity);
  }

  function renderLegend() {
    legend.replaceChildren(
      h('span', { class: 'muted' }, colourBy === 'family' ? 'family:' : 'behaviour:'),
      ...key.entries.map((e) =>
        h(
          'span',
          { class: 'legend-entry', testid: 'scatter-legend-entry', 'data-key': e.key },
          h('span', { class: 'swatch', style: `background:${e.colour}`, 'aria-hidden': 'true' }),
          ` ${e.label} `,
          h('span', { class: 'muted' }, `(${e.count})`),
        ),
      ),
      h(
        'span',
        { class: 'muted legend-note' },
        'Designs on one spot form a stack: a larger disc, its count inside, sliced by colour. Drag a rectangle to filter, wheel or +/− to zoom, shift-drag to pan.',
      ),
    );
  }

  new ResizeObserver(() => draw()).observe(container);

  return {
    update(next, xLabel, yLabel, by = colourBy) {
      points = next;
      labels = { x: xLabel, y: yLabel };
      colourBy = by;
      key = colourKey(points, colourBy);
      hovered = null;
      focused = null;
      pinned = null;
      tip.classList.remove('pinned');
      tip.hidden = true;
      transform = d3.zoomIdentity;
      svgEl.property('__zoom', d3.zoomIdentity);
      renderLegend();
      draw();
    },
    /** Colours the same points by 'behaviour' or 'family'. */
    setColour(by) {
      colourBy = by;
      key = colourKey(points, colourBy);
      renderLegend();
      draw();
    },
    zoomBy,
    resetZoom,
  };
}
