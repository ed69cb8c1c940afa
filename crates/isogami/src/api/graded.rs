//! The graded-sheet entry point (issue 25): grade a design's finite sheet towards a target
//! outline, then check the result the other way (its own motion from closed to opened).

use crate::error::Result;
use crate::graded::{
    check_path, grade, GradedProgress, GradedReport, GradedRequest, GradedSheet, PathCheck,
};
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
    Ok(GradedRun {
        sheet,
        report,
        path,
    })
}
