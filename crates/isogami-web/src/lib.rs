//! The isogami material browser (paper §6, and past it: live design).
//!
//! [`router`] serves the embedded front end and the JSON API over a design database;
//! [`serve`] binds it to an address; [`write_site`] writes the same catalogue as a static
//! site. Every simulation goes through `isogami::api` and every query through
//! `isogami-store`: this crate only translates HTTP to those calls and back.
//!
//! | module | what |
//! |---|---|
//! | [`assets`] | the built front end, embedded at compile time |
//! | [`error`] | API errors: status, kind, one-line message, hint |
//! | [`export`] | fabrication and interchange exports as downloads |
//! | [`filters`] | query strings → store queries |
//! | [`finite`] | finite sheets: a region's DOF, its completion and finite deployment |
//! | [`graded`] | graded-sheet jobs: start, progress with snapshots, stop, download |
//! | [`inverse`] | inverse-design jobs: start, progress, stop, save |
//! | [`jobs`] | what both kinds of job share: the registry, caps, stopping, a job's life |
//! | [`live`] | deployments of posted designs, bounded in time and cancelled with the client |
//! | [`view`] | the design view: report, geometry, linkages, notices |
//! | [`thumbnail`] | closed/open thumbnails as SVG |
//! | [`routes`] | the handlers |
//! | [`state`] | the shared state: database connections, settings |
//! | [`site`] | the static site |

pub mod assets;
pub mod error;
pub mod export;
pub mod filters;
pub mod finite;
pub mod graded;
pub mod inverse;
pub mod jobs;
pub mod live;
pub mod routes;
pub mod site;
pub mod state;
pub mod thumbnail;
pub mod view;

pub use routes::router;
pub use site::{slug, write_site, SiteReport};
pub use state::{AppState, ServerSettings};

use std::net::SocketAddr;
use std::time::Duration;

/// [`serve`] on a multi-threaded tokio runtime of its own, for callers without one.
pub fn serve_blocking(
    state: AppState,
    addr: SocketAddr,
    on_ready: impl FnOnce(SocketAddr) -> std::io::Result<()>,
) -> std::io::Result<()> {
    tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?
        .block_on(serve(state, addr, on_ready))
}

/// Serves `state` on `addr` until Ctrl-C (which also stops running inverse-design and
/// graded-sheet jobs).
/// `on_ready` gets the bound address (port 0 picks a free one) once the server accepts
/// connections; its error (e.g. the announcement could not be printed) ends `serve` before
/// anything is served.
pub async fn serve(
    state: AppState,
    addr: SocketAddr,
    on_ready: impl FnOnce(SocketAddr) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let listener = tokio::net::TcpListener::bind(addr).await?;
    on_ready(listener.local_addr()?)?;
    let jobs = state.clone();
    serve_on(listener, state, async move {
        let _ = tokio::signal::ctrl_c().await;
        jobs.jobs().stop_all();
        jobs.graded_jobs().stop_all();
    })
    .await
}

/// Serves `state` on `listener` until `shutdown` completes, then lets open connections
/// finish their requests (at most [`SHUTDOWN_GRACE`]). Each connection is closed when it
/// sends no complete request headers within `header_timeout` (idle keep-alive connections
/// and slow or unfinished headers alike); bodies are bounded by the router.
pub async fn serve_on(
    listener: tokio::net::TcpListener,
    state: AppState,
    shutdown: impl std::future::Future<Output = ()> + Send,
) -> std::io::Result<()> {
    use hyper_util::rt::{TokioIo, TokioTimer};
    use hyper_util::service::TowerToHyperService;

    let header_timeout = state.settings().header_timeout;
    let app = router(state);
    let (stop, stopped) = tokio::sync::watch::channel(false);
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let stream = tokio::select! {
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                // Out of file descriptors and the like: wait, do not spin.
                Err(_) => {
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            },
            _ = &mut shutdown => break,
        };
        let service = TowerToHyperService::new(app.clone());
        let mut stopped = stopped.clone();
        tokio::spawn(async move {
            let mut builder = hyper::server::conn::http1::Builder::new();
            builder
                .timer(TokioTimer::new())
                .header_read_timeout(header_timeout);
            let conn = builder.serve_connection(TokioIo::new(stream), service);
            let mut conn = std::pin::pin!(conn);
            tokio::select! {
                _ = conn.as_mut() => {}
                _ = stopped.changed() => {
                    conn.as_mut().graceful_shutdown();
                    let _ = conn.await;
                }
            }
        });
    }
    drop(stopped);
    let _ = stop.send(true);
    let _ = tokio::time::timeout(SHUTDOWN_GRACE, stop.closed()).await;
    Ok(())
}

/// Longest [`serve_on`] waits for open connections after its shutdown signal.
pub const SHUTDOWN_GRACE: Duration = Duration::from_secs(5);
