//! Unit cells and a×b supercells of an isohedral tiling in its closed state.
//!
//! A cell holds its tiles as counter-clockwise polygons, the tiling vectors u and w, and every
//! unique edge once, with the cell offset of the neighbouring tile. Labels are combinatorial:
//! every tile is its aspect's image of the prototile moved by an integer lattice translate
//! fixed per family (not chosen per shape), so which tile is "tile i", and which tile edges and
//! cell offset form "edge e", are the same at every valid shape of the family; geometry only
//! places the tiles (two tiles share an edge when they share both endpoints, and the offset is
//! the exact integer translate between them). The two endpoints of an edge are its joint
//! candidates. Plain data; no I/O.

mod build;
mod dims;
mod error;
mod legacy;
mod validate;

pub use build::{CellEdge, End, Tile, UnitCell};
pub use dims::CellDims;
pub use error::{CellError, GeometryProblem};
pub use legacy::{legacy_edges, LegacyEdge};
