//! Property tests of the binary over every numeric flag and the design argument: whatever is
//! typed, `isogami` either succeeds with finite output (no NaN, no infinity, no `null` where a
//! number belongs) or fails with exactly one line on stderr, nothing on stdout and exit code
//! 2. Values inside a flag's documented range must succeed, values outside must fail.
//!
//! Each case spawns the binary, so there are a few dozen cases per flag, on fast inputs
//! (rotating squares; a one-unit exploration of the square grid; kerfs of at least 1e-3).

use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use serde_json::Value;
use std::process::{Command, Output};

const RS: &str = "rotating-squares";

/// Keys whose value may be `null` (an absent value, not a number that went wrong).
const NULLABLE: &[&str] = &[
    "behaviour",
    "motion",
    "largest_zero",
    "smallest_nonzero",
    "gap_decades",
    "linkage_signature",
    // The smallest covered share of no completed patch (none of the designs completes).
    "min_covered",
];

fn isogami(args: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_isogami"))
        .args(args)
        .output()
        .expect("binary runs")
}

/// A fresh scratch directory per case, removed when the guard drops.
fn scratch() -> tempfile::TempDir {
    tempfile::Builder::new()
        .prefix("isogami-cli-props-")
        .tempdir()
        .expect("temp dir")
}

/// Every number in `v` is finite (serde_json cannot hold anything else) and `null` appears
/// only under a [`NULLABLE`] key.
fn check_json(v: &Value, key: &str, path: &str) -> Result<(), String> {
    match v {
        Value::Null if !NULLABLE.contains(&key) => Err(format!("null at {path}")),
        Value::Array(items) => items
            .iter()
            .enumerate()
            .try_for_each(|(i, x)| check_json(x, key, &format!("{path}[{i}]"))),
        Value::Object(map) => map
            .iter()
            .try_for_each(|(k, x)| check_json(x, k, &format!("{path}.{k}"))),
        _ => Ok(()),
    }
}

/// A word in text output that a NaN or an infinity was formatted as.
fn non_finite_word(text: &str) -> Option<&str> {
    text.split(|c: char| c.is_whitespace() || "=(),[]:;%°".contains(c))
        .map(|w| w.trim_start_matches(['+', '-']))
        .find(|w| *w == "NaN" || *w == "inf")
}

/// The contract of every invocation; `expect`: whether it must succeed (`None`: either).
/// Returns the parsed JSON of a successful `--json` run.
fn well_behaved(args: &[String], expect: Option<bool>) -> Result<Option<Value>, TestCaseError> {
    let out = isogami(args);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.success() {
        prop_assert!(
            expect != Some(false),
            "{args:?} should have failed: {stdout}"
        );
        prop_assert!(!stdout.is_empty(), "{args:?}: empty output");
        if let Some(word) = non_finite_word(&stdout) {
            return Err(TestCaseError::fail(format!(
                "{args:?} printed '{word}': {stdout}"
            )));
        }
        if args.iter().any(|a| a == "--json") {
            let v: Value = serde_json::from_str(&stdout)
                .map_err(|e| TestCaseError::fail(format!("{args:?}: invalid JSON: {e}")))?;
            check_json(&v, "", "").map_err(|e| TestCaseError::fail(format!("{args:?}: {e}")))?;
            return Ok(Some(v));
        }
        Ok(None)
    } else {
        prop_assert!(
            expect != Some(true),
            "{args:?} should have succeeded: {stderr}"
        );
        prop_assert_eq!(out.status.code(), Some(2), "{:?}: {}", args, stderr);
        prop_assert!(stdout.is_empty(), "{args:?} printed to stdout: {stdout}");
        prop_assert_eq!(stderr.lines().count(), 1, "{:?}: {:?}", args, stderr);
        prop_assert!(stderr.starts_with("error: "), "{args:?}: {stderr:?}");
        Ok(None)
    }
}

fn args(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

/// Text typed where a number is expected: numbers in every notation, the non-finite
/// spellings Rust's parser accepts, and junk.
fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        3 => any::<f64>().prop_map(|x| x.to_string()),
        2 => (-1e3..1e3f64).prop_map(|x| format!("{x:e}")),
        2 => prop::sample::select(vec![
            "nan", "NaN", "inf", "-inf", "+inf", "infinity", "1e400", "-1e400", "-0", "0", "",
            " ", "0x10", "1_000", "1,5", "1e", ".", "٣", "1 2",
        ])
        .prop_map(str::to_string),
        2 => "[-+0-9.eE]{1,8}",
    ]
}

/// An integer flag's text: in-range, out-of-range and junk.
fn count_text(valid: std::ops::RangeInclusive<u64>) -> impl Strategy<Value = String> {
    prop_oneof![
        3 => valid.prop_map(|n| n.to_string()),
        2 => any::<u64>().prop_map(|n| n.to_string()),
        1 => any::<i64>().prop_map(|n| n.to_string()),
        2 => number_text(),
    ]
}

/// Whether `text` is a finite number in `[lo, hi]` as Rust parses it.
fn in_range(text: &str, lo: f64, hi: f64) -> bool {
    text.parse::<f64>().is_ok_and(|x| (lo..=hi).contains(&x))
}

/// Kerfs in (0, 1e-3) are valid but slow (the gap takes many small steps): not sampled.
fn slow_kerf(text: &str) -> bool {
    text.parse::<f64>().is_ok_and(|x| x > 0.0 && x < 1e-3)
}

fn kerf_text() -> impl Strategy<Value = String> {
    prop_oneof![
        2 => (1e-3..=0.2f64).prop_map(|x| x.to_string()),
        1 => (0.2..10.0f64).prop_map(|x| x.to_string()),
        2 => number_text(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn deploy_kerf(kerf in kerf_text(), method in prop::sample::select(vec!["rigid-modes", "ncm", "springs"])) {
        prop_assume!(!slow_kerf(&kerf));
        let a = args(&["deploy", "--design", RS, "--method", method, &format!("--kerf={kerf}"), "--json"]);
        let valid = kerf.parse::<f64>().is_ok_and(|x| x > 0.0 && x <= 0.2);
        if let Some(v) = well_behaved(&a, Some(valid))? {
            prop_assert_eq!(v["kerf"].as_f64(), kerf.parse::<f64>().ok());
        }
    }

    #[test]
    fn deploy_frame_count(n in count_text(2..=10_000), all_steps in any::<bool>()) {
        let mut a = args(&["deploy", "--design", RS, &format!("--frame-count={n}"), "--json"]);
        if all_steps {
            a.push("--all-steps".into());
        }
        let valid = n.parse::<u64>().is_ok_and(|k| (2..=10_000).contains(&k));
        if let Some(v) = well_behaved(&a, Some(valid))? {
            let frames = v["frames"].as_array().map_or(0, Vec::len);
            prop_assert!(frames >= 2);
            if !all_steps {
                prop_assert!(frames as u64 <= n.parse::<u64>().unwrap_or(0));
            }
        }
    }

    #[test]
    fn deploy_polar_t(values in prop::collection::vec(prop_oneof![3 => (0.0..=1.0f64).prop_map(|x| x.to_string()), 1 => number_text()], 0..14)) {
        let dir_guard = scratch();
    let dir = dir_guard.path();
        let plot = dir.join("plot.svg");
        let list = values.join(",");
        let a = args(&["deploy", "--design", RS, &format!("--polar-t={list}"), "--plot", plot.to_str().expect("utf-8")]);
        let valid = (1..=12).contains(&values.len()) && values.iter().all(|v| in_range(v.trim(), 0.0, 1.0));
        well_behaved(&a, Some(valid))?;
        prop_assert_eq!(plot.exists(), valid);
        prop_assert_eq!(dir.join("plot-polar.svg").exists(), valid);
    }

    #[test]
    fn analyze_tol(tol in number_text()) {
        let a = args(&["analyze", "--design", RS, &format!("--tol={tol}"), "--json"]);
        let valid = tol.parse::<f64>().is_ok_and(|x| x.is_finite() && x > 0.0 && x < 1.0);
        if let Some(v) = well_behaved(&a, Some(valid))? {
            prop_assert!(v["dof"].as_u64().is_some());
        }
    }

    #[test]
    fn compare_kerf(kerf in kerf_text()) {
        prop_assume!(!slow_kerf(&kerf));
        let a = args(&["compare", "--design", RS, &format!("--kerf={kerf}"), "--json"]);
        let valid = kerf.parse::<f64>().is_ok_and(|x| x > 0.0 && x <= 0.2);
        well_behaved(&a, Some(valid))?;
    }

    #[test]
    fn cell_params(params in prop::collection::vec(prop_oneof![3 => (-1.0..1.5f64).prop_map(|x| x.to_string()), 1 => number_text()], 0..4)) {
        let list = params.join(",");
        let a = args(&["cell", "--family", "IH28", &format!("--params={list}"), "--json"]);
        // Whether a shape is valid is the library's call; bad numbers are never accepted (a
        // blank list means the defaults).
        // Judged on the joined list: a sampled text such as "1,5" is two numbers there.
        let junk = list.split(',').any(|p| !p.trim().parse::<f64>().is_ok_and(f64::is_finite));
        let expect = if junk && !list.trim().is_empty() { Some(false) } else { None };
        well_behaved(&a, expect)?;
    }

    #[test]
    fn cell_size(a in 0u8..12, b in 0u8..12, sep in prop::sample::select(vec!["x", "X", "*", ""])) {
        let text = format!("{a}{sep}{b}");
        let args = args(&["cell", "--family", "IH28", "--cell", &text, "--json"]);
        let valid = sep.eq_ignore_ascii_case("x") && (1..=4).contains(&a) && (1..=4).contains(&b);
        if let Some(v) = well_behaved(&args, Some(valid))? {
            // IH28 has 4 tiles per minimal cell.
            prop_assert_eq!(v["tiles"].as_array().map_or(0, Vec::len), 4 * usize::from(a * b));
        }
    }

    #[test]
    fn design_argument(spec in prop_oneof![
        ".{0,30}",
        "(IH[0-9]{1,2}|rotating-squares)(:[-0-9.,e]{0,8}){0,2}(:[0-5]x[0-5])?(:[-abx]{0,12})?",
    ], command in prop::sample::select(vec!["analyze", "linkages"])) {
        prop_assume!(!spec.contains('\0'));
        let a = args(&[command, &format!("--design={spec}"), "--json"]);
        well_behaved(&a, None)?;
    }
}

/// A one-unit exploration (the square grid, minimal cell: a fraction of a second) into a
/// fresh database with `extra` flags.
fn explore(extra: &[String], expect: Option<bool>) -> Result<(), TestCaseError> {
    let dir_guard = scratch();
    let dir = dir_guard.path();
    let db = dir.join("designs.db");
    let mut a = args(&[
        "explore",
        "--families",
        "IH76",
        "--cells",
        "1x1",
        "--db",
        db.to_str().expect("utf-8"),
        "--json",
    ]);
    a.extend_from_slice(extra);
    let result = well_behaved(&a, expect);
    if matches!(result, Ok(None)) {
        // A refused run leaves no database behind.
        prop_assert!(!db.exists(), "{a:?} created the database");
    }
    result.map(|_| ())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn explore_threshold(t in prop_oneof![2 => (0.0..3.0f64).prop_map(|x| x.to_string()), 2 => number_text()]) {
        let valid = t.parse::<f64>().is_ok_and(|x| x.is_finite() && x >= 0.0);
        // Very large finite thresholds are the settings' call; only junk must fail.
        explore(&[format!("--threshold={t}")], if valid && in_range(&t, 0.0, 3.0) { Some(true) } else if !valid { Some(false) } else { None })?;
    }

    #[test]
    fn explore_samples(n in count_text(1..=20)) {
        let parsed = n.parse::<u64>().ok();
        prop_assume!(parsed.is_none_or(|k| k <= 20 || k > 10_000));
        explore(&[format!("--samples={n}")], Some(parsed.is_some_and(|k| (1..=20).contains(&k))))?;
    }

    #[test]
    fn explore_jobs(n in count_text(1..=4)) {
        let parsed = n.parse::<u64>().ok();
        prop_assume!(parsed.is_none_or(|k| k <= 4 || k > 1024));
        explore(&[format!("--jobs={n}")], Some(parsed.is_some_and(|k| (1..=4).contains(&k))))?;
    }

    #[test]
    fn explore_shard(i in count_text(0..=5), n in count_text(1..=5), sep in prop::sample::select(vec!["/", "/", ":", ""])) {
        let text = format!("{i}{sep}{n}");
        let valid = match (sep, i.trim().parse::<u64>(), n.trim().parse::<u64>()) {
            ("/", Ok(i), Ok(n)) => i < n && n <= 100_000,
            _ => false,
        };
        explore(&[format!("--shard={text}")], Some(valid))?;
    }
}
