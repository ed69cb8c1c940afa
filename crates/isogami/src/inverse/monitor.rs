//! Progress and stopping across threads: the work runs on a scoped thread (and rayon's pool
//! from there) and sends an event after every evaluation; the calling thread turns events
//! into [`InverseProgress`] for the caller's callback, which need not be `Send` (a Python
//! callable, a terminal progress bar), and raises the stop flag when it returns `false`.

use super::request::{InverseProgress, Stage};
use crate::math::Real;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Sender};

/// What the work tells the calling thread.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Event {
    /// A stage starts with this many planned evaluations.
    Stage(Stage, usize),
    /// One evaluation finished, with its objective when valid.
    Evaluated(Option<Real>),
}

/// The work's side: the stop flag and the event channel.
pub(crate) struct Monitor<'a> {
    stop: &'a AtomicBool,
    events: Sender<Event>,
}

impl Monitor<'_> {
    /// The flag evaluations poll.
    pub(crate) fn stop_flag(&self) -> &AtomicBool {
        self.stop
    }

    /// True once the caller asked to stop.
    pub(crate) fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// Announces a stage.
    pub(crate) fn stage(&self, stage: Stage, total: usize) {
        // The receiver lives until the work returns; a send cannot fail before then.
        let _ = self.events.send(Event::Stage(stage, total));
    }

    /// Reports one evaluation.
    pub(crate) fn evaluated(&self, objective: Option<Real>) {
        let _ = self.events.send(Event::Evaluated(objective));
    }
}

/// Runs `work` on a scoped thread, feeding `progress` from the calling thread.
pub(crate) fn monitored<R: Send>(
    progress: &mut dyn FnMut(&InverseProgress) -> bool,
    work: impl FnOnce(&Monitor<'_>) -> R + Send,
) -> R {
    let stop = AtomicBool::new(false);
    let (tx, rx) = channel();
    std::thread::scope(|scope| {
        let flag = &stop;
        let handle = scope.spawn(move || {
            let monitor = Monitor {
                stop: flag,
                events: tx,
            };
            work(&monitor)
        });
        let mut state = InverseProgress {
            stage: Stage::Confirm,
            done: 0,
            total: 0,
            best: None,
        };
        // Ends when the work returns and drops its sender.
        for event in rx {
            match event {
                Event::Stage(stage, total) => {
                    state.stage = stage;
                    state.done = 0;
                    state.total = total;
                }
                Event::Evaluated(objective) => {
                    state.done += 1;
                    state.total = state.total.max(state.done);
                    if let Some(v) = objective {
                        state.best = Some(state.best.map_or(v, |b: Real| b.min(v)));
                    }
                }
            }
            if !stop.load(Ordering::Relaxed) && !progress(&state) {
                stop.store(true, Ordering::Relaxed);
            }
        }
        match handle.join() {
            Ok(r) => r,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}
