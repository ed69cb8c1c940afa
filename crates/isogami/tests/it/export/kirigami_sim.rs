//! kirigami_sim files, parsed as its README and utils.py describe them (whitespace-separated,
//! 1-based, clockwise tiles): pins = joints of the patch, pinned vertices coincide, hull tiles
//! are the tiles with an edge on the boundary (found here by matching edges, independently of
//! the patch's outline), the hull vertices run clockwise around the whole patch.

use super::fixtures::{area, closed, dist, open, COLS, DESIGNS, EDGE_MM, ROWS};
use isogami::export::kirigami_sim::kirigami_sim_files;

fn parse_tiles(text: &str) -> Vec<Vec<[f64; 2]>> {
    text.lines()
        .map(|l| {
            let xs: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert!(xs.len() >= 6 && xs.len().is_multiple_of(2));
            xs.chunks(2).map(|c| [c[0], c[1]]).collect()
        })
        .collect()
}

fn parse_ints(text: &str, per_line: usize) -> Vec<Vec<usize>> {
    text.lines()
        .map(|l| {
            let v: Vec<usize> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            assert_eq!(v.len(), per_line, "{l}");
            assert!(v.iter().all(|&x| x >= 1), "1-based");
            v
        })
        .collect()
}

#[test]
fn pins_are_the_joints_and_pinned_vertices_coincide() {
    for patches in [closed(), open()] {
        for (p, spec) in patches.iter().zip(DESIGNS) {
            let [vertices, constraints, _, _] = kirigami_sim_files(p);
            let tiles = parse_tiles(&vertices);
            assert_eq!(tiles.len(), p.tiles.len());
            for t in &tiles {
                assert!(area(t) < 0.0, "{spec}: tiles are clockwise");
            }
            let pins = parse_ints(&constraints, 4);
            assert_eq!(pins.len(), p.joints.len(), "{spec}");
            for c in &pins {
                let a = tiles[c[0] - 1][c[1] - 1];
                let b = tiles[c[2] - 1][c[3] - 1];
                assert!(dist(a, b) <= 1e-9 * EDGE_MM, "{spec}: {c:?}");
                assert_ne!(c[0], c[2]);
            }
        }
    }
    // rotating-squares: a 2R×2C grid of squares pinned across every shared edge.
    let pins = parse_ints(&kirigami_sim_files(&closed()[0])[1], 4).len();
    let (r, c) = (2 * ROWS, 2 * COLS);
    assert_eq!(pins, r * (c - 1) + (r - 1) * c);
}

#[test]
fn hull_files_list_the_boundary_tiles_and_the_outline_clockwise() {
    for (p, spec) in closed().iter().zip(DESIGNS) {
        let [vertices, _, hull_tiles, hull_vertices] = kirigami_sim_files(p);
        let tiles = parse_tiles(&vertices);
        // A tile edge is interior when another tile has the same edge reversed.
        let tol = 1e-7 * EDGE_MM;
        let mut boundary: Vec<usize> = Vec::new();
        for (i, t) in tiles.iter().enumerate() {
            let n = t.len();
            let open_edge = (0..n).any(|k| {
                let (a, b) = (t[k], t[(k + 1) % n]);
                !tiles.iter().enumerate().any(|(j, s)| {
                    let m = s.len();
                    j != i && (0..m).any(|q| dist(s[q], b) < tol && dist(s[(q + 1) % m], a) < tol)
                })
            });
            if open_edge {
                boundary.push(i + 1);
            }
        }
        let listed: Vec<usize> = parse_ints(&hull_tiles, 1)
            .into_iter()
            .map(|v| v[0])
            .collect();
        assert_eq!(listed, boundary, "{spec}");
        let ring: Vec<[f64; 2]> = parse_ints(&hull_vertices, 2)
            .iter()
            .map(|v| tiles[v[0] - 1][v[1] - 1])
            .collect();
        let total: f64 = tiles.iter().map(|t| -area(t)).sum();
        assert!(
            (area(&ring) + total).abs() < 1e-9 * total,
            "{spec}: clockwise patch outline"
        );
    }
}
