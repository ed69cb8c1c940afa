// Small DOM helpers shared by the pages: element creation, number formatting (0 for what is
// zero up to rounding; a negative expansion in words), the in-place notice that explains an
// error with what to do, and a debounce.

/** Creates an element: h('button', {class: 'x', onclick: f}, 'text', child…). */
export function h(tag, attrs = {}, ...children) {
  const el = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === null || v === undefined || v === false) continue;
    if (k.startsWith('on')) el.addEventListener(k.slice(2), v);
    else if (k === 'class') el.className = v;
    else if (k === 'testid') el.dataset.testid = v;
    else if (k in el && typeof v !== 'string') el[k] = v;
    else el.setAttribute(k, v === true ? '' : v);
  }
  for (const c of children.flat()) {
    if (c === null || c === undefined || c === false) continue;
    el.append(c instanceof Node ? c : String(c));
  }
  return el;
}

/** Below this many units in the last place of `scale`, a number is zero up to rounding. */
const ROUNDING_ULPS = 16;

/** A number for a table: 4 significant digits, integers as they are, missing as "–". A value
 * that is zero up to rounding — |v| ≤ 16 ulp of `scale`, the size of the quantities it was
 * computed from (1 for the page's non-dimensional measures: F, expansions, radians, × L) —
 * prints 0, so 4.441e-16 (2 ulp of 1) is 0 while 1e-9 still prints; pass scale 0 for exact. */
export function fmt(v, scale = 1) {
  if (v === null || v === undefined) return '–';
  if (typeof v !== 'number') return String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  if (a <= ROUNDING_ULPS * Number.EPSILON * Math.abs(scale)) return '0';
  if (a < 1e-3 || a >= 1e5) return v.toExponential(3);
  return String(Number(v.toPrecision(4)));
}

/** A principal expansion ε (stretch − 1) with what it means when the sheet gets smaller:
 * "−0.004365 (contracts 0.44 %)"; an expansion ≥ 0, or 0 up to rounding, is the number alone. */
export function fmtExpansion(e) {
  const text = fmt(e);
  if (typeof e !== 'number' || !(e < 0) || text === '0') return text;
  const pct = Number((-100 * e).toPrecision(2));
  return `${text} (contracts ${pct} %)`;
}

/** Shows an error or notice in place: a visible `.notice` with the message and the hint. */
export function showNotice(container, { message, hint, kind }) {
  container.replaceChildren(
    h(
      'div',
      { class: `notice notice-${kind || 'error'}`, role: 'alert', testid: 'notice', 'data-kind': kind || 'error' },
      h('strong', {}, message),
      hint ? h('p', { class: 'hint' }, hint) : null,
    ),
  );
  container.hidden = false;
}

export function clearNotice(container) {
  container.replaceChildren();
  container.hidden = true;
}

/** Calls `f` once `ms` after the last call. */
export function debounce(f, ms) {
  let timer = null;
  return (...args) => {
    clearTimeout(timer);
    timer = setTimeout(() => f(...args), ms);
  };
}
