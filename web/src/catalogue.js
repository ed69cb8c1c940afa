// The catalogue page (index.html): facet filters with disjunctive counts, range filters, a
// scatter of any two measures (stacks with counts, colour by behaviour or family, brushing sets
// the two axes' ranges; scatter.js), a grid or table of designs with thumbnails, sorting by
// any column either way, paging, a spec box, downloads. The default view is the mechanisms
// view (issue 24 item 2): one card per distinct motion (GET /api/motions or query.js's
// motionGroups) with its counts and ranges over the matching designs, its best example's
// thumbnail, and its variants expanding in place; the grid and table list designs. Default
// order: largest area ratio first. A facet with one value is shown as a one-line fact. The
// page's query string is remembered in sessionStorage for the design page's back link.
// The whole view lives in the URL (history.replaceState). Data comes through data.js, so
// the page is the same over `isogami serve` and over a static site.

import { openData } from './data.js';
import { h, fmt, showNotice, clearNotice, debounce } from './dom.js';
import { createScatter } from './scatter.js';
import {
  FACETS, MEASURES, MAIN_MEASURES, TEXT_SORT_KEYS, facetLabel, facetText, measureHelp, measureLabel, setMeasures,
} from './schema.js';
import { HAS_SHEET_RANGE, shapeStatus, sheetStatus } from './buildable.js';
import {
  PAGE_SIZES, catalogueSearch, designHref, filterParams, parseCatalogueState, rememberCatalogue,
} from './url.js';
import { allRows, catalogueCsv, catalogueJson, dictionaryCsv, download } from './export.js';
import { revealedScroll, specBreaks, tableColumns } from './table-model.js';

const $ = (id) => document.getElementById(id);

/** A spec as text that may break after its commas and colons (a narrow sticky column). */
const specText = (spec) => specBreaks(spec).flatMap((piece, k) => (k ? [h('wbr'), piece] : [piece]));

/** The badge of a design's finite sheet (buildable.js): "no one-DOF sheet", or the fraction
 * its one-DOF sheet keeps; the explanation on hover and, on a card, for screen readers in the
 * text (a table cell is "none" or "92 %" under its column's heading, explained on hover). */
function sheetBadge(row, { short = false } = {}) {
  const s = sheetStatus(row);
  return h(
    'span',
    { class: 'sheet-badge', 'data-sheet': s.kind, title: s.title, testid: 'sheet-badge' },
    short ? s.short : s.text,
    short ? null : h('span', { class: 'visually-hidden' }, `: ${s.title}`),
  );
}

/** The badge of a design's shape tolerance (buildable.js): "special shape" for a design that
 * opens only at its exact shape, the tolerance in mm at 20 mm edges otherwise; none when not
 * measured or the family's shape is fixed. */
function shapeBadge(row) {
  const s = shapeStatus(row);
  if (!s.text) return null;
  return h(
    'span',
    { class: 'shape-badge', 'data-shape': s.kind, title: s.title, testid: 'shape-badge' },
    s.text,
    h('span', { class: 'visually-hidden' }, `: ${s.title}`),
  );
}

let data;
let state;
let scatter;
let seq = 0;
let lastScatterKey = null;

async function main() {
  data = await openData();
  // The server's measures (a static site's list), before the URL is read: a range on a measure
  // this page does not know by name is kept.
  try {
    setMeasures(await data.measures());
  } catch {
    // The page's own list of measures stays.
  }
  state = parseCatalogueState(location.search);
  document.body.dataset.mode = data.mode;
  $('mode').textContent = data.mode === 'static' ? 'static site (read-only)' : 'live server';
  setupSpecBox();
  setupToolbar();
  setupRanges();
  setupScatter();
  try {
    const stats = await data.stats();
    $('stats').textContent = `${stats.designs} designs · isogami ${stats.tool_version ?? '?'}`;
  } catch (e) {
    showError(e);
  }
  await refresh();
}

/** The scatter: stacks of designs, colour select, brush → the two axes' ranges, clear them. */
function setupScatter() {
  scatter = createScatter($('scatter'), {
    onOpen: (spec) => {
      location.href = designHref(spec);
    },
    onBrush: ({ x, y }) =>
      change(() => {
        const ranges = state.ranges.filter((r) => r.measure !== state.x && r.measure !== state.y);
        if (state.x === state.y) {
          ranges.push({ measure: state.x, min: Math.max(x[0], y[0]), max: Math.min(x[1], y[1]) });
        } else {
          ranges.push({ measure: state.x, min: x[0], max: x[1] }, { measure: state.y, min: y[0], max: y[1] });
        }
        state.ranges = ranges;
        state.offset = 0;
      }),
    href: (spec) => designHref(spec),
    thumbnailUrl: (spec) => data.thumbnailUrl(spec),
    countEl: $('scatter-count'),
  });
  $('scatter-colour').addEventListener('change', () => {
    state.colour = $('scatter-colour').value;
    history.replaceState(null, '', `${location.pathname}${catalogueSearch(state)}`);
    scatter.setColour(state.colour);
  });
  $('scatter-clear').addEventListener('click', () =>
    change(() => {
      state.ranges = state.ranges.filter((r) => r.measure !== state.x && r.measure !== state.y);
      state.offset = 0;
    }),
  );
}

/** The scatter's controls in agreement with the state. */
function syncScatter() {
  $('scatter-colour').value = state.colour;
  const axisRanges = state.ranges.filter((r) => r.measure === state.x || r.measure === state.y);
  $('scatter-clear').hidden = axisRanges.length === 0;
  $('scatter-clear').textContent = `clear the ${axisRanges.map((r) => measureLabel(r.measure)).join(' and ')} range${axisRanges.length > 1 ? 's' : ''}`;
}

function showError(e) {
  showNotice($('notice'), { message: e.message, hint: e.hint || 'reload the page; if it persists, check the server', kind: e.kind });
}

/** Applies a change of the view: URL, then page, facets and (when needed) the scatter. */
async function refresh() {
  const token = ++seq;
  history.replaceState(null, '', `${location.pathname}${catalogueSearch(state)}`);
  rememberCatalogue(catalogueSearch(state));
  const mechanisms = state.view === 'mechanisms';
  syncControls();
  syncScatter();
  const scatterKey = `${filterParams(state)}|${state.x}|${state.y}`;
  const wantScatter = scatterKey !== lastScatterKey;
  document.body.classList.add('loading');
  try {
    const [page, facets, points] = await Promise.all([
      mechanisms ? data.motions(state) : data.designs(state),
      data.facets(state),
      wantScatter ? data.scatter(state, state.x, state.y) : null,
    ]);
    if (token !== seq) return;
    if (!mechanisms && page.total > 0 && state.offset >= page.total) {
      state.offset = Math.floor((page.total - 1) / state.limit) * state.limit;
      refresh();
      return;
    }
    clearNotice($('notice'));
    renderFacets(facets);
    if (mechanisms) renderMechanisms(page);
    else renderPage(page);
    if (points) {
      lastScatterKey = scatterKey;
      scatter.update(points, measureLabel(state.x), measureLabel(state.y), state.colour);
    }
  } catch (e) {
    if (token === seq) showError(e);
  } finally {
    if (token === seq) document.body.classList.remove('loading');
  }
}

function change(mutate) {
  mutate();
  refresh();
}

function setupSpecBox() {
  $('spec-form').addEventListener('submit', (event) => {
    event.preventDefault();
    const spec = $('spec-input').value.trim();
    if (spec) location.href = designHref(spec);
  });
}

function measureOptions(select, names) {
  select.replaceChildren(...names.map((n) => h('option', { value: n }, measureLabel(n))));
}

function setupToolbar() {
  const all = MEASURES.map((m) => m.name);
  measureOptions($('x'), all);
  measureOptions($('y'), all);
  $('x').addEventListener('change', () => change(() => (state.x = $('x').value)));
  $('y').addEventListener('change', () => change(() => (state.y = $('y').value)));
  $('sort-key').replaceChildren(
    ...TEXT_SORT_KEYS.filter((k) => k !== 'spec').concat(['spec']).map((k) => h('option', { value: k }, k.replace(/_/g, ' '))),
    ...MEASURES.map((m) => h('option', { value: m.name }, m.label)),
  );
  $('sort-key').addEventListener('change', () =>
    change(() => {
      const key = $('sort-key').value;
      state.sort = { key, desc: state.sort?.desc ?? false };
      state.offset = 0;
    }),
  );
  $('sort-dir').addEventListener('click', () =>
    change(() => {
      state.sort = { key: state.sort?.key ?? 'spec', desc: !state.sort?.desc };
      state.offset = 0;
    }),
  );
  $('limit').replaceChildren(...PAGE_SIZES.map((n) => h('option', { value: n }, String(n))));
  $('limit').addEventListener('change', () =>
    change(() => {
      state.limit = Number($('limit').value);
      state.offset = 0;
    }),
  );
  $('view-mechanisms').addEventListener('click', () => change(() => (state.view = 'mechanisms')));
  $('view-grid').addEventListener('click', () => change(() => (state.view = 'grid')));
  $('view-table').addEventListener('click', () => change(() => (state.view = 'table')));
  $('prev').addEventListener('click', () => change(() => (state.offset = Math.max(0, state.offset - state.limit))));
  $('next').addEventListener('click', () => change(() => (state.offset += state.limit)));
  $('clear').addEventListener('click', () =>
    change(() => {
      for (const f of FACETS) state.filters[f.name] = [];
      state.ranges = [];
      state.offset = 0;
    }),
  );
  $('download-csv').addEventListener('click', () => exportRows('csv'));
  $('download-json').addEventListener('click', () => exportRows('json'));
  $('download-dictionary').addEventListener('click', async () => {
    try {
      download('isogami-dictionary.csv', dictionaryCsv(await data.dictionary()), 'text/csv');
    } catch (e) {
      showError(e);
    }
  });
}

async function exportRows(kind) {
  const button = $(`download-${kind}`);
  button.disabled = true;
  const snapshot = structuredClone(state);
  try {
    const [rows, dictionary, stats] = await Promise.all([
      allRows((offset, limit) => data.designs({ ...snapshot, offset, limit })),
      data.dictionary(),
      data.stats(),
    ]);
    if (kind === 'csv') download('isogami-catalogue.csv', catalogueCsv(rows, dictionary), 'text/csv');
    else {
      const params = filterParams(snapshot);
      const query = Object.fromEntries([...new Set(params.keys())].map((k) => [k, params.getAll(k)]));
      if (snapshot.sort) query.sort = `${snapshot.sort.desc ? '-' : ''}${snapshot.sort.key}`;
      download('isogami-catalogue.json', catalogueJson(rows, { stats, dictionary, query }), 'application/json');
    }
  } catch (e) {
    showError(e);
  } finally {
    button.disabled = false;
  }
}

function setupRanges() {
  const row = (name) => {
    const apply = () =>
      change(() => {
        const lo = $(`min-${name}`).value.trim();
        const hi = $(`max-${name}`).value.trim();
        state.ranges = state.ranges.filter((r) => r.measure !== name);
        const min = lo === '' ? null : Number(lo);
        const max = hi === '' ? null : Number(hi);
        const ok = (v) => v === null || Number.isFinite(v);
        if ((min !== null || max !== null) && ok(min) && ok(max)) state.ranges.push({ measure: name, min, max });
        state.offset = 0;
      });
    const later = debounce(apply, 500);
    const input = (bound) =>
      h('input', {
        id: `${bound}-${name}`,
        type: 'number',
        step: 'any',
        inputmode: 'decimal',
        placeholder: bound,
        'aria-label': `${bound} ${measureLabel(name)}`,
        testid: `range-${bound}-${name}`,
        onchange: apply,
        oninput: later,
      });
    return h('div', { class: 'range' }, h('span', { class: 'range-label' }, measureLabel(name)), input('min'), input('max'));
  };
  const main = MAIN_MEASURES.map(row);
  const more = MEASURES.filter((m) => !MAIN_MEASURES.includes(m.name)).map((m) => row(m.name));
  // Buildability: only the designs with a one-DOF finite sheet (a range on finite_covered).
  const buildable = h(
    'label',
    { class: 'buildable-only', title: measureHelp('finite_covered') },
    h('input', {
      type: 'checkbox',
      id: 'buildable-only',
      testid: 'buildable-only',
      onchange: (e) =>
        change(() => {
          state.ranges = state.ranges.filter((r) => r.measure !== HAS_SHEET_RANGE.measure);
          if (e.target.checked) state.ranges.push({ ...HAS_SHEET_RANGE });
          state.offset = 0;
        }),
    }),
    ' only designs with a one-DOF finite sheet (buildable)',
  );
  // Lead with what can be made: buildable designs first (a one-DOF sheet and the shape
  // tolerance of ±0.05 mm at 20 mm edges), each part in the sort's order.
  const lead = h(
    'label',
    { class: 'buildable-only', title: 'Buildable designs (a one-DOF finite sheet, and they keep 95 % of their opening under shape errors of ±0.05 mm at 20 mm edges) come first, in the chosen order; then the others.' },
    h('input', {
      type: 'checkbox',
      id: 'lead-buildable',
      testid: 'lead-buildable',
      onchange: (e) =>
        change(() => {
          state.lead = e.target.checked ? 'buildable' : 'all';
          state.offset = 0;
        }),
    }),
    ' buildable designs first',
  );
  $('ranges').replaceChildren(
    h('h2', {}, 'Ranges'),
    buildable,
    lead,
    ...main,
    h('details', {}, h('summary', {}, 'more measures'), ...more),
  );
}

/** Puts every control in agreement with the state (after a reload or a change). */
function syncControls() {
  $('x').value = state.x;
  $('y').value = state.y;
  $('sort-key').value = state.sort ? state.sort.key : 'spec';
  const desc = state.sort?.desc ?? false;
  $('sort-dir').textContent = desc ? '↓ descending' : '↑ ascending';
  $('sort-dir').setAttribute('aria-pressed', String(desc));
  $('limit').value = String(state.limit);
  $('view-mechanisms').setAttribute('aria-pressed', String(state.view === 'mechanisms'));
  $('view-grid').setAttribute('aria-pressed', String(state.view === 'grid'));
  // The mechanisms view lists every matching class: no pages.
  $('limit').closest('label').hidden = state.view === 'mechanisms';
  $('pager').hidden = state.view === 'mechanisms';
  $('view-table').setAttribute('aria-pressed', String(state.view === 'table'));
  for (const m of MEASURES) {
    const r = state.ranges.find((x) => x.measure === m.name);
    for (const bound of ['min', 'max']) {
      const el = $(`${bound}-${m.name}`);
      if (el && document.activeElement !== el) el.value = r && r[bound] !== null ? String(r[bound]) : '';
    }
  }
  $('buildable-only').checked = state.ranges.some((r) => r.measure === HAS_SHEET_RANGE.measure);
  $('lead-buildable').checked = state.lead === 'buildable';
  if (state.ranges.some((r) => !MAIN_MEASURES.includes(r.measure) && r.measure !== HAS_SHEET_RANGE.measure)) {
    $('ranges').querySelector('details').open = true;
  }
}

/** Values a long facet list shows until opened; the facets opened by the user. */
const FACET_SHOWN = 8;
const openFacets = new Set();

function renderFacets(facets) {
  const boxes = FACETS.map((f) => {
    const counts = [...(facets[f.name] || [])];
    const selected = state.filters[f.name];
    // One value and nothing ticked: not a filter, a fact about every design shown.
    if (counts.length === 1 && selected.length === 0) {
      return h(
        'p',
        { class: 'facet-fact', testid: `facet-fact-${f.name}` },
        h('span', { class: 'facet-name' }, `${f.label}: `),
        `${facetLabel(f.name, counts[0].value)} (all ${counts[0].count} shown)`,
      );
    }
    for (const text of selected) {
      if (!counts.some((c) => facetText(f.name, c.value) === text)) counts.push({ value: text, count: 0, missing: true });
    }
    const items = counts.map((c) => {
      const text = c.missing ? c.value : facetText(f.name, c.value);
      const toggle = (e) =>
        change(() => {
          const list = state.filters[f.name];
          state.filters[f.name] = e.target.checked ? [...list, text] : list.filter((v) => v !== text);
          state.offset = 0;
        });
      const box = h('input', {
        type: 'checkbox',
        checked: selected.includes(text),
        testid: `facet-${f.name}-${text}`,
        onchange: toggle,
      });
      const label = c.missing ? text : facetLabel(f.name, c.value);
      return h('li', {}, h('label', {}, box, ` ${label} `, h('span', { class: 'count' }, String(c.count))));
    });
    // A long list shows its first FACET_SHOWN values (and any ticked) until it is opened, so
    // the keyboard and a phone reach the results without passing every family.
    const long = items.length > FACET_SHOWN + 1;
    const open = openFacets.has(f.name);
    const shown = long && !open ? items.filter((_, i) => i < FACET_SHOWN || counts[i].missing || selected.includes(facetText(f.name, counts[i].value))) : items;
    const flip = () => {
      if (open) openFacets.delete(f.name);
      else openFacets.add(f.name);
      renderFacets(facets);
      $('facets').querySelector(`[data-testid="facet-more-${f.name}"]`)?.focus();
    };
    const more = long && h('button', { type: 'button', class: 'facet-more', testid: `facet-more-${f.name}`, 'aria-expanded': String(open), onclick: flip }, open ? 'show fewer' : `show all ${items.length}`);
    return h(
      'fieldset',
      { class: 'facet', testid: `facet-${f.name}` },
      h('legend', {}, f.label),
      items.length ? h('ul', {}, shown) : h('p', { class: 'empty' }, 'none'),
      more,
    );
  });
  $('facets').replaceChildren(h('h2', {}, 'Facets'), ...boxes);
}

function renderPage(page) {
  $('total').textContent = String(page.total);
  $('total-label').textContent = page.total === 1 ? 'design' : 'designs';
  $('mechanism-count').textContent = '';
  const pages = Math.max(1, Math.ceil(page.total / state.limit));
  const current = Math.floor(state.offset / state.limit) + 1;
  $('page-info').textContent = `page ${current} of ${pages}`;
  $('prev').disabled = state.offset === 0;
  $('next').disabled = state.offset + state.limit >= page.total;
  const list = $('list');
  if (!page.rows.length) {
    list.replaceChildren(h('p', { class: 'empty' }, 'No design matches these filters.'));
    return;
  }
  // The table keeps its horizontal scroll across a re-render and brings the sorted column
  // into view (a re-render used to scroll back to the left edge, hiding the column just
  // clicked).
  const scrolled = list.querySelector('.table-wrap')?.scrollLeft ?? 0;
  list.replaceChildren(state.view === 'table' ? table(page.rows) : grid(page.rows));
  const wrap = list.querySelector('.table-wrap');
  if (wrap) {
    wrap.scrollLeft = scrolled;
    revealSortedColumn(wrap);
  }
}

/** Scrolls a table sideways so its sorted column is in view beside the sticky spec column,
 * no column left half under it (revealedScroll); the room that needs after the last column is
 * the table's right margin. */
function revealSortedColumn(wrap) {
  const heads = [...wrap.querySelectorAll('thead th')];
  const i = heads.findIndex((th) => th.classList.contains('sorted'));
  const table = wrap.querySelector('table');
  table.style.marginRight = '';
  if (i <= 0) return;
  // The sticky column's offsetLeft moves with the scroll: it starts the table at 0.
  const columns = heads.map((th, k) => ({ left: k ? th.offsetLeft : 0, width: th.offsetWidth }));
  const { scroll, tail } = revealedScroll(columns, i, wrap.clientWidth, wrap.scrollLeft);
  if (tail > 0) table.style.marginRight = `${tail}px`;
  wrap.scrollLeft = scroll;
}

/** A span of values as text: one value, or "lo–hi". */
function spanText(s) {
  if (!s) return '–';
  const minus = (t) => t.replace(/^-/, '−');
  const lo = minus(fmt(s.min));
  const hi = minus(fmt(s.max));
  if (lo === hi) return lo;
  // A dash between negative numbers reads as a minus sign: "−0.65 to −0.004".
  return s.min < 0 ? `${lo} to ${hi}` : `${lo}–${hi}`;
}

/** "IH2, IH3, IH9 +4" for a card's heading. */
function listText(items, shown = 4) {
  const head = items.slice(0, shown).join(', ');
  return items.length > shown ? `${head} +${items.length - shown}` : head;
}

const plural = (n, word) => `${n} ${word}${n === 1 ? '' : 's'}`;

let cardSeq = 0;

/** One mechanism card: counts, ranges over its matching designs, best example, variants. */
function motionCard(g) {
  const best = g.members[0];
  const id = `variants-${++cardSeq}`;
  const unclassified = g.representative === null;
  const cells = g.cells.map((c) => facetLabel('cell', c));
  const title = unclassified
    ? `${plural(g.designs, 'design')} without a computed motion class`
    : `${listText(g.families.map(String))} · ${listText(cells, 3)}`;
  const behaviours = g.behaviours
    .map((b) => `${facetLabel('behaviour', b.value)}${g.behaviours.length > 1 ? ` (${b.count})` : ''}`)
    .join(', ');
  const variants = h(
    'ul',
    { id, class: 'variants', hidden: true, testid: 'card-variants' },
    g.members.map((m) =>
      h(
        'li',
        {},
        h(
          'a',
          { href: designHref(m.spec), testid: 'card-variant', 'data-spec': m.spec, 'data-area': String(m.max_area_ratio) },
          h('img', { src: data.thumbnailUrl(m.spec), alt: '', loading: 'lazy', width: 120, height: 60 }),
          h('code', { class: 'spec' }, m.spec),
          h('span', { class: 'facts' }, `area ${fmt(m.max_area_ratio)} · max ε ${fmt(m.max_expansion)} · ${facetLabel('behaviour', m.behaviour)}`),
        ),
      ),
    ),
  );
  const toggle = h(
    'button',
    {
      type: 'button',
      class: 'expand',
      'aria-expanded': 'false',
      'aria-controls': id,
      testid: 'motion-expand',
      onclick: () => {
        const open = toggle.getAttribute('aria-expanded') !== 'true';
        toggle.setAttribute('aria-expanded', String(open));
        variants.hidden = !open;
        toggle.textContent = open ? `hide the ${plural(g.designs, 'variant')}` : `show the ${plural(g.designs, 'variant')}`;
      },
    },
    `show the ${plural(g.designs, 'variant')}`,
  );
  return h(
    'li',
    {
      class: `motion-card${unclassified ? ' unclassified' : ''}`,
      testid: 'motion-card',
      'data-representative': g.representative ?? '',
      'data-designs': String(g.designs),
      'data-best': best.spec,
    },
    h(
      'a',
      { class: 'card', href: designHref(best.spec), testid: 'design-card', 'data-spec': best.spec },
      h('img', { src: data.thumbnailUrl(best.spec), alt: `closed and open state of ${best.spec}`, loading: 'lazy', width: 200, height: 100 }),
      h('span', { class: 'best' }, unclassified ? 'first design' : 'best example', ': ', h('code', {}, best.spec)),
    ),
    h('h3', {}, title),
    h(
      'p',
      { class: 'counts', testid: 'motion-counts' },
      unclassified
        ? 'not one degree of freedom at their shape, saved since the last explore, or classes not computed'
        : `${plural(g.designs, 'design')} · ${plural(g.topologies, 'topology').replace('topologys', 'topologies')} · ${plural(g.families.length, 'family').replace('familys', 'families')} · ${plural(g.cells.length, 'cell')}`,
    ),
    h(
      'dl',
      { class: 'ranges' },
      h('dt', {}, 'area ratio'), h('dd', { testid: 'motion-area' }, spanText(g.max_area_ratio)),
      h('dt', {}, 'max ε'), h('dd', {}, spanText(g.max_expansion)),
      h('dt', {}, 'min ε'), h('dd', {}, spanText(g.min_expansion)),
      h('dt', {}, 'Poisson-like ν'), h('dd', {}, spanText(g.poisson)),
      h('dt', {}, 'behaviour'), h('dd', {}, behaviours),
    ),
    g.designs > 1 ? toggle : null,
    g.designs > 1 ? variants : null,
  );
}

/** The mechanisms view: one card per distinct motion, the unclassified designs last. */
function renderMechanisms(answer) {
  const groups = answer.unclassified ? [...answer.groups, answer.unclassified] : answer.groups;
  $('total').textContent = String(answer.total);
  $('total-label').textContent = answer.total === 1 ? 'design' : 'designs';
  $('mechanism-count').textContent = ` in ${plural(answer.groups.length, 'distinct motion')}${
    answer.unclassified ? ` and ${answer.unclassified.designs} without a motion class` : ''
  }`;
  const list = $('list');
  if (!groups.length) {
    list.replaceChildren(h('p', { class: 'empty' }, 'No design matches these filters.'));
    return;
  }
  const note = answer.computed
    ? []
    : [h('p', { class: 'muted' }, 'This database has no motion classes yet: run `isogami explore` on it once to compute them.')];
  list.replaceChildren(...note, h('ul', { class: 'mechanisms', testid: 'mechanisms' }, groups.map(motionCard)));
}

function grid(rows) {
  return h(
    'ul',
    { class: 'grid' },
    rows.map((r) =>
      h(
        'li',
        {},
        h(
          'a',
          { class: 'card', href: designHref(r.spec), testid: 'design-card', 'data-spec': r.spec },
          h('img', { src: data.thumbnailUrl(r.spec), alt: `closed and open state of ${r.spec}`, loading: 'lazy', width: 200, height: 100 }),
          h('code', { class: 'spec' }, r.spec),
          h(
            'span',
            { class: 'facts' },
            `${facetLabel('behaviour', r.behaviour ?? null)} · max ε ${fmt(r.max_expansion)} · area ${fmt(r.max_area_ratio)}`,
          ),
          sheetBadge(r),
          shapeBadge(r),
        ),
      ),
    ),
  );
}

function table(rows) {
  const columns = tableColumns(MEASURES);
  const head = columns.map(([key, label]) => {
    const active = state.sort?.key === key || (!state.sort && key === 'spec');
    const desc = active && state.sort?.desc;
    return h(
      'th',
      {
        scope: 'col',
        class: active ? 'sorted' : '',
        'aria-sort': active ? (desc ? 'descending' : 'ascending') : 'none',
        title: measureHelp(key) || null,
      },
      h(
        'button',
        {
          type: 'button',
          testid: `sort-${key}`,
          onclick: () =>
            change(() => {
              state.sort = { key, desc: active ? !desc : false };
              state.offset = 0;
            }),
        },
        label,
        active ? (desc ? ' ↓' : ' ↑') : '',
      ),
    );
  });
  const body = rows.map((r) =>
    h(
      'tr',
      { testid: 'design-row', 'data-spec': r.spec },
      columns.map(([key]) => {
        const sorted = state.sort?.key === key ? ' sorted' : '';
        if (key === 'finite_covered') return h('td', { class: `num${sorted}` }, sheetBadge(r, { short: true }));
        if (key === 'spec') return h('td', { class: sorted.trim() }, h('a', { href: designHref(r.spec) }, h('code', {}, specText(r.spec))));
        if (key === 'cell') return h('td', { class: sorted.trim() }, facetLabel('cell', r.cell));
        const v = r[key];
        const num = typeof v === 'number';
        const wraps = key === 'behaviour' || key === 'linkage_signature' ? ' wraps' : '';
        return h('td', { class: `${num ? 'num' : ''}${sorted}${wraps}`.trim() }, num ? fmt(v) : facetLabel(key, v ?? null));
      }),
    ),
  );
  return h('div', { class: 'table-wrap' }, h('table', { class: 'designs' }, h('thead', {}, h('tr', {}, head)), h('tbody', {}, body)));
}

main().catch((e) => showError(e));
