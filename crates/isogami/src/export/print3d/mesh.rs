//! A closed triangle mesh in millimetres: what the STL and 3MF writers write.

use crate::math::Real;

/// An indexed triangle mesh, triangles counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PrintMesh {
    /// Vertex positions, mm.
    pub positions: Vec<[Real; 3]>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
}

impl PrintMesh {
    /// The corners of triangle `t`.
    pub fn corners(&self, t: usize) -> [[Real; 3]; 3] {
        self.triangles[t].map(|i| self.positions[i as usize])
    }

    /// Unit normal of triangle `t` by the right-hand rule (zero for a degenerate triangle).
    pub fn normal(&self, t: usize) -> [Real; 3] {
        let [a, b, c] = self.corners(t);
        let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if len > 0.0 && len.is_finite() {
            n.map(|x| x / len)
        } else {
            [0.0; 3]
        }
    }

    /// Enclosed volume (divergence theorem; positive for an outward-wound closed mesh), mm³.
    pub fn volume(&self) -> Real {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                    + a[2] * (b[0] * c[1] - b[1] * c[0])
            })
            .sum::<Real>()
            / 6.0
    }

    /// Lower and upper corners of the bounding box.
    pub fn bounds(&self) -> ([Real; 3], [Real; 3]) {
        let mut lo = [Real::INFINITY; 3];
        let mut hi = [Real::NEG_INFINITY; 3];
        for p in &self.positions {
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
        (lo, hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit tetrahedron wound outward.
    pub(crate) fn tetra() -> PrintMesh {
        PrintMesh {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    #[test]
    fn volume_normals_and_bounds_of_a_tetrahedron() {
        let m = tetra();
        assert!((m.volume() - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(m.normal(0), [0.0, 0.0, -1.0]);
        assert_eq!(m.bounds(), ([0.0; 3], [1.0; 3]));
        let mut flipped = m.clone();
        flipped.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        assert!((flipped.volume() + 1.0 / 6.0).abs() < 1e-15);
    }
}
