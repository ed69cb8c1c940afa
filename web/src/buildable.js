// Whether a design can be cut as a finite sheet that opens with its one motion, as the
// catalogue measured it (issue 40): `finite_raw_dof` is the DOF of the raw 6×6-cell patch as
// cut, `finite_covered` the fraction of that patch its completion to a one-DOF sheet keeps,
// null when there is none (isostatic cells, where every finite sheet flops along its
// boundary, and a few others). Designs saved from the browser and live designs have neither.
// The badge of catalogue cards, table rows and the design page, the export panel's advice and
// the catalogue query of neighbours that have a sheet. Pure, no DOM.

import { catalogueSearch, emptyCatalogueState } from './url.js';

/** The range that passes exactly the designs with a one-DOF sheet: a range never passes a
 * design that lacks the measure, and every kept fraction is positive. */
export const HAS_SHEET_RANGE = Object.freeze({ measure: 'finite_covered', min: 0, max: null });

/** The fabrication tolerance the catalogue calls buildable (isogami::catalog::FABRICATION_TOLERANCE:
 * vertex moves of 0.0025 of the mean edge, ±0.05 mm at 20 mm edges). */
export const FABRICATION_TOLERANCE = 0.0025;

/**
 * True when a catalogue row is buildable, the rule of the store's DesignSummary::buildable
 * (which orders the API's lead=buildable): a one-DOF finite sheet, margins measured, and the
 * shape tolerance at least the fabrication tolerance (or a family without shape parameters).
 */
export function isBuildable(row) {
  const tol = row?.shape_tolerance;
  return typeof row?.finite_covered === 'number'
    && typeof row?.open_t === 'number'
    && (tol === null || tol === undefined || tol >= FABRICATION_TOLERANCE);
}

/**
 * What a row says about its shape tolerance: `{kind, text, title}` with kind `special` (it
 * opens only at its exact shape), `tight` (below the fabrication tolerance), `ok`, `fixed` (no
 * shape parameters) or `unknown` (not measured).
 */
export function shapeStatus(row) {
  const tol = row?.shape_tolerance;
  if (typeof row?.open_t !== 'number') return { kind: 'unknown', text: '', title: '' };
  if (tol === null || tol === undefined) {
    return { kind: 'fixed', text: '', title: 'The family has no shape parameters: its shape is fixed.' };
  }
  const mm = (t) => (t * 20).toFixed(t * 20 < 0.1 ? 2 : 1);
  if (tol === 0) {
    return {
      kind: 'special',
      text: 'special shape',
      title: 'Special: it opens only at its exact shape. Moved by 1e-6 of the edge length it loses its opening (locks early), so a cut or printed sheet will not open as shown. `isogami analyze` names the constraint its shape must keep.',
    };
  }
  if (tol < FABRICATION_TOLERANCE) {
    return {
      kind: 'tight',
      text: `±${mm(tol)} mm`,
      title: `It keeps 95 % of its opening only under shape errors up to ${tol} of the edge length (±${mm(tol)} mm at 20 mm edges): tighter than ±0.05 mm.`,
    };
  }
  return {
    kind: 'ok',
    text: `±${mm(tol)} mm`,
    title: `It keeps 95 % of its opening under shape errors up to ${tol} of the edge length (±${mm(tol)} mm at 20 mm edges).`,
  };
}

/** A covered fraction as a whole percentage that says 100 only when it is 1. */
export function percentText(covered) {
  const p = Math.round(covered * 100);
  return String(covered < 1 && p >= 100 ? 99 : p);
}

/**
 * What a catalogue row (a DesignSummary, or a design view's `summary`; null for a live
 * design) says about its finite sheet: `{kind, covered, rawDof, text, short, title}` where kind
 * is `sheet` (it has a one-DOF sheet), `none` (measured: it has none) or `unknown` (not
 * measured); `text` is the badge, `short` the table cell, `title` the explanation.
 */
export function sheetStatus(row) {
  const covered = typeof row?.finite_covered === 'number' ? row.finite_covered : null;
  const rawDof = typeof row?.finite_raw_dof === 'number' ? row.finite_raw_dof : null;
  if (covered !== null) {
    const pct = percentText(covered);
    const raw = rawDof === 1
      ? ' Cut as it is, the patch already opens with one motion.'
      : rawDof !== null
        ? ` Cut as it is, the patch has ${rawDof} DOF: its boundary tiles flop.`
        : '';
    return {
      kind: 'sheet',
      covered,
      rawDof,
      text: `one-DOF sheet · ${pct} % kept`,
      short: `${pct} %`,
      title: `Buildable: its 6×6-cell patch completed to one degree of freedom (the tiles that would flop at the boundary removed, a ring closing open loops added) keeps ${pct} % of its area and opens with the design's one motion.${raw}`,
    };
  }
  if (rawDof !== null) {
    return {
      kind: 'none',
      covered: null,
      rawDof,
      text: 'no one-DOF sheet',
      short: 'none',
      title: `No finite sheet of this design opens with one motion: its 6×6-cell patch as cut has ${rawDof} DOF (its boundary tiles flop), and no completion keeping half of it or more reaches one DOF (an isostatic cell, 3n − 2p = 0, flops along any boundary). Export the raw rectangle (--raw), try another region, or choose a design of the same family that has one.`,
    };
  }
  return {
    kind: 'unknown',
    covered: null,
    rawDof: null,
    text: 'sheet not measured',
    short: '–',
    title: 'Not measured: designs saved from the browser and live designs have no finite-sheet measures. The design page’s Finite sheet panel checks any region.',
  };
}

/** The catalogue query of the designs of `family` (every family when null) that have a
 * one-DOF sheet, the largest kept fraction first. */
export function neighbourState(family, limit = 1) {
  const s = emptyCatalogueState();
  if (family) s.filters.family = [String(family)];
  s.ranges = [{ ...HAS_SHEET_RANGE }];
  s.sort = { key: 'finite_covered', desc: true };
  s.limit = limit;
  s.view = 'grid';
  return s;
}

/** The catalogue link listing the designs of `family` (every family when null) that have a
 * one-DOF sheet. */
export function neighbourHref(family) {
  const s = neighbourState(family);
  s.limit = emptyCatalogueState().limit;
  return `./index.html${catalogueSearch(s)}`;
}

/** The family of a spec's text (`IH22:…` → `IH22`), or null for a name such as
 * `rotating-squares`. */
export function familyOfSpec(text) {
  const m = /^\s*(IH\d+):/.exec(String(text ?? ''));
  return m ? m[1] : null;
}

/** The design of `family` with a one-DOF sheet that keeps the most, from `data` (data.js: the
 * server or the static site's query engine), other than `spec`; null when the family has none. */
export async function findNeighbour(data, family, spec = null) {
  if (!family) return null;
  const page = await data.designs(neighbourState(family, 2));
  return page.rows.find((r) => r.spec !== spec) ?? null;
}

/** The query of GET /api/sheet that tells whether the graded page's design and region have a
 * one-DOF sheet (its `refused` says why not), or null while the form cannot be asked about
 * (no design, or a region the form itself refuses: `regionProblem` of graded-model.js). */
export function sheetCheckQuery(form, regionProblem = () => '') {
  const design = String(form.design ?? '').trim();
  if (!design || regionProblem(form)) return null;
  return new URLSearchParams({ design, region: `${Number(form.rows)}x${Number(form.cols)}` }).toString();
}

/** The library's reason without its lead ("no one-DOF sheet in this region: …" → "…"). */
export function refusalReason(refused) {
  return String(refused ?? '').replace(/^no one-DOF sheet in this region:\s*/, '');
}
