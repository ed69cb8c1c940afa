//! Probe for graded sheets (not part of the tests): grades a design towards a disc and
//! prints the report and every state of the path check, one line each.
//!
//! `cargo run --release -p isogami --example graded_probe -- [CELLS|ROWSxCOLS [STATES [DESIGN [T]]]]`
//!
//! `GRADED_SVG=FILE` also draws the closed tiling, the fitted opened state and every state of
//! the path check side by side, the first overlapping pair filled.

use isogami::api::graded_sheet;
use isogami::graded::GradedRequest;
use isogami::stop::NEVER;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |k: usize| args.get(k).cloned();
    // CELLS: a number (square region) or ROWSxCOLS.
    let cells = arg(1).unwrap_or_else(|| "3".into());
    let (rows, cols) = match cells.split_once('x') {
        Some((r, c)) => (r.parse().expect("ROWS"), c.parse().expect("COLS")),
        None => {
            let n: usize = cells.parse().expect("CELLS is a number or ROWSxCOLS");
            (n, n)
        }
    };
    let states: usize = arg(2).map_or(8, |a| a.parse().expect("STATES is a number"));
    let design = arg(3).unwrap_or_else(|| "rotating-squares".into());
    let t: Option<f64> = arg(4).map(|a| a.parse().expect("T is a number"));
    let mut request = GradedRequest {
        design,
        rows,
        cols,
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
        ("FIELDW", &mut w.field),
        ("SMOOTH", &mut w.smooth),
        ("BOUNDS", &mut w.bounds),
        ("JOINTS", &mut w.joints),
        ("OPENING", &mut w.opening),
        ("CORNER", &mut w.corner_fraction),
        ("ANGLE", &mut w.angle_fraction),
        ("EDGE", &mut w.edge_fraction),
        ("PIN", &mut w.pin_fraction),
        ("PRIOR", &mut w.prior),
        ("STATEEXP", &mut w.state_exponent),
    ] {
        if let Some(v) = env(name) {
            *slot = v;
        }
    }
    if let Ok(text) = std::env::var("GRADED_TARGET") {
        request.outline = isogami::graded::parse_outline(&text).expect("a target");
    }
    if let Ok(text) = std::env::var("GRADED_FIELD") {
        request.field = Some(isogami::graded::parse_field(&text).expect("a field"));
    }
    if let Some(v) = env("ITERATIONS") {
        request.solve.max_iterations = v as usize;
    }
    if let Some(v) = env("PROJECTION") {
        request.solve.max_projection_iterations = v as usize;
    }
    if let Some(v) = env("DECREASE") {
        request.solve.rel_decrease = v;
    }
    // GRADED_TRACE=K: the cost every K iterations.
    let trace = env("TRACE").map(|k| k as usize);
    let clock = std::time::Instant::now();
    let run = graded_sheet(
        &request,
        &mut |p| {
            if let Some(k) = trace {
                if p.iteration % k == 0 {
                    eprintln!(
                        "it {} stage {} cost {:.4e} {:.2} s",
                        p.iteration,
                        p.stage,
                        p.cost,
                        clock.elapsed().as_secs_f64()
                    );
                }
            }
            true
        },
        NEVER,
    )
    .expect("graded");
    let r = &run.report;
    for f in &run.field {
        println!("cell asked {:.3} got {:.3}", f.target, f.ratio);
    }
    // Reflex corners of the closed tiles (a concave family).
    let reflex = (0..run.sheet.tiles.len())
        .map(|i| {
            let p = run.sheet.closed_polygon(i);
            let m = p.len();
            (0..m)
                .filter(|&v| {
                    let (a, b) = (p[(v + 1) % m] - p[v], p[(v + m - 1) % m] - p[v]);
                    a.x * b.y - a.y * b.x < 0.0
                })
                .count()
        })
        .sum::<usize>();
    let (lo, hi) = run
        .sheet
        .nodes
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(l, h), p| {
            (
                [l[0].min(p[0]), l[1].min(p[1])],
                [h[0].max(p[0]), h[1].max(p[1])],
            )
        });
    println!("closed box {:.2} x {:.2}", hi[0] - lo[0], hi[1] - lo[1]);
    println!(
        "design {} reflex corners {reflex} field error {:?} over {} cells",
        run.sheet.design, r.max_field_error, r.field_cells
    );
    println!(
        "tiles {} iterations {} cost {:.3e} -> {:.3e} gap {:.1e} outline max {:.4} median {:.4} outside {:.4} corner {:.3} angle {:.1} edge {:.3} area {:.3} {:.2} s",
        r.tiles, r.iterations, r.cost[0], r.cost[1], r.joint_gap, r.max_outline_error,
        r.median_outline_error, r.max_outside, r.min_corner_fraction, r.min_angle_degrees, r.min_edge_fraction,
        r.min_area_fraction, r.seconds
    );
    // The fit's own states part of the way (before the closing projection's opened state).
    for (k, poses) in run.sheet.path.iter().enumerate() {
        let mut at = run.sheet.clone();
        at.opened = poses.clone();
        println!(
            "fitted state {k} gap {:.2e} overlap {:?}",
            at.joint_gap(),
            isogami::graded::deploy::overlap(&at)
        );
    }
    for s in &run.path.states {
        println!(
            "opening {:.3} gap {:.2e} dof {:?} smallest {:?} overlap {:?}",
            s.opening, s.joint_gap, s.dof, s.smallest, s.overlap
        );
    }
    if let Some((a, b)) = run.path.states.iter().find_map(|s| s.overlap) {
        let (ta, tb) = (&run.sheet.tiles[a], &run.sheet.tiles[b]);
        let pinned = run
            .sheet
            .joints
            .iter()
            .any(|j| (j.a, j.b) == (a, b) || (j.a, j.b) == (b, a));
        let shared: Vec<usize> = ta
            .nodes
            .iter()
            .filter(|n| tb.nodes.contains(n))
            .copied()
            .collect();
        println!(
            "first overlap (signs {:?}): tile {a} (cell {:?} tile {}) and {b} (cell {:?} tile {}), pinned {pinned}, shared nodes {shared:?}",
            run.sheet
                .joints
                .iter()
                .filter(|j| (j.a, j.b) == (a, b) || (j.a, j.b) == (b, a))
                .map(|j| run.sheet.opened[j.b].theta - run.sheet.opened[j.a].theta)
                .collect::<Vec<_>>(),
            ta.cell,
            ta.tile,
            tb.cell,
            tb.tile
        );
    }
    println!(
        "closed spread {:.3e}, reached {}",
        run.path.closed_spread, run.path.reached
    );
    // GRADED_SVG=FILE: the closed tiling, the fitted opened state and each state of the path
    // check side by side, the two tiles of the first overlap filled.
    if let Ok(file) = std::env::var("GRADED_SVG") {
        let hit = run.path.states.iter().find_map(|s| s.overlap);
        let n = run.sheet.tiles.len();
        let mut panels: Vec<Vec<Vec<isogami::math::Vec2>>> =
            vec![(0..n).map(|i| run.sheet.closed_polygon(i)).collect()];
        for poses in
            std::iter::once(&run.sheet.opened).chain(run.path.states.iter().map(|s| &s.poses))
        {
            let mut at = run.sheet.clone();
            at.opened = poses.clone();
            panels.push((0..n).map(|i| at.opened_polygon(i)).collect());
        }
        let size = panels
            .iter()
            .flatten()
            .flatten()
            .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
        let cell = 2.2 * size;
        let mut out = format!(
            "<svg xmlns='http://www.w3.org/2000/svg' viewBox='{} {} {} {cell}' width='{}' height='400'>",
            -1.1 * size,
            -1.1 * size,
            cell * panels.len() as f64,
            400 * panels.len()
        );
        for (k, tiles) in panels.iter().enumerate() {
            let dx = cell * k as f64;
            for (i, poly) in tiles.iter().enumerate() {
                let points: String = poly
                    .iter()
                    .map(|p| format!("{:.4},{:.4} ", p.x + dx, -p.y))
                    .collect();
                let fill = match hit {
                    Some((a, b)) if i == a || i == b => "red",
                    _ => "none",
                };
                out += &format!(
                    "<polygon points='{points}' fill='{fill}' fill-opacity='0.5' stroke='black' stroke-width='{}'/>",
                    size / 400.0
                );
            }
        }
        out += "</svg>";
        std::fs::write(file, out).expect("write the SVG");
    }
}
