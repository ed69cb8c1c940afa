//! Issue 8 §4 through the command line: every command that takes a database leaves a foreign,
//! old, future or damaged file byte-for-byte unchanged, creates nothing beside it, and says
//! why in one line with exit code 2.

use rusqlite::Connection;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
}

fn dir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-db-safety-{name}-"))
        .tempdir()
        .unwrap()
}

fn run(args: &[&str]) -> Output {
    bin().args(args).output().unwrap()
}

fn explore(db: &Path) {
    let out = run(&[
        "explore",
        "--quick",
        "--families",
        "IH83,IH90",
        "--db",
        db.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The files in a directory with their bytes.
fn listing(d: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            let bytes = std::fs::read(&p).unwrap();
            (p, bytes)
        })
        .collect();
    v.sort();
    v
}

/// Runs every command that takes a database on `file` (alone in its directory); each must
/// refuse with one line naming the file and containing `expect`, exit 2, and change nothing
/// in the directory.
fn refused_everywhere(file: &Path, good: &Path, expect: &str) {
    let d = file.parent().unwrap();
    let before = listing(d);
    let f = file.to_str().unwrap();
    // Outside `d`, whose listing must not change.
    let new_guard = dir("new-target");
    let new_target = new_guard.path().join(format!(
        "new-{}.db",
        file.file_name().unwrap().to_string_lossy()
    ));
    let commands: Vec<Vec<&str>> = vec![
        vec!["db", "stats", "--db", f],
        vec!["db", "stats", "--json", "--db", f],
        vec!["explore", "--quick", "--families", "IH90", "--db", f],
        vec!["merge", "--into", f, good.to_str().unwrap()],
        vec!["merge", "--into", new_target.to_str().unwrap(), f],
    ];
    for args in &commands {
        let out = run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: one line, got {err}");
        assert!(err.contains(f) && err.contains(expect), "{args:?}: {err}");
        assert!(
            !err.contains("UNIQUE") && !err.contains("constraint"),
            "{err}"
        );
        assert_eq!(listing(d), before, "{args:?} changed {}", d.display());
    }
    assert!(
        !new_target.exists(),
        "a merge from a refused shard creates nothing"
    );
}

fn sqlite_file(path: &Path, sql: &str) {
    Connection::open(path).unwrap().execute_batch(sql).unwrap();
}

#[test]
fn foreign_old_and_future_files_are_refused_unchanged() {
    let root_guard = dir("foreign");
    let root = root_guard.path();
    let good = root.join("good.db");
    explore(&good);
    let case = |name: &str| {
        let d = root.join(name);
        std::fs::create_dir_all(&d).unwrap();
        d.join("file.db")
    };
    let text = case("text");
    std::fs::write(&text, "not a database\n").unwrap();
    refused_everywhere(&text, &good, "not an isogami database");

    let unrelated = case("unrelated");
    sqlite_file(
        &unrelated,
        "CREATE TABLE users(name); INSERT INTO users VALUES ('a');",
    );
    refused_everywhere(&unrelated, &good, "not an isogami database");

    // The case that used to get half-created tables.
    let designs = case("designs");
    sqlite_file(
        &designs,
        "CREATE TABLE designs(spec TEXT PRIMARY KEY, note TEXT); \
         INSERT INTO designs VALUES ('IH1::1x1:ab', 'mine');",
    );
    refused_everywhere(&designs, &good, "not an isogami database");

    // The case that used to be switched to WAL.
    let wal = case("wal");
    sqlite_file(&wal, "PRAGMA journal_mode = WAL; CREATE TABLE t(x);");
    refused_everywhere(&wal, &good, "not an isogami database");

    let v1 = case("v1");
    sqlite_file(
        &v1,
        "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
         INSERT INTO meta VALUES ('schema_version', '1');
         CREATE TABLE designs(spec TEXT PRIMARY KEY);",
    );
    refused_everywhere(&v1, &good, "re-run explore into a new file");

    let future = case("future");
    std::fs::copy(&good, &future).unwrap();
    sqlite_file(
        &future,
        "UPDATE meta SET value = '99' WHERE key = 'schema_version'",
    );
    refused_everywhere(&future, &good, "schema version 99");
}

#[test]
fn reading_commands_never_write() {
    let d_guard = dir("read");
    let d = d_guard.path();
    let db = d.join("x.db");
    explore(&db);
    let before = listing(d);
    for args in [
        vec!["db", "stats", "--db", db.to_str().unwrap()],
        vec!["db", "stats", "--json", "--db", db.to_str().unwrap()],
    ] {
        assert!(run(&args).status.success());
        assert_eq!(listing(d), before, "{args:?}");
    }
    // A missing or empty file is not created or filled by a reader.
    let missing = d.join("missing.db");
    let out = run(&["db", "stats", "--db", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!missing.exists());
    let empty = d.join("empty.db");
    std::fs::write(&empty, b"").unwrap();
    let out = run(&["db", "stats", "--db", empty.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(std::fs::read(&empty).unwrap().len(), 0);
    // A writer may create in an empty file.
    explore(&empty);
    assert!(run(&["db", "stats", "--db", empty.to_str().unwrap()])
        .status
        .success());
}

fn page_size(bytes: &[u8]) -> usize {
    match u16::from_be_bytes([bytes[16], bytes[17]]) {
        1 => 65536,
        n => usize::from(n),
    }
}

/// Every row plain SQLite reads, and whether its integrity check passes.
fn sqlite_view(path: &Path) -> Option<(Vec<String>, bool)> {
    let c = Connection::open_with_flags(path, rusqlite::OpenFlags::SQLITE_OPEN_READ_ONLY).ok()?;
    let mut rows = Vec::new();
    for table in [
        "meta",
        "work_units",
        "stage_counts",
        "designs",
        "design_data",
    ] {
        let mut stmt = c.prepare(&format!("SELECT * FROM {table}")).ok()?;
        let n = stmt.column_count();
        let mut q = stmt.query([]).ok()?;
        while let Some(r) = q.next().ok()? {
            let cols: Vec<String> = (0..n)
                .map(|i| format!("{:?}", r.get_ref(i).map(|v| v.as_str().ok())))
                .collect();
            rows.push(cols.join("|"));
        }
    }
    let ok = c
        .query_row("PRAGMA integrity_check", [], |r| r.get::<_, String>(0))
        .is_ok_and(|s| s == "ok");
    Some((rows, ok))
}

/// `good` with one byte after the first live occurrence of `needle` changed by `change`
/// (free space inside pages can hold stale copies of cells, whose change damages nothing).
fn change_live(good: &[u8], needle: &[u8], offset: usize, probe: &Path) -> Vec<u8> {
    std::fs::write(probe, good).unwrap();
    let reference = sqlite_view(probe).unwrap();
    let mut from = 0;
    while let Some(k) = good[from..].windows(needle.len()).position(|w| w == needle) {
        let at = from + k + offset;
        let mut bytes = good.to_vec();
        bytes[at] = if bytes[at] == b'7' { b'8' } else { b'7' };
        std::fs::write(probe, &bytes).unwrap();
        if sqlite_view(probe) != Some(reference.clone()) {
            let _ = std::fs::remove_file(probe);
            return bytes;
        }
        from += k + 1;
    }
    panic!("no live occurrence");
}

#[test]
fn damaged_copies_of_a_real_database_are_refused_unchanged() {
    let root_guard = dir("damage");
    let root = root_guard.path();
    let good = root.join("good.db");
    explore(&good);
    let bytes = std::fs::read(&good).unwrap();
    let ps = page_size(&bytes);
    let pages = bytes.len() / ps;
    assert!(pages >= 8);
    let probe = root.join("probe.db");
    let mut copies: Vec<(&str, Vec<u8>)> = Vec::new();
    let mut with = |name, f: &dyn Fn(&mut Vec<u8>)| {
        let mut b = bytes.clone();
        f(&mut b);
        assert_ne!(b, bytes, "{name}");
        copies.push((name, b));
    };
    with("truncated-half", &|b| b.truncate(ps * (pages / 2)));
    with("truncated-last-page", &|b| b.truncate(ps * (pages - 1)));
    with("truncated-mid-page", &|b| {
        b.truncate(ps * (pages - 3) + 1000)
    });
    with("flip-page1-header", &|b| b[100] ^= 0x08);
    with("flip-page2", &|b| b[ps + 3] ^= 0x40);
    with("flip-page4-cell-pointer", &|b| b[3 * ps + 8] ^= 0x10);
    with("flip-digit-in-report", &|b| {
        *b = change_live(b, b"\"area_ratio\":", "\"area_ratio\":".len() + 2, &probe)
    });
    with("flip-spec", &|b| {
        *b = change_live(b, b"IH90::1x1:", 4, &probe)
    });
    with("zeroed-page2", &|b| b[ps..2 * ps].fill(0));
    with("zeroed-middle", &|b| {
        b[(pages / 2) * ps..(pages / 2 + 1) * ps].fill(0)
    });
    with("zeroed-last", &|b| b[(pages - 1) * ps..].fill(0));
    assert!(copies.len() >= 9);
    for (name, b) in copies {
        let d = root.join(name);
        std::fs::create_dir_all(&d).unwrap();
        let file = d.join("file.db");
        std::fs::write(&file, &b).unwrap();
        refused_everywhere(&file, &good, "damaged");
    }
}

#[test]
fn a_refused_merge_of_several_inputs_leaves_the_target_as_it_was() {
    let d_guard = dir("merge-several");
    let d = d_guard.path();
    let p = |name: &str| d.join(name);
    explore(&p("a.db"));
    // The same families with another threshold: other settings.
    let out = run(&[
        "explore",
        "--quick",
        "--families",
        "IH83,IH90",
        "--threshold",
        "0.2",
        "--db",
        p("other.db").to_str().unwrap(),
    ]);
    assert!(out.status.success());
    // A second input with the first's settings and units the target lacks.
    let out = run(&[
        "explore",
        "--quick",
        "--families",
        "IH76",
        "--db",
        p("b.db").to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let s = |name: &str| p(name).to_str().unwrap().to_string();
    std::fs::copy(p("a.db"), p("target.db")).unwrap();
    for extra in [&[][..], &["--allow-incomplete"][..]] {
        // Into an existing target: b.db would be merged first, then other.db refused.
        let before = std::fs::read(p("target.db")).unwrap();
        let mut args = vec!["merge".to_string(), "--into".into(), s("target.db")];
        args.extend(extra.iter().map(|x| x.to_string()));
        args.extend([s("b.db"), s("other.db")]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains("other.db") && err.contains("nothing merged"),
            "{err}"
        );
        assert_eq!(
            std::fs::read(p("target.db")).unwrap(),
            before,
            "{args:?} changed the target"
        );
        // Into a new target: the inputs disagree with each other; no file is left.
        let mut args = vec!["merge".to_string(), "--into".into(), s("new.db")];
        args.extend(extra.iter().map(|x| x.to_string()));
        args.extend([s("a.db"), s("other.db")]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2));
        assert!(!p("new.db").exists(), "{args:?} left a target behind");
    }
    // Inputs that agree are all merged.
    let out = run(&["merge", "--into", &s("new.db"), &s("a.db"), &s("b.db")]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
