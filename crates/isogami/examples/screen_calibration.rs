//! The data behind the cheap screen (`isogami::catalog::screen`): for every unique topology of
//! the given units, its first-order closing rates along both signs of the motion and what the
//! full deployment makes of it, with a summary of what the screen would reject.
//!
//! ```text
//! cargo run -p isogami --release --example screen_calibration -- IH21/1x1 IH28/1x1 ... [--rows]
//! ```
//!
//! `--rows` prints one line per topology: unit, spec, closing rate (+, −), locked (0/1),
//! steps, largest principal expansion, end reason, deployment seconds. Deployments run in parallel.

use isogami::api;
use isogami::catalog::screen::{closing_rates, screen_rate};
use isogami::catalog::CatalogSettings;
use isogami::cell::CellDims;
use isogami::deploy::EndReason;
use isogami::explore::enumerate_topologies;
use isogami::tiling::Family;
use rayon::prelude::*;
use std::time::Instant;

struct Row {
    unit: String,
    spec: String,
    rates: [f64; 2],
    locked: bool,
    steps: usize,
    max_expansion: f64,
    end: String,
    seconds: f64,
}

fn main() {
    let settings = CatalogSettings::default();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let print_rows = args.iter().any(|a| a == "--rows");
    let mut rows = Vec::new();
    for a in args.iter().filter(|a| !a.starts_with("--")) {
        let Some((f, d)) = a.split_once('/') else {
            eprintln!("expected FAMILY/AxB, got {a}");
            std::process::exit(2);
        };
        let (Ok(f), Ok(d)) = (f.parse::<Family>(), d.parse::<CellDims>()) else {
            eprintln!("expected FAMILY/AxB, got {a}");
            std::process::exit(2);
        };
        let topo = match enumerate_topologies(f, d, &settings.topology) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("{a}: {e}");
                std::process::exit(2);
            }
        };
        let found: Vec<Row> = topo
            .designs
            .par_iter()
            .filter_map(|design| {
                let rates = closing_rates(design, &settings)?;
                let t = Instant::now();
                let report = api::deploy(design, &settings.deploy_request(), &mut |_| true)
                    .ok()?
                    .report;
                Some(Row {
                    unit: a.clone(),
                    spec: design.to_string(),
                    rates,
                    locked: matches!(report.end_reason, EndReason::Locked) || report.steps < 2,
                    steps: report.steps,
                    max_expansion: report.max_expansion,
                    end: format!("{:?}", report.end_reason),
                    seconds: t.elapsed().as_secs_f64(),
                })
            })
            .collect();
        rows.extend(found);
    }
    if print_rows {
        for r in &rows {
            println!(
                "{} {} {:.6e} {:.6e} {} {} {:.4} {} {:.4}",
                r.unit,
                r.spec,
                r.rates[0],
                r.rates[1],
                u8::from(r.locked),
                r.steps,
                r.max_expansion,
                r.end,
                r.seconds
            );
        }
    }
    let kerf = settings.deploy.contact.kerf;
    let rate = screen_rate(&settings);
    let blocked = |r: &Row| r.rates.iter().all(|&x| x >= rate);
    let admitted = |r: &Row| !r.locked && r.max_expansion >= settings.threshold;
    let screened: Vec<&Row> = rows.iter().filter(|r| blocked(r)).collect();
    let total_time: f64 = rows.iter().map(|r| r.seconds).sum();
    let screened_time: f64 = screened.iter().map(|r| r.seconds).sum();
    let largest = screened
        .iter()
        .map(|r| r.max_expansion)
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let admitted_smaller_rate = rows
        .iter()
        .filter(|r| admitted(r))
        .map(|r| r.rates[0].min(r.rates[1]))
        .fold(0.0, f64::max);
    // The reach: expansion reached per kerf / r of arc, r the smaller closing rate, over the
    // designs that are not locked although both signs close some cut (r > 0.01).
    let reach = rows
        .iter()
        .filter(|r| !r.locked && r.rates[0].min(r.rates[1]) > 0.01)
        .map(|r| r.max_expansion * r.rates[0].min(r.rates[1]) / kerf)
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    println!(
        "{} topologies, {} locked, {} admitted (largest smaller closing rate of an admitted \
         design {admitted_smaller_rate:.2e}); largest reach {reach:.3} (expansion per kerf / r \
         of arc, designs not locked whose two signs close some cut at r > 0.01)",
        rows.len(),
        rows.iter().filter(|r| r.locked).count(),
        rows.iter().filter(|r| admitted(r)).count(),
    );
    println!(
        "screened (both signs close at >= {rate}): {}, of which locked {}, admitted \
         {}; largest expansion among them {largest:.4}",
        screened.len(),
        screened.iter().filter(|r| r.locked).count(),
        screened.iter().filter(|r| admitted(r)).count(),
    );
    println!("deployment seconds: {screened_time:.1} of {total_time:.1} on screened topologies");
}
