//! Follows a written graded sheet's path again, with as many steps as asked (not part of the
//! tests): where exactly does its motion stop? The path check of `isogami graded` takes 20.
//!
//! `cargo run --release -p isogami --example graded_recheck -- SHEET.json [STEPS]`
//!
//! SHEET.json is what `isogami graded --out` writes; one line per state: its opening, pin
//! gap, DOF and any overlapping pair.

use isogami::graded::{check_path, problem_of, GradedSheet, Outline, Weights};
use isogami::stop::NEVER;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let file = args
        .get(1)
        .expect("SHEET.json, as `isogami graded --out` writes it");
    let steps: usize = args
        .get(2)
        .map_or(20, |a| a.parse().expect("STEPS is a number"));
    let text = std::fs::read_to_string(file).expect("a readable file");
    let json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let sheet: GradedSheet = serde_json::from_value(json["sheet"].clone()).expect("a sheet");
    // The path check weighs the pins, the opening and the turning rows only (the outline does
    // not enter it), at the default weights that `isogami graded` uses.
    let problem = problem_of(&sheet, Outline::Disc, Weights::default());
    let path = check_path(&sheet, &problem, steps, NEVER).expect("the path check");
    for s in &path.states {
        let dof = s.dof.map_or("?".into(), |d| d.to_string());
        let overlap = s
            .overlap
            .map_or("none".into(), |(a, b)| format!("tiles {a} and {b}"));
        println!(
            "{:.4} open: pins {:.2e} DOF {dof} overlap {overlap}",
            s.opening, s.joint_gap
        );
    }
    println!(
        "closed spread {:.3e}, reached {}",
        path.closed_spread, path.reached
    );
}
