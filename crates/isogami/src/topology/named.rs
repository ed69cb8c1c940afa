//! Named classic designs.

use super::design::{Design, JointChoice};
use crate::cell::{CellDims, UnitCell};
use crate::tiling::{Family, Tiling};

/// Designs from eleven families that open as one-degree-of-freedom mechanisms and deploy to a
/// contact limit (found by random search over joint choices at default shapes). Used by
/// tests and benchmarks; the first three turn away from their initial eigenvector, which is
/// what the baselines cannot follow.
pub const SAMPLE_OPENING_DESIGNS: &[&str] = &[
    "rotating-squares",
    "IH1:0.12239750492,0.5,0.143395479017,0.625:2x1:--bbb-",
    "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:a--aa-",
    "IH40::1x1:bbabbbbba",
    "IH44:0.5,0.102564102564:1x1:-aaa",
    "IH53:0.5,0.102564102564,0.102564102564:1x1:bbaab-b-",
    "IH61::1x1:aaaa",
    "IH78:0.230769230769:1x1:bbaaab",
    "IH85:0.5,0.196416770201:1x1:abbbbb",
    "IH88::1x1:bbbaabbab",
    "IH90::1x1:aaa",
];

/// Names accepted wherever a design is expected.
pub const NAMED_DESIGNS: &[&str] = &["rotating-squares"];

/// The design with this name, if there is one.
pub fn named_design(name: &str) -> Option<Design> {
    match name {
        "rotating-squares" => Some(rotating_squares()),
        _ => None,
    }
}

/// The rotating-squares mechanism: the square grid (IH76) in a 2×2 cell, every edge hinged at
/// one corner such that each square's hinges run round it in a pinwheel whose handedness
/// alternates like a chessboard. One degree of freedom: neighbours counter-rotate.
fn rotating_squares() -> Design {
    let family = Family::from_number(76).expect("IH76 is realizable");
    let dims = CellDims::new(2, 2).expect("2x2 is valid");
    let cell = UnitCell::new(&Tiling::default_for(family), dims).expect("square grid builds");
    // A square of even chessboard parity hinges every edge at the edge's counter-clockwise
    // end; seen from the odd neighbour that vertex is the edge's start.
    let parity = |t: usize| (cell.tiles[t].copy[0] + cell.tiles[t].copy[1]).is_multiple_of(2);
    let joints = cell
        .edges
        .iter()
        .map(|e| {
            if parity(e.tile_a) {
                JointChoice::B
            } else {
                JointChoice::A
            }
        })
        .collect();
    Design {
        family,
        params: Vec::new(),
        dims,
        joints,
    }
}
