// What the graded-sheet page asks for and shows, as data: the form checked against the
// server's caps, the outline's text (disc, ellipse, or a polygon drawn point by point), a
// star-shaped check of a drawn polygon (the library's rule, for a static site and instant
// feedback; the server answers with the library's own message), the body of POST /api/graded
// and the equivalent `isogami graded …` command, the tiles of a graded sheet placed from the
// poses of a state, the bounds that frame them, and the report's lines; of a finished run, the
// library's verdict as it gives it (its one line, whether the sheet opens — `verdict.opens`, or
// `path.reached` in a file written before the verdict —), the outline's fit figures, the worst
// boundary point and the deepest overlap the drawing marks (which state, which tiles, how deep in
// mm at the verdict's nominal edge). Pure functions over plain data; graded.js draws the page.
//
// Form state: { design, rows, cols, outline: 'disc' | 'ellipse' | 'polygon' | 'field' | 'svg',
// aspect, points: [[x, y], …] (the drawn polygon, y up), from, to, degrees (a field target: the
// area ratio at the two ends of a ramp and its direction), svg: { name, text } | null (an
// uploaded SVG file; `text` null when restored from a job, which names it only), iterations,
// states, t (the last two '' for the defaults: the page has no fields for them, but a job
// restored from the server may have other values), tolerance ('' for the library's default),
// fallBack (false: `--no-fallback`) } where numbers are the text of their fields.

import { shellWord } from './export-request.js';

/** Defaults when the server gives none (a static site). */
export const DEFAULTS = Object.freeze({
  design: 'rotating-squares',
  rows: 3,
  cols: 3,
  outline: 'disc',
  states: 8,
  iterations: 200, // the library's default (graded::SolveSettings)
  tolerance: 0.05, // the library's graded::verdict::OUTLINE_TOLERANCE
  fall_back: true,
});

/** A blank form: the design from `?design=` when given, else the server's default. */
export function emptyForm(settings, search = '') {
  const d = { ...DEFAULTS, ...(settings?.defaults ?? {}) };
  const given = new URLSearchParams(search).get('design');
  return {
    design: given && given.trim() ? given.trim() : d.design,
    rows: String(d.rows),
    cols: String(d.cols),
    outline: 'disc',
    aspect: '1.4',
    points: [],
    from: '1.3',
    to: '1.7',
    degrees: '0',
    svg: null,
    iterations: String(d.iterations),
    states: '',
    t: '',
    tolerance: '',
    fallBack: true,
  };
}

/** The form that started a job, from the request its view echoes (`GET /api/graded/{id}`'s
 * `request`): what a page attaching to a running or finished job shows, so that its command
 * line is the job's. `settings` gives the default number of states (left out of the command
 * when the job used it). An SVG target keeps its name and drawn outline (the file's text stays
 * with the page that chose it). */
export function formFromJob(request, settings) {
  const d = { ...DEFAULTS, ...(settings?.defaults ?? {}) };
  const f = {
    ...emptyForm(settings),
    design: String(request.design ?? d.design),
    rows: String(request.rows),
    cols: String(request.cols),
    iterations: String(request.iterations),
    states: request.states === undefined || request.states === null || request.states === d.states ? '' : String(request.states),
    t: request.t === undefined || request.t === null ? '' : String(request.t),
    tolerance: request.tolerance === undefined || request.tolerance === null ? '' : String(request.tolerance),
    fallBack: request.fall_back !== false,
  };
  const text = String(request.outline ?? 'disc').trim();
  const [kind, rest = ''] = text.split(/:(.*)/s);
  const numbers = rest.split(',').map((v) => v.trim());
  if (text.startsWith('@')) {
    f.outline = 'svg';
    f.svg = { name: text.slice(1), text: null, points: request.outline_points ?? null };
  } else if (kind === 'ellipse' && numbers.length === 2) {
    const [a, b] = numbers.map(Number);
    f.outline = 'ellipse';
    f.aspect = b === 1 ? numbers[0] : num(a / b);
  } else if (kind === 'polygon') {
    const corners = parseCorners(rest.replace(/;/g, '; '));
    if (!corners.error) {
      f.outline = 'polygon';
      f.points = corners.points;
    }
  } else if (kind === 'field' && numbers.length >= 2) {
    f.outline = 'field';
    [f.from, f.to] = numbers;
    f.degrees = numbers[2] ?? '0';
  }
  return f;
}

/** The corners of a polygon as the page's text field shows them: `x,y; x,y; …` (y up). */
export function cornersText(points) {
  return points.map(([x, y]) => `${num(x)},${num(y)}`).join('; ');
}

/** The corners typed in the text field (`x,y; x,y; …`, a trailing `;` allowed): `{ points }`,
 * or `{ error }` naming the first corner that is not two numbers. */
export function parseCorners(text) {
  const parts = String(text ?? '').split(';').map((p) => p.trim());
  if (parts.length && parts.at(-1) === '') parts.pop();
  const points = [];
  for (let k = 0; k < parts.length; k += 1) {
    const xy = parts[k].split(',').map((v) => v.trim());
    const v = xy.map((t) => (t === '' ? NaN : Number(t)));
    if (xy.length !== 2 || !v.every(Number.isFinite)) {
      return { error: `corner ${k + 1}: "${parts[k]}" is not two numbers x,y (corners are x,y; x,y; …)` };
    }
    points.push(v);
  }
  return { points };
}

/** A whole number field's problem, or ''. */
function wholeProblem(name, text, min, cap) {
  const t = String(text ?? '').trim();
  if (t === '') return `${name}: give a whole number`;
  const v = Number(t);
  if (!Number.isInteger(v) || v < min) return `${name} must be a whole number of at least ${min}`;
  if (cap !== undefined && v > cap) return `${name} ${v} is above this server's limit of ${cap}`;
  return '';
}

/** The tolerance field's problem ('' is the library's default), in the library's words, or ''. */
export function toleranceProblem(form) {
  const t = String(form.tolerance ?? '').trim();
  if (t === '') return '';
  const v = Number(t);
  return Number.isFinite(v) && v > 0 ? '' : `tolerance ${t} must be a positive fraction (0.05: 5 %)`;
}

/** The region's problem as one line (checked as typed against the server's caps), or ''. */
export function regionProblem(form, limits = {}) {
  const side = limits.side;
  const rows = wholeProblem('rows', form.rows, 1, side);
  if (rows) return rows;
  const cols = wholeProblem('columns', form.cols, 1, side);
  if (cols) return cols;
  const cells = Number(form.rows) * Number(form.cols);
  if (limits.cells !== undefined && cells > limits.cells) {
    return `a region of ${form.rows}x${form.cols} = ${cells} cells is above this server's limit of ${limits.cells} cells`;
  }
  return '';
}

/** The iterations field's problem, or ''. */
export function iterationsProblem(form, limits = {}) {
  return wholeProblem('iterations', form.iterations, 1, limits.iterations);
}

/** A number for an outline's text: at most 4 decimals, no trailing zeros. */
function num(v) {
  const r = Math.round(v * 1e4) / 1e4;
  return String(Object.is(r, -0) ? 0 : r);
}

/** The target's text as `isogami graded --target` reads it (`@NAME` for an SVG file). */
export function outlineText(form) {
  if (form.outline === 'ellipse') return `ellipse:${String(form.aspect).trim()},1`;
  if (form.outline === 'field') {
    const [from, to, degrees] = [form.from, form.to, form.degrees].map((v) => String(v ?? '').trim());
    return `field:${from},${to}${degrees === '' || Number(degrees) === 0 ? '' : `,${degrees}`}`;
  }
  if (form.outline === 'svg') return `@${form.svg?.name || 'outline.svg'}`;
  if (form.outline === 'polygon') return `polygon:${form.points.map(([x, y]) => `${num(x)},${num(y)}`).join(';')}`;
  return 'disc';
}

/** The ellipse's aspect ratio's problem, or ''. */
export function aspectProblem(form) {
  if (form.outline !== 'ellipse') return '';
  const v = Number(String(form.aspect).trim());
  if (String(form.aspect).trim() === '' || !Number.isFinite(v) || v <= 0) return 'the aspect ratio must be a positive number';
  return '';
}

/** A field target's problem (the library's rule: finite ratios above 1, a finite direction),
 * or ''. */
export function fieldProblem(form) {
  if (form.outline !== 'field') return '';
  const number = (v) => (String(v ?? '').trim() === '' ? NaN : Number(String(v).trim()));
  const [from, to] = [number(form.from), number(form.to)];
  if (!(Number.isFinite(from) && from > 1 && Number.isFinite(to) && to > 1)) {
    return 'the area ratios at the two ends must be numbers above 1 (the sheet opens)';
  }
  const degrees = String(form.degrees ?? '').trim();
  if (degrees !== '' && !Number.isFinite(Number(degrees))) return 'the direction must be an angle in degrees';
  return '';
}

/** An SVG target's problem before the server reads it, or ''. */
export function svgProblem(form) {
  if (form.outline !== 'svg') return '';
  return form.svg ? '' : 'choose an SVG file with one closed shape';
}

/** The signed area of a polygon ([[x, y], …], counter-clockwise positive). */
export function signedArea(p) {
  let a = 0;
  for (let k = 0; k < p.length; k += 1) {
    const [x0, y0] = p[k];
    const [x1, y1] = p[(k + 1) % p.length];
    a += x0 * y1 - x1 * y0;
  }
  return a / 2;
}

/** The area centroid of a polygon. */
export function centroid(p) {
  let a = 0;
  let cx = 0;
  let cy = 0;
  for (let k = 0; k < p.length; k += 1) {
    const [x0, y0] = p[k];
    const [x1, y1] = p[(k + 1) % p.length];
    const w = x0 * y1 - x1 * y0;
    a += w;
    cx += (x0 + x1) * w;
    cy += (y0 + y1) * w;
  }
  return [cx / (3 * a), cy / (3 * a)];
}

function diagonal(p) {
  const xs = p.map((v) => v[0]);
  const ys = p.map((v) => v[1]);
  return Math.hypot(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
}

/** Why a drawn polygon cannot be a target, in the library's words (graded::Outline::validated:
 * at least three points, some area, every edge turning counter-clockwise as seen from the
 * centroid), or '' when it can. The server's answer is the one shown when there is a server. */
export function starProblem(points) {
  if (points.length < 3 || points.some((v) => !v.every(Number.isFinite))) {
    return 'bad target: an outline needs at least three finite points';
  }
  const area = signedArea(points);
  if (Math.abs(area) <= 1e-12 * diagonal(points) ** 2) return 'bad target: the outline encloses no area';
  const p = area < 0 ? [...points].reverse() : points;
  const [cx, cy] = centroid(p);
  const q = p.map(([x, y]) => [x - cx, y - cy]);
  const s = diagonal(q);
  for (let k = 0; k < q.length; k += 1) {
    const [ax, ay] = q[k];
    const [bx, by] = q[(k + 1) % q.length];
    if (ax * by - ay * bx <= 1e-9 * s * s) {
      return `bad target: the outline is not seen whole from its centroid (edge ${k}); give a star-shaped outline`;
    }
  }
  return '';
}

/** The body of POST /api/graded: the target's text, or an SVG file's text and name. */
export function gradedBody(form) {
  const body = {
    design: String(form.design).trim(),
    rows: Number(form.rows),
    cols: Number(form.cols),
  };
  if (form.outline === 'svg') {
    body.svg = form.svg?.text ?? '';
    body.svg_name = form.svg?.name ?? 'outline.svg';
  } else {
    body.target = outlineText(form);
  }
  body.iterations = Number(form.iterations);
  if (String(form.states ?? '').trim() !== '') body.states = Number(form.states);
  if (String(form.t ?? '').trim() !== '') body.t = Number(form.t);
  if (String(form.tolerance ?? '').trim() !== '') body.tolerance = Number(form.tolerance);
  if (form.fallBack === false) body.fall_back = false;
  return body;
}

/** The `isogami graded …` command that grades the same sheet and writes the same file. */
export function cliCommand(form) {
  const b = gradedBody(form);
  return ['isogami', 'graded', '--design', shellWord(b.design), '--region', `${b.rows}x${b.cols}`,
    '--target', shellWord(outlineText(form)), ...(b.t === undefined ? [] : ['--t', String(b.t)]),
    ...(b.states === undefined ? [] : ['--states', String(b.states)]), '--iterations', String(b.iterations),
    ...(b.tolerance === undefined ? [] : ['--tolerance', String(b.tolerance)]), ...(b.fall_back === false ? ['--no-fallback'] : []),
    '--out', 'graded.json'].join(' ');
}

/** The export formats the page offers: laser (closed sheet) and print files. */
export const EXPORTS = Object.freeze([
  { format: 'svg', label: 'Laser SVG' },
  { format: 'dxf', label: 'Laser DXF' },
  { format: 'stl', label: 'Print STL' },
  { format: '3mf', label: 'Print 3MF' },
]);

/** The mean edge length's problem (mm, a positive number), or ''. */
export function edgeProblem(text) {
  const t = String(text ?? '').trim();
  const v = Number(t);
  if (t === '' || !Number.isFinite(v) || v <= 0) return 'the mean edge length must be a positive number of mm';
  return '';
}

/** The query of GET /api/graded/{id}/export (keys named as `isogami export --sheet`'s flags). */
export function exportParams(format, edgeMm) {
  const p = new URLSearchParams({ format });
  const e = String(edgeMm ?? '').trim();
  if (e !== '') p.set('edge_mm', e);
  return p.toString();
}

/** The `isogami export` command that writes the same file from the downloaded sheet. */
export function exportCommand(format, edgeMm, rows, cols) {
  const sheet = `graded-${rows}x${cols}.json`;
  const ext = format === '3mf' ? '3mf' : format;
  const words = ['isogami', 'export', '--sheet', sheet, '--format', format];
  const e = String(edgeMm ?? '').trim();
  if (e !== '') words.push('--edge-mm', shellWord(e));
  words.push('--out', `graded-${rows}x${cols}.${ext}`);
  return words.join(' ');
}

/** A field result's cells as table rows (1-based cell numbers, in the library's order). */
export function fieldRows(result) {
  return (result?.field ?? []).map((c, k) => ({
    cell: k + 1,
    target: c.target,
    ratio: c.ratio,
    error: c.ratio - c.target,
    opened: c.opened,
    closed: c.closed,
  }));
}

/** A colour for a cell's error: white at 0 to red (too open) or blue (too closed) at `scale`. */
export function errorColour(error, scale = 0.05) {
  const f = Math.max(-1, Math.min(1, scale > 0 ? error / scale : 0));
  const k = Math.round(255 * (1 - Math.abs(f)));
  return f >= 0 ? `rgb(255,${k},${k})` : `rgb(${k},${k},255)`;
}

/** Convex hull (monotone chain) of points, counter-clockwise. */
export function convexHull(points) {
  const p = [...points].sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  if (p.length < 3) return p;
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const lower = [];
  for (const v of p) {
    while (lower.length >= 2 && cross(lower.at(-2), lower.at(-1), v) <= 0) lower.pop();
    lower.push(v);
  }
  const upper = [];
  for (const v of [...p].reverse()) {
    while (upper.length >= 2 && cross(upper.at(-2), upper.at(-1), v) <= 0) upper.pop();
    upper.push(v);
  }
  return lower.slice(0, -1).concat(upper.slice(0, -1));
}

/** The outline (points at scale 1, centred) scaled to cover `area`: how the page sizes the
 * target under the sheet while the run goes (the library scales it to the area the start
 * covers; its report gives the fitted outline at the end). */
export function outlineAtArea(points, area) {
  const a = Math.abs(signedArea(points));
  if (!(a > 0) || !(area > 0)) return points;
  const s = Math.sqrt(area / a);
  return points.map(([x, y]) => [s * x, s * y]);
}

/** The area of the convex hull of every corner of `polygons`. */
export function hullArea(polygons) {
  return Math.abs(signedArea(convexHull(polygons.flat())));
}

/** The closed polygon of every tile of a graded sheet (GradedSheet JSON). */
export function closedPolygons(sheet) {
  return sheet.tiles.map((t) => t.nodes.map((n) => [...sheet.nodes[n]]));
}

/** Every tile placed by `poses` (one {x, y, theta} per tile): its closed polygon turned by
 * theta about its first node, that node at (x, y) (GradedSheet::opened_polygon). */
export function posedPolygons(sheet, poses) {
  return sheet.tiles.map((t, i) => {
    const { x, y, theta } = poses[i];
    const c = Math.cos(theta);
    const s = Math.sin(theta);
    const [fx, fy] = sheet.nodes[t.nodes[0]];
    return t.nodes.map((n) => {
      const dx = sheet.nodes[n][0] - fx;
      const dy = sheet.nodes[n][1] - fy;
      return [x + c * dx - s * dy, y + s * dx + c * dy];
    });
  });
}

/** [minX, minY, maxX, maxY] of every point of every list given. */
export function bounds(...lists) {
  let b = [Infinity, Infinity, -Infinity, -Infinity];
  for (const list of lists) {
    for (const poly of list) {
      for (const [x, y] of poly) {
        b = [Math.min(b[0], x), Math.min(b[1], y), Math.max(b[2], x), Math.max(b[3], y)];
      }
    }
  }
  return b;
}

/** The player's states, closed first: slider position k shows `path.states[n - 1 - k]` (the
 * path check lists them from the optimised opened state to the closed one). */
export function playerStates(result) {
  return [...(result?.path?.states ?? [])].reverse();
}

const pct = (v) => `${(100 * v).toFixed(2)} %`;

/** The report in lines: fit, shapes, pins, the path check (DOF per state, overlaps named with
 * their depth). Whether the sheet opens is the library's (`opensOf`); the lines give the
 * figures behind it. */
export function reportLines(result) {
  const r = result.report;
  const p = result.path;
  const lines = [];
  lines.push({
    key: 'fit',
    text: r.max_field_error === null || r.max_field_error === undefined
      ? `Fit: the opened outline is within ${pct(r.max_outline_error)} of the target (median ${pct(r.median_outline_error)}), ${pct(r.max_outside)} outside it at most.`
      : `Fit: the area ratio is within ${r.max_field_error.toFixed(4)} of the field in each of ${r.field_cells} cells (max field error ${r.max_field_error.toFixed(4)}).`,
  });
  lines.push({
    key: 'sheet',
    text: `Sheet: ${r.tiles} tiles, ${result.sheet.joints.length} pins, ${result.sheet.nodes.length} nodes; ${r.iterations} iterations, cost ${fmtCost(r.cost[0])} → ${fmtCost(r.cost[1])} in ${r.seconds.toFixed(1)} s.`,
  });
  lines.push({
    key: 'pins',
    text: `Pins closed to ${r.joint_gap.toExponential(1)} L after the optimisation; smallest angle ${r.min_angle_degrees.toFixed(1)}°, corners keep ≥ ${(100 * r.min_corner_fraction).toFixed(0)} % of their sine, edges ≥ ${(100 * r.min_edge_fraction).toFixed(0)} % of their length, tiles ≥ ${(100 * r.min_area_fraction).toFixed(0)} % of their area.`,
  });
  // The library's own measures travel with its check: the gap under which a pin is closed,
  // the opening from which a state must have one DOF (the closed tiling is singular).
  const tolerance = p.pin_tolerance;
  const counted = p.states.filter((s) => s.opening > 0 && s.opening >= (p.dof_from_opening ?? 0));
  const dofs = counted.map((s) => (s.dof === null || s.dof === undefined ? '?' : String(s.dof)));
  const oneDof = dofs.every((d) => d === '1');
  const from = p.dof_from_opening > 0 ? ` from ${(100 * p.dof_from_opening).toFixed(0)} % open (the closed tiling is singular)` : '';
  const gap = Math.max(0, ...p.states.map((s) => s.joint_gap));
  // Where the pins open widest, when that is more than closed.
  const widest = p.states.find((s) => s.joint_gap === gap);
  const where = tolerance !== undefined && gap >= tolerance && widest ? `, widest at ${(100 * widest.opening).toFixed(0)} % open` : '';
  const closedMeans = tolerance !== undefined ? ` (closed means below ${tolerance.toExponential(0)} L)` : '';
  lines.push({
    key: 'path',
    text: opensOf(result)
      ? `Opens along one motion: the path check reached the closed tiling from the opened state in ${p.states.length} states, one DOF at each${from}, pins closed to ${gap.toExponential(1)} L, no overlap.`
      : `Does NOT open along one motion: ${[
        oneDof ? `one DOF at every state${from}` : `DOF ${dofs.join(' ')} at the states${from}, the opened one first`,
        `pins closed to ${gap.toExponential(1)} L on the way${where}${closedMeans}`,
        `closed-state spread ${p.closed_spread.toExponential(1)} rad`,
      ].join('; ')}.`,
  });
  const edge = verdictEdgeMm(result.verdict);
  const overlaps = p.states
    .map((s) => s.overlap && { a: s.overlap[0], b: s.overlap[1], opening: s.opening, depth: s.overlap_depth })
    .filter(Boolean);
  const deep = (o) => (typeof o.depth === 'number' && o.depth > 0 ? ` (${mmText(o.depth, edge)} deep)` : '');
  const crossing = p.self_intersecting ?? [];
  lines.push({
    key: 'overlaps',
    text: `${overlaps.length
      ? `Overlaps: ${overlaps.map((o) => `tiles ${o.a} and ${o.b} at ${(100 * o.opening).toFixed(0)} % open${deep(o)}`).join(', ')}.`
      : 'No two tiles overlap at any state of the path.'}${crossing.length
      ? ` Closed tile${crossing.length === 1 ? '' : 's'} ${crossing.join(', ')} cross${crossing.length === 1 ? 'es itself' : ' themselves'}.`
      : ''}`,
  });
  return lines;
}

/** The edge length (mm) the library's verdict states its sizes at by default
 * (graded::verdict::NOMINAL_EDGE_MM, the exports' default edge). */
export const NOMINAL_EDGE_MM = 20;

/** The edge length (mm) a verdict states its sizes at: the number in its text's "… mm at E mm
 * edges", else the nominal one. */
export function verdictEdgeMm(verdict) {
  const m = /\bat ([\d.]+) mm edges\b/.exec(verdict?.text ?? '');
  const e = m ? Number(m[1]) : NaN;
  return Number.isFinite(e) && e > 0 ? e : NOMINAL_EDGE_MM;
}

/** A length in edge lengths L as the verdict says it: mm (3 decimals) at `edgeMm` edges. */
export function mmText(l, edgeMm = NOMINAL_EDGE_MM) {
  return `${(l * edgeMm).toFixed(3)} mm at ${edgeMm} mm edges`;
}

/** Whether the sheet opens along one motion: the library's verdict (`verdict.opens`), or the
 * path check's `reached` in a file written before the library gave a verdict. */
export function opensOf(result) {
  const v = result?.verdict?.opens;
  return typeof v === 'boolean' ? v : Boolean(result?.path?.reached);
}

/** The verdict to show, as the library gives it: its one line (`text`, null in an older file
 * without a verdict), whether it opens, meets its target, and a level for the page's colour:
 * 'passes' (opens and meets it), 'misses' (opens, misses it), 'fails' (does not open). */
export function verdictView(result) {
  const v = result?.verdict;
  const opens = opensOf(result);
  if (!v) return { text: null, opens, meets: null, partial: false, level: opens ? 'opens' : 'fails' };
  return {
    text: String(v.text),
    opens,
    meets: Boolean(v.meets_target),
    partial: typeof v.target_fraction === 'number' && v.target_fraction < 1,
    level: !opens ? 'fails' : v.meets_target ? 'passes' : 'misses',
  };
}

/** The outline's fit to its target, in percent of the target's equivalent radius: the
 * Hausdorff distance (the error judged), the mean, and how far inside and outside it the
 * outline goes at most. Empty for a field target (or a file without the fit). */
export function fitFigures(result) {
  const f = result?.fit;
  if (!f) return [];
  return [
    { key: 'hausdorff', label: 'Hausdorff (worst)', value: f.hausdorff },
    { key: 'mean', label: 'mean', value: f.mean },
    { key: 'inside', label: 'inside', value: f.inside },
    { key: 'outside', label: 'outside', value: f.outside },
  ].filter((x) => typeof x.value === 'number').map((x) => ({ ...x, text: pct(x.value) }));
}

/** The worst boundary point ([x, y], in the opened sheet's frame, as the target and the poses):
 * where the outline is farthest from its target; null for a field or without a fit. */
export function worstPoint(result) {
  const w = result?.fit?.worst;
  return Array.isArray(w) && w.length === 2 && w.every(Number.isFinite) ? [w[0], w[1]] : null;
}

/** The player's index (closed first, see playerStates) of the state with the path's deepest
 * overlap: the verdict's (its opening and its two tiles), or in a file without a verdict the
 * state whose overlap is deepest (the first overlapping one when no depths are given); null
 * when no two tiles overlap. */
export function deepestOverlapIndex(result) {
  const states = playerStates(result);
  const v = result?.verdict;
  const same = (o, t) => Array.isArray(o) && ((o[0] === t[0] && o[1] === t[1]) || (o[0] === t[1] && o[1] === t[0]));
  if (v) {
    const tiles = v.deepest_overlap_tiles;
    if (!Array.isArray(tiles)) return null;
    let best = null;
    states.forEach((st, k) => {
      if (!same(st.overlap, tiles)) return;
      const off = Math.abs(st.opening - (v.deepest_overlap_at ?? st.opening));
      if (best === null || off < best.off) best = { k, off };
    });
    return best?.k ?? null;
  }
  let best = null;
  states.forEach((st, k) => {
    if (!st.overlap) return;
    const depth = typeof st.overlap_depth === 'number' ? st.overlap_depth : 0;
    if (best === null || depth > best.depth) best = { k, depth };
  });
  return best?.k ?? null;
}

/** What the drawing marks at player state `k`: that state's overlapping pair (its deepest),
 * whether it is the path's deepest overlap (`deepestK`, from deepestOverlapIndex), its depth in
 * L and in mm at the verdict's nominal edge, and the label; null when no two tiles overlap
 * there. */
export function overlapMark(result, k, deepestK = deepestOverlapIndex(result)) {
  const st = playerStates(result)[k];
  if (!st?.overlap) return null;
  const [a, b] = st.overlap;
  const deepest = k === deepestK;
  const given = deepest && typeof result.verdict?.deepest_overlap === 'number' ? result.verdict.deepest_overlap : st.overlap_depth;
  const depth = typeof given === 'number' ? given : null;
  const edge = verdictEdgeMm(result.verdict);
  return {
    tiles: [a, b],
    deepest,
    depth,
    mm: depth === null ? null : depth * edge,
    label: `tiles ${a} and ${b} overlap${depth === null ? '' : ` ${mmText(depth, edge)}`}${deepest ? ' (deepest)' : ''}`,
  };
}

/** Where an overlap's label goes: midway between the two tiles' centroids. */
export function overlapAnchor(polygons, [a, b]) {
  const [ax, ay] = centroid(polygons[a]);
  const [bx, by] = centroid(polygons[b]);
  return [(ax + bx) / 2, (ay + by) / 2];
}

/** A cost for a line of text. */
export function fmtCost(v) {
  if (typeof v !== 'number' || !Number.isFinite(v)) return '–';
  return v.toExponential(3);
}

/** The progress line of a job view. */
export function progressLine(job) {
  const p = job.progress;
  if (!p) return job.state === 'running' ? 'Setting up the sheet…' : '';
  return `iteration ${p.iteration} (limit ${p.max_iterations}) · cost ${fmtCost(p.cost)} · stage ${p.stage + 1} of ${p.stages} · ${job.elapsed.toFixed(1)} s`;
}
