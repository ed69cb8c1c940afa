// View state ↔ URL. The catalogue's query string is the API's query string (filters, ranges,
// sort, limit, offset) plus the page's own keys (scatter axes and colour, grid/table view), so a shared
// link restores the view and the same text queries the API; the default sort (largest area
// ratio first) and view (mechanisms: one card per distinct motion) are left out of it. The
// catalogue remembers its query string in the tab's sessionStorage, so that the design page's
// "back to the catalogue" returns to the same filters, sort and view. The design page keeps its spec,
// patch size, kerf, colouring and t. Pure functions over URLSearchParams, no DOM.

import { FACETS, MEASURE_NAMES, SORT_KEYS } from './schema.js';

export const DEFAULT_LIMIT = 50;
export const PAGE_SIZES = [10, 25, 50, 100, 200];
export const DEFAULT_X = 'max_expansion';
export const DEFAULT_Y = 'max_area_ratio';
/** The catalogue's default order: largest area ratio first (the API's own default is spec). */
export const DEFAULT_SORT = Object.freeze({ key: 'max_area_ratio', desc: true });
/** The catalogue's views: one card per distinct motion (default), design grid, design table. */
export const VIEWS = ['mechanisms', 'grid', 'table'];

/** The empty catalogue view. */
export function emptyCatalogueState() {
  return {
    filters: Object.fromEntries(FACETS.map((f) => [f.name, []])),
    ranges: [],
    sort: { ...DEFAULT_SORT },
    // Buildable designs first (the API's lead=buildable), each part in the sort's order.
    lead: 'buildable',
    limit: DEFAULT_LIMIT,
    offset: 0,
    x: DEFAULT_X,
    y: DEFAULT_Y,
    view: 'mechanisms',
    colour: 'behaviour',
  };
}

function parseBound(text) {
  if (text === undefined || text.trim() === '') return null;
  const v = Number(text);
  return Number.isFinite(v) ? v : undefined;
}

/** Reads a catalogue view from a query string; unknown or malformed entries are dropped. */
export function parseCatalogueState(search) {
  const p = new URLSearchParams(search);
  const s = emptyCatalogueState();
  for (const f of FACETS) {
    s.filters[f.name] = [...new Set(p.getAll(f.param).filter((v) => v !== ''))];
  }
  for (const r of p.getAll('range')) {
    const [measure, lo, hi] = r.split(':');
    const min = parseBound(lo);
    const max = parseBound(hi);
    if (MEASURE_NAMES.has(measure) && min !== undefined && max !== undefined && (min !== null || max !== null)) {
      s.ranges = s.ranges.filter((x) => x.measure !== measure);
      s.ranges.push({ measure, min, max });
    }
  }
  const sort = p.get('sort');
  if (sort) {
    const desc = sort.startsWith('-');
    const key = desc ? sort.slice(1) : sort;
    if (SORT_KEYS.has(key)) s.sort = { key, desc };
  }
  if (p.get('lead') === 'all') s.lead = 'all';
  const limit = Number(p.get('limit'));
  if (Number.isInteger(limit) && limit >= 1 && limit <= 500) s.limit = limit;
  const offset = Number(p.get('offset'));
  if (Number.isInteger(offset) && offset >= 0) s.offset = offset;
  if (MEASURE_NAMES.has(p.get('x'))) s.x = p.get('x');
  if (MEASURE_NAMES.has(p.get('y'))) s.y = p.get('y');
  if (VIEWS.includes(p.get('view'))) s.view = p.get('view');
  if (p.get('colour') === 'family') s.colour = 'family';
  return s;
}

/** The filter part of the query string (what /api/facets and /api/scatter take). */
export function filterParams(state) {
  const p = new URLSearchParams();
  for (const f of FACETS) {
    for (const v of state.filters[f.name]) p.append(f.param, v);
  }
  for (const r of state.ranges) {
    p.append('range', `${r.measure}:${r.min ?? ''}:${r.max ?? ''}`);
  }
  return p;
}

/** The order part of the query string: sort and lead (what /api/designs and /api/motions take). */
export function orderParams(state, p = new URLSearchParams()) {
  if (state.sort) p.set('sort', `${state.sort.desc ? '-' : ''}${state.sort.key}`);
  if (state.lead === 'buildable') p.set('lead', 'buildable');
  return p;
}

/** The query string of /api/designs: filters, sort and page. */
export function pageParams(state) {
  const p = orderParams(state, filterParams(state));
  p.set('limit', String(state.limit));
  p.set('offset', String(state.offset));
  return p;
}

/** The page's query string: the API's plus the view's own keys (defaults left out). */
export function catalogueSearch(state) {
  const p = filterParams(state);
  const sort = state.sort ?? { key: 'spec', desc: false };
  if (sort.key !== DEFAULT_SORT.key || sort.desc !== DEFAULT_SORT.desc) {
    p.set('sort', `${sort.desc ? '-' : ''}${sort.key}`);
  }
  if (state.lead === 'all') p.set('lead', 'all');
  if (state.limit !== DEFAULT_LIMIT) p.set('limit', String(state.limit));
  if (state.offset) p.set('offset', String(state.offset));
  if (state.x !== DEFAULT_X) p.set('x', state.x);
  if (state.y !== DEFAULT_Y) p.set('y', state.y);
  if (state.view !== 'mechanisms') p.set('view', state.view);
  if (state.colour === 'family') p.set('colour', 'family');
  const text = p.toString();
  return text ? `?${text}` : '';
}

export const DESIGN_DEFAULTS = { rows: 4, cols: 4, colour: 'linkage', t: 0, cell: false, links: true };

/** Reads the design page's view: spec, patch rows × columns, kerf, colouring, t. */
export function parseDesignState(search) {
  const p = new URLSearchParams(search);
  const int18 = (v, d) => {
    const n = Number(v);
    return Number.isInteger(n) && n >= 1 && n <= 8 ? n : d;
  };
  const t = Number(p.get('t'));
  const kerf = p.get('kerf') === null ? null : Number(p.get('kerf'));
  return {
    spec: (p.get('spec') || '').trim(),
    rows: int18(p.get('R'), DESIGN_DEFAULTS.rows),
    cols: int18(p.get('C'), DESIGN_DEFAULTS.cols),
    kerf: kerf !== null && Number.isFinite(kerf) && kerf > 0 ? kerf : null,
    colour: p.get('colour') === 'rotation' ? 'rotation' : 'linkage',
    t: Number.isFinite(t) && t >= 0 && t <= 1 ? t : 0,
    cell: p.get('cell') === '1',
    links: p.get('links') !== '0',
  };
}

/** The design page's query string. */
export function designSearch(s) {
  const p = new URLSearchParams();
  p.set('spec', s.spec);
  if (s.rows !== DESIGN_DEFAULTS.rows) p.set('R', String(s.rows));
  if (s.cols !== DESIGN_DEFAULTS.cols) p.set('C', String(s.cols));
  if (s.kerf !== null && s.kerf !== undefined) p.set('kerf', String(s.kerf));
  if (s.colour !== DESIGN_DEFAULTS.colour) p.set('colour', s.colour);
  if (s.t) p.set('t', String(Math.round(s.t * 1000) / 1000));
  if (s.cell) p.set('cell', '1');
  if (!s.links) p.set('links', '0');
  return `?${p.toString()}`;
}

/** Relative link to a design page. */
export function designHref(spec, extra = {}) {
  return `./design.html${designSearch({ ...DESIGN_DEFAULTS, kerf: null, ...extra, spec })}`;
}

const CATALOGUE_KEY = 'isogami.catalogue';

/** The tab's sessionStorage, or null where the browser refuses it (or outside a browser). */
function tabStorage() {
  try {
    return globalThis.sessionStorage ?? null;
  } catch {
    return null;
  }
}

/** Remembers the catalogue's query string (`storage`: the tab's sessionStorage by default). */
export function rememberCatalogue(search, storage = tabStorage()) {
  try {
    storage?.setItem(CATALOGUE_KEY, search);
  } catch {
    // Storage refused (private mode, quota): the back link then opens the default view.
  }
}

/** The link back to the catalogue with the query string it last had in this tab. */
export function catalogueHref(storage = tabStorage()) {
  let search = '';
  try {
    search = storage?.getItem(CATALOGUE_KEY) ?? '';
  } catch {
    search = '';
  }
  return `./index.html${search.startsWith('?') ? search : ''}`;
}
