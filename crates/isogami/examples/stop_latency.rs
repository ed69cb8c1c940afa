//! How soon a large finite-sheet call stops once its progress hook says stop (issue 42,
//! item 20: `timeout=1.0` on a 40×40 analysis must raise within 1.5 s). Each entry point that
//! analyses a finite sheet runs on rotating squares' 40×40 region with a hook that answers
//! `false` from `--after` seconds on; the time from then to the call's return is the latency.
//! Reports the median and the largest over `--runs` runs.
//!
//! `cargo run --release -p isogami --example stop_latency -- [--after 1.0] [--runs 5]`
use isogami::api::{
    deploy_sheet, finite_sheet, pull_sheet, resolve_design, SheetDeployRequest, SheetPullRequest,
    SheetRequest,
};
use isogami::export::{export_design, ExportOptions, Format, PatchRequest};
use isogami::finite::Region;
use std::time::{Duration, Instant};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |name: &str, default: f64| -> f64 {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let after = Duration::from_secs_f64(value("--after", 1.0));
    let runs = value("--runs", 5.0) as usize;
    let design = resolve_design("rotating-squares").unwrap();
    let sheet = SheetRequest {
        region: Region::Cells { rows: 40, cols: 40 },
        complete: false,
        ..SheetRequest::default()
    };
    type Call<'a> = Box<dyn Fn(&mut dyn FnMut(usize) -> bool) -> bool + 'a>;
    let calls: Vec<(&str, Call)> = vec![
        (
            "finite_sheet (raw)",
            Box::new(|p| finite_sheet(&design, &sheet, p).is_err()),
        ),
        (
            "deploy_sheet",
            Box::new(|p| {
                let request = SheetDeployRequest {
                    sheet: SheetRequest {
                        complete: true,
                        ..sheet.clone()
                    },
                    ..SheetDeployRequest::default()
                };
                deploy_sheet(&design, &request, p).is_err()
            }),
        ),
        (
            "pull_sheet (raw)",
            Box::new(|p| {
                let request = SheetPullRequest {
                    sheet: sheet.clone(),
                    grips: None,
                    frames: 24,
                };
                pull_sheet(&design, &request, p).is_err()
            }),
        ),
        (
            "export svg 40x40",
            Box::new(|p| {
                let request = PatchRequest {
                    rows: 40,
                    cols: 40,
                    ..PatchRequest::default()
                };
                export_design(&design, &request, Format::Svg, &ExportOptions::default(), p).is_err()
            }),
        ),
    ];
    for (name, call) in &calls {
        let mut late: Vec<f64> = Vec::new();
        for _ in 0..runs {
            let started = Instant::now();
            let stopped = call(&mut |_| started.elapsed() < after);
            let elapsed = started.elapsed();
            if !stopped {
                println!(
                    "{name}: finished in {:.2} s before the stop",
                    elapsed.as_secs_f64()
                );
                break;
            }
            late.push(elapsed.saturating_sub(after).as_secs_f64());
        }
        if late.is_empty() {
            continue;
        }
        late.sort_by(f64::total_cmp);
        println!(
            "{name}: returned {:.3} s after the stop (median of {}), at most {:.3} s",
            late[late.len() / 2],
            late.len(),
            late[late.len() - 1]
        );
    }
}
