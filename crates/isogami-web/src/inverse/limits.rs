//! The caps an inverse-design job obeys on this server, and the settings the browser's panel
//! reads (`GET /api/inverse`; a static site stores the same under `inverse` in
//! `data/site.json`).

use isogami::inverse::{InverseRequest, Target};
use serde_json::{json, Value};
use std::time::Duration;

/// Caps of one inverse-design job. The defaults keep a run under a few minutes on two cores
/// (about 5 800 deployments at most, and [`max_run`](Self::max_run) regardless); larger
/// searches belong to `isogami inverse` on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InverseLimits {
    /// Most topologies kept and refined (default 5).
    pub max_top: usize,
    /// Most evaluations per refined design (default 200).
    pub max_budget: usize,
    /// Most pre-screened designs re-deployed (default 200).
    pub max_confirm: usize,
    /// Most screened designs given a first, short refinement (default 80 = 16 × 5, the
    /// library's default at the largest `top`).
    pub max_triage: usize,
    /// Most fresh shape samples per topology (default 20).
    pub max_samples: usize,
    /// Longest a job runs before it is stopped (default 5 min).
    pub max_run: Duration,
    /// A running job nobody polls for this long is stopped (default 60 s).
    pub abandon: Duration,
    /// An ended job is forgotten this long after it ended (default 10 min).
    pub keep: Duration,
    /// Most ended jobs remembered (default 16; the oldest go first).
    pub max_kept: usize,
}

impl Default for InverseLimits {
    fn default() -> Self {
        InverseLimits {
            max_top: 5,
            max_budget: 200,
            max_confirm: 200,
            max_triage: 80,
            max_samples: 20,
            max_run: Duration::from_secs(300),
            abandon: Duration::from_secs(60),
            keep: Duration::from_secs(600),
            max_kept: 16,
        }
    }
}

impl InverseLimits {
    /// What the panel needs: the request's defaults, these caps, whether saving is allowed
    /// and the database's file name (for the equivalent `isogami inverse` command).
    pub fn describe(&self, allow_save: bool, database: &str) -> Value {
        let d = InverseRequest::new(Target {
            terms: Vec::new(),
            constraints: Default::default(),
        });
        json!({
            "defaults": {
                "top": d.top,
                "budget": d.budget,
                "samples": d.samples,
                "kerf": d.kerf,
                "refine_kerf": d.refine_kerf,
            },
            "limits": {
                "top": self.max_top,
                "budget": self.max_budget,
                "confirm": self.max_confirm,
                "triage": self.max_triage,
                "samples": self.max_samples,
                "seconds": self.max_run.as_secs_f64(),
                "abandon_seconds": self.abandon.as_secs_f64(),
                "keep_seconds": self.keep.as_secs_f64(),
            },
            "save": allow_save,
            "database": database,
        })
    }
}
