//! The server's graded-sheet jobs: at most [`GradedLimits::max_running`] running; ended ones
//! kept for [`GradedLimits::keep`] (and at most [`GradedLimits::max_kept`] of them), then
//! forgotten.

use super::job::GradedJob;
use super::limits::GradedLimits;
use crate::error::{ApiError, ApiResult};
use crate::inverse::JobState;
use axum::http::StatusCode;
use isogami::graded::GradedRequest;
use std::sync::{Arc, Mutex, MutexGuard};

#[derive(Debug, Default)]
struct Registry {
    next: u64,
    /// Oldest first.
    jobs: Vec<Arc<GradedJob>>,
}

/// Every graded-sheet job this server remembers.
#[derive(Debug, Default)]
pub struct GradedJobs {
    inner: Mutex<Registry>,
}

/// 404 for an id this server does not know (or has forgotten).
fn unknown(id: &str, limits: &GradedLimits) -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not_found",
        format!(
            "no graded-sheet job {:?} on this server",
            crate::filters::truncate(id)
        ),
        format!(
            "jobs are forgotten {} minutes after they end; POST /api/graded starts one",
            limits.keep.as_secs() / 60
        ),
    )
}

impl GradedJobs {
    fn lock(&self) -> MutexGuard<'_, Registry> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Forgets ended jobs past their keeping time, and the oldest ended beyond the count.
    fn prune(r: &mut Registry, limits: &GradedLimits) {
        r.jobs
            .retain(|j| j.ended().is_none_or(|t| t.elapsed() <= limits.keep));
        let ended = r.jobs.iter().filter(|j| j.ended().is_some()).count();
        let mut extra = ended.saturating_sub(limits.max_kept);
        r.jobs.retain(|j| {
            if extra > 0 && j.ended().is_some() {
                extra -= 1;
                false
            } else {
                true
            }
        });
    }

    /// A new running job for `request` (its outline given as `outline`), or 409 `busy` while
    /// the most jobs run.
    pub fn start(
        &self,
        request: &GradedRequest,
        outline: &str,
        limits: &GradedLimits,
    ) -> ApiResult<Arc<GradedJob>> {
        let mut r = self.lock();
        Self::prune(&mut r, limits);
        let running: Vec<u64> = r
            .jobs
            .iter()
            .filter(|j| j.state() == JobState::Running)
            .map(|j| j.id())
            .collect();
        if running.len() >= limits.max_running.max(1) {
            let ids: Vec<String> = running.iter().map(u64::to_string).collect();
            return Err(ApiError::new(
                StatusCode::CONFLICT,
                "busy",
                format!(
                    "{} graded sheet{} already being optimised on this server (job {}), its \
                     limit",
                    running.len(),
                    if running.len() == 1 { " is" } else { "s are" },
                    ids.join(", ")
                ),
                format!(
                    "wait for one to end, or stop it (DELETE /api/graded/{})",
                    running[0]
                ),
            ));
        }
        r.next += 1;
        let job = Arc::new(GradedJob::new(r.next, request, outline, *limits));
        r.jobs.push(job.clone());
        Ok(job)
    }

    /// The job `id`, or 404.
    pub fn get(&self, id: &str, limits: &GradedLimits) -> ApiResult<Arc<GradedJob>> {
        let mut r = self.lock();
        Self::prune(&mut r, limits);
        let n: Option<u64> = id.parse().ok();
        r.jobs
            .iter()
            .find(|j| Some(j.id()) == n)
            .cloned()
            .ok_or_else(|| unknown(id, limits))
    }

    /// Asks every running job to stop (the server is shutting down).
    pub fn stop_all(&self) {
        for j in &self.lock().jobs {
            j.request_stop();
        }
    }

    /// The running jobs' ids, oldest first.
    pub fn running(&self) -> Vec<u64> {
        self.lock()
            .jobs
            .iter()
            .filter(|j| j.state() == JobState::Running)
            .map(|j| j.id())
            .collect()
    }
}
