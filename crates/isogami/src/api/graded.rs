//! The graded-sheet entry point (issue 25): grade a design's finite sheet towards a target
//! outline, then check the result the other way (its own motion from closed to opened).

use crate::error::Result;
use crate::graded::field::{cell_ratios, FieldCell};
use crate::graded::{
    check_path, grade, GradedProgress, GradedReport, GradedRequest, GradedSheet, PathCheck,
};
use crate::math::Real;
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

/// States of the path check.
pub const PATH_STEPS: usize = 20;

/// Grades `request`'s sheet and checks its path. `progress` is called after every accepted
/// step of the optimisation with the iteration, the cost and the sheet as it stands (false
/// stops it: a cancelled error); `keep_going` is polled by the path check too.
pub fn graded_sheet(
    request: &GradedRequest,
    progress: &mut dyn FnMut(&GradedProgress) -> bool,
    keep_going: KeepGoing<'_>,
) -> Result<GradedRun> {
    let (sheet, problem, report) = grade(request, progress, keep_going)?;
    let path = check_path(&sheet, &problem, PATH_STEPS, keep_going)?;
    let field = field_results(&sheet, &problem.field);
    Ok(GradedRun {
        sheet,
        report,
        path,
        field,
    })
}
