// The catalogue page (index.html): facet filters with disjunctive counts, range filters, a
// scatter of any two measures (hover shows the design, click opens it), a grid or table of
// designs with thumbnails, sorting by any column either way, paging, a spec box, downloads.
// The whole view lives in the URL (history.replaceState). Data comes through data.js, so
// the page is the same over `isogami serve` and over a static site.

import { openData } from './data.js';
import { h, fmt, showNotice, clearNotice, debounce } from './dom.js';
import { createScatter } from './scatter.js';
import {
  FACETS, MEASURES, MAIN_MEASURES, TEXT_SORT_KEYS, facetLabel, facetText, measureLabel,
} from './schema.js';
import {
  PAGE_SIZES, catalogueSearch, designHref, filterParams, parseCatalogueState,
} from './url.js';
import { allRows, catalogueCsv, catalogueJson, dictionaryCsv, download } from './export.js';

const $ = (id) => document.getElementById(id);

const TABLE_COLUMNS = [
  ['spec', 'spec'], ['family', 'family'], ['cell', 'cell'], ['tile_count', 'tiles'],
  ['behaviour', 'behaviour'], ['linkage_signature', 'linkages'], ['end_reason', 'end'],
  ['max_expansion', 'max ε'], ['min_expansion', 'min ε'], ['max_area_ratio', 'area ratio'],
  ['max_tile_rotation', 'max rotation'], ['poisson_min', 'ν min'], ['poisson_max', 'ν max'],
  ['steps', 'steps'], ['kerf', 'kerf'], ['origin', 'origin'],
];

let data;
let state;
let scatter;
let seq = 0;
let lastScatterKey = null;

async function main() {
  data = await openData();
  state = parseCatalogueState(location.search);
  document.body.dataset.mode = data.mode;
  $('mode').textContent = data.mode === 'static' ? 'static site (read-only)' : 'live server';
  setupSpecBox();
  setupToolbar();
  setupRanges();
  scatter = createScatter($('scatter'), {
    onClick: (p) => {
      location.href = designHref(p.spec);
    },
    describe: (p, tip) => {
      tip.replaceChildren(
        h('img', { src: data.thumbnailUrl(p.spec), alt: '', width: 96, height: 48 }),
        h('code', {}, p.spec),
        h('div', {}, `${measureLabel(state.x)}: ${fmt(p.x)}`),
        h('div', {}, `${measureLabel(state.y)}: ${fmt(p.y)}`),
      );
    },
  });
  try {
    const stats = await data.stats();
    $('stats').textContent = `${stats.designs} designs · isogami ${stats.tool_version ?? '?'}`;
  } catch (e) {
    showError(e);
  }
  await refresh();
}

function showError(e) {
  showNotice($('notice'), { message: e.message, hint: e.hint || 'reload the page; if it persists, check the server', kind: e.kind });
}

/** Applies a change of the view: URL, then page, facets and (when needed) the scatter. */
async function refresh() {
  const token = ++seq;
  history.replaceState(null, '', `${location.pathname}${catalogueSearch(state)}`);
  syncControls();
  const scatterKey = `${filterParams(state)}|${state.x}|${state.y}`;
  const wantScatter = scatterKey !== lastScatterKey;
  document.body.classList.add('loading');
  try {
    const [page, facets, points] = await Promise.all([
      data.designs(state),
      data.facets(state),
      wantScatter ? data.scatter(state, state.x, state.y) : null,
    ]);
    if (token !== seq) return;
    if (page.total > 0 && state.offset >= page.total) {
      state.offset = Math.floor((page.total - 1) / state.limit) * state.limit;
      refresh();
      return;
    }
    clearNotice($('notice'));
    renderFacets(facets);
    renderPage(page);
    if (points) {
      lastScatterKey = scatterKey;
      scatter.update(points, measureLabel(state.x), measureLabel(state.y));
      $('scatter-count').textContent = `${points.length} points`;
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
    h('option', { value: '' }, 'default (spec)'),
    ...TEXT_SORT_KEYS.filter((k) => k !== 'spec').concat(['spec']).map((k) => h('option', { value: k }, k.replace(/_/g, ' '))),
    ...MEASURES.map((m) => h('option', { value: m.name }, m.label)),
  );
  $('sort-key').addEventListener('change', () =>
    change(() => {
      const key = $('sort-key').value;
      state.sort = key ? { key, desc: state.sort?.desc ?? false } : null;
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
  $('ranges').replaceChildren(
    h('h2', {}, 'Ranges'),
    ...main,
    h('details', {}, h('summary', {}, 'more measures'), ...more),
  );
}

/** Puts every control in agreement with the state (after a reload or a change). */
function syncControls() {
  $('x').value = state.x;
  $('y').value = state.y;
  $('sort-key').value = state.sort ? state.sort.key : '';
  const desc = state.sort?.desc ?? false;
  $('sort-dir').textContent = desc ? '↓ descending' : '↑ ascending';
  $('sort-dir').setAttribute('aria-pressed', String(desc));
  $('limit').value = String(state.limit);
  $('view-grid').setAttribute('aria-pressed', String(state.view === 'grid'));
  $('view-table').setAttribute('aria-pressed', String(state.view === 'table'));
  for (const m of MEASURES) {
    const r = state.ranges.find((x) => x.measure === m.name);
    for (const bound of ['min', 'max']) {
      const el = $(`${bound}-${m.name}`);
      if (el && document.activeElement !== el) el.value = r && r[bound] !== null ? String(r[bound]) : '';
    }
  }
  if (state.ranges.some((r) => !MAIN_MEASURES.includes(r.measure))) $('ranges').querySelector('details').open = true;
}

function renderFacets(facets) {
  const boxes = FACETS.map((f) => {
    const counts = [...(facets[f.name] || [])];
    const selected = state.filters[f.name];
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
    return h(
      'fieldset',
      { class: 'facet', testid: `facet-${f.name}` },
      h('legend', {}, f.label),
      items.length ? h('ul', {}, items) : h('p', { class: 'empty' }, 'none'),
    );
  });
  $('facets').replaceChildren(h('h2', {}, 'Facets'), ...boxes);
}

function renderPage(page) {
  $('total').textContent = String(page.total);
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
  list.replaceChildren(state.view === 'table' ? table(page.rows) : grid(page.rows));
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
        ),
      ),
    ),
  );
}

function table(rows) {
  const head = TABLE_COLUMNS.map(([key, label]) => {
    const active = state.sort?.key === key || (!state.sort && key === 'spec');
    const desc = active && state.sort?.desc;
    return h(
      'th',
      { scope: 'col', 'aria-sort': active ? (desc ? 'descending' : 'ascending') : 'none' },
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
      TABLE_COLUMNS.map(([key]) => {
        if (key === 'spec') return h('td', {}, h('a', { href: designHref(r.spec) }, h('code', {}, r.spec)));
        if (key === 'cell') return h('td', {}, facetLabel('cell', r.cell));
        const v = r[key];
        return h('td', { class: typeof v === 'number' ? 'num' : '' }, typeof v === 'number' ? fmt(v) : facetLabel(key, v ?? null));
      }),
    ),
  );
  return h('div', { class: 'table-wrap' }, h('table', { class: 'designs' }, h('thead', {}, h('tr', {}, head)), h('tbody', {}, body)));
}

main().catch((e) => showError(e));
