//! Peak memory of work units while they run (issue 13: "peak memory reported per unit").
//!
//! A sampler thread reads the process's resident set size every [`INTERVAL`] and raises the
//! peak of every unit in flight; a unit's figure is the largest sample between its start and
//! its end (both sampled too). Units run one at a time per worker and share the process, so
//! the figure is the unit's own peak plus whatever the process held besides it: exact up to
//! the process baseline when the unit ran alone (`--jobs 1`, or a big unit at the end of a
//! run), an upper bound otherwise, which is what sizing a cluster task needs. A spike shorter
//! than the interval can be missed; the memory that matters (deduplication's classes, the
//! expansion's frontier) is held for seconds. Linux only (`/proc/self/status`); elsewhere no
//! figure is recorded.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// Time between two samples.
pub(crate) const INTERVAL: Duration = Duration::from_millis(10);

/// The resident set size of this process in bytes (`VmRSS`), or None where it cannot be read.
pub(crate) fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    vm_rss(&status)
}

/// `VmRSS` of a `/proc/<pid>/status` text, in bytes.
fn vm_rss(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let mut words = line["VmRSS:".len()..].split_whitespace();
    let kib: u64 = words.next()?.parse().ok()?;
    (words.next() == Some("kB")).then_some(kib * 1024)
}

/// Peaks of the units in flight, keyed by the caller's unit number.
#[derive(Debug, Default)]
pub(crate) struct PeakMemory {
    in_flight: Mutex<HashMap<usize, u64>>,
}

impl PeakMemory {
    /// Starts tracking unit `key`.
    pub(crate) fn begin(&self, key: usize) {
        let now = resident_bytes().unwrap_or(0);
        self.lock().insert(key, now);
    }

    /// Stops tracking unit `key`; its peak, or None when nothing could be measured.
    pub(crate) fn end(&self, key: usize) -> Option<u64> {
        self.sample();
        self.lock().remove(&key).filter(|&b| b > 0)
    }

    /// Raises every unit's peak to the current resident size.
    fn sample(&self) {
        if let Some(now) = resident_bytes() {
            for peak in self.lock().values_mut() {
                *peak = (*peak).max(now);
            }
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<usize, u64>> {
        // A panic elsewhere cannot leave the map half-updated: every update is one operation.
        self.in_flight.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Samples every [`INTERVAL`] until `stop` is set (run it on its own thread).
    pub(crate) fn sample_until(&self, stop: &AtomicBool) {
        while !stop.load(Ordering::Relaxed) {
            self.sample();
            std::thread::sleep(INTERVAL);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vm_rss_reads_kib_and_refuses_what_it_does_not_know() {
        let status = "Name:\tx\nVmHWM:\t  9000 kB\nVmRSS:\t  1234 kB\nThreads:\t1\n";
        assert_eq!(vm_rss(status), Some(1234 * 1024));
        assert_eq!(vm_rss("VmRSS:\t12 MB\n"), None);
        assert_eq!(vm_rss("Name:\tx\n"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_unit_that_holds_memory_has_a_peak_at_least_that_large() {
        let mem = PeakMemory::default();
        let stop = AtomicBool::new(false);
        let before = resident_bytes().unwrap();
        let held = std::thread::scope(|s| {
            s.spawn(|| mem.sample_until(&stop));
            mem.begin(7);
            // 256 MiB, every page touched, held for several sampling intervals, then freed.
            let mut block = vec![0u8; 256 << 20];
            for page in block.chunks_mut(4096) {
                page[0] = 1;
            }
            std::thread::sleep(INTERVAL * 5);
            let touched = block.iter().step_by(4096).filter(|&&b| b == 1).count();
            drop(block);
            let peak = mem.end(7).unwrap();
            stop.store(true, Ordering::Relaxed);
            (peak, touched)
        });
        assert_eq!(held.1, (256 << 20) / 4096);
        assert!(
            held.0 >= before + (256 << 20) * 9 / 10,
            "{} vs {before}",
            held.0
        );
        // The unit is no longer tracked.
        assert_eq!(mem.end(7), None);
    }
}
