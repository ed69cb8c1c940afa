//! The verdict on a graded sheet, with its sizes: does it open along one motion, how deep
//! do its tiles overlap and how wide do its pins gap where it does not, and how far from its
//! target does it stay.

use super::deploy::PathCheck;
use crate::math::Real;
use serde::{Deserialize, Serialize};

/// Largest Hausdorff distance between the opened outline and the target, relative to the
/// target's equivalent radius, for a sheet to meet an outline target by default (what the
/// user may change).
pub const OUTLINE_TOLERANCE: Real = 0.05;

/// Largest relative error of a measured cell's area ratio for a sheet to meet a field by
/// default.
pub const FIELD_TOLERANCE: Real = 0.05;

/// Edge length, in millimetres, at which a verdict's sizes are said by default (the
/// exports' default edge).
pub const NOMINAL_EDGE_MM: Real = 20.0;

/// Whether a graded sheet opens and meets its target, with the sizes that say by how much.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GradedVerdict {
    /// It opens along one motion: every closed tile simple, no overlap and closed pins at
    /// every state of its path, one DOF, the closed tiling reached.
    pub opens: bool,
    /// Its error is within the tolerance.
    pub meets_target: bool,
    /// How far towards the target it was graded (1: the target asked; less: the nearest
    /// sheet found that opens, the target blended with the design's own sheet).
    pub target_fraction: Real,
    /// The error judged: the outline's Hausdorff distance to the target over the target's
    /// equivalent radius, or a field's largest relative cell error.
    pub error: Real,
    /// The largest error that meets the target.
    pub tolerance: Real,
    /// Deepest overlap of two tiles along the path (length scales; 0: none).
    pub deepest_overlap: Real,
    /// Its state's opening (fraction of the opened state's; None without an overlap).
    pub deepest_overlap_at: Option<Real>,
    /// Its two tiles (None without an overlap).
    pub deepest_overlap_tiles: Option<(usize, usize)>,
    /// Widest pin gap along the path (length scales).
    pub widest_pin_gap: Real,
    /// Closed tiles that are not simple polygons.
    pub self_intersecting: usize,
    /// The whole sheet's opening: its opened outer boundary's area over the closed one's.
    pub sheet_opening: Real,
    /// The largest area ratio the design's periodic sheet reaches along its path (None when
    /// not known: a sheet read from a file).
    pub periodic_opening: Option<Real>,
    /// The verdict in one line at [`NOMINAL_EDGE_MM`] edges ([`GradedVerdict::line`]): what
    /// every front end shows.
    pub text: String,
}

impl GradedVerdict {
    /// Judges a sheet from its path check, its error and the tolerance.
    pub fn new(
        path: &PathCheck,
        error: Real,
        tolerance: Real,
        target_fraction: Real,
        sheet_opening: Real,
        periodic_opening: Option<Real>,
    ) -> GradedVerdict {
        let deepest = path.deepest_overlap();
        let mut verdict = GradedVerdict {
            opens: path.reached,
            meets_target: error <= tolerance,
            target_fraction,
            error,
            tolerance,
            deepest_overlap: deepest.map_or(0.0, |s| s.overlap_depth),
            deepest_overlap_at: deepest.map(|s| s.opening),
            deepest_overlap_tiles: deepest.and_then(|s| s.overlap),
            widest_pin_gap: path.widest_gap().map_or(0.0, |s| s.joint_gap),
            self_intersecting: path.self_intersecting.len(),
            sheet_opening,
            periodic_opening,
            text: String::new(),
        };
        verdict.text = verdict.line(NOMINAL_EDGE_MM);
        verdict
    }

    /// It opens along one motion and meets its target.
    pub fn passed(&self) -> bool {
        self.opens && self.meets_target
    }

    /// The verdict in one line, sizes in millimetres at `edge_mm` edges and in edge lengths.
    pub fn line(&self, edge_mm: Real) -> String {
        let size = |l: Real| format!("{:.3} mm at {edge_mm} mm edges ({:.1e} L)", l * edge_mm, l);
        let mut parts = Vec::new();
        if self.opens {
            parts.push("opens along one motion".to_string());
        } else {
            parts.push("does NOT open along one motion".to_string());
            if self.self_intersecting > 0 {
                parts.push(format!(
                    "{} closed tiles cross themselves",
                    self.self_intersecting
                ));
            }
            if let Some(at) = self.deepest_overlap_at {
                parts.push(format!(
                    "tiles overlap {} deep at {:.0} % open",
                    size(self.deepest_overlap),
                    100.0 * at
                ));
            }
            parts.push(format!("pins gap {} at most", size(self.widest_pin_gap)));
        }
        parts.push(format!(
            "{} the target: off by {:.2} % (tolerance {:.2} %)",
            if self.meets_target { "meets" } else { "MISSES" },
            100.0 * self.error,
            100.0 * self.tolerance
        ));
        if self.target_fraction < 1.0 {
            parts.push(format!(
                "the target asked does not open; this is the sheet graded {:.0} % of the way to it from the design's own sheet",
                100.0 * self.target_fraction
            ));
        }
        parts.join("; ")
    }
}
