//! Duplicates across cells and families, after each cell's own deduplication: the same
//! motion found on an a×b cell and its rotated b×a twin, on a cell that repeats a smaller
//! one in a way the per-cell repeat test does not see, or in two families whose default
//! shapes give congruent sheets.

use super::motion::{MotionIndex, MOTION_TOL};
use crate::explore::pipeline::TopologyReport;
use crate::tiling::Family;

/// A motion index and the (report, design) owner of each of its entries.
type IndexScope = (MotionIndex, Vec<(usize, usize)>);

/// Duplicates across reports: for every design of every report, the (report, design) indices
/// of the first earlier design — in report order, then design order — whose motion invariant
/// matches (the invariant is comparable between cells with the same number of unique edges;
/// it does not depend on the cell's orientation or units). With `same_family`, only designs of
/// the same family are compared: a×b designs and their rotated b×a twins, designs that
/// repeat a smaller cell's design in a way the per-cell repeat test does not see. Without it,
/// also families whose default shapes give congruent sheets. Order the reports smallest cell
/// first to keep the smallest cell's design.
pub fn duplicates_across(
    reports: &[TopologyReport],
    same_family: bool,
) -> Vec<Vec<Option<(usize, usize)>>> {
    let mut indices: std::collections::BTreeMap<Option<Family>, IndexScope> =
        std::collections::BTreeMap::new();
    reports
        .iter()
        .enumerate()
        .map(|(r, report)| {
            let scope = same_family.then_some(report.family);
            let (index, owners) = indices.entry(scope).or_default();
            report
                .details
                .iter()
                .enumerate()
                .map(|(d, det)| match index.find(&det.invariant, MOTION_TOL) {
                    Some(id) => Some(owners[id]),
                    None => {
                        index.insert(det.invariant.clone());
                        owners.push((r, d));
                        None
                    }
                })
                .collect()
        })
        .collect()
}
