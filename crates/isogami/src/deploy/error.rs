//! What can stop a deployment: settings, a design with nothing to deploy, a frame that fails
//! its final check, a report with a non-finite number, or the caller cancelling.

use crate::contact::{ContactError, Overlap};
use crate::math::Real;
use crate::measure::MeasureError;
use crate::mobility::MobilityError;
use crate::settings_error::SettingsError;
use std::fmt;
use thiserror::Error;

/// A deployment that could not be run or finished.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum DeployError {
    /// A deploy or contact setting outside its range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The contact model cannot be built or queried.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// The mobility analysis failed.
    #[error(transparent)]
    Mobility(#[from] MobilityError),
    /// A frame could not be measured.
    #[error(transparent)]
    Measure(#[from] MeasureError),
    /// A design with no degree of freedom.
    #[error("the design is rigid (0 degrees of freedom): nothing to deploy")]
    Rigid,
    /// A design whose degrees of freedom give no opening motion.
    #[error("the design is rigid: nothing to deploy (no opening motion among its {dof} degree(s) of freedom)")]
    NoMotion {
        /// Degrees of freedom found.
        dof: usize,
    },
    /// A pull whose grip is the held tile or not a tile of the mechanism.
    #[error("invalid setting: grip tile {grip} must be one of tiles 1..{tiles} (tile 0 is held)")]
    Grip {
        /// The grip asked for.
        grip: usize,
        /// Tiles of the mechanism.
        tiles: usize,
    },
    /// A first-order mode asked for that the design does not have.
    #[error("invalid setting: mode {mode} does not exist: the design has {dof} degree(s) of freedom ({})", modes_named(*dof))]
    ModeOutOfRange {
        /// The mode asked for.
        mode: usize,
        /// Degrees of freedom of the design.
        dof: usize,
    },
    /// A reported frame that breaks an invariant.
    #[error("numerical failure: step {step}: {problem}")]
    Frame {
        /// The accepted step (index into the trajectory).
        step: usize,
        /// What failed.
        problem: FrameProblem,
    },
    /// More frames asked for than the trajectory has states, and a state inserted between two
    /// of them could not be made or failed its frame check.
    #[error(
        "cannot return {asked} frames: the deployment has {states} states and a state inserted \
         after step {step} {problem}; ask for at most {states} frames (or all steps)"
    )]
    FrameCount {
        /// Frames asked for.
        asked: usize,
        /// States of the trajectory (accepted steps + 1): the most frames it gives without
        /// inserted states.
        states: usize,
        /// The accepted step the failed state was to follow.
        step: usize,
        /// What went wrong.
        problem: InsertProblem,
    },
    /// A deployment report holding NaN or infinity.
    #[error("numerical failure: deployment report field {field} is {value}")]
    ReportNotFinite {
        /// The first offending field.
        field: ReportField,
        /// Its value.
        value: Real,
    },
    /// The caller's progress callback asked to stop (a closed connection, Ctrl-C).
    #[error("cancelled")]
    Cancelled,
    /// One method of a comparison failed; says which.
    #[error("{method}: {error}")]
    InMethod {
        /// The method that failed.
        method: super::Method,
        /// Its error.
        error: Box<DeployError>,
    },
    /// A comparison measure that came out NaN or infinite.
    #[error("numerical failure: comparison: {method} gave a non-finite measure")]
    ComparisonNotFinite {
        /// The method.
        method: super::Method,
    },
    /// A trajectory without any state (never produced by `deploy`).
    #[error("numerical failure: a deployment without states")]
    EmptyTrajectory,
}

/// Why a frame failed its final check.
#[derive(Debug, Clone, PartialEq)]
pub enum FrameProblem {
    /// The state holds NaN or infinity.
    NonFinite,
    /// A joint open by more than the frame tolerance.
    JointResidual {
        /// Largest joint residual (units of L).
        residual: Real,
        /// The tolerance it exceeds.
        tolerance: Real,
    },
    /// Two collision polygons of the sheet overlap.
    Overlap(Overlap),
}

impl fmt::Display for FrameProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FrameProblem::NonFinite => f.write_str("state holds NaN or infinity"),
            FrameProblem::JointResidual {
                residual,
                tolerance,
            } => write!(f, "joint residual {residual:.3e} above {tolerance:.1e}"),
            FrameProblem::Overlap(o) => write!(f, "{o}"),
        }
    }
}

/// Why a state inserted between two accepted states (for a frame count above the number of
/// states) could not be used.
#[derive(Debug, Clone, PartialEq)]
pub enum InsertProblem {
    /// The projection onto the joint constraints produced NaN or infinity.
    NonFinite,
    /// The eigen-decomposition of the projection did not converge.
    Eigen,
    /// The projection did not close the joints to the step tolerance.
    NotConverged {
        /// Largest joint residual reached (units of L).
        residual: Real,
    },
    /// The projected state failed a frame check.
    Check(FrameProblem),
    /// The projected state's measures could not be taken.
    Measure(crate::measure::MeasureError),
    /// Its t is not above the previous frame's (the gap of t it was to split is too narrow).
    NotIncreasing,
}

impl fmt::Display for InsertProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            InsertProblem::NonFinite => f.write_str("became non-finite"),
            InsertProblem::Eigen => f.write_str("could not be projected (eigen-solver failed)"),
            InsertProblem::NotConverged { residual } => write!(
                f,
                "could not be projected onto the joints (residual {residual:.3e})"
            ),
            InsertProblem::Check(p) => write!(f, "fails its check: {p}"),
            InsertProblem::Measure(m) => write!(f, "cannot be measured: {m}"),
            InsertProblem::NotIncreasing => {
                f.write_str("would not be later in t than the frame before")
            }
        }
    }
}

/// A field of a deployment report: a top-level one, or one of frame `frame`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReportField {
    /// The frame, or `None` for a field of the whole report.
    pub frame: Option<usize>,
    /// The field's name, e.g. "area_ratio" or "F".
    pub name: &'static str,
}

impl fmt::Display for ReportField {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.frame {
            Some(k) => write!(f, "frames[{k}].{}", self.name),
            None => f.write_str(self.name),
        }
    }
}

/// The modes a design with `dof` degrees of freedom has, in words.
fn modes_named(dof: usize) -> String {
    match dof {
        0 => "no modes".into(),
        1 => "mode 0 only".into(),
        2 => "modes 0 and 1".into(),
        n => format!("modes 0 to {}", n - 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactModel;
    use crate::deploy::{build_report, deploy, frame_records, DeploySettings};
    use crate::kinematics::Mechanism;
    use crate::settings_error::{Requirement, SettingValue};
    use crate::topology::named_design;

    fn squares() -> Mechanism {
        let d = named_design("rotating-squares").unwrap();
        Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap()
    }

    #[test]
    fn settings_and_mode_errors_carry_their_values() {
        let mech = squares();
        let bad = DeploySettings {
            max_halvings: 51,
            ..DeploySettings::default()
        };
        match deploy(&mech, &bad, &mut |_| true) {
            Err(DeployError::Settings(e)) => {
                assert_eq!(e.name, "max_halvings");
                assert_eq!(e.value, SettingValue::Count(51));
                assert_eq!(e.requirement, Requirement::AtMost(50.0));
            }
            other => panic!("{other:?}"),
        }
        let mode = DeploySettings {
            mode: Some(3),
            ..DeploySettings::default()
        };
        assert_eq!(
            deploy(&mech, &mode, &mut |_| true).unwrap_err(),
            DeployError::ModeOutOfRange { mode: 3, dof: 1 }
        );
        // The modes named as they are (was "modes 0..2" for modes 0 and 1).
        let e = DeployError::ModeOutOfRange { mode: 2, dof: 2 }.to_string();
        assert!(e.ends_with("2 degree(s) of freedom (modes 0 and 1)"), "{e}");
        let e = DeployError::ModeOutOfRange { mode: 5, dof: 4 }.to_string();
        assert!(e.ends_with("(modes 0 to 3)"), "{e}");
        let stop = deploy(&mech, &DeploySettings::default(), &mut |n| n < 3);
        assert_eq!(stop.unwrap_err(), DeployError::Cancelled);
    }

    #[test]
    fn frame_and_report_failures_name_the_step_and_field() {
        let mech = squares();
        let settings = DeploySettings::default();
        let traj = deploy(&mech, &settings, &mut |_| true).unwrap();
        let contact = ContactModel::new(&mech, settings.contact).unwrap();
        let last = traj.steps.len() - 1;
        match frame_records(&mech, &contact, &traj, &[0, last], 0.0) {
            Err(DeployError::Frame {
                step,
                problem:
                    FrameProblem::JointResidual {
                        residual,
                        tolerance,
                    },
            }) => {
                assert!(step == 0 || step == last);
                assert!(residual > 0.0 && tolerance == 0.0);
            }
            other => panic!("{other:?}"),
        }
        let frames = frame_records(&mech, &contact, &traj, &[0, last], 1e-8).unwrap();
        let mut report =
            build_report("rotating-squares", &mech, &settings, &traj, &frames).unwrap();
        report.check_finite().unwrap();
        report.frames[1].t = f64::INFINITY;
        let e = report.check_finite().unwrap_err();
        assert!(matches!(
            e,
            DeployError::ReportNotFinite { field: ReportField { frame: Some(1), name: "t" }, value }
                if value == f64::INFINITY
        ));
        assert_eq!(
            e.to_string(),
            "numerical failure: deployment report field frames[1].t is inf"
        );
    }
}
