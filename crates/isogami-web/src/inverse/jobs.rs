//! The server's inverse-design jobs: at most one running; ended ones kept for
//! [`InverseLimits::keep`](super::InverseLimits::keep) (and at most
//! [`max_kept`](super::InverseLimits::max_kept) of them), then forgotten.

use super::job::Job;
use super::limits::InverseLimits;
use super::view::JobState;
use crate::error::{ApiError, ApiResult};
use axum::http::StatusCode;
use isogami::inverse::InverseRequest;
use std::sync::{Arc, Mutex, MutexGuard};

#[derive(Debug, Default)]
struct Registry {
    next: u64,
    /// Oldest first.
    jobs: Vec<Arc<Job>>,
}

/// Every job this server remembers.
#[derive(Debug, Default)]
pub struct Jobs {
    inner: Mutex<Registry>,
}

/// 404 for an id this server does not know (or has forgotten).
fn unknown(id: &str, limits: &InverseLimits) -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not_found",
        format!(
            "no inverse-design job {:?} on this server",
            crate::filters::truncate(id)
        ),
        format!(
            "jobs are forgotten {} minutes after they end; POST /api/inverse starts one",
            limits.keep.as_secs() / 60
        ),
    )
}

impl Jobs {
    fn lock(&self) -> MutexGuard<'_, Registry> {
        self.inner.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Forgets ended jobs past their keeping time, and the oldest ended beyond the count.
    fn prune(r: &mut Registry, limits: &InverseLimits) {
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

    /// A new running job for `request`, or 409 `busy` while another runs.
    pub fn start(&self, request: &InverseRequest, limits: &InverseLimits) -> ApiResult<Arc<Job>> {
        let mut r = self.lock();
        Self::prune(&mut r, limits);
        if let Some(j) = r.jobs.iter().find(|j| j.state() == JobState::Running) {
            return Err(ApiError::new(
                StatusCode::CONFLICT,
                "busy",
                format!(
                    "an inverse design is already running on this server (job {})",
                    j.id()
                ),
                format!(
                    "wait for it to end, or stop it (DELETE /api/inverse/{})",
                    j.id()
                ),
            ));
        }
        r.next += 1;
        let job = Arc::new(Job::new(r.next, request, *limits));
        r.jobs.push(job.clone());
        Ok(job)
    }

    /// The job `id`, or 404.
    pub fn get(&self, id: &str, limits: &InverseLimits) -> ApiResult<Arc<Job>> {
        let mut r = self.lock();
        Self::prune(&mut r, limits);
        let n: Option<u64> = id.parse().ok();
        r.jobs
            .iter()
            .find(|j| Some(j.id()) == n)
            .cloned()
            .ok_or_else(|| unknown(id, limits))
    }

    /// Asks every running job to stop (the server is shutting down: the runtime waits for
    /// its blocking tasks).
    pub fn stop_all(&self) {
        for j in &self.lock().jobs {
            j.request_stop();
        }
    }

    /// The running job's id, if one runs.
    pub fn running(&self) -> Option<u64> {
        let r = self.lock();
        r.jobs
            .iter()
            .find(|j| j.state() == JobState::Running)
            .map(|j| j.id())
    }
}
