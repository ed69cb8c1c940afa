//! Probe for graded sheets (not part of the tests): grades a design towards a disc and
//! prints the report and every state of the path check, one line each.
//!
//! `cargo run --release -p isogami --example graded_probe -- [CELLS [STATES [DESIGN [T]]]]`

use isogami::api::graded_sheet;
use isogami::graded::GradedRequest;
use isogami::stop::NEVER;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |k: usize| args.get(k).cloned();
    let cells: usize = arg(1).map_or(3, |a| a.parse().expect("CELLS is a number"));
    let states: usize = arg(2).map_or(8, |a| a.parse().expect("STATES is a number"));
    let design = arg(3).unwrap_or_else(|| "rotating-squares".into());
    let t: Option<f64> = arg(4).map(|a| a.parse().expect("T is a number"));
    let mut request = GradedRequest {
        design,
        rows: cells,
        cols: cells,
        states,
        t,
        ..GradedRequest::default()
    };
    // Overrides for probing: GRADED_<NAME>=value.
    let env = |name: &str| -> Option<f64> {
        std::env::var(format!("GRADED_{name}"))
            .ok()
            .map(|v| v.parse().expect("a number"))
    };
    let w = &mut request.weights;
    for (name, slot) in [
        ("FIT", &mut w.fit),
        ("SMOOTH", &mut w.smooth),
        ("BOUNDS", &mut w.bounds),
        ("JOINTS", &mut w.joints),
        ("OPENING", &mut w.opening),
        ("CORNER", &mut w.corner_fraction),
        ("ANGLE", &mut w.angle_fraction),
        ("EDGE", &mut w.edge_fraction),
        ("PIN", &mut w.pin_fraction),
        ("PRIOR", &mut w.prior),
    ] {
        if let Some(v) = env(name) {
            *slot = v;
        }
    }
    if let Some(v) = env("ITERATIONS") {
        request.solve.max_iterations = v as usize;
    }
    if let Some(v) = env("DECREASE") {
        request.solve.rel_decrease = v;
    }
    let run = graded_sheet(&request, &mut |_| true, NEVER).expect("graded");
    let r = &run.report;
    println!(
        "tiles {} iterations {} cost {:.3e} -> {:.3e} gap {:.1e} outline max {:.4} median {:.4} outside {:.4} corner {:.3} angle {:.1} edge {:.3} area {:.3} {:.2} s",
        r.tiles, r.iterations, r.cost[0], r.cost[1], r.joint_gap, r.max_outline_error,
        r.median_outline_error, r.max_outside, r.min_corner_fraction, r.min_angle_degrees, r.min_edge_fraction,
        r.min_area_fraction, r.seconds
    );
    for s in &run.path.states {
        println!(
            "opening {:.3} gap {:.2e} dof {:?} smallest {:?} overlap {:?}",
            s.opening, s.joint_gap, s.dof, s.smallest, s.overlap
        );
    }
    println!(
        "closed spread {:.3e}, reached {}",
        run.path.closed_spread, run.path.reached
    );
}
