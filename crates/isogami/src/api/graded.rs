//! The graded-sheet entry point (issue 25): grade a design's finite sheet towards a target
//! outline, then check the result the other way (its own motion from closed to opened).

use crate::error::Result;
use crate::graded::field::{cell_ratios, FieldCell};
use crate::graded::measures::{
    opened_boundary, outer_boundary, outline_fit, sheet_opening, tip_outline,
};
use crate::graded::verdict::{FIELD_TOLERANCE, OUTLINE_TOLERANCE};
use crate::graded::{
    grade_until_open, GradedProgress, GradedReport, GradedRequest, GradedSheet, GradedVerdict,
    OutlineFit, PathCheck,
};
use crate::math::Real;
use crate::math::Vec2;
use crate::stop::KeepGoing;
use serde::Serialize;

/// A graded sheet, how its optimisation went and whether it opens along one motion.
#[derive(Debug, Clone, Serialize)]
pub struct GradedRun {
    /// The graded sheet (closed nodes, pins, opened state, the states part of the way).
    pub sheet: GradedSheet,
    /// The optimisation and its fit to the target.
    pub report: GradedReport,
    /// The path from the opened state back to the closed tiling.
    pub path: PathCheck,
    /// A field target: every measured cell's target and achieved area ratio (empty, and left
    /// out of the JSON, for an outline target). Their largest difference is the report's
    /// `max_field_error`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub field: Vec<FieldResult>,
    /// An outline target: the whole opened outline against it (None for a field).
    pub fit: Option<OutlineFit>,
    /// Whether the sheet opens along one motion and meets its target, with the sizes.
    pub verdict: GradedVerdict,
}

/// One cell a field target is measured on, in the graded sheet: the quadrilateral of four
/// neighbouring cells' reference corners, its area ratio asked and achieved.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FieldResult {
    /// The area ratio the field asks of the cell.
    pub target: Real,
    /// Its opened area over its closed area in the graded sheet.
    pub ratio: Real,
    /// The quadrilateral's corners closed (counter-clockwise, the sheet's units).
    pub closed: [[Real; 2]; 4],
    /// The same corners opened.
    pub opened: [[Real; 2]; 4],
}

/// Each of `cells` measured on `sheet` (see [`FieldResult`]).
pub fn field_results(sheet: &GradedSheet, cells: &[FieldCell]) -> Vec<FieldResult> {
    cell_ratios(sheet, cells)
        .into_iter()
        .zip(cells)
        .map(|(ratio, c)| FieldResult {
            target: c.target,
            ratio,
            closed: c.corners.map(|(_, n)| {
                let p = sheet.node(n);
                [p.x, p.y]
            }),
            opened: c.corners.map(|(i, n)| {
                let p = sheet.opened_corner(i, n);
                [p.x, p.y]
            }),
        })
        .collect()
}

pub use crate::graded::homotopy::PATH_STEPS;

/// Grades `request`'s sheet and checks its path; when the sheet asked for does not open
/// along one motion, the nearest one found that does (see [`crate::graded::homotopy`]).
/// `progress` is called after every accepted step of the first optimisation with the
/// iteration, the cost and the sheet as it stands (false stops it: a cancelled error);
/// `keep_going` is polled throughout.
pub fn graded_sheet(
    request: &GradedRequest,
    progress: &mut dyn FnMut(&GradedProgress) -> bool,
    keep_going: KeepGoing<'_>,
) -> Result<GradedRun> {
    let graded = grade_until_open(request, progress, keep_going)?;
    let (sheet, problem) = (&graded.sheet, &graded.problem);
    let field = field_results(sheet, &problem.field);
    let cycle = outer_boundary(sheet);
    let fit = if problem.field.is_empty() {
        let target: Vec<Vec2> = graded
            .report
            .target
            .iter()
            .map(|p| Vec2::new(p[0], p[1]))
            .collect();
        outline_fit(
            &tip_outline(sheet, &cycle, &problem.tips),
            &opened_boundary(sheet, &cycle),
            &target,
        )
    } else {
        None
    };
    let (error, tolerance) = match fit {
        Some(f) => (f.hausdorff, request.tolerance.unwrap_or(OUTLINE_TOLERANCE)),
        None => (
            field
                .iter()
                .map(|c| (c.ratio / c.target - 1.0).abs())
                .fold(0.0, Real::max),
            request.tolerance.unwrap_or(FIELD_TOLERANCE),
        ),
    };
    let verdict = GradedVerdict::new(
        &graded.path,
        error,
        tolerance,
        graded.target_fraction,
        sheet_opening(sheet, &cycle),
        problem.periodic_opening,
    );
    Ok(GradedRun {
        sheet: graded.sheet,
        report: graded.report,
        path: graded.path,
        field,
        fit,
        verdict,
    })
}
