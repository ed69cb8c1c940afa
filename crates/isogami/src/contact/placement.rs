//! Collision polygons placed in the world at a state q: x = R(θ)s + p + k_u u + k_w w.

use super::aabb::Aabb;
use super::lattice::{Lattice, LatticeProblem};
use crate::kinematics::StateLayout;
use crate::math::{rotation, DVec, Real, Vec2};
use std::cell::OnceCell;

/// One tile's collision polygon in the centre cell at state q.
#[derive(Debug, Clone)]
pub(crate) struct PlacedTile {
    /// R(θ)s for every vertex s (the lever arms of the rotation).
    pub(crate) arms: Vec<Vec2>,
    /// World vertices R(θ)s + p.
    pub(crate) world: Vec<Vec2>,
    /// Bounding box of `world`.
    pub(crate) aabb: Aabb,
    /// The tile's reference point p (the centre of its bounding circle).
    pub(crate) centre: Vec2,
}

/// Every tile's collision polygon in the centre cell, plus the tiling vectors.
#[derive(Debug, Clone)]
pub(crate) struct Placement {
    pub(crate) tiles: Vec<PlacedTile>,
    pub(crate) u: Vec2,
    pub(crate) w: Vec2,
    /// The lattice of u and w (or why it has none), reduced on first use: queries that take
    /// their pairs from a Verlet list never need it.
    lattice: OnceCell<Result<Lattice, LatticeProblem>>,
}

impl Placement {
    /// Places the tile-frame polygons `shapes` at state q (q.len() must fit `layout`).
    pub(crate) fn new(layout: StateLayout, shapes: &[Vec<Vec2>], q: &DVec) -> Placement {
        let tiles = shapes
            .iter()
            .enumerate()
            .map(|(i, shape)| {
                let k = layout.tile(i);
                let (p, r) = (Vec2::new(q[k], q[k + 1]), rotation(q[k + 2]));
                let arms: Vec<Vec2> = shape.iter().map(|s| r * s).collect();
                let world: Vec<Vec2> = arms.iter().map(|a| a + p).collect();
                let aabb = Aabb::of(&world);
                PlacedTile {
                    arms,
                    world,
                    aabb,
                    centre: p,
                }
            })
            .collect();
        Placement::with_tiles(layout, tiles, q)
    }

    /// The reference points and lattice of state q without any polygon (tiles have empty
    /// vertex lists and empty boxes): enough for the broad phase and `reach` bounds, which
    /// use only centres, extents and u, w.
    pub(crate) fn centres_only(layout: StateLayout, q: &DVec) -> Placement {
        let empty = Aabb {
            lo: Vec2::repeat(Real::INFINITY),
            hi: Vec2::repeat(Real::NEG_INFINITY),
        };
        let tiles = (0..layout.tiles)
            .map(|i| {
                let k = layout.tile(i);
                PlacedTile {
                    arms: Vec::new(),
                    world: Vec::new(),
                    aabb: empty,
                    centre: Vec2::new(q[k], q[k + 1]),
                }
            })
            .collect();
        Placement::with_tiles(layout, tiles, q)
    }

    /// The placement of `tiles` with the lattice of state q.
    fn with_tiles(layout: StateLayout, tiles: Vec<PlacedTile>, q: &DVec) -> Placement {
        let (iu, iw) = (layout.u(), layout.w());
        let (u, w) = (Vec2::new(q[iu], q[iu + 1]), Vec2::new(q[iw], q[iw + 1]));
        Placement {
            tiles,
            u,
            w,
            lattice: OnceCell::new(),
        }
    }

    /// The lattice of u and w, or why they span none.
    pub(crate) fn lattice(&self) -> Result<Lattice, LatticeProblem> {
        *self.lattice.get_or_init(|| Lattice::new(self.u, self.w))
    }

    /// The smallest singular value of [u w] (the lattice's `sigma_min`, without reducing it),
    /// or why u and w span no lattice.
    pub(crate) fn sigma_min(&self) -> Result<Real, LatticeProblem> {
        match self.lattice.get() {
            Some(lattice) => lattice.map(|l| l.sigma_min),
            None => Lattice::smallest_singular_value(self.u, self.w),
        }
    }

    /// Translation of the cell at `offset`.
    pub(crate) fn shift(&self, offset: [i32; 2]) -> Vec2 {
        self.u * Real::from(offset[0]) + self.w * Real::from(offset[1])
    }

    /// Tile `i`'s world collision polygon in the cell at `offset`.
    pub(crate) fn polygon(&self, i: usize, offset: [i32; 2]) -> Vec<Vec2> {
        let s = self.shift(offset);
        self.tiles[i].world.iter().map(|v| v + s).collect()
    }
}
