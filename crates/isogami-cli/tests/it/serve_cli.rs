//! `isogami serve` as the Quick start runs it.

use crate::common::{isogami, scratch};
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// `serve --open` on a machine without a desktop says so, with the address to open, instead of
/// starting a browser that dies unseen (Debian's chromium installed, no DISPLAY: it used to
/// print nothing); it serves all the same.
#[test]
fn open_without_a_desktop_says_so_and_serves() {
    let dir = scratch("serve-open");
    let db = dir.path().join("quick.db");
    let explored = isogami(&[
        "explore",
        "--quick",
        "--families",
        "IH76",
        "--db",
        db.to_str().unwrap(),
    ]);
    assert!(
        explored.status.success(),
        "{}",
        String::from_utf8_lossy(&explored.stderr)
    );
    let mut child = Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(["serve", "--open", "--addr", "127.0.0.1:0", "--db"])
        .arg(&db)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        // A browser that would be started anyway is one that cannot be: the test fails on
        // its message rather than leaving one behind.
        .env("BROWSER", dir.path().join("no-such-browser"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Each stream's first line, read aside so that a server that says nothing fails the test
    // after a while instead of hanging it.
    let first_line = |stream: Box<dyn std::io::Read + Send>| {
        let (send, receive) = mpsc::channel();
        std::thread::spawn(move || {
            let mut line = String::new();
            let _ = BufReader::new(stream).read_line(&mut line);
            let _ = send.send(line);
        });
        receive
    };
    let stdout = first_line(Box::new(child.stdout.take().unwrap()));
    let stderr = first_line(Box::new(child.stderr.take().unwrap()));
    let wait = Duration::from_secs(60);
    let listening = stdout.recv_timeout(wait);
    let said = stderr.recv_timeout(wait);
    child.kill().unwrap();
    child.wait().unwrap();
    let listening = listening.expect("serve printed where it listens");
    let said = said.expect("serve --open said something on stderr");
    let url = listening
        .trim()
        .strip_prefix("listening on ")
        .unwrap_or_else(|| panic!("first line: {listening:?}"));
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");
    assert_eq!(
        said.trim(),
        format!("no desktop here (DISPLAY and WAYLAND_DISPLAY are unset), so no browser: open {url} yourself")
    );
}

/// The first line `serve` prints on stdout ("listening on ..."), then the server is stopped;
/// its stderr as it was written until then.
fn serve_until_listening(db: &std::path::Path) -> (String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(["serve", "--addr", "127.0.0.1:0", "--db"])
        .arg(db)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = child.stdout.take().unwrap();
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(out).read_line(&mut line);
        let _ = send.send(line);
    });
    let listening = receive.recv_timeout(Duration::from_secs(600));
    child.kill().unwrap();
    let done = child.wait_with_output().unwrap();
    let listening = listening.expect("serve printed where it listens");
    (
        listening,
        String::from_utf8_lossy(&done.stderr).into_owned(),
    )
}

fn designs(db: &std::path::Path) -> u64 {
    crate::common::json(&["db", "stats", "--json", "--db", db.to_str().unwrap()])["designs"]
        .as_u64()
        .unwrap()
}

/// Issue 42 item 22: a first-run exploration stopped part way (Ctrl-C left 2 of 116 designs)
/// was served as it was, without a word. Stopped first runs are recognised by the marker
/// `serve` writes before it explores (here: a quick exploration of one family and the
/// marker, as a stop leaves them), resumed, and then served whole; a finished first run
/// leaves no marker.
#[test]
fn serve_resumes_a_first_run_exploration_that_was_stopped() {
    let dir = scratch("serve-resume");
    let whole = dir.path().join("whole.db");
    let (_, said) = serve_until_listening(&whole);
    assert!(said.contains("does not exist"), "{said}");
    let marker = |db: &std::path::Path| {
        let mut name = db.as_os_str().to_owned();
        name.push(".first-run");
        std::path::PathBuf::from(name)
    };
    assert!(
        !marker(&whole).exists(),
        "a finished first run leaves no marker"
    );
    let want = designs(&whole);

    let stopped = dir.path().join("stopped.db");
    let partial = isogami(&[
        "explore",
        "--quick",
        "--families",
        "IH76",
        "--db",
        stopped.to_str().unwrap(),
    ]);
    assert!(partial.status.success());
    std::fs::write(marker(&stopped), b"").unwrap();
    assert!(designs(&stopped) < want);
    let (listening, said) = serve_until_listening(&stopped);
    assert!(listening.starts_with("listening on "), "{listening}");
    assert!(said.contains("unfinished first-run exploration"), "{said}");
    assert_eq!(designs(&stopped), want);
    assert!(!marker(&stopped).exists());
    // Served again: nothing to resume, nothing said about it.
    let (_, said) = serve_until_listening(&stopped);
    assert!(!said.contains("first-run"), "{said}");
}
