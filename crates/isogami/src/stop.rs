//! Stopping long work from outside.
//!
//! A deployment reports to a [`Progress`] callback after every accepted state, and the
//! callback's `false` stops it. The stages after a deployment (a finite sheet's completion,
//! a print's layout and solid) run rounds in parallel, where a `FnMut` cannot be called, so
//! they poll a [`KeepGoing`] check instead; [`watched`] makes one from a caller's progress
//! callback, asking it on the caller's thread while the work runs on another.

use crate::deploy::Progress;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// A check that work polls between its rounds: `true` while it should go on.
pub type KeepGoing<'a> = &'a (dyn Fn() -> bool + Sync);

fn go_on() -> bool {
    true
}

/// A check that never stops the work.
pub const NEVER: KeepGoing<'static> = &go_on;

/// How often [`watched`] asks the caller's progress callback.
const POLL: Duration = Duration::from_millis(20);

/// Runs `work` on a scoped thread with a check that turns `false` for good once `progress`
/// returns `false`. `progress` is asked on the calling thread every 20 ms while `work`
/// runs, with `states`: the count of states it last saw (the work adds none), so a progress
/// bar stands still and a callback that stops on a deadline or a signal is still heard.
/// A panic in `work` is resumed on the calling thread.
///
/// Called on a worker of rayon's pool (a parallel caller, such as inverse design's
/// evaluations), the work runs on that thread instead, its check fixed by one question to
/// `progress` before it starts: blocking the worker while the work's own parallel parts wait
/// for the pool could leave the pool with no thread to run them.
pub fn watched<T: Send>(
    progress: Progress<'_>,
    states: usize,
    work: impl FnOnce(KeepGoing<'_>) -> T + Send,
) -> T {
    if rayon::current_thread_index().is_some() {
        let go_on = progress(states);
        return work(&move || go_on);
    }
    let stop = AtomicBool::new(false);
    let caller = std::thread::current();
    std::thread::scope(|scope| {
        let stop = &stop;
        let worker = scope.spawn(move || {
            let out = work(&|| !stop.load(Ordering::Relaxed));
            caller.unpark();
            out
        });
        while !worker.is_finished() {
            if !stop.load(Ordering::Relaxed) && !progress(states) {
                stop.store(true, Ordering::Relaxed);
            }
            std::thread::park_timeout(POLL);
        }
        worker
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    #[test]
    fn work_that_ends_by_itself_returns_its_value() {
        // The callback is asked with the count given (how often depends on scheduling).
        let out = watched(
            &mut |n| {
                assert_eq!(n, 7);
                true
            },
            7,
            |keep_going| keep_going() as u32 + 1,
        );
        assert_eq!(out, 2);
    }

    #[test]
    fn a_progress_callback_that_says_stop_stops_polling_work() {
        let started = Instant::now();
        let rounds = watched(
            &mut |_| started.elapsed() < Duration::from_millis(100),
            0,
            |keep_going| {
                let mut rounds = 0u64;
                while keep_going() {
                    rounds += 1;
                    std::thread::sleep(Duration::from_millis(1));
                    assert!(started.elapsed() < Duration::from_secs(60), "never stopped");
                }
                rounds
            },
        );
        assert!(rounds > 0);
        assert!(NEVER(), "the never-stopping check goes on");
    }

    #[test]
    fn callers_on_rayon_workers_never_wait_on_a_busy_pool() {
        use rayon::prelude::*;
        // Every worker of the pool in a watched call whose work needs the pool: a worker
        // blocked while its work waits for the pool would never finish.
        let (done, finished) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let calls = 4 * rayon::current_num_threads() as u64;
            let sums: Vec<u64> = (0..calls)
                .into_par_iter()
                .map(|i| {
                    watched(&mut |_| true, 0, |keep_going| {
                        assert!(keep_going());
                        let (a, b) = rayon::join(|| i, || i + 1);
                        a + b
                    })
                })
                .collect();
            let _ = done.send(sums);
        });
        let sums = finished
            .recv_timeout(Duration::from_secs(60))
            .expect("a watched call on a rayon worker waited on a pool with no free thread");
        assert_eq!(sums[3], 7);
        // Told to stop before it starts, the work there stops at its first poll.
        let stopped = rayon::scope(|_| watched(&mut |_| false, 0, |keep_going| keep_going()));
        assert!(!stopped);
    }

    #[test]
    #[should_panic(expected = "inside the work")]
    fn a_panic_in_the_work_reaches_the_caller() {
        watched(&mut |_| true, 0, |_| -> () { panic!("inside the work") });
    }
}
