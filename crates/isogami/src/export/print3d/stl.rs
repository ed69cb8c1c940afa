//! Binary STL: an 80-byte header (naming isogami, the units and the design; never starting
//! with `solid`, which readers take for ASCII STL), the triangle count as a little-endian
//! u32, then per triangle its unit normal and three corners as little-endian f32 and a zero
//! attribute word. STL has no units: the numbers are millimetres, as slicers assume.

use super::mesh::PrintMesh;

/// Bytes of the header.
pub const STL_HEADER_LEN: usize = 80;

/// Bytes per triangle record.
pub const STL_TRIANGLE_LEN: usize = 50;

/// The binary STL of `mesh` with `title` in its header (cut to fit).
pub fn stl_bytes(mesh: &PrintMesh, title: &str) -> Vec<u8> {
    let mut out = Vec::with_capacity(STL_HEADER_LEN + 4 + STL_TRIANGLE_LEN * mesh.triangles.len());
    let mut header = format!("isogami binary STL, units mm: {title}").into_bytes();
    // Cut at a character boundary of the UTF-8 text.
    let mut cut = header.len().min(STL_HEADER_LEN);
    while cut > 0 && cut < header.len() && (header[cut] & 0xC0) == 0x80 {
        cut -= 1;
    }
    header.truncate(cut);
    header.resize(STL_HEADER_LEN, b' ');
    out.extend_from_slice(&header);
    let count = u32::try_from(mesh.triangles.len()).unwrap_or(u32::MAX);
    out.extend_from_slice(&count.to_le_bytes());
    for t in 0..count as usize {
        for x in mesh.normal(t) {
            out.extend_from_slice(&(x as f32).to_le_bytes());
        }
        for corner in mesh.corners(t) {
            for x in corner {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetra() -> PrintMesh {
        PrintMesh {
            positions: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        }
    }

    fn f32_at(b: &[u8], at: usize) -> f32 {
        f32::from_le_bytes(b[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn byte_layout_header_count_normals_corners() {
        let title = "rotating-squares é".repeat(6);
        let b = stl_bytes(&tetra(), &title);
        assert_eq!(b.len(), 80 + 4 + 4 * 50);
        assert!(b.starts_with(b"isogami binary STL, units mm: rotating"));
        assert!(!b.starts_with(b"solid"));
        assert!(
            std::str::from_utf8(&b[..80]).is_ok(),
            "header cut inside a character"
        );
        assert_eq!(u32::from_le_bytes(b[80..84].try_into().unwrap()), 4);
        // Triangle 0 = corners 0, 2, 1: normal -z, then (0,0,0), (0,1,0), (1,0,0).
        let t0 = 84;
        assert_eq!(
            [f32_at(&b, t0), f32_at(&b, t0 + 4), f32_at(&b, t0 + 8)],
            [0.0, 0.0, -1.0]
        );
        assert_eq!(f32_at(&b, t0 + 12 + 12 + 4), 1.0, "second corner's y");
        assert_eq!(f32_at(&b, t0 + 12 + 24), 1.0, "third corner's x");
        assert_eq!(&b[t0 + 48..t0 + 50], &[0, 0]);
        // The last triangle's normal is (1,1,1)/√3.
        let t3 = 84 + 3 * 50;
        assert!((f32_at(&b, t3) - 1.0 / 3f32.sqrt()).abs() < 1e-6);
    }
}
