//! The caps a graded-sheet job obeys on this server, and the settings the browser's page
//! reads (`GET /api/graded`).

use isogami::graded::verdict::{FIELD_TOLERANCE, OUTLINE_TOLERANCE};
use isogami::graded::{GradedRequest, MAX_GRADED_CELLS, MAX_STATES};
use serde_json::{json, Value};
use std::time::Duration;

/// Caps of graded-sheet jobs. The defaults keep a run under about a minute on two cores
/// (a debug build is slower); larger sheets belong to `isogami graded` on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradedLimits {
    /// Most cells along either side of the region (default 8).
    pub max_side: usize,
    /// Most cells in the region, rows × columns (default 36).
    pub max_cells: usize,
    /// Most tiles in the region before its completion, rows × columns × the design's tiles
    /// per cell (default 300).
    pub max_tiles: usize,
    /// Most iterations of the fit (default 800; the library's default is lower).
    pub max_iterations: usize,
    /// Most states the pins must close in (default: the library's most).
    pub max_states: usize,
    /// Jobs running at once (default 2: a run takes one core most of the time).
    pub max_running: usize,
    /// Longest a job runs before it is stopped (default 3 min).
    pub max_run: Duration,
    /// A running job nobody polls for this long is stopped (default 60 s).
    pub abandon: Duration,
    /// An ended job is forgotten this long after it ended (default 10 min).
    pub keep: Duration,
    /// Most ended jobs remembered (default 16; the oldest go first).
    pub max_kept: usize,
    /// Least time between two snapshots of the sheet as it stands (default 200 ms: taking
    /// one clones the sheet).
    pub snapshot_every: Duration,
}

impl Default for GradedLimits {
    fn default() -> Self {
        GradedLimits {
            max_side: 8,
            max_cells: 36,
            max_tiles: 300,
            max_iterations: 800,
            max_states: MAX_STATES,
            max_running: 2,
            max_run: Duration::from_secs(180),
            abandon: Duration::from_secs(60),
            keep: Duration::from_secs(600),
            max_kept: 16,
            snapshot_every: Duration::from_millis(200),
        }
    }
}

impl GradedLimits {
    /// What the page needs: the request's defaults (the tolerance an outline target is met
    /// within, and a field's) and these caps.
    pub fn describe(&self) -> Value {
        let d = GradedRequest::default();
        json!({
            "defaults": {
                "design": d.design,
                "rows": 3,
                "cols": 3,
                "outline": "disc",
                "states": d.states,
                "iterations": d.solve.max_iterations,
                "tolerance": OUTLINE_TOLERANCE,
                "field_tolerance": FIELD_TOLERANCE,
                "fall_back": d.fall_back,
            },
            "limits": {
                "side": self.max_side.min(MAX_GRADED_CELLS),
                "cells": self.max_cells,
                "tiles": self.max_tiles,
                "iterations": self.max_iterations,
                "states": self.max_states.min(MAX_STATES),
                "running": self.max_running,
                "seconds": self.max_run.as_secs_f64(),
                "abandon_seconds": self.abandon.as_secs_f64(),
                "keep_seconds": self.keep.as_secs_f64(),
            },
        })
    }
}
