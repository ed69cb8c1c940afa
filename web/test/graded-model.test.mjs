// The graded-sheet page's pure logic: the form pre-filled from ?design=, the region checked
// against the caps as typed, the outline's text, the star-shaped check (the library's rule and
// words, on the same cases as its tests), the POST body and the command saying the same thing,
// tiles placed from poses as GradedSheet::opened_polygon places them, the player's order, the
// target sized to an area, and the report's lines; the library's verdict shown as it gives it
// (an older file without one read from its path check), the fit figures, the worst boundary
// point, and the deepest overlap's state, tiles and depth in mm on a hand-made result.

import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  DEFAULTS, EXPORTS, NOMINAL_EDGE_MM, bounds, centroid, cliCommand, closedPolygons, convexHull, cornersText, deepestOverlapIndex, edgeProblem,
  emptyForm, errorColour, exportCommand, exportParams, fieldProblem, fieldRows, fitFigures, formFromJob, gradedBody, hullArea, iterationsProblem,
  mmText, opensOf, outlineAtArea, outlineText, overlapAnchor, overlapMark, parseCorners, playerStates, posedPolygons, regionProblem, reportLines,
  signedArea, starProblem, svgProblem, toleranceProblem, verdictEdgeMm, verdictView, worstPoint,
} from '../src/graded-model.js';
import { shellSplit } from './shell.mjs';

const limits = { side: 8, cells: 36, tiles: 300, iterations: 800, states: 16 };

test('the form starts from ?design= or the default, with the server’s defaults', () => {
  assert.equal(emptyForm(null).design, 'rotating-squares');
  assert.equal(emptyForm(null, '?design=IH6%3A0.5%3A1x1%3Abb').design, 'IH6:0.5:1x1:bb');
  assert.equal(emptyForm(null, '?design=%20').design, 'rotating-squares');
  const f = emptyForm({ defaults: { rows: 4, cols: 5, iterations: 100 } });
  assert.deepEqual([f.rows, f.cols, f.iterations, f.outline], ['4', '5', '100', 'disc']);
  assert.equal(emptyForm(null).iterations, String(DEFAULTS.iterations));
});

test('the region and iterations are checked against the caps as typed', () => {
  const f = (rows, cols, iterations = '60') => ({ rows, cols, iterations });
  assert.equal(regionProblem(f('3', '3'), limits), '');
  assert.equal(regionProblem(f('', '3'), limits), 'rows: give a whole number');
  assert.equal(regionProblem(f('0', '3'), limits), 'rows must be a whole number of at least 1');
  assert.equal(regionProblem(f('2.5', '3'), limits), 'rows must be a whole number of at least 1');
  assert.equal(regionProblem(f('3', '9'), limits), "columns 9 is above this server's limit of 8");
  assert.equal(regionProblem(f('7', '7'), limits), "a region of 7x7 = 49 cells is above this server's limit of 36 cells");
  assert.equal(regionProblem(f('40', '40'), {}), '', 'no caps on a static site');
  assert.equal(iterationsProblem(f('3', '3', '801'), limits), "iterations 801 is above this server's limit of 800");
  assert.equal(iterationsProblem(f('3', '3', '0'), limits), 'iterations must be a whole number of at least 1');
});

test('outlines are written as isogami graded --target reads them', () => {
  assert.equal(outlineText({ outline: 'disc' }), 'disc');
  assert.equal(outlineText({ outline: 'ellipse', aspect: '1.4' }), 'ellipse:1.4,1');
  const points = [[0, -1], [1.23456, 0], [0, 1], [-1, -0.00001]];
  assert.equal(outlineText({ outline: 'polygon', points }), 'polygon:0,-1;1.2346,0;0,1;-1,0');
});

test('a drawn polygon is refused when its centroid does not see it whole, in the library’s words', () => {
  // The library's own cases (graded::target tests).
  assert.equal(starProblem([[0, -1], [2, 0], [1, 2], [-1, 2], [-2, 0]]), '');
  assert.equal(starProblem([[-1, -1], [2, -1], [2, 2], [-1, 2]]), '');
  assert.equal(starProblem([[-1, -1], [-1, 2], [2, 2], [2, -1]]), '', 'clockwise is fine');
  const u = [[0, 0], [4, 0], [4, 4], [3, 4], [3, 1], [1, 1], [1, 4], [0, 4]];
  assert.match(starProblem(u), /^bad target: the outline is not seen whole from its centroid \(edge \d+\); give a star-shaped outline$/);
  assert.equal(starProblem([[0, 0], [1, 0]]), 'bad target: an outline needs at least three finite points');
  assert.equal(starProblem([[0, 0], [1, 1], [2, 2]]), 'bad target: the outline encloses no area');
});

test('the body and the command say the same thing', () => {
  const form = { design: ' rotating-squares ', rows: '2', cols: '3', outline: 'polygon', points: [[0, -1], [1, 0], [0, 1], [-1, 0]], iterations: '60' };
  const body = gradedBody(form);
  assert.deepEqual(body, { design: 'rotating-squares', rows: 2, cols: 3, target: 'polygon:0,-1;1,0;0,1;-1,0', iterations: 60 });
  const words = shellSplit(cliCommand(form));
  assert.deepEqual(words, ['isogami', 'graded', '--design', 'rotating-squares', '--region', '2x3', '--target', body.target,
    '--iterations', '60', '--out', 'graded.json']);
  const spec = cliCommand({ ...form, design: 'IH6:0.5:1x1:b b' });
  assert.equal(shellSplit(spec)[3], 'IH6:0.5:1x1:b b');
});

// Two unit squares side by side, the second turned a quarter about its first node.
const sheet = {
  nodes: [[0, 0], [1, 0], [1, 1], [0, 1], [2, 0], [2, 1]],
  tiles: [{ nodes: [0, 1, 2, 3] }, { nodes: [1, 4, 5, 2] }],
  joints: [{ a: 0, b: 1, node: 1 }],
};

test('tiles are placed from poses as GradedSheet::opened_polygon places them', () => {
  const close = (a, b) => a.every((p, i) => Math.abs(p[0] - b[i][0]) < 1e-12 && Math.abs(p[1] - b[i][1]) < 1e-12);
  const rest = posedPolygons(sheet, [{ x: 0, y: 0, theta: 0 }, { x: 1, y: 0, theta: 0 }]);
  assert.deepEqual(rest, closedPolygons(sheet));
  const turned = posedPolygons(sheet, [{ x: 0, y: 0, theta: 0 }, { x: 5, y: 1, theta: Math.PI / 2 }]);
  assert.ok(close(turned[1], [[5, 1], [5, 2], [4, 2], [4, 1]]), JSON.stringify(turned[1]));
  assert.deepEqual(bounds(turned), [0, 0, 5, 2]);
});

test('the player runs closed to opened: the path check lists the opened state first', () => {
  const result = { path: { states: [{ opening: 1 }, { opening: 0.5 }, { opening: 0 }] } };
  assert.deepEqual(playerStates(result).map((s) => s.opening), [0, 0.5, 1]);
  assert.deepEqual(playerStates(null), []);
});

test('areas, hulls and the target sized to an area', () => {
  const square = [[-1, -1], [1, -1], [1, 1], [-1, 1]];
  assert.equal(signedArea(square), 4);
  assert.deepEqual(centroid([[0, 0], [2, 0], [2, 2], [0, 2]]), [1, 1]);
  assert.deepEqual(convexHull([[0, 0], [1, 0], [0.5, 0.2], [1, 1], [0, 1]]), [[0, 0], [1, 0], [1, 1], [0, 1]]);
  assert.equal(hullArea(closedPolygons(sheet)), 2);
  const scaled = outlineAtArea(square, 16);
  assert.equal(signedArea(scaled), 16);
  assert.deepEqual(scaled[0], [-2, -2]);
});

test('the report names the fit, the path’s verdict and the overlapping tiles', () => {
  const state = (opening, extra = {}) => ({ opening, dof: 1, joint_gap: 1e-7, overlap: null, poses: [], ...extra });
  const result = {
    sheet: { joints: [1, 2, 3], nodes: [1, 2, 3, 4, 5] },
    report: {
      tiles: 2, iterations: 60, cost: [9.4, 0.55], seconds: 0.5, joint_gap: 4.6e-6, max_outline_error: 0.0212,
      median_outline_error: 0.0027, max_outside: 0.0212, min_corner_fraction: 0.35, min_angle_degrees: 31.5, min_edge_fraction: 0.44,
      min_area_fraction: 0.52, target: [],
    },
    path: {
      states: [state(1), state(0.5, { overlap: [3, 7] }), state(0)], closed_spread: 2e-16, reached: false,
      pin_tolerance: 1e-6, dof_from_opening: 0.1,
    },
  };
  const lines = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.match(lines.fit, /within 2\.12 % of the target \(median 0\.27 %\)/);
  assert.match(lines.pins, /^Pins closed to 4\.6e-6 L.*smallest angle 31\.5°, corners keep ≥ 35 % of their sine/);
  assert.match(lines.path, /^Does NOT open along one motion: one DOF at every state/);
  assert.match(lines.path, /pins closed to 1\.0e-7 L on the way \(closed/, 'closed pins: no place named');
  assert.equal(lines.overlaps, 'Overlaps: tiles 3 and 7 at 50 % open.');
  // Pins open on the way: the line says at which state they open widest.
  result.path.states[2].joint_gap = 8.4e-4;
  const open = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.match(open.path, /pins closed to 8\.4e-4 L on the way, widest at 0 % open \(closed means below 1e-6 L\)/);
  // The verdict is the library's, read from the check: with its tolerance at 1e-3 the same
  // gap is closed (no place named); with DOF counted from 60 % open, the two DOF at 50 %
  // are the closed tiling's singularity, not a second motion.
  result.path.pin_tolerance = 1e-3;
  result.path.dof_from_opening = 0.6;
  result.path.states[1].dof = 2;
  const theirs = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.match(theirs.path, /one DOF at every state from 60 % open .*pins closed to 8\.4e-4 L on the way \(closed means below 1e-3 L\)/);
  result.path.dof_from_opening = 0.1;
  const second = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.match(second.path, /DOF 1 2 at the states from 10 % open \(the closed tiling is singular\), the opened one first/);
  result.path.pin_tolerance = 1e-6;
  result.path.states[1].dof = 1;
  result.path.states[2].joint_gap = 1e-7;
  result.path.reached = true;
  result.path.states[1].overlap = null;
  const ok = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.match(ok.path, /^Opens along one motion: the path check reached the closed tiling .* in 3 states/);
  assert.equal(ok.overlaps, 'No two tiles overlap at any state of the path.');
});

test('a field target is written as --target field:FROM,TO[,DEGREES] and checked as the library does', () => {
  const form = { ...emptyForm(null), outline: 'field', from: '1.3', to: ' 1.7', degrees: '0', rows: '2', cols: '2', iterations: '40' };
  assert.equal(outlineText(form), 'field:1.3,1.7');
  assert.equal(outlineText({ ...form, degrees: '90' }), 'field:1.3,1.7,90');
  assert.equal(fieldProblem(form), '');
  assert.equal(fieldProblem({ ...form, from: '0.8' }), 'the area ratios at the two ends must be numbers above 1 (the sheet opens)');
  assert.equal(fieldProblem({ ...form, to: '' }), 'the area ratios at the two ends must be numbers above 1 (the sheet opens)');
  assert.equal(fieldProblem({ ...form, degrees: 'east' }), 'the direction must be an angle in degrees');
  assert.equal(fieldProblem({ ...form, outline: 'disc', from: 'x' }), '', 'only a field is checked');
  assert.deepEqual(gradedBody({ ...form, degrees: '45' }), { design: 'rotating-squares', rows: 2, cols: 2, target: 'field:1.3,1.7,45', iterations: 40 });
  const words = shellSplit(cliCommand({ ...form, degrees: '45' }));
  assert.equal(words[words.indexOf('--target') + 1], 'field:1.3,1.7,45');
});

test('an SVG file is posted as its text and named as the CLI’s @FILE', () => {
  const form = { ...emptyForm(null), outline: 'svg', svg: null };
  assert.equal(svgProblem(form), 'choose an SVG file with one closed shape');
  const svg = { name: 'my outline.svg', text: '<svg/>' };
  assert.equal(svgProblem({ ...form, svg }), '');
  assert.equal(svgProblem({ ...form, outline: 'disc' }), '');
  const body = gradedBody({ ...form, svg });
  assert.deepEqual([body.svg, body.svg_name, body.target], ['<svg/>', 'my outline.svg', undefined]);
  const words = shellSplit(cliCommand({ ...form, svg }));
  assert.equal(words[words.indexOf('--target') + 1], '@my outline.svg');
});

test('exports: laser and print formats, the query and the command naming the same flags', () => {
  assert.deepEqual(EXPORTS.map((e) => e.format), ['svg', 'dxf', 'stl', '3mf']);
  assert.equal(exportParams('dxf', ' 15 '), 'format=dxf&edge_mm=15');
  assert.equal(exportParams('svg', ''), 'format=svg');
  assert.deepEqual(shellSplit(exportCommand('3mf', '15', 2, 3)),
    ['isogami', 'export', '--sheet', 'graded-2x3.json', '--format', '3mf', '--edge-mm', '15', '--out', 'graded-2x3.3mf']);
  assert.equal(edgeProblem('20'), '');
  assert.equal(edgeProblem('-1'), 'the mean edge length must be a positive number of mm');
  assert.equal(edgeProblem(''), 'the mean edge length must be a positive number of mm');
});

test('a field result: a row per cell, coloured by its error, and the fit line names the field error', () => {
  const quad = [[0, 0], [1, 0], [1, 1], [0, 1]];
  const result = { field: [{ target: 1.3, ratio: 1.31, opened: quad, closed: quad }, { target: 1.7, ratio: 1.65, opened: quad, closed: quad }] };
  const rows = fieldRows(result);
  assert.deepEqual(rows.map((r) => r.cell), [1, 2]);
  assert.ok(Math.abs(rows[1].error + 0.05) < 1e-12);
  assert.deepEqual(fieldRows({}), []);
  assert.equal(errorColour(0), 'rgb(255,255,255)');
  assert.equal(errorColour(0.05), 'rgb(255,0,0)');
  assert.equal(errorColour(-1), 'rgb(0,0,255)');
  const state = { opening: 1, dof: 1, joint_gap: 1e-7, overlap: null, poses: [] };
  const lines = reportLines({
    sheet: { joints: [], nodes: [] },
    report: {
      tiles: 16, iterations: 60, cost: [1, 0.1], seconds: 0.5, joint_gap: 1e-7, max_outline_error: 0, median_outline_error: 0,
      max_outside: 0, min_corner_fraction: 0.5, min_angle_degrees: 40, min_edge_fraction: 0.5, min_area_fraction: 0.5, target: [],
      max_field_error: 0.0512, field_cells: 2,
    },
    path: { states: [state], closed_spread: 0, reached: true },
  });
  assert.equal(lines[0].text, 'Fit: the area ratio is within 0.0512 of the field in each of 2 cells (max field error 0.0512).');
});

/** The request a job's view echoes for the body `b` (as the server's graded::job::Echo). */
function echoOf(b, defaults = DEFAULTS) {
  return {
    design: b.design,
    rows: b.rows,
    cols: b.cols,
    outline: b.svg !== undefined ? `@${b.svg_name}` : b.target,
    outline_points: [[1, 0], [0, 1], [-1, 0]],
    field: null,
    t: b.t ?? null,
    states: b.states ?? defaults.states,
    iterations: b.iterations,
    tolerance: b.tolerance ?? null,
    fall_back: b.fall_back ?? true,
  };
}

test('a job’s echoed request gives back the form and command that started it', () => {
  const base = emptyForm(null);
  const forms = [
    base,
    { ...base, design: 'IH6:0.5:1x1:bb', rows: '2', cols: '5', iterations: '800' },
    { ...base, outline: 'ellipse', aspect: '1.35' },
    { ...base, outline: 'polygon', points: [[0, 1], [-0.9, -0.6], [0.9, -0.6]] },
    { ...base, outline: 'field', from: '1.2', to: '1.8', degrees: '90' },
    { ...base, outline: 'field', from: '1.2', to: '1.8', degrees: '0' },
    { ...base, states: '4', t: '0.5' },
    { ...base, tolerance: '0.02', fallBack: false },
  ];
  for (const f of forms) {
    const restored = formFromJob(echoOf(gradedBody(f)), null);
    assert.equal(cliCommand(restored), cliCommand(f), JSON.stringify(f));
    assert.deepEqual(gradedBody(restored), gradedBody(f));
    assert.equal(restored.outline, f.outline);
  }
  // The default number of states is left out of the command; another is in it.
  assert.doesNotMatch(cliCommand(base), /--states|--t /);
  assert.deepEqual(shellSplit(cliCommand({ ...base, states: '4', t: '0.5' })).slice(6, 12),
    ['--target', 'disc', '--t', '0.5', '--states', '4']);
  // An ellipse given with another minor axis keeps its ratio.
  assert.equal(formFromJob({ ...echoOf(gradedBody(base)), outline: 'ellipse:3,2' }, null).aspect, '1.5');
  // An SVG target: its name and outline, not its text (the page that chose the file has it).
  const svg = { ...base, outline: 'svg', svg: { name: 'star.svg', text: '<svg/>', points: null } };
  const restored = formFromJob(echoOf(gradedBody(svg)), null);
  assert.deepEqual(restored.svg, { name: 'star.svg', text: null, points: [[1, 0], [0, 1], [-1, 0]] });
  assert.equal(cliCommand(restored), cliCommand(svg));
});

test('the polygon’s corners as text: written as the pad draws them, read back or refused by corner', () => {
  const points = [[0, 1], [-0.9, -0.6], [0.91234, -0.6]];
  assert.equal(cornersText(points), '0,1; -0.9,-0.6; 0.9123,-0.6');
  assert.deepEqual(parseCorners(cornersText(points)).points, [[0, 1], [-0.9, -0.6], [0.9123, -0.6]]);
  assert.deepEqual(parseCorners(' 0 , 1 ;-1,-1;1,-1; ').points, [[0, 1], [-1, -1], [1, -1]]);
  assert.deepEqual(parseCorners('').points, []);
  assert.match(parseCorners('0,1; -1').error, /^corner 2: "-1" is not two numbers/);
  assert.match(parseCorners('0,1;; 1,1').error, /^corner 2: "" is not/);
  assert.match(parseCorners('0,1; a,b').error, /^corner 2/);
  assert.match(parseCorners('0,1,2').error, /^corner 1/);
});

test('the tolerance and the fall-back: left out at their defaults, else --tolerance and --no-fallback', () => {
  const base = { ...emptyForm(null), rows: '2', cols: '2' };
  assert.equal(toleranceProblem(base), '', 'empty: the library’s default');
  assert.deepEqual(Object.keys(gradedBody(base)).sort(), ['cols', 'design', 'iterations', 'rows', 'target']);
  assert.doesNotMatch(cliCommand(base), /--tolerance|--no-fallback/);
  const asked = { ...base, tolerance: ' 0.1 ', fallBack: false };
  assert.equal(toleranceProblem(asked), '');
  const body = gradedBody(asked);
  assert.deepEqual([body.tolerance, body.fall_back], [0.1, false]);
  const words = shellSplit(cliCommand(asked));
  assert.deepEqual(words.slice(-5), ['--tolerance', '0.1', '--no-fallback', '--out', 'graded.json']);
  for (const bad of ['0', '-0.1', 'five']) {
    assert.equal(toleranceProblem({ ...base, tolerance: bad }), `tolerance ${bad} must be a positive fraction (0.05: 5 %)`);
  }
});

// A hand-made result of three states (the path check lists the opened one first): tiles 3 and
// 7 overlap at 50 % open, 1 and 2 (shallower) at 100 %; the library's verdict names the
// deepest.
function overlapping({ verdict = true } = {}) {
  const state = (opening, overlap, depth) => ({ opening, dof: 1, joint_gap: 1e-7, overlap, overlap_depth: depth, poses: [] });
  const result = {
    sheet: { joints: [], nodes: [] },
    report: {
      tiles: 8, iterations: 30, cost: [1, 0.5], seconds: 0.2, joint_gap: 1e-7, max_outline_error: 0.1, median_outline_error: 0.05,
      max_outside: 0.1, min_corner_fraction: 0.5, min_angle_degrees: 30, min_edge_fraction: 0.5, min_area_fraction: 0.5, target: [],
    },
    path: {
      states: [state(1, [1, 2], 0.002), state(0.5, [7, 3], 0.01575), state(0, null, 0)], closed_spread: 0, reached: true,
      self_intersecting: [], pin_tolerance: 1e-6, dof_from_opening: 0.1,
    },
    fit: { hausdorff: 0.1016, mean: 0.0468, inside: 0.1015, outside: 0.0018, radius: 3, worst: [0.5, -1.25] },
  };
  if (verdict) {
    result.verdict = {
      opens: false, meets_target: false, target_fraction: 1, error: 0.1016, tolerance: 0.05, deepest_overlap: 0.01575,
      deepest_overlap_at: 0.5, deepest_overlap_tiles: [3, 7], widest_pin_gap: 1e-7, self_intersecting: 0, sheet_opening: 2,
      periodic_opening: 2,
      text: 'does NOT open along one motion; tiles overlap 0.315 mm at 20 mm edges (1.6e-2 L) deep at 50 % open; pins gap 0.000 mm at 20 mm edges (1.0e-7 L) at most; MISSES the target: off by 10.16 % (tolerance 5.00 %)',
    };
  }
  return result;
}

test('the verdict is the library’s: its line and its opens, an older file’s read from its path check', () => {
  const result = overlapping();
  const v = verdictView(result);
  assert.equal(v.text, result.verdict.text, 'shown as the library wrote it');
  assert.deepEqual([v.opens, v.meets, v.level, v.partial], [false, false, 'fails', false]);
  // The verdict's opens, not the path check's, decides the report's line.
  assert.equal(opensOf(result), false);
  assert.match(Object.fromEntries(reportLines(result).map((l) => [l.key, l.text])).path, /^Does NOT open along one motion/);
  result.verdict = { ...result.verdict, opens: true, meets_target: false, target_fraction: 0.5 };
  assert.deepEqual([verdictView(result).level, verdictView(result).partial], ['misses', true]);
  result.verdict.meets_target = true;
  assert.equal(verdictView(result).level, 'passes');
  // A file written before the verdict: no line of its own, opens from path.reached.
  const old = overlapping({ verdict: false });
  assert.deepEqual(verdictView(old), { text: null, opens: true, meets: null, partial: false, level: 'opens' });
  old.path.reached = false;
  assert.equal(opensOf(old), false);
  assert.equal(verdictView(old).level, 'fails');
});

test('the fit figures in percent and the worst boundary point', () => {
  const result = overlapping();
  assert.deepEqual(fitFigures(result).map((f) => [f.key, f.text]), [
    ['hausdorff', '10.16 %'], ['mean', '4.68 %'], ['inside', '10.15 %'], ['outside', '0.18 %'],
  ]);
  assert.deepEqual(worstPoint(result), [0.5, -1.25]);
  // A field target has no outline fit.
  assert.deepEqual(fitFigures({ ...result, fit: null }), []);
  assert.equal(worstPoint({ ...result, fit: null }), null);
  assert.equal(worstPoint({ fit: { worst: [Number.NaN, 1] } }), null);
});

test('the deepest overlap: the verdict’s state and tiles, filled and labelled with their depth in mm', () => {
  const result = overlapping();
  // Closed first: state 1 of the player is 50 % open, where tiles 7 and 3 (the verdict's 3, 7) overlap.
  assert.equal(deepestOverlapIndex(result), 1);
  const mark = overlapMark(result, 1);
  assert.deepEqual(mark.tiles, [7, 3]);
  assert.equal(mark.deepest, true);
  assert.equal(mark.depth, 0.01575);
  assert.ok(Math.abs(mark.mm - 0.315) < 1e-12);
  assert.equal(mark.label, 'tiles 7 and 3 overlap 0.315 mm at 20 mm edges (deepest)');
  // Another state's overlap: marked with its own depth, not the deepest.
  const other = overlapMark(result, 2);
  assert.deepEqual([other.tiles, other.deepest, other.label], [[1, 2], false, 'tiles 1 and 2 overlap 0.040 mm at 20 mm edges']);
  assert.equal(overlapMark(result, 0), null, 'the closed state: no overlap');
  // The edge the verdict states its sizes at.
  assert.equal(verdictEdgeMm(result.verdict), NOMINAL_EDGE_MM);
  assert.equal(verdictEdgeMm({ text: 'does NOT open; tiles overlap 0.236 mm at 15 mm edges (1.6e-2 L) deep' }), 15);
  assert.equal(mmText(0.01575, 15), '0.236 mm at 15 mm edges');
  // The report names each overlap with its depth.
  const lines = Object.fromEntries(reportLines(result).map((l) => [l.key, l.text]));
  assert.equal(lines.overlaps, 'Overlaps: tiles 1 and 2 at 100 % open (0.040 mm at 20 mm edges deep), tiles 7 and 3 at 50 % open (0.315 mm at 20 mm edges deep).');
  // No overlap in the verdict: nothing marked as deepest.
  const clear = overlapping();
  clear.verdict = { ...clear.verdict, deepest_overlap: 0, deepest_overlap_at: null, deepest_overlap_tiles: null };
  assert.equal(deepestOverlapIndex(clear), null);
  // A file without a verdict: the deepest by the states' own depths.
  assert.equal(deepestOverlapIndex(overlapping({ verdict: false })), 1);
  const flat = overlapping({ verdict: false });
  for (const st of flat.path.states) delete st.overlap_depth;
  assert.equal(deepestOverlapIndex(flat), 1, 'no depths: the first overlapping state, closed first');
  assert.equal(overlapMark(flat, 1, 1).label, 'tiles 7 and 3 overlap (deepest)');
  // Self-crossing closed tiles are named.
  result.path.self_intersecting = [4];
  assert.match(Object.fromEntries(reportLines(result).map((l) => [l.key, l.text])).overlaps, / Closed tile 4 crosses itself\.$/);
});

test('an overlap’s label sits midway between the two tiles’ centroids', () => {
  const polygons = [[[0, 0], [2, 0], [2, 2], [0, 2]], [[4, 0], [6, 0], [6, 2], [4, 2]]];
  assert.deepEqual(overlapAnchor(polygons, [0, 1]), [3, 1]);
});
