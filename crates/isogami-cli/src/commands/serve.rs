//! `isogami serve`: the material browser over a design database, and `isogami site`: the
//! same catalogue as a static site. Both are thin calls into `isogami-web`.

use super::explore;
use crate::output::{emit, CliResult};
use indicatif::{ProgressBar, ProgressStyle};
use isogami_web::{serve_blocking, write_site, AppState, ServerSettings};
use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

/// Arguments of `serve`.
#[derive(Debug, clap::Args)]
pub struct ServeArgs {
    /// The design database; when it does not exist, the quick exploration creates it first.
    #[arg(long, default_value = "isogami.db")]
    db: PathBuf,
    /// Address to listen on (port 0 picks a free port). Localhost unless you mean otherwise.
    #[arg(long, default_value = "127.0.0.1:8080")]
    addr: SocketAddr,
    /// Open the browser at the served address.
    #[arg(long)]
    open: bool,
    /// Longest a live re-simulation may run, in seconds.
    #[arg(long, default_value_t = 2.0)]
    sim_timeout: f64,
    /// Refuse to save user designs to the database.
    #[arg(long)]
    read_only: bool,
}

/// The marker beside `db` that says its first-run exploration has not finished: made before
/// `serve` explores a missing database, removed when the exploration has finished.
fn first_run_marker(db: &std::path::Path) -> PathBuf {
    let mut name = db.as_os_str().to_owned();
    name.push(".first-run");
    PathBuf::from(name)
}

/// Makes the database with the quick exploration when it does not exist, and finishes that
/// exploration when an earlier `serve` was stopped during it (the marker is still there): the
/// exploration skips the work units already committed, so it resumes where it stopped.
fn first_run(db: &std::path::Path) -> CliResult {
    let marker = first_run_marker(db);
    if db.exists() && !marker.exists() {
        return Ok(());
    }
    if db.exists() {
        eprintln!(
            "{} is an unfinished first-run exploration (stopped before the end): resuming it",
            db.display()
        );
    } else {
        eprintln!(
            "{} does not exist: running the quick exploration to create it",
            db.display()
        );
        std::fs::write(
            &marker,
            b"the first-run exploration of isogami serve has not finished\n",
        )
        .map_err(|e| format!("{}: {e}", marker.display()))?;
    }
    explore::run(explore::Args::quick(db.to_path_buf()))?;
    std::fs::remove_file(&marker).map_err(|e| format!("{}: {e}", marker.display()))
}

/// Serves until Ctrl-C.
pub fn serve(args: ServeArgs) -> CliResult {
    if !(args.sim_timeout.is_finite() && args.sim_timeout > 0.0 && args.sim_timeout <= 600.0) {
        return Err(format!(
            "--sim-timeout must lie in (0, 600] seconds, got {}",
            args.sim_timeout
        ));
    }
    first_run(&args.db)?;
    let settings = ServerSettings {
        sim_timeout: Duration::from_secs_f64(args.sim_timeout),
        allow_save: !args.read_only,
        ..ServerSettings::default()
    };
    // The store's full check (every row's checksum), as `db stats` runs: a damaged or edited
    // file is refused here, in one line, before anything is served.
    let state =
        AppState::open(&args.db, settings).map_err(|e| format!("{}: {e}", args.db.display()))?;
    let open = args.open;
    let mut announce_failed = None;
    let served = serve_blocking(state, args.addr, |addr| {
        let url = format!("http://{addr}/");
        if let Err(e) = announce(&mut std::io::stdout().lock(), &url) {
            announce_failed = Some(format!("cannot write to stdout: {e}"));
            return Err(e);
        }
        if open {
            if !desktop_present() {
                eprintln!(
                    "no desktop here (DISPLAY and WAYLAND_DISPLAY are unset), so no browser: open {url} yourself"
                );
            } else if let Err(e) = webbrowser::open(&url) {
                eprintln!("could not open a browser ({e}); open {url} yourself");
            }
        }
        Ok(())
    });
    match (served, announce_failed) {
        (_, Some(why)) => Err(why),
        (Err(e), None) => Err(format!("cannot serve on {}: {e}", args.addr)),
        (Ok(()), None) => Ok(()),
    }
}

/// Whether a browser started here can be seen. On Linux and the BSDs a desktop session sets
/// DISPLAY or WAYLAND_DISPLAY; without either (a server, a container, ssh without X) a browser
/// that is installed still starts and dies unseen, and `--open` would say nothing.
fn desktop_present() -> bool {
    cfg!(any(target_os = "macos", target_os = "windows"))
        || ["DISPLAY", "WAYLAND_DISPLAY"]
            .iter()
            .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
}

/// Writes the served address to `out`: an error (stdout closed or full) ends `serve`.
fn announce(out: &mut impl Write, url: &str) -> std::io::Result<()> {
    writeln!(out, "listening on {url}")?;
    out.flush()
}

/// Arguments of `site`.
#[derive(Debug, clap::Args)]
pub struct SiteArgs {
    /// The design database.
    #[arg(long, default_value = "isogami.db")]
    db: PathBuf,
    /// Output folder (created; replaced only if it holds an earlier isogami site).
    #[arg(long)]
    out: PathBuf,
}

/// Writes the static site.
pub fn site(args: SiteArgs) -> CliResult {
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} designs, {elapsed}")
            .expect("valid template"),
    );
    let report = write_site(&args.db, &args.out, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })
    .map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    emit(&format!(
        "wrote {} designs, {} files ({:.1} MB) to {}\n",
        report.designs,
        report.files,
        report.bytes as f64 / 1e6,
        args.out.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_or_closed_stdout_is_an_error_not_a_panic() {
        let mut buffer = Vec::new();
        announce(&mut buffer, "http://127.0.0.1:1/").unwrap();
        assert_eq!(buffer, b"listening on http://127.0.0.1:1/\n");
        if let Ok(mut full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
            let e = announce(&mut full, "http://127.0.0.1:1/").unwrap_err();
            assert!(!e.to_string().contains('\n'));
        }
    }
}
