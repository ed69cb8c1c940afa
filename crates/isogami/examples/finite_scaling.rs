//! The zero decision of finite sheets across sizes (issue 42, item 10): for each design and
//! N, the raw N×N-cell region's degrees of freedom at the counting state (t = 0.3), its
//! lowest scaled eigenvalues, the gap, and its completion's kept share and DOF.
//!
//! `cargo run --release -p isogami --example finite_scaling -- [SPEC] [N...]`
//! (default: rotating squares and the IH15 design of the issue at 6, 10, 14, 20, 40).
use isogami::api::{finite_sheet, resolve_design, SheetRequest};
use isogami::finite::Region;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let specs: Vec<String> = match args.first() {
        Some(s) if s.contains(':') || s.contains('-') && s.parse::<usize>().is_err() => {
            vec![s.clone()]
        }
        _ => vec![
            "rotating-squares".into(),
            "IH15:0.04739750492,0.150335752741,0.150335752741:1x2:--aaab-b-aa-".into(),
        ],
    };
    let sizes: Vec<usize> = {
        let n: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
        if n.is_empty() {
            vec![6, 10, 14, 20, 40]
        } else {
            n
        }
    };
    for spec in &specs {
        let design = resolve_design(spec).unwrap();
        for &n in &sizes {
            let started = Instant::now();
            let request = SheetRequest {
                region: Region::Cells { rows: n, cols: n },
                ..SheetRequest::default()
            };
            match finite_sheet(&design, &request, &mut |_| true) {
                Ok(a) => {
                    let m = &a.raw_mobility;
                    let c = a.completion.as_ref().unwrap();
                    println!(
                        "{spec} {n}x{n}: {} tiles, raw {} DOF (largest zero {:.2e}, smallest \
                         non-zero {:.2e}, floor {:.2e}, gap {:.1} decades), closed {} DOF; \
                         completed {} DOF, kept {} of {} ({:.1} %), {:.1} s",
                        m.tiles,
                        m.dof,
                        m.largest_zero.unwrap_or(f64::NAN),
                        m.smallest_nonzero.unwrap_or(f64::NAN),
                        m.threshold,
                        m.gap_decades.unwrap_or(f64::NAN),
                        a.raw_closed_dof,
                        c.mobility.dof,
                        c.report.kept,
                        c.report.requested,
                        100.0 * c.report.covered_fraction,
                        started.elapsed().as_secs_f64()
                    );
                }
                Err(e) => println!(
                    "{spec} {n}x{n}: {e} ({:.1} s)",
                    started.elapsed().as_secs_f64()
                ),
            }
        }
    }
}
