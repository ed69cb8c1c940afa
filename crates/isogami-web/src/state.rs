//! The server's shared state: a small pool of read-only database connections, the
//! database's path (for saving user designs through the store's locked writer), the
//! inverse-design and graded-sheet jobs and the limits every request obeys.

use crate::error::{ApiError, ApiResult};
use crate::graded::{GradedJobs, GradedLimits};
use crate::inverse::{InverseLimits, Jobs};
use isogami_store::{Check, Store, StoreResult};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::Semaphore;

/// Limits and defaults of a server.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServerSettings {
    /// Longest a live deployment may run before it is stopped (default 2 s).
    pub sim_timeout: Duration,
    /// Largest request body in bytes (default 64 KiB).
    pub max_body: usize,
    /// Read-only database connections (default 4).
    pub readers: usize,
    /// Whether users may save designs to the database.
    pub allow_save: bool,
    /// Caps of inverse-design jobs.
    pub inverse: InverseLimits,
    /// Caps of graded-sheet jobs.
    pub graded: GradedLimits,
    /// Longest a connection may take to send a request's headers, idle time before the
    /// first byte included: idle and slow connections are closed after it (default 10 s).
    pub header_timeout: Duration,
    /// Longest a request may take to send its body once its headers are in (default 10 s).
    pub body_timeout: Duration,
    /// Exports and finite sheets (`/api/sheet`) that may run at once (default 2): each holds
    /// one of these while its work runs, past its answer if the library is in a stage that
    /// cannot stop.
    pub heavy_jobs: usize,
}

impl Default for ServerSettings {
    fn default() -> Self {
        ServerSettings {
            sim_timeout: Duration::from_secs(2),
            max_body: 64 * 1024,
            readers: 4,
            allow_save: true,
            inverse: InverseLimits::default(),
            graded: GradedLimits::default(),
            header_timeout: Duration::from_secs(10),
            body_timeout: Duration::from_secs(10),
            heavy_jobs: 2,
        }
    }
}

/// Everything a handler needs; cheap to clone.
#[derive(Debug, Clone)]
pub struct AppState {
    inner: Arc<Inner>,
}

#[derive(Debug)]
struct Inner {
    db: PathBuf,
    readers: Vec<Mutex<Store>>,
    next: AtomicUsize,
    settings: ServerSettings,
    /// Serialises saves of this process (the store's file lock guards against others).
    save: Mutex<()>,
    /// Inverse-design jobs.
    jobs: Jobs,
    /// Graded-sheet jobs.
    graded_jobs: GradedJobs,
    /// Permits of the heavy jobs (exports, finite sheets).
    heavy: Arc<Semaphore>,
}

impl AppState {
    /// Opens `settings.readers` read-only connections to `db`. The first is opened with the
    /// store's full check (SQLite's integrity check, every row's checksum, every stored
    /// document parsed: what `isogami db stats` runs), so a damaged or edited file is refused
    /// before anything is served; the others with SQLite's `quick_check`.
    pub fn open(db: &Path, settings: ServerSettings) -> StoreResult<AppState> {
        let n = settings.readers.clamp(1, 64);
        let mut readers = Vec::with_capacity(n);
        for k in 0..n {
            let check = if k == 0 { Check::Full } else { Check::Quick };
            readers.push(Mutex::new(Store::open_read(db, check)?));
        }
        Ok(AppState {
            inner: Arc::new(Inner {
                db: db.to_path_buf(),
                readers,
                next: AtomicUsize::new(0),
                settings,
                save: Mutex::new(()),
                jobs: Jobs::default(),
                graded_jobs: GradedJobs::default(),
                heavy: Arc::new(Semaphore::new(settings.heavy_jobs.clamp(1, 64))),
            }),
        })
    }

    /// The limits.
    pub fn settings(&self) -> &ServerSettings {
        &self.inner.settings
    }

    /// The inverse-design jobs.
    pub fn jobs(&self) -> &Jobs {
        &self.inner.jobs
    }

    /// The graded-sheet jobs.
    pub fn graded_jobs(&self) -> &GradedJobs {
        &self.inner.graded_jobs
    }

    /// The permits of heavy jobs (see [`ServerSettings::heavy_jobs`]).
    pub fn heavy(&self) -> &Arc<Semaphore> {
        &self.inner.heavy
    }

    /// The database file.
    pub fn db_path(&self) -> &Path {
        &self.inner.db
    }

    /// Runs `f` with a read connection on the blocking pool.
    pub async fn read<T, F>(&self, f: F) -> ApiResult<T>
    where
        T: Send + 'static,
        F: FnOnce(&Store) -> ApiResult<T> + Send + 'static,
    {
        let state = self.clone();
        tokio::task::spawn_blocking(move || state.read_now(f))
            .await
            .map_err(|e| ApiError::internal(format!("query task failed: {e}")))?
    }

    /// Runs `f` with a read connection on this thread (a free one if any, else waits for
    /// the next in turn).
    pub fn read_now<T>(&self, f: impl FnOnce(&Store) -> ApiResult<T>) -> ApiResult<T> {
        let readers = &self.inner.readers;
        for r in readers {
            if let Ok(store) = r.try_lock() {
                return f(&store);
            }
        }
        let k = self.inner.next.fetch_add(1, Ordering::Relaxed) % readers.len();
        let store = readers[k]
            .lock()
            .map_err(|_| ApiError::internal("a database connection was poisoned"))?;
        f(&store)
    }

    /// Holds this process's save lock while `f` runs.
    pub fn with_save_lock<T>(&self, f: impl FnOnce() -> ApiResult<T>) -> ApiResult<T> {
        let _guard = self
            .inner
            .save
            .lock()
            .map_err(|_| ApiError::internal("the save lock was poisoned"))?;
        f()
    }
}
