// The design page's "Same motion elsewhere" panel (issue 13, item 5): the topologies of other
// cells and families whose motion matches this design's (GET /api/motion), each with a link
// to a stored design of it. Hidden when there is nothing to show: a design that is not
// stored, a motion found only here, or a static copy (which has no classes).

import { h } from './dom.js';

/** The panel's rows for `klass` (the API's MotionClass) seen from the design of `topology`:
 * every other variant, as {label, spec, designs}. Pure, for tests. */
export function variantRows(klass, topology) {
  if (!klass) return [];
  return klass.variants
    .filter((v) => v.topology !== topology)
    .map((v) => ({ label: `${v.family} ${v.cell}`, spec: v.example, designs: v.designs, topology: v.topology }));
}

export function createMotionPanel(section, list, { data }) {
  let asked = null;
  return {
    /** Shows the class of the stored design `spec`. */
    async show(spec, stored) {
      asked = spec;
      if (!data.live || !stored || typeof data.motion !== 'function') {
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
      list.replaceChildren(
        ...rows.map((r) =>
          h(
            'li',
            { testid: 'motion-variant' },
            h('a', { href: `./design.html?spec=${encodeURIComponent(r.spec)}` }, r.label),
            ` — ${r.designs} design${r.designs === 1 ? '' : 's'} `,
            h('code', { class: 'muted' }, r.topology),
          ),
        ),
      );
    },
  };
}
