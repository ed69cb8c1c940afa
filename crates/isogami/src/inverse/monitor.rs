//! Progress and stopping across threads: the work runs on a scoped thread (and rayon's pool
//! from there) and sends an event after every evaluation; the calling thread turns events
//! into [`InverseProgress`] for the caller's callback, which need not be `Send` (a Python
//! callable, a terminal progress bar), and raises the stop flag when it returns `false`.
//!
//! The leader board (the best valid design so far of each topology) stays cheap: the work
//! side keeps each topology's best objective and sends a design's spec only when it improves
//! its topology's best (a few dozen times in a run of thousands of evaluations); the calling
//! thread keeps one [`Leader`] per topology and re-sorts the list only on those events.

use super::evaluate::Evaluation;
use super::request::{InverseProgress, Leader, Stage};
use crate::math::Real;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, Sender};
use std::sync::Mutex;

/// What the work tells the calling thread.
#[derive(Debug, Clone)]
pub(crate) enum Event {
    /// A stage starts with this many planned evaluations.
    Stage(Stage, usize),
    /// One evaluation finished, with its objective when valid, and the design when it
    /// improved its topology's best.
    Evaluated(Option<Real>, Option<Improvement>),
}

/// A valid design that improved its topology's best.
#[derive(Debug, Clone)]
pub(crate) struct Improvement {
    topology: String,
    spec: String,
    kerf: Real,
    objective: Real,
}

/// The work's side: the stop flag, the event channel and each topology's best objective.
pub(crate) struct Monitor<'a> {
    stop: &'a AtomicBool,
    events: Sender<Event>,
    bests: Mutex<HashMap<String, Real>>,
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

    /// Reports one evaluation of a design of `topology`.
    pub(crate) fn evaluated(&self, e: &Evaluation, topology: &str) {
        let Some(v) = e.objective() else {
            let _ = self.events.send(Event::Evaluated(None, None));
            return;
        };
        // Sent while the lock is held, so a topology's improvements arrive in order.
        let mut bests = self.bests.lock().unwrap_or_else(|p| p.into_inner());
        let improves = bests.get(topology).is_none_or(|&b| v < b);
        let improvement = improves.then(|| {
            bests.insert(topology.to_string(), v);
            Improvement {
                topology: topology.to_string(),
                spec: e.design.to_string(),
                kerf: e.kerf,
                objective: v,
            }
        });
        let _ = self.events.send(Event::Evaluated(Some(v), improvement));
    }
}

/// The calling thread's view of the run: the progress it reports and every topology's leader.
struct Board {
    state: InverseProgress,
    leaders: HashMap<String, Leader>,
    shown: usize,
}

impl Board {
    fn new(shown: usize) -> Board {
        Board {
            state: InverseProgress {
                stage: Stage::Confirm,
                done: 0,
                total: 0,
                best: None,
                leaders: Vec::new(),
            },
            leaders: HashMap::new(),
            shown,
        }
    }

    /// Applies `event`.
    fn apply(&mut self, event: Event) {
        let state = &mut self.state;
        match event {
            Event::Stage(stage, total) => {
                state.stage = stage;
                state.done = 0;
                state.total = total;
            }
            Event::Evaluated(objective, improvement) => {
                state.done += 1;
                state.total = state.total.max(state.done);
                if let Some(v) = objective {
                    state.best = Some(state.best.map_or(v, |b: Real| b.min(v)));
                }
                if let Some(i) = improvement {
                    self.improve(i);
                }
            }
        }
    }

    /// Takes `i` as its topology's leader if it is better, and re-sorts the list shown.
    fn improve(&mut self, i: Improvement) {
        let better = self
            .leaders
            .get(&i.topology)
            .is_none_or(|l| i.objective < l.objective);
        if !better {
            return;
        }
        let leader = Leader {
            topology: i.topology.clone(),
            spec: i.spec,
            kerf: i.kerf,
            objective: i.objective,
            stage: self.state.stage,
        };
        self.leaders.insert(i.topology, leader);
        let mut all: Vec<&Leader> = self.leaders.values().collect();
        all.sort_by(|a, b| {
            a.objective
                .total_cmp(&b.objective)
                .then_with(|| a.topology.cmp(&b.topology))
        });
        self.state.leaders = all.into_iter().take(self.shown).cloned().collect();
    }
}

/// Runs `work` on a scoped thread, feeding `progress` from the calling thread; progress
/// reports list at most `shown` leaders.
pub(crate) fn monitored<R: Send>(
    progress: &mut dyn FnMut(&InverseProgress) -> bool,
    shown: usize,
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
                bests: Mutex::new(HashMap::new()),
            };
            work(&monitor)
        });
        let mut board = Board::new(shown);
        // Ends when the work returns and drops its sender.
        for event in rx {
            board.apply(event);
            if !stop.load(Ordering::Relaxed) && !progress(&board.state) {
                stop.store(true, Ordering::Relaxed);
            }
        }
        match handle.join() {
            Ok(r) => r,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn improved(topology: &str, objective: Real) -> Event {
        let i = Improvement {
            topology: topology.into(),
            spec: format!("{topology}@{objective}"),
            kerf: 0.01,
            objective,
        };
        Event::Evaluated(Some(objective), Some(i))
    }

    #[test]
    fn the_board_keeps_each_topologys_best_sorted_and_bounded() {
        let mut board = Board::new(2);
        board.apply(improved("a", 3.0));
        board.apply(Event::Evaluated(Some(3.5), None));
        assert_eq!((board.state.done, board.state.best), (2, Some(3.0)));
        board.apply(Event::Stage(Stage::Triage, 10));
        board.apply(improved("b", 2.0));
        // Arriving late from another thread, a worse value for `a` changes nothing.
        board.apply(improved("a", 4.0));
        board.apply(improved("c", 5.0));
        let names = |b: &Board| {
            b.state
                .leaders
                .iter()
                .map(|l| (l.topology.clone(), l.objective))
                .collect::<Vec<_>>()
        };
        assert_eq!(names(&board), [("b".into(), 2.0), ("a".into(), 3.0)]);
        board.apply(improved("c", 1.0));
        assert_eq!(names(&board), [("c".into(), 1.0), ("b".into(), 2.0)]);
        let c = &board.state.leaders[0];
        assert_eq!((c.spec.as_str(), c.stage), ("c@1", Stage::Triage));
        assert_eq!(board.leaders["a"].spec, "a@3", "kept though not shown");
    }
}
