//! The valid range of each shape parameter of a design, the others fixed (issue 24 item 4):
//! the interval around the current value where the design can be built and deployed
//! without an "ill-shaped" refusal — the tiling is valid (not degenerate, not self-crossing,
//! not inverted, no overlap), the cell builds, and every tile can be inset by half the kerf
//! (the same checks `api::deploy` runs, so a slider limited to this interval never meets the
//! server's `ill_shaped`) — and, inside it, the interval where the tile is also well shaped
//! by the exploration's quality rule (`tiling::shape_quality_problem`: angles, edge ratios,
//! no sliver), which a slider can shade as the recommended band.
//!
//! Found by sampling a window around the value and bisecting each end between the last good
//! and the first bad sample, to a tolerance relative to the parameter's scale
//! (`param_scales`). The window is the value ± `WINDOW` scales; an end that reaches the
//! window's edge is reported as open (`lo_open`/`hi_open`).

use super::jacobian::param_scales;
use crate::contact::{ContactModel, ContactSettings};
use crate::kinematics::Mechanism;
use crate::math::{Real, Vec2};
use crate::tiling::{canonical_param, shape_quality_problem, Tiling};
use crate::topology::Design;
use serde::Serialize;

/// Half width of the searched window, in parameter scales.
pub const WINDOW: Real = 2.0;
/// Samples over the window (before bisection).
const SAMPLES: usize = 400;
/// Bisection tolerance, relative to the parameter's scale.
pub const RANGE_TOL: Real = 1e-7;

/// The valid and well-shaped interval of one shape parameter, the others fixed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParamRange {
    /// Parameter index.
    pub index: usize,
    /// Its current value.
    pub value: Real,
    /// Lowest value (canonical, inside the valid set) the design still builds at.
    pub lo: Real,
    /// Highest such value.
    pub hi: Real,
    /// True when `lo` is the window's edge, not a boundary of the valid set.
    pub lo_open: bool,
    /// True when `hi` is the window's edge.
    pub hi_open: bool,
    /// The sub-interval (containing the current value) where the tile is also well shaped;
    /// `None` when the current shape is not.
    pub well_shaped: Option<(Real, Real)>,
    /// The bisection tolerance used (parameter units).
    pub tol: Real,
}

/// Whether `design` builds and its tiles inset by half of `kerf` (L units): what decides
/// the server's "ill_shaped".
pub fn builds(design: &Design, kerf: Real) -> bool {
    let Ok(cell) = design.cell() else {
        return false;
    };
    let Ok(mech) = Mechanism::new(&cell, &design.joints) else {
        return false;
    };
    ContactModel::new(&mech, ContactSettings::with_kerf(kerf)).is_ok()
}

/// Whether `design`'s tiling is valid and its tile well shaped by the exploration's rule.
pub fn well_shaped(design: &Design) -> bool {
    design
        .tiling()
        .is_ok_and(|t| shape_quality_problem(t.prototile()).is_none())
}

/// Prototile edge vectors of `design`'s family at parameter `k` = `x`, when the tiling is
/// valid.
fn edge_vectors(design: &Design, k: usize, x: Real) -> Option<Vec<Vec2>> {
    let mut p = design.params.clone();
    p[k] = x;
    let t = Tiling::new(design.family, &p).ok()?;
    let poly = t.prototile();
    let n = poly.len();
    Some((0..n).map(|i| poly[(i + 1) % n] - poly[i]).collect())
}

/// Whether no edge turned back between two shapes (each edge vector keeps a positive dot
/// product with its former self): an edge whose length passes through zero between two
/// samples leaves a hole in the valid set narrower than the sampling step (the kerf's width
/// around the zero), which this catches.
fn same_branch(a: &[Vec2], b: &[Vec2]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(u, v)| u.dot(v) > 0.0)
}

/// The connected interval around `x0` (where `ok(x0)` holds) within [a, b] of the values
/// where `ok` holds and no edge turns back on the way (`edges`): `SAMPLES` samples, then
/// bisection of each end to `tol`; ends canonical and inside.
fn interval(
    ok: &dyn Fn(Real) -> bool,
    edges: &dyn Fn(Real) -> Option<Vec<Vec2>>,
    x0: Real,
    (a, b): (Real, Real),
    tol: Real,
) -> (Real, Real, bool, bool) {
    let step = (b - a) / SAMPLES as Real;
    let end = |dir: Real, limit: Real| -> (Real, bool) {
        let mut good = x0;
        let mut good_edges = edges(x0);
        loop {
            let next = (good + dir * step).clamp(a, b);
            let reference = good_edges.clone();
            let fine = move |x: Real| {
                ok(x)
                    && match (&reference, edges(x)) {
                        (Some(r), Some(e)) => same_branch(r, &e),
                        _ => true,
                    }
            };
            let at_edge = (next - limit) * dir >= 0.0;
            if !fine(next) {
                return (bisect(&fine, good, next, tol), false);
            }
            if at_edge {
                return (limit, true);
            }
            good = next;
            good_edges = edges(good);
        }
    };
    let (lo, hi) = (end(-1.0, a), end(1.0, b));
    (
        inward(ok, lo.0, tol, 1.0),
        inward(ok, hi.0, tol, -1.0),
        lo.1,
        hi.1,
    )
}

/// The last good point between `good` and `bad` to within `tol`.
fn bisect(ok: &dyn Fn(Real) -> bool, mut good: Real, mut bad: Real, tol: Real) -> Real {
    while (bad - good).abs() > tol {
        let mid = 0.5 * (good + bad);
        if ok(mid) {
            good = mid;
        } else {
            bad = mid;
        }
    }
    good
}

/// `x` in canonical form (12 significant digits), moved towards the inside (`dir`) by
/// `tol` steps until it is good.
fn inward(ok: &dyn Fn(Real) -> bool, x: Real, tol: Real, dir: Real) -> Real {
    let mut c = canonical_param(x);
    for _ in 0..8 {
        if ok(c) {
            return c;
        }
        c = canonical_param(c + dir * tol);
    }
    x
}

/// The valid range of every shape parameter of `design` at `kerf`, each with the others
/// fixed. Empty for a family without parameters; `None` for a design that does not build at
/// its own parameters (its refusal says why).
pub fn param_ranges(design: &Design, kerf: Real) -> Option<Vec<ParamRange>> {
    if !builds(design, kerf) {
        return None;
    }
    let scales = param_scales(design.family);
    let ranges = (0..design.params.len())
        .map(|k| {
            let x0 = design.params[k];
            let at = |x: Real| {
                let mut d = design.clone();
                d.params[k] = x;
                d
            };
            let scale = scales[k];
            let tol = RANGE_TOL * scale;
            let (a, b) = (x0 - WINDOW * scale, x0 + WINDOW * scale);
            let valid = |x: Real| builds(&at(x), kerf);
            let edges = |x: Real| edge_vectors(design, k, x);
            let (lo, hi, lo_open, hi_open) = interval(&valid, &edges, x0, (a, b), tol);
            let good = |x: Real| well_shaped(&at(x)) && builds(&at(x), kerf);
            let well = good(x0).then(|| {
                let (wl, wh, _, _) = interval(&good, &edges, x0, (lo, hi), tol);
                (wl, wh)
            });
            ParamRange {
                index: k,
                value: x0,
                lo,
                hi,
                lo_open,
                hi_open,
                well_shaped: well,
                tol,
            }
        })
        .collect();
    Some(ranges)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::resolve_design;

    /// Designs of several families, the worst sliders among them (IH59, IH68, IH74:
    /// 16 of 21 positions of the old sliders were ill-shaped).
    const DESIGNS: &[&str] = &[
        "IH59:0.030263157895:1x1:aaaa",
        "IH68:0.030263157895:2x2:aaaabbbb",
        "IH74:0.030263157895:2x2:aaaabbbb",
        "IH1:0.04739750492,0.5,0.143395479017,0.4375:1x2:-aaaa-",
        "IH28:0.316978918628,0.35:1x1:a--a-b-bbb",
        "IH6:0.04739750492,0.5,0.150335752741,0.625,0.35:1x1:--a-b-bb-ba-",
        "IH53:0.5,0.027564102564,0.027564102564:1x1:aaaabbbb",
        "IH67:0.155769230769,0.869565217391:1x1:aaaa",
    ];
    const KERF: Real = 0.01;

    /// A deterministic sequence in [0, 1) (a Weyl sequence).
    fn weyl(n: usize) -> impl Iterator<Item = Real> {
        (1..=n).map(|i| (i as Real * 0.618_033_988_749_895).fract())
    }

    #[test]
    fn every_value_inside_builds_and_values_just_outside_do_not() {
        for spec in DESIGNS {
            let design = resolve_design(spec).unwrap();
            let ranges = param_ranges(&design, KERF).unwrap();
            assert_eq!(ranges.len(), design.params.len(), "{spec}");
            for r in &ranges {
                let at = |x: Real| {
                    let mut d = design.clone();
                    d.params[r.index] = x;
                    d
                };
                assert!(
                    r.lo <= r.value && r.value <= r.hi,
                    "{spec} v{}: {r:?}",
                    r.index
                );
                assert!(
                    r.hi - r.lo > 0.0,
                    "{spec} v{}: an interval, not a point",
                    r.index
                );
                let inside = weyl(300)
                    .map(|u| r.lo + u * (r.hi - r.lo))
                    .chain([r.lo, r.hi]);
                for x in inside {
                    assert!(
                        builds(&at(x), KERF),
                        "{spec} v{} = {x} inside {r:?}",
                        r.index
                    );
                }
                if !r.lo_open {
                    let x = r.lo - 3.0 * r.tol;
                    assert!(
                        !builds(&at(x), KERF),
                        "{spec} v{} = {x} below {r:?}",
                        r.index
                    );
                }
                if !r.hi_open {
                    let x = r.hi + 3.0 * r.tol;
                    assert!(
                        !builds(&at(x), KERF),
                        "{spec} v{} = {x} above {r:?}",
                        r.index
                    );
                }
                if let Some((wl, wh)) = r.well_shaped {
                    assert!(r.lo <= wl && wl <= r.value && r.value <= wh && wh <= r.hi);
                    for x in weyl(100).map(|u| wl + u * (wh - wl)) {
                        assert!(well_shaped(&at(x)), "{spec} v{} = {x} in {r:?}", r.index);
                    }
                }
            }
        }
    }

    #[test]
    fn the_old_sliders_left_the_valid_range_and_the_new_ones_do_not() {
        // The design page's sliders used to span default ± max(0.5, |default|): on IH59 most
        // of that is ill-shaped; the computed range is the part that builds.
        let design = resolve_design("IH59:0.030263157895:1x1:aaaa").unwrap();
        let r = &param_ranges(&design, KERF).unwrap()[0];
        let d = design.family.default_params()[0];
        let half = 0.5_f64.max(d.abs());
        let old: Vec<Real> = (0..21)
            .map(|i| d - half + 2.0 * half * i as Real / 20.0)
            .collect();
        let bad = old
            .iter()
            .filter(|&&x| {
                let mut e = design.clone();
                e.params[0] = x;
                !builds(&e, KERF)
            })
            .count();
        assert!(bad > 10, "the reproducer: {bad} of 21 ill-shaped");
        assert!(old.iter().all(|&x| (x < r.lo || x > r.hi) == {
            let mut e = design.clone();
            e.params[0] = x;
            !builds(&e, KERF)
        }));
    }

    #[test]
    fn a_design_that_does_not_build_has_no_ranges() {
        let design = resolve_design("IH28:0.316978918628,0.35:1x1:a--a-b-bbb").unwrap();
        // A kerf as wide as the tile: no inset.
        assert!(param_ranges(&design, 5.0).is_none());
    }
}
