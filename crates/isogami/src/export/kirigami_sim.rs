//! The text files of kirigami_sim (Liu, Choi and Mahadevan's spring-based 2D deployment
//! simulator on pymunk, github.com/lliu12/kirigami_sim), so the paper's baseline can run on
//! our designs. The format, as its README and `utils.py` read it:
//!
//! - **vertices**: one line per tile, its vertex coordinates `x1 y1 x2 y2 …` separated by
//!   spaces, vertices in clockwise order. Our polygons are counter-clockwise, so each tile's
//!   vertices are written reversed; vertex p (1-based) of the file is vertex n − p of ours.
//! - **constraints**: one line per pin, `i p j q` (tabs), 1-based: vertex p of tile i is
//!   pinned to vertex q of tile j. Pinned vertices coincide here, so the simulator joins them
//!   (zero rest length).
//! - **hull tiles** (`--hull_tiles_file`): the 1-based ids of the tiles on the patch boundary,
//!   one per line; the simulator pulls them outward with springs.
//! - **hull vertices** (`--hull_vertices_file`, needed for its area and perimeter): the
//!   outline of the patch as `i p` lines in clockwise order.
//!
//! Coordinates are the patch's at its exported state (the closed sheet by default, which is
//! where the simulator starts), in mm. The simulator collides concave tiles as their convex
//! hulls (a pymunk limitation), so it may stop such sheets early.

use super::patch::Patch;
use std::fmt::Write;

/// File names written by `isogami export --format kirigami-sim` into its folder.
pub const KIRIGAMI_SIM_FILES: [&str; 4] = [
    "vertices.txt",
    "constraints.txt",
    "hull_tiles.txt",
    "hull_vertices.txt",
];

/// The four files' contents, in the order of [`KIRIGAMI_SIM_FILES`].
pub fn kirigami_sim_files(patch: &Patch) -> [String; 4] {
    // File vertex index (1-based) of our vertex k on an n-gon, written clockwise.
    let file_vertex = |tile: usize, k: usize| {
        let n = patch.tiles[tile].polygon_mm.len();
        (n - k) % n + 1
    };
    let mut vertices = String::new();
    for t in &patch.tiles {
        let n = t.polygon_mm.len();
        let line: Vec<String> = (0..n)
            .map(|p| {
                let v = t.polygon_mm[(n - p) % n];
                format!("{} {}", v[0], v[1])
            })
            .collect();
        let _ = writeln!(vertices, "{}", line.join(" "));
    }
    let mut constraints = String::new();
    for j in &patch.joints {
        let _ = writeln!(
            constraints,
            "{}\t{}\t{}\t{}",
            j.a + 1,
            file_vertex(j.a, j.vertex_a),
            j.b + 1,
            file_vertex(j.b, j.vertex_b)
        );
    }
    let mut hull: Vec<usize> = patch
        .outline_vertices
        .iter()
        .flatten()
        .map(|v| v[0])
        .collect();
    hull.sort_unstable();
    hull.dedup();
    let mut hull_tiles = String::new();
    for t in hull {
        let _ = writeln!(hull_tiles, "{}", t + 1);
    }
    // The longest outline loop (the patch's outer boundary), reversed to clockwise.
    let mut hull_vertices = String::new();
    if let Some(ring) = patch.outline_vertices.iter().max_by_key(|l| l.len()) {
        let n = ring.len();
        for p in 0..n {
            let [tile, k] = ring[(n - p) % n];
            let _ = writeln!(hull_vertices, "{} {}", tile + 1, file_vertex(tile, k));
        }
    }
    [vertices, constraints, hull_tiles, hull_vertices]
}
