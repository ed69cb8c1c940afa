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

fn dir(name: &str) -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-explore-{name}-"))
        .tempdir()
        .unwrap()
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
    let d_guard = dir("shards");
    let d = d_guard.path();
    let whole = d.join("whole.db");
    explore(&whole, &["--jobs", "2"]);
    let a = content(&whole);
    assert!(!a.1.is_empty(), "the exploration keeps designs");
    let classes = |db: &Path| {
        Store::open_read(db, Check::Full)
            .unwrap()
            .motion_classes()
            .unwrap()
    };
    // One process, 3 shards and 7 shards (more shards than some families have units).
    for n in [3, 7] {
        let shards: Vec<PathBuf> = (0..n)
            .map(|i| d.join(format!("shard{i}of{n}.db")))
            .collect();
        for (i, s) in shards.iter().enumerate() {
            explore(s, &["--shard", &format!("{i}/{n}"), "--jobs", "1"]);
        }
        let merged = d.join(format!("merged{n}.db"));
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
        assert_eq!(content(&merged), a, "{n} shards");
        assert_eq!(classes(&merged), classes(&whole), "{n} shards");
        // Shards are disjoint.
        let sizes: usize = shards.iter().map(|s| content(s).0.len()).sum();
        assert_eq!(sizes, a.0.len());
    }
}

#[test]
fn killed_run_resumes_without_loss_or_duplicates() {
    let d_guard = dir("kill");
    let d = d_guard.path();
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
}

#[test]
fn database_checks() {
    let d_guard = dir("checks");
    let d = d_guard.path();
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
}

/// Removes one committed work unit with its designs, as if the run had been killed before it.
fn forget_unit(db: &Path, unit: &str) {
    let c = rusqlite::Connection::open(db).unwrap();
    c.execute_batch("BEGIN").unwrap();
    c.execute(
        "DELETE FROM design_data WHERE design IN (SELECT id FROM designs WHERE work_unit = ?1)",
        [unit],
    )
    .unwrap();
    for sql in [
        "DELETE FROM designs WHERE work_unit = ?1",
        "DELETE FROM stage_counts WHERE work_unit = ?1",
        "DELETE FROM unit_memory WHERE work_unit = ?1",
        "DELETE FROM work_units WHERE id = ?1",
    ] {
        assert!(
            c.execute(sql, [unit]).unwrap() > 0
                || sql.contains("designs")
                || sql.contains("unit_memory"),
            "{sql}"
        );
    }
    c.execute_batch("COMMIT").unwrap();
}

fn run(args: &[&str]) -> (Option<i32>, String, String) {
    let out = bin().args(args).output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn merge_proves_the_shards_complete_and_reruns_add_nothing() {
    const FEW: &str = "IH83,IH84,IH90,IH91";
    let d_guard = dir("complete");
    let d = d_guard.path();
    let p = |name: &str| d.join(name).to_str().unwrap().to_string();
    let whole = d.join("whole.db");
    explore_families(FEW, &whole, &[]);
    for i in 0..3 {
        explore_families(
            FEW,
            &d.join(format!("s{i}.db")),
            &["--shard", &format!("{i}/3"), "--jobs", "1"],
        );
    }
    let (s0, s1, s2, merged) = (p("s0.db"), p("s1.db"), p("s2.db"), p("merged.db"));

    // Each shard can be checked on its own.
    let (code, out, _) = run(&["db", "check-shard", "--db", &s1, "--shard", "1/3"]);
    assert_eq!(code, Some(0));
    assert!(
        out.contains("shard 1/3 complete (1 of 1 work units)"),
        "{out}"
    );
    let (_, out, _) = run(&["db", "stats", "--db", &s1]);
    assert!(
        out.contains("shard 1/3 (1 of a 4-unit run) complete: 1 of 1 work units"),
        "{out}"
    );
    let (code, _, err) = run(&["db", "check-shard", "--db", &s1, "--shard", "2/3"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("holds shard 1/3, not 2/3"), "{err}");
    let (code, _, err) = run(&["db", "check-shard", "--db", &p("nope.db"), "--shard", "0/3"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("no such database"), "{err}");
    let (code, _, err) = run(&[
        "db",
        "check-shard",
        "--db",
        &whole.to_string_lossy(),
        "--shard",
        "0/3",
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("not a shard database"), "{err}");

    // A missing shard: refused in one line naming it, the target not even created.
    let (code, _, err) = run(&["merge", "--into", &merged, &s0, &s2]);
    assert_eq!(code, Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("shard 1/3 is missing"), "{err}");
    assert!(!Path::new(&merged).exists());

    // An incomplete shard (a unit lost): refused naming the file and the unit.
    let partial = p("s1-partial.db");
    std::fs::copy(&s1, &partial).unwrap();
    forget_unit(Path::new(&partial), "IH84/1x1");
    let (code, _, err) = run(&["merge", "--into", &merged, &s0, &partial, &s2]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains(&format!(
            "{partial}: shard 1/3 is incomplete (0 of 1 work units; IH84/1x1 missing)"
        )),
        "{err}"
    );
    assert!(!Path::new(&merged).exists());
    let (code, _, err) = run(&["db", "check-shard", "--db", &partial, "--shard", "1/3"]);
    assert_eq!(code, Some(2));
    assert!(err.contains("shard 1/3 is incomplete"), "{err}");
    // Told otherwise, the merge takes what is there.
    let (code, _, err) = run(&[
        "merge",
        "--allow-incomplete",
        "--into",
        &p("part.db"),
        &s0,
        &s2,
    ]);
    assert_eq!(code, Some(0), "{err}");

    // Rerunning the shard runs only the lost unit; the merge then equals one run.
    let out = explore_families(FEW, Path::new(&partial), &["--shard", "1/3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("1 work units run, 0 already in"), "{text}");
    let (code, _, err) = run(&["merge", "--into", &merged, &s0, &partial, &s2]);
    assert_eq!(code, Some(0), "{err}");
    assert_eq!(content(Path::new(&merged)), content(&whole));

    // Rerunning a complete shard, or merging the same shards again, adds no rows.
    let before = content(Path::new(&s1));
    let out = explore_families(FEW, Path::new(&s1), &["--shard", "1/3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("0 work units run, 1 already in"), "{text}");
    assert_eq!(content(Path::new(&s1)), before);
    let (code, out, err) = run(&["merge", "--into", &merged, &s0, &s1, &s2]);
    assert_eq!(code, Some(0), "{err}");
    assert!(
        out.contains("0 work units added (1 already present)"),
        "{out}"
    );
    assert_eq!(content(Path::new(&merged)), content(&whole));
    // A shard run into a file of another shard is refused.
    let (code, _, err) = run(&[
        "explore",
        "--quick",
        "--families",
        FEW,
        "--shard",
        "2/3",
        "--db",
        &s1,
    ]);
    assert_eq!(code, Some(2));
    assert!(err.contains("holds shard 1/3"), "{err}");
}

#[test]
fn db_units_lists_every_unit_with_its_time_and_peak_memory() {
    let d_guard = dir("units");
    let d = d_guard.path();
    let db = d.join("u.db");
    explore_families("IH83,IH84,IH90", &db, &[]);
    let db_arg = db.to_str().unwrap();
    let (code, json, err) = run(&["db", "units", "--db", db_arg, "--json"]);
    assert_eq!(code, Some(0), "{err}");
    let units: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    let store = Store::open_read(&db, Check::Full).unwrap();
    let stored = store.work_units().unwrap();
    assert_eq!(units.len(), stored.len());
    let seconds: Vec<f64> = units
        .iter()
        .map(|u| u["seconds"].as_f64().unwrap())
        .collect();
    assert!(seconds.windows(2).all(|w| w[0] >= w[1]), "{seconds:?}");
    for u in &units {
        let id = u["id"].as_str().unwrap();
        let designs = store.designs_of_unit(id).unwrap().len() as u64;
        assert_eq!(u["designs"].as_u64(), Some(designs), "{id}");
        if cfg!(target_os = "linux") {
            assert!(u["peak_rss_bytes"].as_u64().unwrap() > 1 << 20, "{id}");
        }
    }
    let (code, table, _) = run(&["db", "units", "--db", db_arg, "--top", "1"]);
    assert_eq!(code, Some(0));
    assert!(table.contains(units[0]["id"].as_str().unwrap()), "{table}");
    assert!(!table.contains(units[1]["id"].as_str().unwrap()), "{table}");
    let (code, stats, _) = run(&["db", "stats", "--db", db_arg]);
    assert_eq!(code, Some(0));
    assert!(
        stats.contains("largest peak memory") || !cfg!(target_os = "linux"),
        "{stats}"
    );
    let (code, _, err) = run(&[
        "db",
        "units",
        "--db",
        d.join("missing.db").to_str().unwrap(),
    ]);
    assert_eq!(code, Some(2));
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn db_motions_lists_shared_motions_and_stats_counts_them() {
    let d_guard = dir("motions");
    let d = d_guard.path();
    let db = d.join("m.db");
    explore_families("IH28,IH29,IH83,IH90", &db, &[]);
    let db_arg = db.to_str().unwrap();
    let (code, json, err) = run(&["db", "motions", "--db", db_arg, "--json"]);
    assert_eq!(code, Some(0), "{err}");
    let classes: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    let sizes: Vec<usize> = classes
        .iter()
        .map(|c| c["variants"].as_array().unwrap().len())
        .collect();
    assert!(sizes.windows(2).all(|w| w[0] >= w[1]), "{sizes:?}");
    let shared = sizes.iter().filter(|&&n| n > 1).count();
    assert!(shared >= 2, "{sizes:?}");
    let (code, table, _) = run(&["db", "motions", "--db", db_arg]);
    assert_eq!(code, Some(0));
    assert_eq!(table.matches("\nmotion ").count(), shared, "{table}");
    let (_, all, _) = run(&["db", "motions", "--db", db_arg, "--all"]);
    assert_eq!(all.matches("\nmotion ").count(), classes.len(), "{all}");
    let (_, stats, _) = run(&["db", "stats", "--db", db_arg]);
    let line = format!(
        "{} topologies, {} distinct motions ({shared} found in several",
        sizes.iter().sum::<usize>(),
        classes.len()
    );
    assert!(stats.contains(&line), "{stats}");
}

/// `analyze` and `deploy` say whether a design's finite patch has a one-DOF sheet, as the
/// catalogue stored it: for the first designs by spec of a quick exploration with and
/// without a sheet (up to three of each), the text names the stored fraction or says there
/// is none.
#[test]
fn analyze_and_deploy_say_whether_the_stored_design_has_a_one_dof_sheet() {
    let d = dir("sheet-lines");
    let db = d.path().join("q.db");
    explore(&db, &[]);
    let store = Store::open_read(&db, Check::Full).unwrap();
    let mut rows = store.summaries().unwrap();
    rows.sort_by(|a, b| a.spec.cmp(&b.spec));
    let with: Vec<_> = rows
        .iter()
        .filter(|r| r.finite_covered.is_some())
        .take(3)
        .collect();
    let without: Vec<_> = rows
        .iter()
        .filter(|r| r.finite_covered.is_none())
        .take(3)
        .collect();
    assert!(
        !with.is_empty() && !without.is_empty(),
        "the quick run holds both kinds"
    );
    for r in with.iter().chain(&without) {
        for command in ["analyze", "deploy"] {
            let out = bin().args([command, "--design", &r.spec]).output().unwrap();
            assert!(out.status.success(), "{command} {}", r.spec);
            let text = String::from_utf8_lossy(&out.stdout);
            let line = text
                .lines()
                .find(|l| l.starts_with("sheet "))
                .unwrap_or_else(|| panic!("{command} {}: no sheet line in\n{text}", r.spec));
            match r.finite_covered {
                Some(c) => assert!(
                    line.contains(&format!("keeping {:.0} %", 100.0 * c)),
                    "{command} {}: {line}",
                    r.spec
                ),
                None => assert!(
                    line.contains("NO ONE-DOF SHEET"),
                    "{command} {}: {line}",
                    r.spec
                ),
            }
        }
    }
}

/// `db designs` lists the catalogue as the browser does: buildable designs first, each group
/// by largest area ratio; a range keeps exactly the matching designs; bad arguments are one
/// line and exit 2. Checked against the store's own rows and the buildable rule written out.
#[test]
fn db_designs_lists_buildable_designs_first_and_filters_like_the_catalogue() {
    let d = dir("db-designs");
    let db = d.path().join("q.db");
    explore(&db, &[]);
    let db_arg = db.to_str().unwrap();
    let all = Store::open_read(&db, Check::Full)
        .unwrap()
        .summaries()
        .unwrap();
    let run = |extra: &[&str]| -> serde_json::Value {
        let out = bin()
            .args(["db", "designs", "--db", db_arg, "--json", "--limit", "1000"])
            .args(extra)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let page = run(&[]);
    let rows = page["rows"].as_array().unwrap();
    assert_eq!(page["total"].as_u64(), Some(all.len() as u64));
    assert_eq!(rows.len(), all.len());
    let rule = |r: &serde_json::Value| {
        !r["finite_covered"].is_null()
            && !r["open_t"].is_null()
            && r["shape_tolerance"].as_f64().is_none_or(|t| t >= 0.0025)
    };
    let flags: Vec<bool> = rows
        .iter()
        .map(|r| r["buildable"].as_bool().unwrap())
        .collect();
    for (r, &b) in rows.iter().zip(&flags) {
        assert_eq!(rule(r), b, "{}", r["spec"]);
    }
    assert!(
        flags.contains(&true) && flags.contains(&false),
        "both kinds: {flags:?}"
    );
    assert!(flags.windows(2).all(|w| w[0] >= w[1]), "buildable first");
    for w in rows.windows(2) {
        if w[0]["buildable"] == w[1]["buildable"] {
            assert!(w[0]["max_area_ratio"].as_f64() >= w[1]["max_area_ratio"].as_f64());
        }
    }
    let covered = run(&["--range", "finite_covered:0.9:", "--lead", "all"]);
    let want = all
        .iter()
        .filter(|s| s.finite_covered.is_some_and(|c| c >= 0.9))
        .count();
    assert_eq!(covered["total"].as_u64(), Some(want as u64));
    for bad in [
        &["--range", "finite_covered:x:"][..],
        &["--range", "nope:1:2"],
        &["--sort", "nope"],
        &["--lead", "some"],
        &["--family", "IH999"],
    ] {
        let out = bin()
            .args(["db", "designs", "--db", db_arg])
            .args(bad)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{bad:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{bad:?}: {err}");
        assert!(out.stdout.is_empty(), "{bad:?}");
    }
}
