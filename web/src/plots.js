// Plots drawn with d3: the line plot of min/max principal expansion versus t with a marker at
// the current t (also the inverse page's best objective, on a log scale when it is positive),
// with its legend above the plot area so it never covers a line, and the polar profile of the
// stretch U at the current t (the catalogue's scatter is in scatter.js). Each returns a small
// object with update methods; none fetches data.

import * as d3 from 'd3';

const MARGIN = { top: 12, right: 16, bottom: 40, left: 56 };

function size(container, height) {
  const width = Math.max(240, Math.floor(container.clientWidth || 480));
  return { width, height };
}

function padDomain([lo, hi]) {
  if (lo === undefined || hi === undefined) return [0, 1];
  if (lo === hi) return [lo - 0.5, hi + 0.5];
  const pad = (hi - lo) * 0.04;
  return [lo - pad, hi + pad];
}

/** The x label under the plot and the y label turned along its left side (beside the plot
 * area, which starts below the legend row). */
function axisLabels(svg, width, h, xLabel, yLabel) {
  svg
    .append('text')
    .attr('class', 'axis-label')
    .attr('x', (MARGIN.left + width - MARGIN.right) / 2)
    .attr('y', h - 6)
    .attr('text-anchor', 'middle')
    .text(xLabel);
  svg
    .append('text')
    .attr('class', 'axis-label')
    .attr('transform', `translate(14,${(MARGIN.top + LEGEND_ROW + h - MARGIN.bottom) / 2}) rotate(-90)`)
    .attr('text-anchor', 'middle')
    .text(yLabel);
}

/** Whether a y axis over `values` is drawn on a log scale: asked for, and every value > 0 (an
 * objective that can be negative — a "largest area" goal — stays linear). */
export function useLogScale(values, yLog) {
  return Boolean(yLog) && values.length > 0 && values.every((v) => v > 0 && Number.isFinite(v));
}

/** Log-scale domain of positive values: whole decades around them (one decade at least). */
export function logDomain(values) {
  const lo = Math.min(...values);
  const hi = Math.max(...values);
  const a = 10 ** Math.floor(Math.log10(lo));
  const b = 10 ** Math.ceil(Math.log10(hi));
  return [a, b > a ? b : a * 10];
}

/** Height of the legend row above the plot area. */
const LEGEND_ROW = 18;

/**
 * Line plot of several series over t ∈ [0, 1] with a vertical marker. `series`:
 * `[{name, className, points: [[t, y], …]}]`; their names are a legend row above the plot area.
 * Options for other uses: `xAuto` (x from 0 to the largest x of the points instead of
 * [0, 1]), `steps` (draw each value until the next point), `marker: false` (no marker),
 * `yLog` (a log y axis when every value is positive; the svg's `data-scale` says which).
 */
export function createLinePlot(container, { xLabel, yLabel, height = 220, xAuto = false, steps = false, marker: withMarker = true, yLog = false }) {
  container.classList.add('plot');
  const svg = d3.select(container).append('svg').attr('role', 'img');
  let series = [];
  let marker = 0;

  function draw() {
    const { width, height: h } = size(container, height);
    const all = series.flatMap((s) => s.points.map((p) => p[1]));
    const xs = series.flatMap((s) => s.points.map((p) => p[0]));
    const xMax = xAuto ? Math.max(1, ...xs) : 1;
    const sx = d3.scaleLinear().domain([0, xMax]).range([MARGIN.left, width - MARGIN.right]);
    if (xAuto) sx.nice();
    const top = MARGIN.top + (series.length ? LEGEND_ROW : 0);
    const log = useLogScale(all, yLog);
    const sy = log
      ? d3.scaleLog().domain(logDomain(all)).range([h - MARGIN.bottom, top])
      : d3
          .scaleLinear()
          .domain(padDomain(d3.extent(all.length ? all : [0, 1])))
          .range([h - MARGIN.bottom, top])
          .nice();
    svg.attr('width', width).attr('height', h).attr('viewBox', `0 0 ${width} ${h}`);
    svg.attr('aria-label', `${yLabel}${log ? ' (log scale)' : ''} against ${xLabel}`);
    svg.attr('data-scale', log ? 'log' : 'linear');
    svg.selectAll('*').remove();
    svg
      .append('g')
      .attr('transform', `translate(0,${h - MARGIN.bottom})`)
      .call(d3.axisBottom(sx).ticks(5));
    const yAxis = d3.axisLeft(sy);
    if (log) {
      // Ticks on decades only (at most about six), labels short: 0.001 … 1000 as they are,
      // 1e-6 beyond.
      const [lo, hi] = sy.domain().map((v) => Math.round(Math.log10(v)));
      const every = Math.max(1, Math.ceil((hi - lo) / 5));
      const decades = d3.range(lo, hi + 1).filter((e) => (e - lo) % every === 0);
      yAxis.tickValues(decades.map((e) => 10 ** e)).tickFormat((v) => {
        const e = Math.round(Math.log10(v));
        return e >= -3 && e <= 3 ? d3.format('~g')(10 ** e) : `1e${e}`;
      });
    } else yAxis.ticks(5);
    svg.append('g').attr('class', 'y-axis').attr('transform', `translate(${MARGIN.left},0)`).call(yAxis);
    axisLabels(svg, width, h, xLabel, log ? `${yLabel} (log)` : yLabel);
    const line = d3
      .line()
      .curve(steps ? d3.curveStepAfter : d3.curveLinear)
      .x((p) => sx(p[0]))
      .y((p) => sy(p[1]));
    let x = MARGIN.left;
    series.forEach((s) => {
      svg
        .append('path')
        .attr('class', `series ${s.className}`)
        .attr('data-testid', `series-${s.className}`)
        .attr('d', line(s.points));
      // The legend row, above the plot area: a sample of the line, then the name.
      const y = MARGIN.top + LEGEND_ROW / 2 - 2;
      svg
        .append('line')
        .attr('class', `series ${s.className}`)
        .attr('x1', x)
        .attr('x2', x + 18)
        .attr('y1', y)
        .attr('y2', y);
      const text = svg
        .append('text')
        .attr('class', `legend ${s.className}`)
        .attr('data-testid', `legend-${s.className}`)
        .attr('x', x + 22)
        .attr('y', y + 4)
        .attr('text-anchor', 'start')
        .text(s.name);
      const w = typeof text.node().getComputedTextLength === 'function' ? text.node().getComputedTextLength() : 7 * s.name.length;
      x += 22 + (w || 7 * s.name.length) + 16;
    });
    if (!withMarker) return;
    svg
      .append('line')
      .attr('class', 'marker')
      .attr('data-testid', 'plot-marker')
      .attr('x1', sx(marker))
      .attr('x2', sx(marker))
      .attr('y1', top)
      .attr('y2', h - MARGIN.bottom);
  }

  new ResizeObserver(() => draw()).observe(container);
  return {
    update(next) {
      series = next;
      draw();
    },
    setMarker(t) {
      marker = t;
      const m = svg.select('line.marker');
      if (m.empty()) return;
      const { width } = size(container, height);
      const x = MARGIN.left + t * (width - MARGIN.left - MARGIN.right);
      m.attr('x1', x).attr('x2', x);
    },
  };
}

/** |F·(cos φ, sin φ)|, the stretch of the sheet in direction φ of the closed state. */
export function stretchAt(F, phi) {
  const c = Math.cos(phi);
  const s = Math.sin(phi);
  return Math.hypot(F[0][0] * c + F[0][1] * s, F[1][0] * c + F[1][1] * s);
}

/** Polar plot of the stretch profile r(φ) = |F d(φ)| against the closed state's unit circle. */
export function createPolarPlot(container, { size: side = 240 } = {}) {
  container.classList.add('plot', 'polar');
  const svg = d3
    .select(container)
    .append('svg')
    .attr('role', 'img')
    .attr('width', side)
    .attr('height', side)
    .attr('viewBox', `${-side / 2} ${-side / 2} ${side} ${side}`);
  let rMax = 1.5;
  const radius = side / 2 - 22;

  function frame() {
    svg.selectAll('*').remove();
    const r = d3.scaleLinear().domain([0, rMax]).range([0, radius]);
    const ticks = r.ticks(4).filter((v) => v > 0);
    for (const v of ticks) {
      svg.append('circle').attr('class', 'grid').attr('r', r(v));
      svg
        .append('text')
        .attr('class', 'tick')
        .attr('x', 2)
        .attr('y', -r(v) - 2)
        .text(d3.format('~g')(v));
    }
    for (let k = 0; k < 4; k += 1) {
      const a = (k * Math.PI) / 4;
      svg
        .append('line')
        .attr('class', 'grid')
        .attr('x1', -radius * Math.cos(a))
        .attr('y1', radius * Math.sin(a))
        .attr('x2', radius * Math.cos(a))
        .attr('y2', -radius * Math.sin(a));
    }
    svg.append('circle').attr('class', 'closed').attr('r', r(1));
    svg.append('path').attr('class', 'profile').attr('data-testid', 'polar-profile');
    return r;
  }
  let scale = frame();

  return {
    setMaxRadius(value) {
      rMax = Math.max(1.05, value * 1.05);
      scale = frame();
    },
    update(F) {
      const pts = d3.range(0, 181).map((k) => {
        const phi = (k / 180) * 2 * Math.PI;
        return [phi, stretchAt(F, phi)];
      });
      const line = d3
        .lineRadial()
        .angle((p) => Math.PI / 2 - p[0])
        .radius((p) => scale(p[1]));
      svg.select('path.profile').attr('d', line(pts));
      const lo = d3.min(pts, (p) => p[1]);
      const hi = d3.max(pts, (p) => p[1]);
      svg.attr('aria-label', `stretch in every direction: from ${lo.toFixed(3)} to ${hi.toFixed(3)}`);
    },
  };
}
