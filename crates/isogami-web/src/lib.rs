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
//! | [`inverse`] | inverse-design jobs: start, progress, stop, save |
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
pub mod inverse;
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

/// [`serve`] on a multi-threaded tokio runtime of its own, for callers without one.
pub fn serve_blocking(
    state: AppState,
    addr: SocketAddr,
    on_ready: impl FnOnce(SocketAddr),
) -> std::io::Result<()> {
    tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?
        .block_on(serve(state, addr, on_ready))
}

/// Serves `state` on `addr` until Ctrl-C (which also stops a running inverse-design job).
/// `on_ready` gets the bound address (port 0 picks a free one) once the server accepts
/// connections.
pub async fn serve(
    state: AppState,
    addr: SocketAddr,
    on_ready: impl FnOnce(SocketAddr),
) -> std::io::Result<()> {
    let listener = tokio::net::TcpListener::bind(addr).await?;
    on_ready(listener.local_addr()?);
    let jobs = state.clone();
    axum::serve(listener, router(state))
        .with_graceful_shutdown(async move {
            let _ = tokio::signal::ctrl_c().await;
            jobs.jobs().stop_all();
        })
        .await
}
