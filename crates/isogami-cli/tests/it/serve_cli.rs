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
