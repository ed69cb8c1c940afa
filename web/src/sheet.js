// Draws a design's R×C patch at one t on a <canvas>: tiles filled by linkage or rotation,
// pins, the linkage loops (on by default: each loop a line through its joints in its linkage's
// colour over a white halo, as the paper's Fig. 6) and optionally the unit cell with its
// lattice vectors. The scale is fixed over the whole motion (bounds from patch.js) so the sheet
// visibly opens; the user's zoom and pan (zoom-pan.js) apply on top. The loops drawn are left
// on the canvas as `data-linkage-loops` (JSON: index, colour and points in CSS pixels) so that
// tests can check the pixels along them.

import {
  linkageColour,
  patchLinkages,
  patchPins,
  patchPolygons,
  tileColours,
  unitCell,
} from './patch.js';
import { FIT, zoomPoint, zoomedTransform } from './zoom-pan.js';

/** Draws `frame` of `view` into `canvas` with options {rows, cols, colour, cell, links, bounds,
 * zoom} (zoom: a zoom-pan.js state, FIT when absent). */
export function drawSheet(canvas, view, frame, opts) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth || 600;
  const height = canvas.clientHeight || 600;
  if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
    canvas.width = Math.round(width * ratio);
    canvas.height = Math.round(height * ratio);
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  ctx.fillStyle = '#ffffff';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  if (!frame) return;
  // The scale fits the whole motion (so the sheet visibly opens); the current frame is centred.
  const [x0, y0, x1, y1] = opts.bounds;
  const pad = 12;
  const s = Math.min((width - 2 * pad) / Math.max(1e-9, x1 - x0), (height - 2 * pad) / Math.max(1e-9, y1 - y0));
  const polygons = patchPolygons(view, frame, opts.rows, opts.cols);
  const [cx, cy] = centre(polygons);
  // World y points up; the canvas's down. The user's zoom and pan (zoom-pan.js) on top.
  const zoom = opts.zoom ?? FIT;
  const fit = [s, width / 2 - s * cx, height / 2 + s * cy];
  ctx.setTransform(...zoomedTransform(zoom, width, height, ratio, fit));
  canvas.dataset.zoom = `${zoom.k},${zoom.x},${zoom.y}`;
  const px = 1 / (s * zoom.k);
  const fill = tileColours(view, frame, opts.colour);
  ctx.lineJoin = 'round';
  for (const poly of polygons) {
    ctx.beginPath();
    poly.points.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.closePath();
    ctx.fillStyle = fill(poly.tile);
    ctx.fill();
    ctx.strokeStyle = '#333333';
    ctx.lineWidth = px;
    ctx.stroke();
  }
  ctx.fillStyle = '#222222';
  for (const [x, y] of patchPins(view, frame, opts.rows, opts.cols)) {
    ctx.beginPath();
    ctx.arc(x, y, 2 * px, 0, 2 * Math.PI);
    ctx.fill();
  }
  const loops = opts.links ? patchLinkages(view, frame, opts.rows, opts.cols) : [];
  if (loops.length) {
    const path = (loop) => {
      ctx.beginPath();
      loop.points.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      ctx.closePath();
    };
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = 6 * px;
    for (const loop of loops) {
      path(loop);
      ctx.stroke();
    }
    ctx.lineWidth = 3 * px;
    for (const loop of loops) {
      path(loop);
      ctx.strokeStyle = linkageColour(loop.index);
      ctx.stroke();
    }
    ctx.fillStyle = '#222222';
    for (const loop of loops) {
      for (const [x, y] of loop.points) {
        ctx.beginPath();
        ctx.arc(x, y, 3 * px, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
  }
  const toCss = ([x, y]) => zoomPoint(zoom, width, height, [width / 2 + s * (x - cx), height / 2 - s * (y - cy)]).map(round1);
  canvas.dataset.linkageLoops = JSON.stringify(
    loops.map((l) => ({ index: l.index, colour: linkageColour(l.index), points: l.points.map(toCss) })),
  );
  if (opts.cell) {
    const c = unitCell(view, frame, opts.rows, opts.cols);
    ctx.setLineDash([6 * px, 4 * px]);
    ctx.strokeStyle = '#111111';
    ctx.lineWidth = 1.5 * px;
    ctx.beginPath();
    c.corners.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
    ctx.closePath();
    ctx.stroke();
    ctx.setLineDash([]);
    arrow(ctx, c.origin, c.u, '#c0392b', px);
    arrow(ctx, c.origin, c.w, '#1f5fa8', px);
  }
}

const round1 = (v) => Math.round(v * 10) / 10;

/** Centre of the bounding box of some polygons. */
function centre(polygons) {
  let b = [Infinity, Infinity, -Infinity, -Infinity];
  for (const p of polygons) {
    for (const [x, y] of p.points) b = [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)];
  }
  return [(b[0] + b[2]) / 2, (b[1] + b[3]) / 2];
}

function arrow(ctx, o, v, colour, px) {
  const tip = [o[0] + v[0], o[1] + v[1]];
  const len = Math.hypot(v[0], v[1]) || 1;
  const d = [v[0] / len, v[1] / len];
  const head = 10 * px;
  ctx.strokeStyle = colour;
  ctx.fillStyle = colour;
  ctx.lineWidth = 2.5 * px;
  ctx.beginPath();
  ctx.moveTo(o[0], o[1]);
  ctx.lineTo(tip[0] - d[0] * head, tip[1] - d[1] * head);
  ctx.stroke();
  ctx.beginPath();
  ctx.moveTo(tip[0], tip[1]);
  ctx.lineTo(tip[0] - d[0] * head - d[1] * head * 0.5, tip[1] - d[1] * head + d[0] * head * 0.5);
  ctx.lineTo(tip[0] - d[0] * head + d[1] * head * 0.5, tip[1] - d[1] * head - d[0] * head * 0.5);
  ctx.closePath();
  ctx.fill();
}
