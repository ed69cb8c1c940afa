//! Graded sheets (issue 25's benchmark): the optimisation of rotating squares towards a disc
//! at 100, 400 and 1,600 tiles (5×5, 10×10 and 20×20 cells of the 2×2 design), on the
//! machine's cores (goal: 400 tiles in ≤ 10 s).
//!
//! `cargo bench -p isogami --bench graded` times 100 and 400 tiles; `-- 1600` (or any list of
//! tile counts among 100, 400, 1600) chooses, `-- --runs N` repeats (default 3),
//! `-- --iterations N` caps the fit as `isogami graded --iterations` does (default 200). A solve
//! takes seconds to minutes, so this is a plain timing harness, not criterion's (which takes
//! at least ten samples): each size is graded `runs` times through the library's entry point
//! (`api::graded_sheet`, as every front end) and the median optimisation time (the report's
//! `seconds`: the fit and the closing projection, not the set-up or the path check) is printed
//! with what the solve reached — its iterations, the outline's largest error, the pins' gap and
//! whether the graded sheet follows one motion back to closed — since a fast solve that has
//! not converged is no result.

use isogami::api::graded_sheet;
use isogami::graded::GradedRequest;
use isogami::stop::NEVER;

fn main() {
    let mut sizes: Vec<usize> = Vec::new();
    let mut runs = 3;
    let mut iterations = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--runs" => {
                runs = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|&n| n > 0)
                    .unwrap_or_else(|| fail("--runs takes a positive count"));
            }
            "--iterations" => {
                iterations = Some(
                    args.next()
                        .and_then(|v| v.parse().ok())
                        .filter(|&n| n > 0)
                        .unwrap_or_else(|| fail("--iterations takes a positive count")),
                );
            }
            // cargo bench passes --bench to every harness.
            "--bench" => {}
            tiles => match tiles.parse() {
                Ok(n @ (100 | 400 | 1600)) => sizes.push(n),
                _ => fail(&format!("{tiles}: tile counts are 100, 400 or 1600")),
            },
        }
    }
    if sizes.is_empty() {
        sizes = vec![100, 400];
    }
    for tiles in sizes {
        // The 2×2 design has 4 tiles a cell.
        let cells = ((tiles / 4) as f64).sqrt() as usize;
        let mut request = GradedRequest {
            design: "rotating-squares".into(),
            rows: cells,
            cols: cells,
            ..GradedRequest::default()
        };
        if let Some(n) = iterations {
            request.solve.max_iterations = n;
        }
        let mut seconds = Vec::with_capacity(runs);
        for run in 0..runs {
            let graded = graded_sheet(&request, &mut |_| true, NEVER)
                .unwrap_or_else(|e| fail(&format!("{tiles} tiles: {e}")));
            let (report, path) = (&graded.report, &graded.path);
            let elapsed = report.seconds;
            seconds.push(elapsed);
            println!(
                "graded {tiles} tiles run {}: {elapsed:.2} s, {} iterations, outline within {:.2} %, \
                 pins {:.1e}, one motion back to closed: {}",
                run + 1,
                report.iterations,
                100.0 * report.max_outline_error,
                report.joint_gap,
                path.reached
            );
        }
        seconds.sort_by(f64::total_cmp);
        println!(
            "graded {tiles} tiles: median {:.2} s over {runs} runs",
            seconds[runs / 2]
        );
    }
}

fn fail(message: &str) -> ! {
    eprintln!("graded bench: {message}");
    std::process::exit(2)
}
