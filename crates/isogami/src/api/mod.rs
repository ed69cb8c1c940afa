//! The library's entry points: one function per job, plain data in and out. The CLI, the
//! exploration, the server (`isogami-web`) and the Python bindings (`isogami-py`) call these
//! and hold no pipeline logic of their own, so every front end resolves, validates, analyses
//! and deploys a design the same way.
//!
//! | job | function | returns |
//! |---|---|---|
//! | read a design (name, spec string or JSON) | [`resolve_design`] | [`Design`] |
//! | mobility | [`analyze`] | [`Analysis`] |
//! | deployment | [`deploy`] | [`Deployment`] (the serialisable report and the states) |
//! | deployment in two halves (judge before choosing frames) | [`deploy_path`], [`DeployedPath::into_deployment`] | [`DeployedPath`], then [`Deployment`] |
//! | linkages | [`linkages`] | [`LinkageAnalysis`] |
//! | baseline comparison | [`compare`], [`compare_with`] (progress, cancel) | [`DesignComparison`]: one result per method |
//! | a finite region: mobility with a free boundary, completion to one DOF | [`finite_sheet`] | [`SheetAnalysis`] |
//! | drawing and joint editing | [`sheet_geometry`], [`tile_linkages`] | [`SheetGeometry`] |
//!
//! ```
//! use isogami::api::{deploy, resolve_design, DeployRequest};
//!
//! let design = resolve_design("rotating-squares")?;
//! let run = deploy(&design, &DeployRequest::default(), &mut |_| true)?;
//! assert_eq!(run.report.dof, 1);
//! assert!((run.report.max_area_ratio - 2.0).abs() < 1e-3); // 45°: cos φ + sin φ = √2
//! # Ok::<(), isogami::Error>(())
//! ```

use crate::cell::UnitCell;
use crate::contact::ContactModel;
use crate::deploy::{
    build_report, compare_design_with, deploy_with, frame_records_for, plan_frames,
    summarize_steps, DeploySettings, DeploymentReport, DesignComparison, FramePick, FrameRecord,
    Progress, StepSummary, Trajectory,
};
use crate::error::Result;
use crate::kinematics::Mechanism;
use crate::linkage::{analyze_linkages, LinkageAnalysis};
use crate::math::Real;
use crate::mobility::{Mobility, MobilitySettings};
use crate::settings_error::{Requirement, SettingsError};
pub use crate::topology::Design;
use serde::Serialize;

pub(crate) mod finite;
mod graded;
mod sheet;
mod sheet_deploy;
mod sheet_pull;
pub use finite::{finite_sheet, SheetAnalysis, SheetRequest};
pub(crate) use finite::{opened_step, requested_sheet, sheet_of_trajectory};
pub use graded::{field_results, graded_sheet, FieldResult, GradedRun, PATH_STEPS};
pub use sheet::{sheet_geometry, tile_linkages, EdgeGeometry, SheetGeometry};
pub use sheet_deploy::{
    deploy_sheet, PeriodicEnd, SheetDeployRequest, SheetDeployment, SheetFrame,
};
pub use sheet_pull::{pull_sheet, PullFrame, PullLeave, SheetPull, SheetPullRequest};

/// Most frames a deployment report may hold when frames are picked evenly in t.
pub const MAX_FRAME_COUNT: usize = 10_000;

/// Reads a design given as a name (`rotating-squares`), a spec string
/// (`FAMILY:PARAMS:CELL:JOINTS`) or design JSON, and checks that it builds: valid shape
/// parameters, a supported cell, one joint choice per unique edge.
pub fn resolve_design(text: &str) -> Result<Design> {
    let design = Design::resolve(text)?;
    design.cell()?;
    Ok(design)
}

/// The mobility analysis of a design, with the counts a reader wants beside it.
#[derive(Debug, Clone, Serialize, serde::Deserialize)]
pub struct Analysis {
    /// Spec string.
    pub design: String,
    /// Tiles in the cell.
    pub tiles: usize,
    /// Unique edges of the cell.
    pub edges: usize,
    /// Pin joints.
    pub joints: usize,
    /// Mean edge length L (tiling units).
    pub length_scale: Real,
    /// Degrees of freedom, spectrum, gap and first-order motions.
    #[serde(flatten)]
    pub mobility: Mobility,
}

/// The cell and mechanism of a design.
fn assemble(design: &Design) -> Result<(UnitCell, Mechanism)> {
    let cell = design.cell()?;
    let mech = Mechanism::new(&cell, &design.joints)?;
    Ok((cell, mech))
}

/// Mobility of a design in its closed state (paper §3.2).
pub fn analyze(design: &Design, settings: MobilitySettings) -> Result<Analysis> {
    settings.validate()?;
    let (cell, mech) = assemble(design)?;
    let mobility = crate::mobility::analyze(&mech, &mech.rest, settings)?;
    Ok(Analysis {
        design: design.to_string(),
        tiles: cell.tiles.len(),
        edges: cell.edges.len(),
        joints: mech.joints.len(),
        length_scale: mech.length_scale,
        mobility,
    })
}

/// Which accepted states a deployment report keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameSelection {
    /// Exactly this many states, in 2..=[`MAX_FRAME_COUNT`], increasing in t, the closed state
    /// first and the final state last: distinct accepted states nearest to evenly spaced t
    /// when the trajectory has that many; otherwise every accepted state plus states inserted
    /// between them, projected onto the joint constraints and checked like every frame (see
    /// [`plan_frames`](crate::deploy::plan_frames); a count that cannot be honoured is
    /// refused with [`DeployError::FrameCount`](crate::deploy::DeployError::FrameCount)). A
    /// trajectory of one state (a locked design) has one frame. Summaries never depend on it.
    Evenly(usize),
    /// Every accepted state.
    AllSteps,
}

/// What to deploy with and what to keep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeployRequest {
    /// Method, contact, step control, tolerances.
    pub settings: DeploySettings,
    /// Which states become frames.
    pub frames: FrameSelection,
}

impl Default for DeployRequest {
    /// Rigid modes with default settings, 60 frames.
    fn default() -> Self {
        DeployRequest {
            settings: DeploySettings::default(),
            frames: FrameSelection::Evenly(60),
        }
    }
}

impl DeployRequest {
    /// Checks the settings and the frame selection.
    pub fn validate(&self) -> std::result::Result<(), SettingsError> {
        self.settings.validate()?;
        if let FrameSelection::Evenly(n) = self.frames {
            if !(2..=MAX_FRAME_COUNT).contains(&n) {
                return Err(SettingsError::new(
                    "frame count",
                    n,
                    Requirement::CountIn {
                        low: 2,
                        high: MAX_FRAME_COUNT as u64,
                    },
                ));
            }
        }
        Ok(())
    }
}

/// A finished deployment: the report every front end shows or stores, and the mechanism,
/// contact model and checked frame states that renderers and exporters need.
#[derive(Debug, Clone)]
pub struct Deployment {
    /// The serialisable report.
    pub report: DeploymentReport,
    /// The frames behind the report (non-dimensional states), in the same order.
    pub frames: Vec<FrameRecord>,
    /// The mechanism the states belong to.
    pub mechanism: Mechanism,
    /// Its contact model (kerf-inset collision polygons).
    pub contact: ContactModel,
    /// Every accepted state.
    pub trajectory: Trajectory,
}

/// Deploys a design from its closed state to the contact limit (paper §3.2) with the
/// request's method and settings. Rigid designs are refused; a design with several degrees
/// of freedom follows its fastest-opening first-order motion and says so (`report.dof`).
/// Every reported frame is re-checked: joints closed to `frame_joint_tolerance`, no two
/// collision polygons of the sheet overlapping, every number finite.
///
/// `progress` is called after every accepted step with the number of states so far; when it
/// returns `false` the run stops with
/// [`DeployError::Cancelled`](crate::deploy::DeployError::Cancelled) (see
/// [`Error::is_cancelled`](crate::Error::is_cancelled)).
pub fn deploy(
    design: &Design,
    request: &DeployRequest,
    progress: Progress<'_>,
) -> Result<Deployment> {
    request.validate()?;
    deploy_path(design, &request.settings, progress)?.into_deployment(design, request.frames)
}

/// A deployment before its frames are chosen: the trajectory of every accepted state, with
/// its mechanism and contact model. Enough to judge a design from its summaries
/// ([`DeployedPath::summary`]) before paying for frames, which [`DeployedPath::into_deployment`]
/// adds (states inserted between accepted ones are projected and checked, which costs more
/// than a short trajectory itself).
#[derive(Debug, Clone)]
pub struct DeployedPath {
    /// The mechanism the states belong to.
    pub mechanism: Mechanism,
    /// Its contact model.
    pub contact: ContactModel,
    /// Every accepted state.
    pub trajectory: Trajectory,
    /// The settings it was deployed with.
    pub settings: DeploySettings,
}

impl DeployedPath {
    /// Summaries over every accepted state (what the report's top-level fields will hold).
    pub fn summary(&self) -> Result<StepSummary> {
        Ok(summarize_steps(&self.mechanism, &self.trajectory)?)
    }

    /// The finished deployment with `frames` chosen and checked, and its report.
    pub fn into_deployment(self, design: &Design, frames: FrameSelection) -> Result<Deployment> {
        DeployRequest {
            settings: self.settings,
            frames,
        }
        .validate()?;
        let DeployedPath {
            mechanism: mech,
            contact,
            trajectory,
            settings,
        } = self;
        let picks = match frames {
            FrameSelection::AllSteps => (0..trajectory.steps.len()).map(FramePick::Step).collect(),
            FrameSelection::Evenly(n) => plan_frames(&trajectory, n),
        };
        let frames = frame_records_for(&mech, &contact, &trajectory, &picks, &settings)?;
        let report = build_report(&design.to_string(), &mech, &settings, &trajectory, &frames)?;
        report.check_finite()?;
        Ok(Deployment {
            report,
            frames,
            mechanism: mech,
            contact,
            trajectory,
        })
    }
}

/// The first half of [`deploy`]: the design's trajectory from its closed state to the end of
/// its motion, without frames (see [`DeployedPath`]).
pub fn deploy_path(
    design: &Design,
    settings: &DeploySettings,
    progress: Progress<'_>,
) -> Result<DeployedPath> {
    settings.validate()?;
    let (_, mech) = assemble(design)?;
    let contact = ContactModel::new(&mech, settings.contact)?;
    let trajectory = deploy_with(&mech, &contact, settings, progress)?;
    Ok(DeployedPath {
        mechanism: mech,
        contact,
        trajectory,
        settings: *settings,
    })
}

/// The linkage analysis of a design (paper §5.1).
pub fn linkages(design: &Design) -> Result<LinkageAnalysis> {
    let cell = design.cell()?;
    Ok(analyze_linkages(&cell, &design.joints)?)
}

/// Rigid modes, NCM and springs on the same design with otherwise equal settings (paper §5,
/// Fig. 4): how far along the rigid-modes path each gets and how much it opens.
pub fn compare(design: &Design, settings: &DeploySettings) -> Result<DesignComparison> {
    compare_with(design, settings, &mut |_| true)
}

/// [`compare`] with a progress callback: called after every accepted step of each method
/// with that method's number of states so far; when it returns `false` the comparison stops
/// with [`DeployError::Cancelled`](crate::deploy::DeployError::Cancelled).
pub fn compare_with(
    design: &Design,
    settings: &DeploySettings,
    progress: Progress<'_>,
) -> Result<DesignComparison> {
    settings.validate()?;
    compare_design_with(design, settings, progress)
}
