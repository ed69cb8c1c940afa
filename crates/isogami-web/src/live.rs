//! Deployments of posted designs: one library call (`isogami::api::deploy`), bounded in
//! time and cancelled when the client goes away, its failures explained in the user's terms.
//! [`run_bounded`] is that bound for any job (exports use it too).

use crate::error::{ApiError, ApiResult};
use crate::export::groups::check_design_text;
use axum::http::StatusCode;
use isogami::api::{deploy, resolve_design, DeployRequest, Deployment, Design, FrameSelection};
use isogami::cell::CellError;
use isogami::contact::{ContactError, ContactSettings};
use isogami::deploy::{DeployError, DeploySettings};
use isogami::tiling::TilingError;
use isogami::topology::DesignError;
use isogami::Error;
use serde::Deserialize;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Frames of a live deployment unless asked otherwise.
pub const DEFAULT_FRAMES: usize = 60;
/// Most frames a live deployment returns.
pub const MAX_FRAMES: usize = 400;

/// The body of `POST /api/deploy` and `POST /api/designs`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LiveRequest {
    /// A design name, spec string or design JSON.
    pub design: String,
    /// Kerf relative to the mean edge length (default: the library's).
    pub kerf: Option<f64>,
    /// Frames to return, 2..=[`MAX_FRAMES`].
    pub frames: Option<usize>,
}

impl LiveRequest {
    /// The design and deploy request, checked.
    pub fn resolve(&self) -> ApiResult<(Design, DeployRequest)> {
        let design = resolve_design(check_design_text(&self.design)?).map_err(|e| explain(&e))?;
        let mut settings = DeploySettings::default();
        if let Some(kerf) = self.kerf {
            if !kerf.is_finite() {
                return Err(ApiError::bad_parameter("kerf must be a finite number"));
            }
            settings.contact = ContactSettings::with_kerf(kerf);
        }
        let frames = self.frames.unwrap_or(DEFAULT_FRAMES);
        if !(2..=MAX_FRAMES).contains(&frames) {
            return Err(ApiError::bad_parameter(format!(
                "frames {frames} outside 2..={MAX_FRAMES}"
            )));
        }
        let request = DeployRequest {
            settings,
            frames: FrameSelection::Evenly(frames),
        };
        request
            .validate()
            .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
        Ok((design, request))
    }
}

/// Sets its flag when dropped: the handler's future is dropped when the client disconnects,
/// and the simulation thread sees the flag at its next step.
struct CancelOnDrop(Arc<AtomicBool>);

impl Drop for CancelOnDrop {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// What a bounded job asks at each step: go on while the client is there and time is left.
#[derive(Debug, Clone)]
pub struct Deadline {
    cancelled: Arc<AtomicBool>,
    started: Instant,
    timeout: Duration,
}

impl Deadline {
    /// Whether the job may go on (the library's progress callbacks return this).
    pub fn keep_going(&self) -> bool {
        !self.cancelled.load(Ordering::Relaxed) && self.started.elapsed() < self.timeout
    }
}

/// Runs `job` on the blocking pool with a [`Deadline`] of `timeout` that also ends when the
/// caller's future is dropped (the client went away). The job stops itself by reading it.
pub async fn run_bounded<T, F>(timeout: Duration, job: F) -> ApiResult<T>
where
    T: Send + 'static,
    F: FnOnce(&Deadline) -> T + Send + 'static,
{
    let deadline = Deadline {
        cancelled: Arc::new(AtomicBool::new(false)),
        started: Instant::now(),
        timeout,
    };
    let _guard = CancelOnDrop(deadline.cancelled.clone());
    tokio::task::spawn_blocking(move || job(&deadline))
        .await
        .map_err(|e| ApiError::internal(format!("simulation task failed: {e}")))
}

/// [`run_bounded`] whose answer never waits longer than `timeout` + [`ANSWER_GRACE`]: for
/// jobs with single steps that do not poll their deadline (a factorisation, a solid's
/// union). Past that the caller gets 422 `timeout` at once while the job's thread ends at its
/// next poll of the deadline (whose flag is set when this future is dropped); whatever the
/// job holds (a heavy-job permit moved into it) is released only then.
pub async fn run_answered<T, F>(timeout: Duration, job: F) -> ApiResult<T>
where
    T: Send + 'static,
    F: FnOnce(&Deadline) -> T + Send + 'static,
{
    tokio::time::timeout(
        timeout.saturating_add(ANSWER_GRACE),
        run_bounded(timeout, job),
    )
    .await
    .unwrap_or_else(|_| Err(timed_out(timeout)))
}

/// How long past its deadline [`run_answered`] waits for the job to stop by itself.
pub const ANSWER_GRACE: Duration = Duration::from_millis(250);

/// 422 `timeout`: a simulation stopped at the server's time limit.
pub fn timed_out(timeout: Duration) -> ApiError {
    ApiError::new(
        StatusCode::UNPROCESSABLE_ENTITY,
        "timeout",
        format!(
            "the deployment did not finish within {:.1} s",
            timeout.as_secs_f64()
        ),
        "try a smaller cell or a wider kerf, or run `isogami deploy` from the command line",
    )
}

/// Deploys on the blocking pool, stopping after `timeout` or when the caller's future is
/// dropped.
pub async fn deploy_bounded(
    design: Design,
    request: DeployRequest,
    timeout: Duration,
) -> ApiResult<Deployment> {
    let run = run_bounded(timeout, move |deadline| {
        deploy(&design, &request, &mut |_| deadline.keep_going())
    })
    .await?;
    run.map_err(|e| {
        if e.is_cancelled() {
            timed_out(timeout)
        } else {
            explain(&e)
        }
    })
}

/// Whether `e` says the shape parameters give no valid tile or cell (as a shape slider pushed
/// too far does), however deep it is wrapped: reading a spec wraps tiling and cell errors in
/// the design error. An unknown family, a wrong parameter count or cell size is a bad spec.
fn gives_no_valid_tile(e: &Error) -> bool {
    let tiling = |t: &TilingError| matches!(t, TilingError::InvalidShape { .. });
    let cell = |c: &CellError| !matches!(c, CellError::BadCell { .. } | CellError::Size { .. });
    match e {
        Error::Tiling(t) | Error::Design(DesignError::Tiling(t)) => tiling(t),
        Error::Cell(c) | Error::Design(DesignError::Cell(c)) => cell(c),
        _ => false,
    }
}

/// A library error in the words of someone tuning a design: 422 with a kind and what to do.
pub fn explain(e: &Error) -> ApiError {
    let unprocessable = |kind, hint: &str| {
        ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, kind, e.to_string(), hint)
    };
    match e {
        Error::Deploy(DeployError::Rigid | DeployError::NoMotion { .. }) => unprocessable(
            "rigid",
            "cut more edges (set joints to none) so the tiles can turn; if a shape slider did \
             this, move it back: some linkages move only at special shapes",
        ),
        Error::Deploy(DeployError::Contact(ContactError::Inset { .. }))
        | Error::Contact(ContactError::Inset { .. }) => unprocessable(
            "ill_shaped",
            "make the kerf narrower, or move the shape sliders back towards the defaults",
        ),
        e if gives_no_valid_tile(e) => unprocessable(
            "ill_shaped",
            "these shape parameters give no valid tile: move the sliders back towards the defaults",
        ),
        Error::Tiling(_) | Error::Cell(_) | Error::Design(_) | Error::Kinematics(_) => {
            ApiError::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "bad_design",
                e.to_string(),
                "a spec is FAMILY:PARAMS:CELL:JOINTS, e.g. IH1:0.12,0.5,0.14,0.62:2x1:--bbb-",
            )
        }
        Error::Settings(_) | Error::Deploy(DeployError::Settings(_)) => {
            ApiError::bad_parameter(e.to_string())
        }
        _ => unprocessable(
            "simulation_failed",
            "the simulation could not follow this design; try nearby parameters or another kerf",
        ),
    }
}
