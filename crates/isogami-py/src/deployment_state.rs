//! A deployment's pickled state (see the `pickle` module): its report, its frames' data
//! and their state vectors, and the contact settings, from which the mechanism and contact
//! model are built again only when a drawing needs them.

use crate::deployment::PyDeployment;
use crate::errors;
use isogami::contact::ContactSettings;
use isogami::deploy::{DeploymentReport, FrameRecord};
use isogami::measure::FrameMeasures;
use pyo3::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// What a deployment keeps of the library's `Deployment` (not the trajectory): the report,
/// the frames' states and the contact settings the contact model is made with.
pub(crate) struct Held {
    pub(crate) report: DeploymentReport,
    pub(crate) frames: Vec<FrameRecord>,
    pub(crate) contact: ContactSettings,
}

/// A frame's data but its state vector (pickled as bytes).
#[derive(Serialize, Deserialize)]
struct FrameState {
    step: usize,
    t: f64,
    measures: FrameMeasures,
    joint_residual: f64,
    min_clearance: f64,
    inserted: bool,
}

/// A deployment's pickled data: the contact settings as (kerf, d̂, κ), the report and the
/// frames (their state vectors, all of one length, follow as one array).
#[derive(Serialize, Deserialize)]
struct DeploymentState {
    contact: [f64; 3],
    report: DeploymentReport,
    frames: Vec<FrameState>,
}

impl crate::pickle::Pickled for PyDeployment {
    const CLASS: &'static str = "Deployment";
    fn save(&self) -> PyResult<(Vec<u8>, Vec<Vec<f64>>)> {
        let h = &self.inner;
        let state = DeploymentState {
            contact: [h.contact.kerf, h.contact.dhat, h.contact.stiffness],
            report: h.report.clone(),
            frames: h
                .frames
                .iter()
                .map(|f| FrameState {
                    step: f.step,
                    t: f.t,
                    measures: f.measures.clone(),
                    joint_residual: f.joint_residual,
                    min_clearance: f.min_clearance,
                    inserted: f.inserted,
                })
                .collect(),
        };
        let q = h.frames.iter().flat_map(|f| f.q.iter().copied()).collect();
        Ok((crate::pickle::to_json(&state)?, vec![q]))
    }
    fn load(json: &[u8], arrays: Vec<Vec<f64>>) -> PyResult<Self> {
        let state: DeploymentState =
            Python::attach(|py| crate::pickle::from_json(py, Self::CLASS, json))?;
        let q = arrays.into_iter().next().unwrap_or_default();
        let n = state.frames.len().max(1);
        let len = q.len() / n;
        if len * state.frames.len() != q.len() {
            return Err(errors::IsogamiError::new_err(format!(
                "pickled deployment: {} state values for {} frames",
                q.len(),
                state.frames.len()
            )));
        }
        let frames = state
            .frames
            .into_iter()
            .zip(q.chunks(len.max(1)))
            .map(|(f, q)| FrameRecord {
                step: f.step,
                t: f.t,
                q: isogami::math::DVec::from_column_slice(q),
                measures: f.measures,
                joint_residual: f.joint_residual,
                min_clearance: f.min_clearance,
                inserted: f.inserted,
            })
            .collect();
        let [kerf, dhat, stiffness] = state.contact;
        Ok(PyDeployment {
            inner: Held {
                report: state.report,
                frames,
                contact: ContactSettings {
                    kerf,
                    dhat,
                    stiffness,
                },
            },
            scene: OnceLock::new(),
        })
    }
}
