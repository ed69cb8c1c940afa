//! Exploration end to end: sharding equivalence, kill -9 resumption, database checks.

use isogami_store::{Check, Store, StoreWriter, SCHEMA_VERSION};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Families whose quick exploration keeps designs and takes seconds even unoptimised.
const FAMILIES: &str = "IH83,IH84,IH85,IH86,IH90,IH91,IH93,IH59,IH61,IH67,IH69,IH73";

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("isogami-explore-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn explore(db: &Path, extra: &[&str]) -> Output {
    explore_families(FAMILIES, db, extra)
}

fn explore_families(families: &str, db: &Path, extra: &[&str]) -> Output {
    let out = bin()
        .args([
            "explore",
            "--quick",
            "--families",
            families,
            "--db",
            db.to_str().unwrap(),
        ])
        .args(extra)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Unit ids, (spec, linkage signature, report) per design, stage counts per unit.
type Content = (
    Vec<String>,
    Vec<(String, String, String)>,
    Vec<Vec<(String, u64, u64)>>,
);

/// Everything a database says about the exploration, minus timings.
fn content(db: &Path) -> Content {
    let s = Store::open_read(db, Check::Full).unwrap();
    content_of(&s)
}

fn content_of(s: &Store) -> Content {
    let units = s.work_units().unwrap();
    let ids = units.iter().map(|(u, _)| u.id.clone()).collect();
    let stages = units
        .iter()
        .map(|(_, st)| {
            st.iter()
                .map(|x| (x.stage.clone(), x.count_in, x.count_out))
                .collect()
        })
        .collect();
    let designs = units
        .iter()
        .flat_map(|(u, _)| s.designs_of_unit(&u.id).unwrap())
        .map(|d| {
            (
                d.summary().spec.clone(),
                d.summary().linkage_signature.clone().unwrap_or_default(),
                d.report_json().to_string(),
            )
        })
        .collect();
    (ids, designs, stages)
}

#[test]
fn shards_merged_equal_one_run() {
    let d = dir("shards");
    let whole = d.join("whole.db");
    explore(&whole, &["--jobs", "2"]);
    let shards: Vec<PathBuf> = (0..3).map(|i| d.join(format!("shard{i}.db"))).collect();
    for (i, s) in shards.iter().enumerate() {
        explore(s, &["--shard", &format!("{i}/3"), "--jobs", "1"]);
    }
    let merged = d.join("merged.db");
    let mut args = vec![
        "merge".to_string(),
        "--into".into(),
        merged.to_str().unwrap().into(),
    ];
    args.extend(shards.iter().map(|s| s.to_str().unwrap().to_string()));
    let out = bin().args(&args).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (a, b) = (content(&whole), content(&merged));
    assert!(!a.1.is_empty(), "the exploration keeps designs");
    assert_eq!(a, b);
    // Shards are disjoint.
    let sizes: usize = shards.iter().map(|s| content(s).0.len()).sum();
    assert_eq!(sizes, a.0.len());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn killed_run_resumes_without_loss_or_duplicates() {
    let d = dir("kill");
    // IH6 and IH7 come first and take a while, so the kill lands mid-run.
    let families = format!("IH6,IH7,{FAMILIES}");
    let reference = d.join("reference.db");
    explore_families(&families, &reference, &["--jobs", "1"]);
    let db = d.join("killed.db");
    let mut child = bin()
        .args([
            "explore",
            "--quick",
            "--families",
            &families,
            "--jobs",
            "1",
            "--db",
            db.to_str().unwrap(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Wait for the first committed unit, then kill -9 in the middle of the run.
    let start = Instant::now();
    loop {
        std::thread::sleep(Duration::from_millis(20));
        let committed = db.exists()
            && Store::open_read(&db, Check::Quick)
                .ok()
                .and_then(|s| s.done_units().ok())
                .is_some_and(|u| !u.is_empty());
        if committed || start.elapsed() > Duration::from_secs(120) {
            break;
        }
    }
    child.kill().unwrap(); // SIGKILL on Unix
    child.wait().unwrap();
    // A kill in the middle of a commit leaves a rollback journal that readers refuse; a writer
    // (as the resumed run will) rolls it back. The lock of the killed process is gone.
    let partial = {
        let w = StoreWriter::open(&db, None, Check::Full).unwrap();
        content_of(&w).0.len()
    };
    let total = content(&reference).0.len();
    assert!(
        partial >= 1 && partial < total,
        "killed after {partial} of {total} units"
    );
    // Resume: only the missing units run, and the result equals an uninterrupted run.
    let out = explore_families(&families, &db, &["--jobs", "1"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(&format!(
            "{} work units run, {partial} already in",
            total - partial
        )),
        "{text}"
    );
    assert_eq!(content(&db), content(&reference));
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn database_checks() {
    let d = dir("checks");
    let db = d.join("a.db");
    explore_families("IH90", &db, &[]);
    // Other settings on the same file are refused.
    let out = bin()
        .args([
            "explore",
            "--quick",
            "--families",
            "IH90",
            "--threshold",
            "0.5",
            "--db",
            db.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("other settings"));
    // A future schema version is refused.
    rusqlite::Connection::open(&db)
        .unwrap()
        .execute(
            "UPDATE meta SET value = ?1 WHERE key = 'schema_version'",
            [(SCHEMA_VERSION + 1).to_string()],
        )
        .unwrap();
    for args in [
        vec![
            "explore",
            "--quick",
            "--families",
            "IH90",
            "--db",
            db.to_str().unwrap(),
        ],
        vec!["db", "stats", "--db", db.to_str().unwrap()],
    ] {
        let out = bin().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("schema version"),
            "{args:?}"
        );
    }
    // Bad arguments.
    for args in [
        vec!["explore", "--shard", "3/3"],
        vec!["explore", "--shard", "x"],
        vec!["explore", "--families", "IH19"],
        vec!["explore", "--cells", "9x9"],
        vec!["explore", "--samples", "0"],
        vec!["db", "stats", "--db", "/nonexistent/x.db"],
        vec!["merge", "--into", "/tmp/x.db", "/nonexistent/y.db"],
    ] {
        let out = bin().args(&args).output().unwrap();
        assert_eq!(
            out.status.code(),
            Some(2),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    std::fs::remove_dir_all(&d).unwrap();
}
