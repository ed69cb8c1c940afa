// The catalogue's scatter of two measures: points on a <canvas> so that 10^4 designs stay
// smooth, hover found with a d3 quadtree in pixel space, axes in SVG. Returns a small object
// with an update method; fetches no data.

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

/** The x label under the plot and the y label turned along its left side. */
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
    .attr('transform', `translate(14,${(MARGIN.top + h - MARGIN.bottom) / 2}) rotate(-90)`)
    .attr('text-anchor', 'middle')
    .text(yLabel);
}

/**
 * Scatter plot of `{spec, x, y}` points. `onClick(point)` opens a design; `describe(point)`
 * fills the hover tooltip element.
 */
export function createScatter(container, { onClick, describe, height = 340 }) {
  container.classList.add('plot', 'scatter');
  const svg = d3.select(container).append('svg').attr('aria-hidden', 'true');
  const canvas = document.createElement('canvas');
  canvas.setAttribute('role', 'img');
  canvas.dataset.testid = 'scatter-canvas';
  container.append(canvas);
  const tip = document.createElement('div');
  tip.className = 'tooltip';
  tip.hidden = true;
  tip.dataset.testid = 'scatter-tooltip';
  container.append(tip);
  let tree = null;
  let state = { points: [], sx: null, sy: null, hovered: null, xLabel: '', yLabel: '' };

  function draw() {
    const { width, height: h } = size(container, height);
    const { points, xLabel, yLabel } = state;
    const sx = d3
      .scaleLinear()
      .domain(padDomain(d3.extent(points, (p) => p.x)))
      .range([MARGIN.left, width - MARGIN.right])
      .nice();
    const sy = d3
      .scaleLinear()
      .domain(padDomain(d3.extent(points, (p) => p.y)))
      .range([h - MARGIN.bottom, MARGIN.top])
      .nice();
    state.sx = sx;
    state.sy = sy;
    svg.attr('width', width).attr('height', h).attr('viewBox', `0 0 ${width} ${h}`);
    svg.selectAll('*').remove();
    svg
      .append('g')
      .attr('transform', `translate(0,${h - MARGIN.bottom})`)
      .call(d3.axisBottom(sx).ticks(Math.max(2, Math.floor(width / 90))));
    svg.append('g').attr('transform', `translate(${MARGIN.left},0)`).call(d3.axisLeft(sy).ticks(6));
    axisLabels(svg, width, h, xLabel, yLabel);
    const ratio = window.devicePixelRatio || 1;
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(h * ratio);
    canvas.style.width = `${width}px`;
    canvas.style.height = `${h}px`;
    canvas.setAttribute('aria-label', `scatter of ${points.length} designs: ${yLabel} against ${xLabel}`);
    const ctx = canvas.getContext('2d');
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, h);
    const r = points.length > 3000 ? 2 : 3;
    ctx.fillStyle = 'rgba(31, 95, 168, 0.6)';
    for (const p of points) {
      ctx.beginPath();
      ctx.arc(sx(p.x), sy(p.y), r, 0, 2 * Math.PI);
      ctx.fill();
    }
    if (state.hovered) {
      ctx.strokeStyle = '#c0392b';
      ctx.lineWidth = 2;
      ctx.beginPath();
      ctx.arc(sx(state.hovered.x), sy(state.hovered.y), r + 4, 0, 2 * Math.PI);
      ctx.stroke();
    }
    tree = d3
      .quadtree()
      .x((p) => sx(p.x))
      .y((p) => sy(p.y))
      .addAll(points);
  }

  function pick(event) {
    if (!tree) return null;
    const rect = canvas.getBoundingClientRect();
    return tree.find(event.clientX - rect.left, event.clientY - rect.top, 10) || null;
  }

  canvas.addEventListener('mousemove', (event) => {
    const p = pick(event);
    if (p !== state.hovered) {
      state.hovered = p;
      draw();
    }
    if (p) {
      const rect = container.getBoundingClientRect();
      describe(p, tip);
      tip.hidden = false;
      const left = event.clientX - rect.left + 14;
      tip.style.left = `${Math.min(left, rect.width - 220)}px`;
      tip.style.top = `${event.clientY - rect.top + 14}px`;
      canvas.style.cursor = 'pointer';
    } else {
      tip.hidden = true;
      canvas.style.cursor = 'default';
    }
  });
  canvas.addEventListener('mouseleave', () => {
    tip.hidden = true;
    if (state.hovered) {
      state.hovered = null;
      draw();
    }
  });
  canvas.addEventListener('click', (event) => {
    const p = pick(event);
    if (p) onClick(p);
  });
  new ResizeObserver(() => draw()).observe(container);

  return {
    update(points, xLabel, yLabel) {
      state = { ...state, points, xLabel, yLabel, hovered: null };
      tip.hidden = true;
      draw();
    },
  };
}
