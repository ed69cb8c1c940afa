// What the design page's "Export / make it" panel asks for, as data: the query of
// GET /api/export, the equivalent `isogami export …` command line, the file name the server
// gives the download (also the CLI's --out) and the name in a Content-Disposition header.
// Pure functions over a form state and the export catalogue (GET /api/export/formats, or a
// static site's data/site.json `export`); export-panel.js draws the form.
//
// The state is sent only for formats whose files change with it (the catalogue's `uses_state`:
// a laser cuts the flat sheet, so SVG and DXF are always the closed state). `patchProblem`
// checks rows × columns against the catalogue's limits before any request.
//
// Form state: { spec, kerf, format, rows, cols, sheet: 'completed'|'raw', scale: 'edge'|'width',
// mm, state: 'closed'|'current'|'open', t, settings: {group: {key: text}} } where `settings` holds only
// the fields the user set (an empty field means the library's default, or the preset's
// value). Values are kept per group: two groups may share a key (a hinge width for laser
// sheets and for printed sheets) and only the groups of the chosen format are sent. The sheet
// is the rows × columns rectangle's completion to one degree of freedom (the default of the
// server and of `isogami export`) unless `sheet` is 'raw' (`raw=true`, `--raw`).

import { slug } from './schema.js';

/** The format named `name` in the catalogue. */
export function formatOf(catalog, name) {
  return catalog.formats.find((f) => f.name === name) ?? catalog.formats[0];
}

/** Whether `format`'s files change with the state (t, open); a catalogue without the flag
 * (an older static site) is taken to say yes. */
export function usesState(catalog, format) {
  return formatOf(catalog, format).uses_state !== false;
}

/** What is wrong with the form's rows × columns for the server, before any request: `null`, or
 * `{field: 'rows'|'cols'|'patch', message}`. Each must be a whole number from 1 to the
 * catalogue's `limits.max_patch` (the library's limit, the command line's too), and the
 * rectangle of a `cellTiles`-tile cell at most `limits.max_tiles` tiles (the server's limit
 * only: `serverOnly` is then true, since `isogami export` makes the file). */
export function patchProblem(form, catalog, cellTiles) {
  const max = catalog.limits.max_patch;
  for (const [field, word] of [['rows', 'rows'], ['cols', 'columns']]) {
    const v = form[field];
    if (!Number.isInteger(v) || v < 1 || v > max) {
      return { field, message: `${word}: a whole number from 1 to ${max}`, serverOnly: false };
    }
  }
  const cap = catalog.limits.max_tiles;
  const tiles = form.rows * form.cols * (cellTiles || 0);
  if (cap && tiles > cap) {
    return {
      field: 'patch',
      message: `${form.rows} × ${form.cols} cells of ${cellTiles} tiles is ${tiles} tiles: the server exports at most ${cap}; export a smaller patch, or run the command below (no limit)`,
      serverOnly: true,
    };
  }
  return null;
}

/** The settings groups `format` uses, in catalogue order. */
export function groupsOf(catalog, format) {
  const used = new Set(formatOf(catalog, format).settings);
  return catalog.settings.filter((g) => used.has(g.name));
}

/** The settings fields of every group `format` uses, in catalogue order. */
export function fieldsOf(catalog, format) {
  return groupsOf(catalog, format).flatMap((g) => g.fields);
}

/** t with at most three decimals (the slider's step). */
function tText(t) {
  return String(Number(Number(t).toFixed(3)));
}

/** The request as ordered [key, value] pairs: the keys of GET /api/export, which are the CLI's
 * flags with underscores. Defaults that change nothing (the kerf, unset settings) are left
 * out. */
export function exportPairs(form, catalog) {
  const pairs = [
    ['design', form.spec],
    ['format', form.format],
    ['patch', `${form.rows}x${form.cols}`],
    [form.scale === 'width' ? 'width_mm' : 'edge_mm', String(form.mm)],
  ];
  if (usesState(catalog, form.format)) {
    pairs.push(['t', form.state === 'open' ? 'open' : form.state === 'current' ? tText(form.t) : '0']);
  }
  if (form.sheet === 'raw') pairs.push(['raw', 'true']);
  const kerf = Number(form.kerf);
  if (form.kerf !== null && form.kerf !== undefined && Math.abs(kerf - catalog.defaults.kerf) > 1e-12) {
    pairs.push(['kerf', String(kerf)]);
  }
  const seen = new Set();
  for (const group of groupsOf(catalog, form.format)) {
    for (const field of group.fields) {
      const value = form.settings?.[group.name]?.[field.name];
      if (value === undefined || value === null || value === '' || seen.has(field.name)) continue;
      if (field.kind === 'flag') {
        if (value === field.default) continue;
        pairs.push([field.name, String(value)]);
      } else pairs.push([field.name, String(value).trim()]);
      seen.add(field.name);
    }
  }
  return pairs;
}

/** The query string of GET /api/export. */
export function exportParams(form, catalog) {
  return new URLSearchParams(exportPairs(form, catalog));
}

/** The download's file name, as the server gives it: `<slug>-<R>x<C>.<ext>`, a folder format
 * as `….<format>.zip`. */
export function exportFileName(spec, rows, cols, format) {
  const stem = `${slug(spec)}-${rows}x${cols}`;
  return format.extension ? `${stem}.${format.extension}` : `${stem}.${format.name}.zip`;
}

/** Where the CLI writes: the same file name, or for a folder format a folder named like the
 * zip without `.zip`. */
export function cliOut(spec, rows, cols, format) {
  return exportFileName(spec, rows, cols, format).replace(/\.zip$/, '');
}

/** A word for a POSIX shell: bare when it is safe, otherwise in single quotes. */
export function shellWord(text) {
  const s = String(text);
  if (/^[A-Za-z0-9_.,:/=+@%~-]+$/.test(s) && !/^[-~]/.test(s)) return s;
  return `'${s.replace(/'/g, `'\\''`)}'`;
}

/** The `isogami export …` command that writes the same file. */
export function cliCommand(form, catalog) {
  const format = formatOf(catalog, form.format);
  const words = ['isogami', 'export'];
  const flags = new Map(catalog.settings.flatMap((g) => g.fields).map((f) => [f.name, f]));
  for (const [key, value] of exportPairs(form, catalog)) {
    const flag = `--${key.replace(/_/g, '-')}`;
    if (flags.get(key)?.kind === 'flag' || key === 'raw') {
      if (value === 'true') words.push(flag);
      continue;
    }
    words.push(flag, key === 'design' ? shellWordAlways(value) : shellWord(value));
  }
  words.push('--out', shellWord(cliOut(form.spec, form.rows, form.cols, format)));
  return words.join(' ');
}

/** A design in single quotes even when it would be safe bare (it is the one long word). */
function shellWordAlways(text) {
  return `'${String(text).replace(/'/g, `'\\''`)}'`;
}

/** The file name of a Content-Disposition header (`attachment; filename="x.svg"`), or null. */
export function attachmentName(header) {
  const m = /filename\s*=\s*(?:"([^"]*)"|([^;\s]+))/i.exec(header || '');
  if (!m) return null;
  const name = (m[1] ?? m[2]).replace(/[\\/]/g, '_');
  return name || null;
}
