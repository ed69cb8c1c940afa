//! Why a laser sheet cannot be laid out or written: typed, one-line messages naming the
//! offending value, tile or joint.

use crate::math::Real;
use thiserror::Error;

/// A laser export refused.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LaserError {
    /// A size that must be positive is zero or negative.
    #[error("{name} must be positive, got {value} mm")]
    NotPositive {
        /// Setting name, e.g. "hinge_mm".
        name: &'static str,
        /// The value given.
        value: Real,
    },
    /// A value is NaN or infinite.
    #[error("{name} must be a finite number, got {value}")]
    NotFinite {
        /// Setting or input name.
        name: &'static str,
        /// The value given.
        value: Real,
    },
    /// A colour is not of the form `#rrggbb`.
    #[error("{name} must be a colour #rrggbb, got {value:?}")]
    BadColour {
        /// Setting name, e.g. "cut colour".
        name: &'static str,
        /// The text given.
        value: String,
    },
    /// The patch has no tiles.
    #[error("the patch has no tiles")]
    NoTiles,
    /// A tile polygon is unusable.
    #[error("tile {tile} is unusable: {problem}")]
    BadTile {
        /// Tile index in the patch.
        tile: usize,
        /// What is wrong with it.
        problem: String,
    },
    /// Tiles overlap: an edge is used more than twice, or twice in the same direction.
    #[error("tiles {tiles:?} overlap along an edge (not a tiling)")]
    Overlap {
        /// Two of the tiles involved.
        tiles: [usize; 2],
    },
    /// A joint's point is not an end of an edge that its two tiles share.
    #[error("joint {joint} (tiles {tiles:?}) is not at the end of an edge the two tiles share")]
    JointNotOnEdge {
        /// Joint index.
        joint: usize,
        /// Its two tiles.
        tiles: [usize; 2],
    },
    /// A tile index of a joint is out of range.
    #[error("joint {joint} names tile {tile}, but the patch has {tiles} tiles")]
    NoSuchTile {
        /// Joint index.
        joint: usize,
        /// The tile named.
        tile: usize,
        /// Number of tiles.
        tiles: usize,
    },
    /// The hinge bridge (with the kerf and the clearance it needs from the other cuts at its
    /// vertex) is longer than the edge it sits on.
    #[error(
        "hinge {hinge_mm} mm does not fit on the {edge_mm:.3} mm edge between tiles {tiles:?}: \
         its bridges need {needed_mm:.3} mm with kerf and clearances"
    )]
    HingeTooWide {
        /// The hinge width asked.
        hinge_mm: Real,
        /// Length of the edge.
        edge_mm: Real,
        /// Length the bridge layout needs on it.
        needed_mm: Real,
        /// The edge's two tiles.
        tiles: [usize; 2],
    },
    /// The patch is too small for its bridges: some edge (scaled with the patch) is shorter
    /// than its bridges need, and those needs do not scale. Names the smallest `edge_mm` at
    /// which every edge fits.
    #[error(
        "hinge {hinge_mm} mm does not fit at edge_mm {edge_mm}: the {len_mm:.3} mm edge between \
         tiles {tiles:?} needs {needed_mm:.3} mm with kerf and clearances; the smallest edge_mm \
         that fits is {min_edge_mm} (or use a narrower hinge)"
    )]
    PatchTooSmall {
        /// The hinge width asked.
        hinge_mm: Real,
        /// The patch's mean edge length asked.
        edge_mm: Real,
        /// The smallest mean edge length at which every bridge fits (rounded up to 0.001).
        min_edge_mm: Real,
        /// Length of the edge that needs the most room for its length.
        len_mm: Real,
        /// Length its bridges need.
        needed_mm: Real,
        /// Its two tiles (ids in the patch).
        tiles: [usize; 2],
    },
    /// The kerf is so wide that a tile would lose an edge (or all its area) to the cuts.
    #[error("kerf {kerf_mm} mm is too wide for tile {tile}: {problem}")]
    KerfTooWide {
        /// The kerf asked.
        kerf_mm: Real,
        /// First tile it destroys.
        tile: usize,
        /// What happens to the tile.
        problem: String,
    },
}
