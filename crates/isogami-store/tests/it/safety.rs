//! Databases that cannot be damaged: reading never writes, foreign and damaged files are
//! refused and left byte-for-byte unchanged with no files created beside them, one writer at
//! a time, interrupted writes are rolled back by the next writer.

use crate::common;

use common::{real_db, run, snapshot, temp};
use isogami_store::{Check, DesignQuery, Store, StoreError, StoreWriter, SCHEMA_VERSION};
use rusqlite::Connection;
use std::path::{Path, PathBuf};

/// Every way of opening a file, each of which must refuse it and leave it untouched.
fn refuse_everywhere(path: &Path) -> Vec<StoreError> {
    let before = snapshot(path);
    let errors = vec![
        Store::open_read(path, Check::Quick).unwrap_err(),
        Store::open_read(path, Check::Full).unwrap_err(),
        StoreWriter::open(path, None, Check::Quick).unwrap_err(),
        StoreWriter::open(path, Some(run()), Check::Full).unwrap_err(),
    ];
    assert_eq!(snapshot(path), before, "{} changed", path.display());
    for e in &errors {
        let text = e.to_string();
        assert!(!text.contains('\n'), "one line: {text}");
    }
    errors
}

fn sqlite_file(path: &Path, sql: &str) {
    let c = Connection::open(path).unwrap();
    c.execute_batch(sql).unwrap();
}

#[test]
fn foreign_files_are_refused_and_left_unchanged() {
    let dir_guard = temp("foreign");
    let dir = dir_guard.path();
    let text = dir.join("notes.txt");
    std::fs::write(&text, "isogami? no: just a text file\n".repeat(20)).unwrap();
    let unrelated = dir.join("unrelated.sqlite");
    sqlite_file(
        &unrelated,
        "CREATE TABLE users(name TEXT); INSERT INTO users VALUES ('x');",
    );
    let designs = dir.join("designs.sqlite");
    sqlite_file(
        &designs,
        "CREATE TABLE designs(spec TEXT PRIMARY KEY, colour TEXT); \
         INSERT INTO designs VALUES ('IH1::1x1:ab', 'red');",
    );
    let no_tables = dir.join("no-tables.sqlite");
    sqlite_file(&no_tables, "PRAGMA user_version = 7;");
    let wal = dir.join("wal.sqlite");
    sqlite_file(
        &wal,
        "PRAGMA journal_mode = WAL; CREATE TABLE t(x); INSERT INTO t VALUES (1);",
    );
    assert!(!common::snapshot(&wal).bytes_empty());
    for path in [&text, &unrelated, &designs, &no_tables, &wal] {
        for e in refuse_everywhere(path) {
            assert!(
                matches!(e, StoreError::NotSqlite | StoreError::Foreign { .. }),
                "{}: {e:?}",
                path.display()
            );
            assert!(e.to_string().contains("not an isogami database"), "{e}");
        }
    }
    let e = Store::open_read(&designs, Check::Quick).unwrap_err();
    assert_eq!(
        e.to_string(),
        "not an isogami database (an SQLite file with tables designs)"
    );
}

#[test]
fn other_schema_versions_are_refused_and_left_unchanged() {
    let dir_guard = temp("versions");
    let dir = dir_guard.path();
    // Version 1 (issue 2): meta(key, value) and no application id.
    let v1 = dir.join("v1.db");
    sqlite_file(
        &v1,
        "CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
         INSERT INTO meta VALUES ('schema_version', '1'), ('settings', '{}');
         CREATE TABLE work_units(id TEXT PRIMARY KEY);
         CREATE TABLE designs(spec TEXT PRIMARY KEY);",
    );
    // A future version.
    let future = dir.join("future.db");
    real_db(&future);
    sqlite_file(
        &future,
        &format!(
            "UPDATE meta SET value = '{}' WHERE key = 'schema_version'",
            SCHEMA_VERSION + 1
        ),
    );
    for (path, found) in [(&v1, 1), (&future, SCHEMA_VERSION + 1)] {
        for e in refuse_everywhere(path) {
            match e {
                StoreError::SchemaVersion { found: f, expected } => {
                    assert_eq!((f, expected), (found, SCHEMA_VERSION))
                }
                other => panic!("{}: {other:?}", path.display()),
            }
        }
        let msg = Store::open_read(path, Check::Quick)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("re-run explore into a new file"), "{msg}");
    }
}

#[test]
fn readers_need_an_existing_database_and_create_nothing() {
    let dir_guard = temp("readers");
    let dir = dir_guard.path();
    let missing = dir.join("missing.db");
    assert!(matches!(
        Store::open_read(&missing, Check::Quick),
        Err(StoreError::NotFound)
    ));
    let empty = dir.join("empty.db");
    std::fs::write(&empty, b"").unwrap();
    assert!(matches!(
        Store::open_read(&empty, Check::Full),
        Err(StoreError::EmptyFile)
    ));
    assert!(matches!(
        Store::open_read(dir, Check::Quick),
        Err(StoreError::NotAFile)
    ));
    assert_eq!(std::fs::read_dir(dir).unwrap().count(), 1, "only empty.db");
    // A real database: every read leaves it as it was, with nothing beside it.
    let db = dir.join("real.db");
    real_db(&db);
    let before = snapshot(&db);
    let s = Store::open_read(&db, Check::Full).unwrap();
    s.stats().unwrap();
    s.page(&DesignQuery::default()).unwrap();
    s.all_facet_counts(&DesignQuery::default()).unwrap();
    drop(s);
    assert_eq!(snapshot(&db), before);
}

#[test]
fn writers_create_only_in_new_or_empty_files() {
    let dir_guard = temp("create");
    let dir = dir_guard.path();
    let empty = dir.join("empty.db");
    std::fs::write(&empty, b"").unwrap();
    let fresh = dir.join("fresh.db");
    for path in [&empty, &fresh] {
        drop(StoreWriter::open(path, Some(run()), Check::Full).unwrap());
        let s = Store::open_read(path, Check::Full).unwrap();
        assert_eq!(s.settings().unwrap().as_deref(), Some(common::SETTINGS));
        // Nothing left beside it once the writer is gone.
        assert!(isogami_store::sidecar_paths(path)
            .iter()
            .all(|p| !p.exists()));
    }
}

#[test]
fn one_writer_at_a_time_while_readers_read() {
    let dir_guard = temp("lock");
    let dir = dir_guard.path();
    let db = dir.join("db");
    real_db(&db);
    let first = StoreWriter::open(&db, Some(run()), Check::Quick).unwrap();
    let second = StoreWriter::open(&db, Some(run()), Check::Quick);
    assert!(matches!(second, Err(StoreError::Busy)), "{second:?}");
    assert!(second
        .unwrap_err()
        .to_string()
        .contains("another isogami process"));
    // Readers are not blocked by the writer lock.
    assert_eq!(
        Store::open_read(&db, Check::Full)
            .unwrap()
            .work_units()
            .unwrap()
            .len(),
        2
    );
    drop(first);
    drop(StoreWriter::open(&db, None, Check::Quick).unwrap());
}

/// What plain SQLite reads from a database file: every row of every table, and whether its
/// integrity check passes (None when it cannot be read at all).
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
        let mut stmt = c
            .prepare(&format!("SELECT * FROM {table} ORDER BY rowid"))
            .ok()?;
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

/// A change to the first occurrence of `needle` that hits live data: SQLite reads different
/// rows or its integrity check fails. (Free space inside pages can hold stale copies of old
/// cells; changing those damages nothing.)
fn change_live(good: &[u8], needle: &[u8], change: &dyn Fn(&mut [u8], usize)) -> Vec<u8> {
    let dir_guard = temp("probe");
    let dir = dir_guard.path();
    let (probe, original) = (dir.join("probe.db"), dir.join("original.db"));
    std::fs::write(&original, good).unwrap();
    let reference = sqlite_view(&original).unwrap();
    let mut from = 0;
    while let Some(k) = good[from..].windows(needle.len()).position(|w| w == needle) {
        let at = from + k;
        let mut bytes = good.to_vec();
        change(&mut bytes, at);
        std::fs::write(&probe, &bytes).unwrap();
        if sqlite_view(&probe) != Some(reference.clone()) {
            return bytes;
        }
        from = at + 1;
    }
    panic!(
        "no live occurrence of {:?}",
        String::from_utf8_lossy(needle)
    );
}

fn page_size(bytes: &[u8]) -> usize {
    match u16::from_be_bytes([bytes[16], bytes[17]]) {
        1 => 65536,
        n => usize::from(n),
    }
}

/// Damaged copies of a real database, each with what was done to it.
fn damaged_copies(original: &Path, dir: &Path) -> Vec<(String, PathBuf)> {
    let good = std::fs::read(original).unwrap();
    let ps = page_size(&good);
    let pages = good.len() / ps;
    assert!(pages >= 8, "{pages} pages");
    let mut out = Vec::new();
    let mut make = |name: &str, f: &dyn Fn(&mut Vec<u8>)| {
        let mut bytes = good.clone();
        f(&mut bytes);
        assert_ne!(bytes, good, "{name} changes the file");
        let path = dir.join(format!("{name}.db"));
        std::fs::write(&path, &bytes).unwrap();
        out.push((name.to_string(), path));
    };
    // Truncations.
    make("truncated-to-half", &|b| b.truncate(ps * (pages / 2)));
    make("truncated-by-one-page", &|b| b.truncate(ps * (pages - 1)));
    make("truncated-mid-page", &|b| {
        b.truncate(ps * (pages - 2) + ps / 3)
    });
    make("truncated-to-one-page", &|b| b.truncate(ps));
    // Bit flips in different pages and structures.
    make("flip-page1-btree-header", &|b| b[100] ^= 0x08);
    make("flip-page2-header", &|b| b[ps + 3] ^= 0x40);
    make("flip-last-page-cell-pointer", &|b| {
        let p = ps * (pages - 1);
        let header = if b[p] == 0x05 || b[p] == 0x02 { 12 } else { 8 };
        b[p + header] ^= 0x10;
    });
    make("flip-in-report-json", &|b| {
        *b = change_live(b, b"\"frames\"", &|b, at| b[at + 2] ^= 0x01);
    });
    make("flip-in-stored-number", &|b| {
        // A digit inside a report: still valid JSON, a different number.
        let key = b"\"max_expansion\":";
        *b = change_live(b, key, &|b, at| {
            let at = at + key.len();
            let digit = at + b[at..].iter().position(u8::is_ascii_digit).unwrap();
            b[digit] = if b[digit] == b'7' { b'8' } else { b'7' };
        });
    });
    make("flip-in-spec-text", &|b| {
        *b = change_live(b, b"IH90::1x1:", &|b, at| b[at + 3] ^= 0x01);
    });
    // Zeroed pages.
    make("zeroed-page-1", &|b| b[..ps].fill(0));
    make("zeroed-page-3", &|b| b[2 * ps..3 * ps].fill(0));
    make("zeroed-middle-page", &|b| {
        let p = pages / 2;
        b[p * ps..(p + 1) * ps].fill(0)
    });
    make("zeroed-last-page", &|b| b[(pages - 1) * ps..].fill(0));
    out
}

#[test]
fn damaged_copies_are_refused_and_left_unchanged() {
    let dir_guard = temp("damage");
    let dir = dir_guard.path();
    let original = dir.join("original.db");
    real_db(&original);
    let copies = damaged_copies(&original, dir);
    assert!(copies.len() >= 9);
    for (name, path) in &copies {
        let before = snapshot(path);
        let refused = [
            Store::open_read(path, Check::Full).map(drop),
            StoreWriter::open(path, Some(run()), Check::Full).map(drop),
            StoreWriter::open(path, None, Check::Full).map(drop),
        ];
        for r in refused {
            let e = r.expect_err(name);
            let text = e.to_string();
            eprintln!("{name}: {text}");
            assert!(
                text.contains("damaged") && !text.contains('\n'),
                "{name}: {text}"
            );
        }
        assert_eq!(snapshot(path), before, "{name} changed");
    }
}

#[test]
fn quick_check_misses_changed_values_but_reading_them_does_not() {
    let dir_guard = temp("payload");
    let dir = dir_guard.path();
    let original = dir.join("original.db");
    real_db(&original);
    let copies = damaged_copies(&original, dir);
    let (_, path) = copies
        .iter()
        .find(|(n, _)| n == "flip-in-stored-number")
        .unwrap();
    // SQLite's structure check passes: the record's bytes are well formed.
    let s = Store::open_read(path, Check::Quick).expect("quick_check passes");
    // The row checksum catches the change as soon as the design is read.
    let mut damaged = 0;
    for spec in Store::open_read(&original, Check::Quick)
        .unwrap()
        .summaries()
        .unwrap()
        .iter()
        .map(|d| d.spec.clone())
    {
        if let Err(e) = s.design(&spec) {
            assert!(matches!(e, StoreError::Damaged(_)), "{e:?}");
            damaged += 1;
        }
    }
    assert_eq!(damaged, 1);
}

#[test]
fn an_interrupted_write_is_refused_by_readers_and_rolled_back_by_the_next_writer() {
    let dir_guard = temp("journal");
    let dir = dir_guard.path();
    let db = dir.join("db");
    real_db(&db);
    let committed = snapshot(&db);
    // A writer in the middle of a large transaction: its cache spills pages into the file.
    let c = Connection::open(&db).unwrap();
    c.execute_batch("PRAGMA cache_size = 2; BEGIN IMMEDIATE;")
        .unwrap();
    for i in 0..200 {
        c.execute(
            "INSERT INTO meta(key, value, checksum) VALUES (?1, ?2, 0)",
            rusqlite::params![format!("junk{i}"), "x".repeat(2000)],
        )
        .unwrap();
    }
    // The files as a kill -9 at this moment would leave them.
    let crashed = dir.join("crashed.db");
    std::fs::copy(&db, &crashed).unwrap();
    let journal = |p: &Path| {
        let mut s = p.as_os_str().to_owned();
        s.push("-journal");
        PathBuf::from(s)
    };
    std::fs::copy(journal(&db), journal(&crashed)).unwrap();
    c.execute_batch("ROLLBACK").unwrap();
    drop(c);
    assert_ne!(
        std::fs::read(&crashed).unwrap(),
        std::fs::read(&db).unwrap()
    );
    let before = snapshot(&crashed);
    let e = Store::open_read(&crashed, Check::Full).unwrap_err();
    assert!(matches!(e, StoreError::InterruptedWrite), "{e:?}");
    assert_eq!(snapshot(&crashed), before);
    // The next writer rolls the journal back: the file is the committed state again.
    drop(StoreWriter::open(&crashed, Some(run()), Check::Full).unwrap());
    assert!(!journal(&crashed).exists());
    let s = Store::open_read(&crashed, Check::Full).unwrap();
    assert_eq!(s.work_units().unwrap().len(), 2);
    assert_eq!(std::fs::read(&crashed).unwrap().len(), committed.len());
}
