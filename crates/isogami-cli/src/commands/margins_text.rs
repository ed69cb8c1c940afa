//! The margins of a design in words, as `analyze` and `deploy` print them: its shape
//! tolerance (what a special design opens on and how far off it locks), where its path is
//! most open, and whether its finite patch has a one-DOF sheet.

use isogami::catalog::{
    FiniteFigures, MarginsReport, FABRICATION_TOLERANCE, FINITE_PATCH_CELLS, KEPT_FRACTION,
    TOLERANCE_LEVELS,
};

/// The margins in words: the shape tolerance (what a special design opens on and how far off
/// it locks) and where the path is most open.
pub(crate) fn margin_lines(o: &mut String, r: &MarginsReport, edge_mm: f64) {
    let m = &r.margins;
    let n = FINITE_PATCH_CELLS;
    let mm = |rel: f64| rel * edge_mm;
    match m.shape_tolerance {
        None => outln!(
            o,
            "shape       fixed by the family (no shape parameters): no tolerance to measure"
        ),
        Some(0.0) => {
            outln!(
                o,
                "shape       SPECIAL: opens only at its exact shape. Moved by {:.0e} L ({:.1e} mm at \
                 {edge_mm} mm edges) it opens to x{:.4} of x{:.4} (below {:.0} %), and at ±{} L \
                 (±{:.2} mm) to {:.1} % of its largest area ratio",
                TOLERANCE_LEVELS[0],
                mm(TOLERANCE_LEVELS[0]),
                r.opening_off_shape.unwrap_or(1.0),
                r.max_area_ratio,
                100.0 * KEPT_FRACTION,
                FABRICATION_TOLERANCE,
                mm(FABRICATION_TOLERANCE),
                100.0 * m.fabrication_kept.unwrap_or(0.0)
            );
            for n in &r.constraints {
                let terms: Vec<String> = n
                    .iter()
                    .enumerate()
                    .map(|(i, c)| format!("{c:+.4}·dv{i}"))
                    .collect();
                outln!(o, "  constraint {} = 0 (first order)", terms.join(" "));
            }
            outln!(
                o,
                "  keep the shape on it: `isogami shape --design '{}' --set vK=X` moves along it",
                r.design
            );
        }
        Some(t) => {
            let verdict = if t >= FABRICATION_TOLERANCE {
                "the shape holds at ±0.05 mm at 20 mm edges"
            } else {
                "the shape needs better than ±0.05 mm at 20 mm edges"
            };
            let params = r.params_per_displacement.map_or(String::new(), |p| {
                format!(", {:.2e} in parameter units", p * t)
            });
            outln!(
                o,
                "shape       keeps {:.0} % of its largest area ratio under moves up to {t} L (±{:.3} \
                 mm at {edge_mm} mm edges{params}): {verdict}; at ±{} L it keeps {:.1} %",
                100.0 * KEPT_FRACTION,
                mm(t),
                FABRICATION_TOLERANCE,
                100.0 * m.fabrication_kept.unwrap_or(1.0)
            );
        }
    }
    outln!(
        o,
        "open        most open at t = {:.3} (area x{:.4}); the path ends at t = 1 with x{:.4}{}",
        m.open_t,
        r.max_area_ratio,
        m.end_area_ratio,
        if m.end_area_ratio < KEPT_FRACTION * r.max_area_ratio {
            " (it closes again: export with --t open, not --t limit)"
        } else {
            ""
        }
    );
    match &r.finite {
        Some(FiniteFigures {
            covered: Some(c), ..
        }) => outln!(
            o,
            "sheet       a {n}×{n}-cell patch completes to a one-DOF sheet keeping {:.0} % of it",
            100.0 * c
        ),
        Some(FiniteFigures {
            raw_dof,
            covered: None,
        }) => outln!(
            o,
            "sheet       NO ONE-DOF SHEET: a {n}×{n}-cell patch cut from it has {raw_dof} degrees \
             of freedom and no one-DOF part covering half of it, so a cut sheet does not open \
             as one mechanism. Try `isogami sheet --raw` to see the patch as cut, another \
             region (`--region`), or a design of the same motion that has a sheet"
        ),
        None => {}
    }
}
