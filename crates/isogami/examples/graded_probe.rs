//! Probe (not shipped): grades rotating squares toward a disc and follows the path.
use isogami::graded::{check_path, grade, setup, GradedRequest};
use isogami::stop::NEVER;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).map_or(3, |a| a.parse().unwrap());
    let states: usize = args.get(2).map_or(4, |a| a.parse().unwrap());
    let steps: usize = args.get(3).map_or(20, |a| a.parse().unwrap());
    let design = args.get(4).cloned().unwrap_or("rotating-squares".into());
    let t: Option<f64> = args.get(5).map(|a| a.parse().unwrap());
    let request = GradedRequest {
        design,
        rows: n,
        cols: n,
        states,
        t,
        ..GradedRequest::default()
    };
    let (sheet, report) = grade(&request, &mut |_, _| true, NEVER).unwrap();
    println!("{report:?}");
    let (_, problem) = setup(&request).unwrap();
    let path = check_path(&sheet, &problem, steps, NEVER).unwrap();
    for s in &path.states {
        println!(
            "opening {:.3} gap {:.2e} dof {:?} small {:?} overlap {:?}",
            s.opening, s.joint_gap, s.dof, s.smallest, s.overlap
        );
    }
    println!(
        "closed spread {:.3e} reached {}",
        path.closed_spread, path.reached
    );
}
