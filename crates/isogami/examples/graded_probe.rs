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
    let request = GradedRequest {
        design,
        rows: cells,
        cols: cells,
        states,
        t,
        ..GradedRequest::default()
    };
    let run = graded_sheet(&request, &mut |_| true, NEVER).expect("graded");
    println!("{:?}", run.report);
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
