//! Frames for output: exactly the number of states asked for, evenly in t, each with its
//! measures and its invariants (joint residual, clearance) recomputed independently of the
//! solver.
//!
//! When the trajectory has at least as many states as frames asked for, the frames are
//! distinct accepted states ([`select_frames`]). When it has fewer, every accepted state is a
//! frame and the missing ones are inserted between accepted states, in the widest gaps of t
//! first ([`plan_frames`]), each projected back onto the joint constraints (`insert.rs`) and
//! then checked like every other frame. A frame count that cannot be honoured is refused
//! ([`DeployError::FrameCount`]), never answered with fewer frames.

use super::error::{DeployError, FrameProblem, InsertProblem};
use super::insert::project_between;
use super::settings::DeploySettings;
use super::trajectory::Trajectory;
use crate::contact::ContactModel;
use crate::kinematics::Mechanism;
use crate::math::{DVec, Real};
use crate::measure::FrameMeasures;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// One output frame.
#[derive(Debug, Clone)]
pub struct FrameRecord {
    /// Index of the raw step; for an inserted state, the accepted step it follows.
    pub step: usize,
    /// Normalised arc length.
    pub t: Real,
    /// The state (non-dimensional).
    pub q: DVec,
    /// Expansion measures at this state.
    pub measures: FrameMeasures,
    /// Largest joint residual, recomputed (units of L).
    pub joint_residual: Real,
    /// Smallest clearance between collision polygons, recomputed (units of L).
    pub min_clearance: Real,
    /// True for a state inserted between accepted steps `step` and `step + 1` because more
    /// frames were asked for than the trajectory has states (see [`FramePick::Between`]).
    pub inserted: bool,
}

/// Where one frame comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FramePick {
    /// Accepted state `k` of the trajectory, as it is.
    Step(usize),
    /// A state between accepted states `step` and `step + 1`: the point `fraction` ∈ (0, 1) of
    /// the way along the chord between them, projected onto the joint constraints by a
    /// minimum-norm Gauss–Newton correction (orthogonal to the motion to first order). Its t is
    /// that of the chord's point, t_k + fraction · (t_{k+1} − t_k).
    Between {
        /// The accepted step before it.
        step: usize,
        /// How far along the chord, strictly between 0 and 1.
        fraction: Real,
    },
}

/// Indices of `min(count, states)` distinct accepted states, increasing, nearest to evenly
/// spaced t (`count` is at least 2; the first and the last state are always included).
///
/// Frame j aims at t = j / (count − 1); it takes the state nearest that t unless an earlier
/// frame took it or later frames would run out of states, in which case it takes the nearest
/// state that keeps the assignment strictly increasing with room for the rest. Accepted states
/// are used as they are, never interpolated, so every index is an exact solution of the joint
/// constraints. Exports pick their states this way; deployment frames go through
/// [`plan_frames`], which inserts states when there are fewer than asked for.
pub fn select_frames(traj: &Trajectory, count: usize) -> Vec<usize> {
    let n = traj.steps.len();
    if n == 0 {
        return Vec::new();
    }
    if n == 1 {
        return vec![0];
    }
    let count = count.clamp(2, n);
    let mut out: Vec<usize> = Vec::with_capacity(count);
    let mut nearest = 0;
    for j in 0..count {
        let target = j as Real / (count - 1) as Real;
        while nearest + 1 < n
            && (traj.t(nearest + 1) - target).abs() <= (traj.t(nearest) - target).abs()
        {
            nearest += 1;
        }
        // Frame j needs a state after the previous frame's and must leave count − 1 − j
        // states for the frames after it.
        let low = out.last().map_or(0, |&k| k + 1);
        let high = n - count + j;
        out.push(nearest.clamp(low, high));
    }
    debug_assert_eq!(out.len(), count);
    debug_assert!(out[0] == 0 && out[count - 1] == n - 1);
    out
}

/// Where each of `count` frames comes from: exactly `count` picks, increasing in t, the closed
/// state first and the final state last. With at least `count` states, the accepted states of
/// [`select_frames`]; with fewer, every accepted state plus `count − states` states inserted
/// between them, each gap of t cut into pieces as even as possible (the next insert goes to
/// the gap whose pieces are widest).
///
/// A trajectory of one state (a deployment that never left the closed state, such as a
/// locked design) has one pick whatever `count` is: there is no path to place other frames
/// on, and its `end_reason` says why.
pub fn plan_frames(traj: &Trajectory, count: usize) -> Vec<FramePick> {
    let n = traj.steps.len();
    let count = count.max(2);
    if n <= 1 || n >= count {
        return select_frames(traj, count)
            .into_iter()
            .map(FramePick::Step)
            .collect();
    }
    let mut pieces = vec![1usize; n - 1];
    let mut heap: BinaryHeap<Gap> = (0..n - 1)
        .map(|k| Gap {
            width: traj.t(k + 1) - traj.t(k),
            segment: k,
        })
        .collect();
    for _ in 0..count - n {
        let widest = heap
            .pop()
            .expect("a trajectory of two or more states has a gap");
        let k = widest.segment;
        pieces[k] += 1;
        heap.push(Gap {
            width: (traj.t(k + 1) - traj.t(k)) / pieces[k] as Real,
            segment: k,
        });
    }
    let mut picks = Vec::with_capacity(count);
    for (k, &p) in pieces.iter().enumerate() {
        picks.push(FramePick::Step(k));
        picks.extend((1..p).map(|i| FramePick::Between {
            step: k,
            fraction: i as Real / p as Real,
        }));
    }
    picks.push(FramePick::Step(n - 1));
    debug_assert_eq!(picks.len(), count);
    picks
}

/// A gap of t between two accepted states, as cut so far: the widest piece comes first, ties
/// to the earlier segment, so the plan is deterministic.
#[derive(Debug, Clone, Copy)]
struct Gap {
    width: Real,
    segment: usize,
}

impl PartialEq for Gap {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Gap {}

impl PartialOrd for Gap {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Gap {
    fn cmp(&self, other: &Self) -> Ordering {
        self.width
            .total_cmp(&other.width)
            .then(other.segment.cmp(&self.segment))
    }
}

/// Frame records for the chosen steps; fails if a frame breaks an invariant (a joint open
/// by more than `joint_tolerance`, overlapping tiles, a non-finite value).
pub fn frame_records(
    mech: &Mechanism,
    contact: &ContactModel,
    traj: &Trajectory,
    indices: &[usize],
    joint_tolerance: Real,
) -> Result<Vec<FrameRecord>, DeployError> {
    indices
        .iter()
        .map(|&k| {
            let fail = |problem| DeployError::Frame { step: k, problem };
            checked_record(
                mech,
                contact,
                &traj.steps[k].q,
                k,
                traj.t(k),
                joint_tolerance,
            )
            .map_err(|e| e.into_error(fail))
        })
        .collect()
}

/// How many times an inserted state that fails its check is moved halfway towards the frame
/// before it before the frame count is refused.
const INSERT_RETRIES: usize = 10;

/// Frame records for `picks` (from [`plan_frames`]): accepted states as
/// [`frame_records`] checks them; inserted states projected onto the joint constraints (to
/// `settings.joint_tolerance`, like an accepted step) and then given the same checks. An
/// inserted state that cannot be made or fails a check is moved towards the frame before it
/// (at most [`INSERT_RETRIES`] times) before it refuses the whole frame count
/// ([`DeployError::FrameCount`], which says how many frames the trajectory can give).
pub fn frame_records_for(
    mech: &Mechanism,
    contact: &ContactModel,
    traj: &Trajectory,
    picks: &[FramePick],
    settings: &DeploySettings,
) -> Result<Vec<FrameRecord>, DeployError> {
    let tolerance = settings.frame_joint_tolerance;
    let refuse = |step: usize, problem: InsertProblem| DeployError::FrameCount {
        asked: picks.len(),
        states: traj.steps.len(),
        step,
        problem,
    };
    let mut out: Vec<FrameRecord> = Vec::with_capacity(picks.len());
    for &pick in picks {
        let record = match pick {
            FramePick::Step(k) => {
                let fail = |problem| DeployError::Frame { step: k, problem };
                checked_record(mech, contact, &traj.steps[k].q, k, traj.t(k), tolerance)
                    .map_err(|e| e.into_error(fail))?
            }
            FramePick::Between { step, fraction } => {
                let (t0, t1) = (traj.t(step), traj.t(step + 1));
                // Where the frame before it sits in this gap (0: the accepted state itself).
                let low = match out.last() {
                    Some(prev) if prev.step == step && prev.inserted && t1 > t0 => {
                        (prev.t - t0) / (t1 - t0)
                    }
                    _ => 0.0,
                };
                // A chord point near contact may project onto an overlapping state: move it
                // towards the clean state before it (halving its distance, a few times), so
                // the frame count is still honoured, a little off even spacing in t.
                let mut f = fraction;
                let mut attempt = 0;
                loop {
                    let tried = project_between(mech, traj, step, f, settings).and_then(|q| {
                        let t = t0 + f * (t1 - t0);
                        checked_record(mech, contact, &q, step, t, tolerance).map_err(|e| match e {
                            Check::Frame(p) => InsertProblem::Check(p),
                            Check::Measure(m) => InsertProblem::Measure(m),
                        })
                    });
                    match tried {
                        Ok(mut r) => {
                            r.inserted = true;
                            break r;
                        }
                        Err(p) if attempt >= INSERT_RETRIES => return Err(refuse(step, p)),
                        Err(_) => {
                            attempt += 1;
                            f = low + 0.5 * (f - low);
                        }
                    }
                }
            }
        };
        if let Some(prev) = out.last() {
            if record.t <= prev.t {
                return Err(refuse(record.step, InsertProblem::NotIncreasing));
            }
        }
        out.push(record);
    }
    Ok(out)
}

/// Why a state failed its frame check.
enum Check {
    /// A broken invariant.
    Frame(FrameProblem),
    /// The measures could not be taken.
    Measure(crate::measure::MeasureError),
}

impl Check {
    fn into_error(self, frame: impl FnOnce(FrameProblem) -> DeployError) -> DeployError {
        match self {
            Check::Frame(p) => frame(p),
            Check::Measure(m) => DeployError::Measure(m),
        }
    }
}

/// The record of state `q` at `t` after the checks every frame gets: finite, joints closed
/// to `joint_tolerance`, no two collision polygons overlapping (exact test).
fn checked_record(
    mech: &Mechanism,
    contact: &ContactModel,
    q: &DVec,
    step: usize,
    t: Real,
    joint_tolerance: Real,
) -> Result<FrameRecord, Check> {
    if q.iter().any(|x| !x.is_finite()) {
        return Err(Check::Frame(FrameProblem::NonFinite));
    }
    let joint_residual = mech.residual(q).amax();
    if joint_residual > joint_tolerance {
        return Err(Check::Frame(FrameProblem::JointResidual {
            residual: joint_residual,
            tolerance: joint_tolerance,
        }));
    }
    if let Some(overlap) = contact.overlapping_pair(mech, q) {
        return Err(Check::Frame(FrameProblem::Overlap(overlap)));
    }
    Ok(FrameRecord {
        step,
        t,
        q: q.clone(),
        measures: FrameMeasures::from_states(mech, &mech.rest, q, t).map_err(Check::Measure)?,
        joint_residual,
        min_clearance: contact.min_clearance(mech, q),
        inserted: false,
    })
}
