// Files the pages offer for download, built in the browser: the filtered catalogue as CSV
// and JSON (every row, fetched page by page, with the data dictionary, tool version and
// settings), the dictionary as CSV, a design's trajectory as JSON and as CSV (one row per
// frame per tile), and an SVG of the current frame drawn from the same geometry as the
// canvas. The text builders are pure; `download` alone touches the DOM.

import { linkageColour, patchLinkages, patchPins, patchPolygons, tileColours } from './patch.js';
import { cellText } from './schema.js';

/** One CSV field (RFC 4180 quoting). */
export function csvField(v) {
  if (v === null || v === undefined) return '';
  const s = typeof v === 'number' ? String(v) : String(v);
  return /[",\n\r]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
}

export function csvLine(values) {
  return values.map(csvField).join(',');
}

/** Columns of the catalogue CSV: every DesignSummary field, `cell` as "AxB" and `params` spread
 * into v0…v5. */
export function catalogueColumns(dictionary) {
  const cols = [];
  for (const d of dictionary) {
    if (d.field === 'params') {
      for (let k = 0; k < 6; k += 1) cols.push(`v${k}`);
    } else cols.push(d.field);
  }
  return cols;
}

function cellValue(row, column) {
  if (/^v[0-5]$/.test(column)) return row.params?.[Number(column.slice(1))];
  if (column === 'cell') return cellText(row.cell);
  const v = row[column];
  if (Array.isArray(v)) return v.join(';');
  if (v !== null && typeof v === 'object') return JSON.stringify(v);
  return v;
}

/** The catalogue as CSV: a header line of column names, then one line per design. */
export function catalogueCsv(rows, dictionary) {
  const cols = catalogueColumns(dictionary);
  return `${[csvLine(cols), ...rows.map((r) => csvLine(cols.map((c) => cellValue(r, c))))].join('\n')}\n`;
}

/** The dictionary of the CSV's columns (field, type, unit, meaning), v0…v5 included. */
export function dictionaryCsv(dictionary) {
  const lines = [csvLine(['field', 'type', 'unit', 'meaning'])];
  for (const d of dictionary) {
    if (d.field === 'params') {
      for (let k = 0; k < 6; k += 1) {
        lines.push(csvLine([`v${k}`, 'number', d.unit, `shape parameter v${k} (empty when the family has fewer); ${d.meaning}`]));
      }
    } else if (d.field === 'cell') {
      lines.push(csvLine([d.field, 'text AxB', d.unit, d.meaning]));
    } else lines.push(csvLine([d.field, d.type, d.unit, d.meaning]));
  }
  return `${lines.join('\n')}\n`;
}

/** The catalogue as JSON: provenance, the query, the dictionary and every filtered design. */
export function catalogueJson(rows, { stats, dictionary, query }) {
  return JSON.stringify(
    {
      tool_version: stats.tool_version ?? null,
      settings: stats.settings ?? null,
      exported: new Date().toISOString(),
      query,
      total: rows.length,
      dictionary,
      designs: rows,
    },
    null,
    1,
  );
}

/** Every row of a filtered catalogue, paging through `fetchPage(offset, limit)`. */
export async function allRows(fetchPage, pageSize = 500) {
  const rows = [];
  let total = Infinity;
  while (rows.length < total) {
    const page = await fetchPage(rows.length, pageSize);
    total = page.total;
    if (!page.rows.length) break;
    rows.push(...page.rows);
  }
  return rows;
}

const TRAJ_COLUMNS = [
  'frame', 'step', 't', 'tile', 'x', 'y', 'theta', 'tile_rotation',
  'u_x', 'u_y', 'w_x', 'w_y', 'F11', 'F12', 'F21', 'F22',
  'min_expansion', 'max_expansion', 'area_ratio', 'lattice_rotation',
];

/** A trajectory as CSV: one row per frame per tile (tiling units, radians). */
export function trajectoryCsv(report) {
  const lines = [csvLine(TRAJ_COLUMNS)];
  report.frames.forEach((f, k) => {
    const m = f.measures;
    f.tiles.forEach((p, i) => {
      lines.push(
        csvLine([
          k, f.step, f.t, i, p.x, p.y, p.theta, m.tile_rotations[i],
          f.u[0], f.u[1], f.w[0], f.w[1], f.F[0][0], f.F[0][1], f.F[1][0], f.F[1][1],
          m.min_expansion, m.max_expansion, m.area_ratio, m.lattice_rotation,
        ]),
      );
    });
  });
  return `${lines.join('\n')}\n`;
}

const num = (v) => Number(v.toFixed(6));

/** SVG of the patch in `frame` (tiling units, y up), as drawn on the canvas: tiles, pins and,
 * with `links`, the linkage loops through their joints in their colours over a white halo. */
export function frameSvg(view, frame, { rows, cols, colour, bounds, links = false }) {
  const [x0, y0, x1, y1] = bounds;
  const pad = 0.02 * Math.max(x1 - x0, y1 - y0);
  const w = x1 - x0 + 2 * pad;
  const h = y1 - y0 + 2 * pad;
  const fill = tileColours(view, frame, colour);
  const stroke = num(0.004 * Math.max(w, h));
  const polys = patchPolygons(view, frame, rows, cols).map(
    (p) =>
      `<polygon data-tile="${p.tile}" data-cell="${p.cell.join(',')}" fill="${fill(p.tile)}" points="${p.points
        .map(([x, y]) => `${num(x)},${num(y)}`)
        .join(' ')}"/>`,
  );
  const loopPoints = (l) => l.points.map(([x, y]) => `${num(x)},${num(y)}`).join(' ');
  const loops = links ? patchLinkages(view, frame, rows, cols) : [];
  const halo = loops.map((l) => `<polygon points="${loopPoints(l)}"/>`);
  const strokes = loops.map(
    (l) => `<polygon data-linkage="${l.index}" data-cell="${l.cell.join(',')}" stroke="${linkageColour(l.index)}" points="${loopPoints(l)}"/>`,
  );
  const pins = patchPins(view, frame, rows, cols).map(
    ([x, y]) => `<circle cx="${num(x)}" cy="${num(y)}" r="${num(stroke * 1.5)}"/>`,
  );
  return [
    `<svg xmlns="http://www.w3.org/2000/svg" viewBox="${num(x0 - pad)} ${num(-y1 - pad)} ${num(w)} ${num(h)}" width="800" height="${Math.round((800 * h) / w)}">`,
    `<desc>isogami ${escapeXml(view.spec)} at t=${num(frame.t)}, ${rows}x${cols} cells, tiling units</desc>`,
    `<g transform="scale(1,-1)">`,
    `<g stroke="#333" stroke-width="${stroke}" stroke-linejoin="round">`,
    ...polys,
    '</g>',
    ...(loops.length
      ? [
          `<g fill="none" stroke="#fff" stroke-width="${num(stroke * 3)}" stroke-linejoin="round">`,
          ...halo,
          '</g>',
          `<g fill="none" stroke-width="${num(stroke * 1.5)}" stroke-linejoin="round" data-testid="linkage-loops">`,
          ...strokes,
          '</g>',
        ]
      : []),
    `<g fill="#222">`,
    ...pins,
    '</g></g></svg>',
  ].join('\n');
}

function escapeXml(s) {
  return String(s).replace(/[<>&"]/g, (c) => ({ '<': '&lt;', '>': '&gt;', '&': '&amp;', '"': '&quot;' })[c]);
}

/** A file name made of a spec string. */
export function fileStem(spec) {
  return spec.replace(/[^A-Za-z0-9.-]+/g, '_');
}

/** Offers `text` as a file. */
export function download(name, text, type) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}
