//! Unit cells and a×b supercells of an isohedral tiling in its closed state.
//!
//! A cell holds its tiles as counter-clockwise polygons, the tiling vectors u and w, and every
//! unique edge once, with the cell offset of the neighbouring tile. Adjacency is found
//! geometrically: two tiles share an edge when they share both endpoints. The two endpoints of
//! an edge are its joint candidates. Plain data; no I/O.

mod build;
mod dims;
mod error;
mod validate;

pub use build::{CellEdge, End, Tile, UnitCell};
pub use dims::CellDims;
pub use error::{CellError, GeometryProblem};
