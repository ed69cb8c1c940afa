//! Two writers on one database (issue 8 §4): the second `explore` (or a `merge` into the same
//! file) is refused at once with a clear one-line message, never a raw SQL error; readers keep
//! working; the lock dies with its process.
//!
//! Units run longest first, so the slow unit commits first; the first writer is then paused
//! (SIGSTOP) while the others try, so the checks never race its remaining quick units.

use isogami_store::{Check, Store};
use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
}

fn dir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-db-conc-{name}-"))
        .tempdir()
        .unwrap()
}

/// IH21's minimal cell keeps a writer busy for many seconds and runs first (longest first);
/// IH27, IH56 and IH28 take a few seconds each after it.
const SLOW: [&str; 8] = [
    "explore",
    "--families",
    "IH21,IH27,IH56,IH28",
    "--cells",
    "1x1",
    "--jobs",
    "1",
    "--db",
];

fn slow_explore(db: &Path) -> Child {
    bin()
        .args(SLOW)
        .arg(db)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

fn committed(db: &Path) -> usize {
    Store::open_read(db, Check::Quick)
        .ok()
        .and_then(|s| s.done_units().ok())
        .map_or(0, |u| u.len())
}

fn wait_for(what: &str, cond: impl Fn() -> bool) {
    let start = Instant::now();
    while !cond() {
        assert!(
            start.elapsed() < Duration::from_secs(300),
            "timed out: {what}"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// Sends `signal` (e.g. `STOP`, `CONT`) to a child process.
fn signal(child: &Child, signal: &str) {
    let status = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(child.id().to_string())
        .status()
        .unwrap();
    assert!(status.success(), "kill -{signal}");
}

/// The number N in the summary line's "N already in".
fn already_in(summary: &str) -> usize {
    let words: Vec<&str> = summary.split_whitespace().collect();
    let at = words
        .windows(2)
        .position(|w| w == ["already", "in"])
        .unwrap_or_else(|| panic!("no 'already in' in {summary}"));
    words[at - 1].trim_end_matches(',').parse().unwrap()
}

fn assert_busy(out: &Output) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("another isogami process"), "{err}");
    assert!(
        !err.contains("UNIQUE") && !err.contains("constraint"),
        "{err}"
    );
}

#[test]
fn a_second_writer_is_refused_while_the_first_runs() {
    let d_guard = dir("second");
    let d = d_guard.path();
    let db = d.join("db");
    let mut first = slow_explore(&db);
    wait_for("the first unit", || committed(&db) >= 1);
    // Paused, it holds the lock and its uncommitted units for as long as the checks take.
    signal(&first, "STOP");
    assert!(
        first.try_wait().unwrap().is_none(),
        "the first writer ended before its quick units ran"
    );
    let before = committed(&db);
    assert!(before < 4, "the first writer finished every unit");
    // The second explore with the same settings, and a merge into the same file.
    let out = bin().args(SLOW).arg(&db).output().unwrap();
    assert_busy(&out);
    let shard = d.join("shard.db");
    let made = bin()
        .args(["explore", "--families", "IH1", "--cells", "1x1", "--db"])
        .arg(&shard)
        .output()
        .unwrap();
    assert!(made.status.success());
    let out = bin()
        .args(["merge", "--into"])
        .arg(&db)
        .arg(&shard)
        .output()
        .unwrap();
    assert_busy(&out);
    // Readers are not blocked.
    let stats = bin()
        .args(["db", "stats", "--db"])
        .arg(&db)
        .output()
        .unwrap();
    assert!(
        stats.status.success(),
        "{}",
        String::from_utf8_lossy(&stats.stderr)
    );
    assert!(
        first.try_wait().unwrap().is_none(),
        "the first writer still runs"
    );
    // The lock dies with its process, even killed; the work it committed stays, and a new
    // writer resumes it.
    first.kill().unwrap();
    first.wait().unwrap();
    let out = bin()
        .args([
            "explore",
            "--families",
            "IH21,IH1",
            "--cells",
            "1x1",
            "--jobs",
            "1",
            "--db",
        ])
        .arg(&db)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // IH21 (committed before the kill) is not run again; IH1 is new.
    assert_eq!(already_in(&text), 1, "{text}");
    let units = Store::open_read(&db, Check::Full)
        .unwrap()
        .done_units()
        .unwrap();
    assert!(
        units.contains("IH21/1x1") && units.contains("IH1/1x1"),
        "{units:?}"
    );
    assert_eq!(units.len(), before + 1, "{units:?}");
}

#[test]
fn two_explores_started_together_on_a_new_file_one_refused() {
    let d_guard = dir("together");
    let d = d_guard.path();
    let db = d.join("db");
    let mut a = slow_explore(&db);
    let mut b = slow_explore(&db);
    // Exactly one ends at once, refused; the other keeps running.
    let start = Instant::now();
    let (loser, mut winner) = loop {
        if let Some(s) = a.try_wait().unwrap() {
            break ((s, a), b);
        }
        if let Some(s) = b.try_wait().unwrap() {
            break ((s, b), a);
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "neither was refused"
        );
        std::thread::sleep(Duration::from_millis(10));
    };
    let (status, child) = loser;
    let out = child.wait_with_output().unwrap();
    assert_eq!(status.code(), Some(2));
    assert_busy(&Output { status, ..out });
    assert!(winner.try_wait().unwrap().is_none(), "the other still runs");
    wait_for("the winner's first unit", || committed(&db) >= 1);
    winner.kill().unwrap();
    winner.wait().unwrap();
}
