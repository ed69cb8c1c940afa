// The design page's "Same motion elsewhere" panel (issue 13 item 5, issue 24 item 6): the
// topologies of other cells and families in this design's motion class (GET /api/motion, or
// query.js's motionOf on a static site). Honest about what is shared: the linkage motion (the
// mechanism), not the opening — the other cut patterns have other tile shapes or cells, so
// each row shows its example's own area ratio (and its designs' range) beside this design's.
// Rows are sorted by family number (IH1 before IH10), then cell, then area ratio (largest
// first), each with a thumbnail; long lists show the first few and a "show all" button.
// Hidden when there is nothing to show: a design that is not stored or a motion found only here.

import { h, fmt } from './dom.js';

/** Rows shown before "show all". */
export const SHOWN = 8;

const cellKey = (cell) => String(cell).split('x').map(Number);
const familyNumber = (f) => Number(String(f).replace(/^IH/, ''));

/** The panel's rows for `klass` (the API's MotionClass) seen from the design of `topology`:
 * every other variant, as {label, spec, designs, topology, area, range}, sorted by family
 * number, cell, then area ratio (largest first). Pure, for tests. */
export function variantRows(klass, topology) {
  if (!klass) return [];
  return klass.variants
    .filter((v) => v.topology !== topology)
    .map((v) => ({
      label: `${v.family} ${String(v.cell).replace('x', '×')}`,
      family: v.family,
      cell: v.cell,
      spec: v.example,
      designs: v.designs,
      topology: v.topology,
      area: v.example_area_ratio ?? null,
      range: v.area_ratio ?? null,
    }))
    .sort((a, b) => {
      const fa = familyNumber(a.family);
      const fb = familyNumber(b.family);
      if (fa !== fb) return fa - fb;
      const [ca, cb] = [cellKey(a.cell), cellKey(b.cell)];
      if (ca[0] !== cb[0]) return ca[0] - cb[0];
      if (ca[1] !== cb[1]) return ca[1] - cb[1];
      return (b.area ?? -Infinity) - (a.area ?? -Infinity);
    })
    .map(({ family, cell, ...row }) => row);
}

/** "opens to 1.33× · its 4 designs 1.21–1.45×" for a row. */
export function areaText(row) {
  if (row.area === null) return '';
  const own = `opens to ${fmt(row.area)}×`;
  if (!row.range || row.designs < 2) return own;
  const [lo, hi] = row.range.map(fmt);
  return lo === hi ? own : `${own} · its ${row.designs} designs ${lo}–${hi}×`;
}

export function createMotionPanel(section, list, { data }) {
  let asked = null;
  const intro = section.querySelector('.help');
  return {
    /** Shows the class of the stored design `spec` (`area`: this design's own area ratio). */
    async show(spec, stored, area = null) {
      asked = spec;
      if (!stored || typeof data.motion !== 'function') {
        section.hidden = true;
        return;
      }
      let answer;
      try {
        answer = await data.motion(spec);
      } catch {
        answer = { class: null };
      }
      if (asked !== spec) return;
      const rows = variantRows(answer.class, answer.topology);
      section.hidden = rows.length === 0;
      if (intro) {
        intro.textContent =
          'These cut patterns share this design’s mechanism — the same linkage motion (one motion class) — ' +
          'but have other tile shapes or cells, so each opens to its own area ratio' +
          (area === null ? '.' : `; this design opens to ${fmt(area)}×.`);
      }
      const item = (r) =>
        h(
          'li',
          { testid: 'motion-variant', 'data-spec': r.spec, 'data-area': r.area === null ? '' : String(r.area) },
          h('img', { src: data.thumbnailUrl(r.spec), alt: '', loading: 'lazy', width: 96, height: 48 }),
          h(
            'span',
            { class: 'motion-text' },
            h('a', { href: `./design.html?spec=${encodeURIComponent(r.spec)}` }, r.label),
            ` ${areaText(r)} `,
            h('code', { class: 'muted' }, r.topology),
          ),
        );
      const head = rows.slice(0, SHOWN).map(item);
      const rest = rows.slice(SHOWN);
      const more = rest.length
        ? h(
            'li',
            { class: 'motion-more' },
            h(
              'button',
              {
                type: 'button',
                testid: 'motion-show-all',
                onclick: (e) => {
                  e.currentTarget.closest('li').replaceWith(...rest.map(item));
                  list.querySelector(`li:nth-child(${SHOWN + 1}) a`)?.focus();
                },
              },
              `show all ${rows.length}`,
            ),
          )
        : null;
      list.replaceChildren(...head, ...(more ? [more] : []));
    },
  };
}
