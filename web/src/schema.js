// The catalogue's vocabulary, shared by every page: facets, measures and sort keys with the
// names the JSON API uses, how a facet value of a DesignSummary row is read and written as
// URL text, and how a measure is read from a row. Pure data and functions, no DOM.

/** Facets: `name` as in /api/facets, `param` as in the query string. */
export const FACETS = [
  { name: 'family', param: 'family', label: 'Family' },
  { name: 'cell', param: 'cell', label: 'Cell' },
  { name: 'tile_count', param: 'tiles', label: 'Tiles in cell' },
  { name: 'behaviour', param: 'behaviour', label: 'Behaviour' },
  { name: 'linkage_signature', param: 'linkage', label: 'Linkages' },
  { name: 'end_reason', param: 'end', label: 'End reason' },
  { name: 'origin', param: 'origin', label: 'Origin' },
];

/** Labels of the measures this page knows by name; a measure the server adds later gets its
 * name as label and its dictionary meaning as help (setMeasures). */
const KNOWN = {
  max_expansion: { label: 'max expansion', short: 'max ε' },
  min_expansion: { label: 'min expansion', short: 'min ε' },
  max_area_ratio: { label: 'max area ratio', short: 'area' },
  max_tile_rotation: { label: 'max tile rotation (rad)', short: 'rot' },
  poisson_min: { label: 'Poisson-like ratio min', short: 'ν min' },
  poisson_max: { label: 'Poisson-like ratio max', short: 'ν max' },
  steps: { label: 'steps', short: 'steps' },
  tile_count: { label: 'tiles in cell', short: 'tiles' },
  kerf: { label: 'kerf (× edge length)', short: 'kerf' },
  finite_raw_dof: { label: 'raw 6×6 sheet DOF', short: 'raw DOF' },
  finite_covered: { label: 'one-DOF sheet: fraction kept', short: 'one-DOF sheet' },
  ...Object.fromEntries([0, 1, 2, 3, 4, 5].map((k) => [`v${k}`, { label: `shape parameter v${k}`, short: `v${k}` }])),
};

/** A measure of the list GET /api/measures (or a static site's `measures`) as the pages use it:
 * `{name, label, short, help, unit}`. */
export function measureEntry(doc) {
  const known = KNOWN[doc.name];
  return {
    name: doc.name,
    label: known?.label ?? doc.name.replace(/_/g, ' '),
    short: known?.short ?? doc.name.replace(/_/g, ' '),
    help: doc.meaning ?? '',
    unit: doc.unit ?? '',
  };
}

/** Numeric columns: range filters, sort keys, scatter axes and table columns. The list is the
 * server's (setMeasures, from GET /api/measures or a static site's data/site.json); until then,
 * and where neither has one, the measures this page knows. */
export const MEASURES = Object.keys(KNOWN).map((name) => measureEntry({ name }));

/** The measures offered as scatter axes and in the main range filters. */
export const MAIN_MEASURES = MEASURES.slice(0, 7).map((m) => m.name);

export const MEASURE_NAMES = new Set(MEASURES.map((m) => m.name));

/** Sort keys that are not measures. */
export const TEXT_SORT_KEYS = ['spec', 'family', 'cell', 'behaviour', 'linkage_signature', 'end_reason', 'origin'];

export const SORT_KEYS = new Set([...TEXT_SORT_KEYS, ...MEASURE_NAMES]);

/** Replaces the measures (in place: every importer sees the new list) with the server's list
 * `docs` ([{name, type, unit, meaning}]); an empty or missing list keeps the current one.
 * Call it before reading a URL, so that a range on a measure the server added is kept. */
export function setMeasures(docs) {
  if (!Array.isArray(docs) || !docs.length) return;
  const entries = docs.filter((d) => d && typeof d.name === 'string').map(measureEntry);
  if (!entries.length) return;
  MEASURES.splice(0, MEASURES.length, ...entries);
  MEASURE_NAMES.clear();
  for (const m of entries) MEASURE_NAMES.add(m.name);
  SORT_KEYS.clear();
  for (const k of [...TEXT_SORT_KEYS, ...MEASURE_NAMES]) SORT_KEYS.add(k);
}

export function measureLabel(name) {
  const m = MEASURES.find((x) => x.name === name);
  return m ? m.label : name;
}

/** The dictionary's meaning of a measure ('' when none is known). */
export function measureHelp(name) {
  return MEASURES.find((x) => x.name === name)?.help ?? '';
}

/** The value of measure `name` of a DesignSummary row, or null when the row lacks it. */
export function measureOf(row, name) {
  if (/^v[0-5]$/.test(name)) {
    const v = row.params[Number(name.slice(1))];
    return v === undefined ? null : v;
  }
  const v = row[name];
  return v === undefined ? null : v;
}

/** The value of facet `name` of a row, as the API serialises it. */
export function facetOf(row, name) {
  const v = row[name];
  return v === undefined ? null : v;
}

/** A facet value (as the API serialises it) as URL text. */
export function facetText(name, value) {
  if (name === 'cell' && Array.isArray(value)) return `${value[0]}x${value[1]}`;
  if (value === null) return 'none';
  return String(value);
}

/** A facet value as shown to a reader. */
export function facetLabel(name, value) {
  if (value === null) return name === 'behaviour' ? 'unclassified' : 'none';
  if (name === 'cell') return facetText(name, value).replace('x', '×');
  if (name === 'behaviour' || name === 'end_reason') return String(value).replace(/_/g, ' ');
  return String(value);
}

/** Does a row's facet value match the URL text `text`? */
export function facetMatches(name, value, text) {
  if (name === 'behaviour' && text === 'none') return value === null;
  if (value === null) return false;
  return facetText(name, value) === text;
}

/** slug(spec): the file name stem of a design in a static site, `:` as `_`, `,` as `~` and any
 * other character outside [A-Za-z0-9.-] as `_` (crates/isogami-web's `slug` does the same). */
export function slug(spec) {
  return spec.replace(/[^A-Za-z0-9.-]/g, (c) => (c === ',' ? '~' : '_'));
}

/** The cell of a spec string or summary, as "AxB". */
export function cellText(cell) {
  return `${cell[0]}x${cell[1]}`;
}
