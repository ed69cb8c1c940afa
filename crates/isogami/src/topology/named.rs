//! Named classic designs.

use super::design::{Design, JointChoice};
use crate::cell::{CellDims, UnitCell};
use crate::tiling::{Family, Tiling};

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
    let parity = |t: usize| (cell.tiles[t].copy[0] + cell.tiles[t].copy[1]) % 2 == 0;
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
