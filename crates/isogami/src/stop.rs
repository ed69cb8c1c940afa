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
pub fn watched<T: Send>(
    progress: Progress<'_>,
    states: usize,
    work: impl FnOnce(KeepGoing<'_>) -> T + Send,
) -> T {
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
        let mut asked = 0;
        let out = watched(
            &mut |n| {
                asked += 1;
                assert_eq!(n, 7);
                true
            },
            7,
            |keep_going| keep_going() as u32 + 1,
        );
        assert_eq!(out, 2);
        assert!(asked <= 1, "asked {asked} times for work that took no time");
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
    #[should_panic(expected = "inside the work")]
    fn a_panic_in_the_work_reaches_the_caller() {
        watched(&mut |_| true, 0, |_| -> () { panic!("inside the work") });
    }
}
