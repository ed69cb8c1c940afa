// Zoom and pan of a drawing on a canvas (the design page's sheet and the finite-sheet panel):
// a pure model — a scale k about the canvas centre and an offset in CSS pixels, applied after
// the drawing's own fit — and `attachZoom`, which wires a canvas to it: the wheel zooms about
// the pointer, a drag pans, a double click (or the 0 key) fits again, + and − zoom and the
// arrow keys pan when the canvas has the focus. The state is left on the canvas as
// `data-zoom` ("k,x,y") for tests.

export const MIN_ZOOM = 1;
export const MAX_ZOOM = 64;

/** A zoom state: `{k, x, y}`, k ≥ 1 about the canvas centre, then (x, y) CSS pixels. */
export const FIT = Object.freeze({ k: 1, x: 0, y: 0 });

/** The canvas point (CSS px) where a point drawn at (px, py) by the unzoomed fit goes under
 * zoom `z` on a canvas of `width` × `height`. */
export function zoomPoint(z, width, height, [px, py]) {
  return [width / 2 + z.k * (px - width / 2) + z.x, height / 2 + z.k * (py - height / 2) + z.y];
}

/** `z` zoomed by `factor` about the canvas point (cx, cy), which stays where it is; k clamped
 * to [MIN_ZOOM, MAX_ZOOM], and back to FIT at k = 1. */
export function zoomAbout(z, factor, cx, cy, width, height) {
  const k = Math.min(MAX_ZOOM, Math.max(MIN_ZOOM, z.k * factor));
  if (k === MIN_ZOOM) return FIT;
  const f = k / z.k;
  // The point under (cx, cy) stays: c = w/2 + k'(p − w/2) + x' with p fixed.
  const x = cx - width / 2 - f * (cx - width / 2 - z.x);
  const y = cy - height / 2 - f * (cy - height / 2 - z.y);
  return { k, x, y };
}

/** `z` panned by (dx, dy) CSS pixels (nothing to pan at k = 1). */
export function panBy(z, dx, dy) {
  if (z.k === MIN_ZOOM) return FIT;
  return { k: z.k, x: z.x + dx, y: z.y + dy };
}

/** The canvas transform (for ctx.setTransform, device pixels) of a fit `[s, tx, ty]` (world
 * → CSS px: x' = s·x + tx, y' = −s·y + ty) under zoom `z`, at device ratio `ratio`. */
export function zoomedTransform(z, width, height, ratio, [s, tx, ty]) {
  const [ox, oy] = zoomPoint(z, width, height, [tx, ty]);
  return [ratio * s * z.k, 0, 0, -ratio * s * z.k, ratio * ox, ratio * oy];
}

/**
 * Wires `canvas` to a zoom state read by `get()` and written by `set(z)` (which redraws):
 * wheel, drag, double click, keys. Returns a function that removes the listeners.
 */
export function attachZoom(canvas, get, set) {
  const size = () => [canvas.clientWidth || 1, canvas.clientHeight || 1];
  const local = (e) => {
    const r = canvas.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  let drag = null;
  const on = {
    wheel: (e) => {
      e.preventDefault();
      const [w, h] = size();
      const [cx, cy] = local(e);
      set(zoomAbout(get(), Math.exp(-e.deltaY / 300), cx, cy, w, h));
    },
    pointerdown: (e) => {
      if (e.button !== 0 || get().k === MIN_ZOOM) return;
      drag = { id: e.pointerId, at: [e.clientX, e.clientY] };
      canvas.setPointerCapture?.(e.pointerId);
    },
    pointermove: (e) => {
      if (!drag || e.pointerId !== drag.id) return;
      const [x, y] = [e.clientX, e.clientY];
      set(panBy(get(), x - drag.at[0], y - drag.at[1]));
      drag.at = [x, y];
    },
    pointerup: () => {
      drag = null;
    },
    dblclick: () => set(FIT),
    keydown: (e) => {
      const [w, h] = size();
      const step = 40;
      const moves = { ArrowLeft: [step, 0], ArrowRight: [-step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
      if (e.key === '+' || e.key === '=') set(zoomAbout(get(), 1.5, w / 2, h / 2, w, h));
      else if (e.key === '-') set(zoomAbout(get(), 1 / 1.5, w / 2, h / 2, w, h));
      else if (e.key === '0') set(FIT);
      else if (moves[e.key]) set(panBy(get(), ...moves[e.key]));
      else return;
      e.preventDefault();
    },
  };
  if (!canvas.hasAttribute('tabindex')) canvas.tabIndex = 0;
  canvas.style.touchAction = 'none';
  // Wheel and keys call preventDefault (no page scroll): never passive.
  for (const [type, f] of Object.entries(on)) canvas.addEventListener(type, f, { passive: false });
  return () => {
    for (const [type, f] of Object.entries(on)) canvas.removeEventListener(type, f);
  };
}
