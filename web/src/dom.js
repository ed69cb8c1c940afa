// Small DOM helpers shared by the pages: element creation, number formatting, the in-place
// notice that explains an error with what to do, and a debounce.

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

/** A number for a table: 4 significant digits, integers as they are, missing as "–". */
export function fmt(v) {
  if (v === null || v === undefined) return '–';
  if (typeof v !== 'number') return String(v);
  if (Number.isInteger(v)) return String(v);
  const a = Math.abs(v);
  if (a !== 0 && (a < 1e-3 || a >= 1e5)) return v.toExponential(3);
  return String(Number(v.toPrecision(4)));
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
