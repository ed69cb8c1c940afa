//! Test designs and their patches, made once per test binary.

use isogami::api::resolve_design;
use isogami::export::{patch_at, Patch, PatchRequest, Scale, State};
use std::sync::OnceLock;

/// rotating-squares and opening designs of five other families. IH2 and IH44 are the
/// library's sample designs; the IH6, IH22 and IH28 shapes were found by perturbing the
/// parameters of explored topologies until a tile turned concave (one degree of freedom kept,
/// area ratio above 1.2); `the_test_designs_include_concave_tiles` checks that they are.
pub const DESIGNS: &[&str] = &[
    "rotating-squares",
    "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:a--aa-",
    "IH44:0.5,0.102564102564:1x1:-aaa",
    "IH6:0.4512,0.7209,0.5231,0.9206,0.7110:1x1:-a-aaaaaaa--",
    "IH22:0.1312,0.2611,0.4191:1x1:aa-a-",
    "IH28:0.1136,0.2021:1x1:a--a-b-bbb",
];

/// Designs of [`DESIGNS`] with a concave tile.
pub const CONCAVE: &[&str] = &[
    "IH6:0.4512,0.7209,0.5231,0.9206,0.7110:1x1:-a-aaaaaaa--",
    "IH22:0.1312,0.2611,0.4191:1x1:aa-a-",
    "IH28:0.1136,0.2021:1x1:a--a-b-bbb",
];

/// Rows and columns of the shared patches (not square, so rows and columns cannot be
/// swapped unnoticed).
pub const ROWS: usize = 3;
pub const COLS: usize = 4;
/// Mean edge length of the shared patches, mm.
pub const EDGE_MM: f64 = 20.0;

fn make(state: State) -> Vec<Patch> {
    DESIGNS
        .iter()
        .map(|spec| {
            let design = resolve_design(spec).unwrap();
            let request = PatchRequest {
                rows: ROWS,
                cols: COLS,
                scale: Scale::EdgeMm(EDGE_MM),
                state,
                // The R×C rectangle (`--raw`): the format tests check its cells; the
                // completed sheet, the default, has its own tests.
                complete: false,
                ..PatchRequest::default()
            };
            patch_at(&design, &request).unwrap_or_else(|e| panic!("{spec}: {e}"))
        })
        .collect()
}

/// The patches of [`DESIGNS`] in the closed state.
pub fn closed() -> &'static [Patch] {
    static P: OnceLock<Vec<Patch>> = OnceLock::new();
    P.get_or_init(|| make(State::T(0.0)))
}

/// The patches of [`DESIGNS`] open at the contact limit.
pub fn open() -> &'static [Patch] {
    static P: OnceLock<Vec<Patch>> = OnceLock::new();
    P.get_or_init(|| make(State::Open))
}

/// Twice the signed area of a polygon.
pub fn area(poly: &[[f64; 2]]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum::<f64>()
}

/// Distance between two points.
pub fn dist(p: [f64; 2], q: [f64; 2]) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// True when some vertex of the counter-clockwise polygon turns clockwise.
pub fn is_concave(poly: &[[f64; 2]]) -> bool {
    let n = poly.len();
    (0..n).any(|k| {
        let (a, b, c) = (poly[k], poly[(k + 1) % n], poly[(k + 2) % n]);
        (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) < -1e-9
    })
}
