//! Catalogue building: the last stages of the exploration (paper §4.1, deployment and the
//! expansion threshold; §4.2, shape sampling) and the characterisation of every kept design.
//!
//! A work unit is one (family, supercell): enumerate its joint topologies (`explore`), deploy
//! each unique topology at the default shape and keep those that expand past the threshold,
//! then sample the family's shape parameters for each kept topology, deploy every sample and
//! keep those past the threshold, each with its deployment report, linkage analysis and the figures of its finite 6×6 patch
//! ([`FiniteFigures`], from the same deployment). Designs
//! whose cuts shut too soon along both signs are screened out cheaply before deployment
//! ([`screen`]). Work
//! units are deterministic and independent, so they can run in any order, in parallel, or on
//! different machines. Plain data out; storing is the caller's business.

mod assess;
mod finite;
mod margins;
pub mod part;
pub mod screen;
mod settings;
mod unit;

pub use assess::{assess, Assessment, Rejection};
pub use finite::{finite_figures, finite_request, FiniteFigures, FINITE_PATCH_CELLS};
pub use margins::{
    largest_area_ratio, margins, margins_report, margins_report_of_trajectory, shape_move, Margins,
    MarginsReport, ShapeMove, FABRICATION_TOLERANCE, KEPT_FRACTION, TOLERANCE_LEVELS,
};
pub use part::{combine_parts, run_unit_part, PartClass, PartOutcome};
pub use settings::CatalogSettings;
pub use unit::{run_unit, CatalogEntry, StageTally, UnitOutcome};
