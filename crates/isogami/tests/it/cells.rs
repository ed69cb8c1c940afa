//! Every family builds cells that tile the plane: at default and perturbed parameters, and
//! as supercells.

use crate::common;

use common::{cell_of, perturbed_params, Rng};
use isogami::cell::{CellDims, UnitCell};
use isogami::geometry::{point_in_polygon_strict, signed_area};
use isogami::math::{cross, Vec2};
use isogami::tiling::{Culprit, TilingError};
use isogami::tiling::{Family, Tiling};

/// Independent of `check_geometry`: random points of a cell parallelogram each lie inside
/// exactly one tile of the cells around it (points within a hair of a boundary
/// are skipped). Together with the 3×3 overlap check this shows the 3×3 block tiles without
/// gaps.
fn covered_exactly_once(cell: &UnitCell, rng: &mut Rng, samples: usize) {
    let tol = 1e-9 * cell.mean_edge_length();
    let mut polys = Vec::new();
    let [ru, rw] = cell.reach();
    for ku in -ru - 1..=ru + 1 {
        for kw in -rw - 1..=rw + 1 {
            for i in 0..cell.tiles.len() {
                polys.push(cell.tile_polygon_at(i, [ku, kw]));
            }
        }
    }
    let origin = cell
        .tiles
        .iter()
        .map(|t| t.centroid)
        .fold(Vec2::zeros(), |a, c| a + c)
        / cell.tiles.len() as f64
        - (cell.u + cell.w) * 0.5;
    for _ in 0..samples {
        let p = origin + cell.u * rng.unit() + cell.w * rng.unit();
        let inside = polys
            .iter()
            .filter(|q| point_in_polygon_strict(&p, q, tol))
            .count();
        let on_boundary = polys.iter().any(|q| {
            (0..q.len()).any(|k| {
                isogami::geometry::point_segment_distance(&p, &q[k], &q[(k + 1) % q.len()]) <= tol
            })
        });
        if !on_boundary {
            assert_eq!(
                inside,
                1,
                "{} {:?} {}: point {p:?} covered {inside} times; u {:?} w {:?} tiles {:?}",
                cell.family,
                cell.params,
                cell.dims,
                cell.u,
                cell.w,
                cell.tiles.iter().map(|t| &t.polygon).collect::<Vec<_>>()
            );
        }
    }
}

fn assert_tiles_plane(cell: &UnitCell, rng: &mut Rng) {
    cell.check_geometry()
        .unwrap_or_else(|e| panic!("{} {:?} {}: {e}", cell.family, cell.params, cell.dims));
    let lattice = cross(&cell.u, &cell.w).abs();
    let area: f64 = cell.tiles.iter().map(|t| signed_area(&t.polygon)).sum();
    assert!(
        (area - lattice).abs() <= 1e-9 * lattice,
        "{}: area {area} vs {lattice}",
        cell.family
    );
    // Every tile edge is in exactly one unique edge, and every unique edge has two sides.
    let nv: usize = cell.tiles.iter().map(|t| t.polygon.len()).sum();
    assert_eq!(2 * cell.edges.len(), nv);
    let mut seen = vec![0; cell.edges.len()];
    for te in &cell.tile_edges {
        for &e in te {
            seen[e] += 1;
        }
    }
    assert!(
        seen.iter().all(|&s| s == 2),
        "{}: edge sides {seen:?}",
        cell.family
    );
    // Partner edges coincide with reversed endpoints after the offset.
    for e in &cell.edges {
        let a = &cell.tiles[e.tile_a].polygon;
        let b = cell.tile_polygon_at(e.tile_b, e.offset);
        let (na, nb) = (a.len(), b.len());
        let tol = 1e-7 * cell.mean_edge_length();
        assert!((a[e.edge_a] - b[(e.edge_b + 1) % nb]).norm() < tol);
        assert!((a[(e.edge_a + 1) % na] - b[e.edge_b]).norm() < tol);
    }
    covered_exactly_once(cell, rng, 60);
}

#[test]
fn all_families_default_minimal_cell() {
    let mut rng = Rng::new(1);
    for f in Family::all() {
        let cell = cell_of(f, &f.default_params(), CellDims::MINIMAL);
        assert_eq!(cell.tiles.len(), f.info().aspect_count);
        assert_tiles_plane(&cell, &mut rng);
    }
}

#[test]
fn all_families_perturbed_parameters() {
    let mut rng = Rng::new(2);
    for f in Family::all().filter(|f| f.param_count() > 0) {
        for _ in 0..3 {
            let p = perturbed_params(&mut rng, f, 0.05);
            assert_tiles_plane(&cell_of(f, &p, CellDims::MINIMAL), &mut rng);
        }
    }
}

#[test]
fn all_families_supercells() {
    let mut rng = Rng::new(3);
    for f in Family::all() {
        for dims in ["2x1", "1x2", "2x2"] {
            let dims: CellDims = dims.parse().unwrap();
            let minimal = cell_of(f, &f.default_params(), CellDims::MINIMAL);
            let cell = cell_of(f, &f.default_params(), dims);
            let copies = usize::from(dims.a() * dims.b());
            assert_eq!(cell.tiles.len(), copies * minimal.tiles.len());
            assert_eq!(cell.edges.len(), copies * minimal.edges.len());
            assert_tiles_plane(&cell, &mut rng);
        }
    }
}

#[test]
fn largest_supercells_of_some_families() {
    let mut rng = Rng::new(4);
    for n in [1, 28, 41, 76, 90] {
        let f = Family::from_number(n).unwrap();
        let p = if f.param_count() > 0 {
            perturbed_params(&mut rng, f, 0.05)
        } else {
            vec![]
        };
        assert_tiles_plane(&cell_of(f, &p, "4x3".parse().unwrap()), &mut rng);
    }
}

/// Any parameters either are refused with an error naming a parameter, or give a cell that
/// tiles the plane; never a panic, never a broken cell.
#[test]
fn random_parameters_are_refused_or_valid() {
    let mut rng = Rng::new(5);
    let (mut ok, mut refused) = (0, 0);
    for f in Family::all().filter(|f| f.param_count() > 0) {
        let d = f.default_params();
        for _ in 0..8 {
            let p: Vec<f64> = d.iter().map(|v| v + 1.5 * rng.sym()).collect();
            match Tiling::new(f, &p) {
                Ok(t) => {
                    let cell = UnitCell::new(&t, CellDims::MINIMAL).unwrap();
                    assert_tiles_plane(&cell, &mut rng);
                    ok += 1;
                }
                Err(TilingError::InvalidShape { culprit, .. }) => {
                    let named = match &culprit {
                        Culprit::Alone(ix) | Culprit::Together(ix) => ix.clone(),
                        Culprit::Defaults => Vec::new(),
                    };
                    assert!(
                        !named.is_empty() && named.iter().all(|&(i, v)| p[i] == v && v != d[i]),
                        "culprit must name changed parameters: {culprit}"
                    );
                    refused += 1;
                }
                Err(e) => panic!("{f} {p:?}: unexpected error {e}"),
            }
        }
    }
    assert!(
        ok > 50 && refused > 50,
        "ok {ok}, refused {refused}: the sample should hit both"
    );
}

#[test]
fn refusal_names_the_parameter() {
    // IH41 is a parallelogram family: v0 collapses it when it makes an edge vanish.
    let f = Family::from_number(41).unwrap();
    let mut found = false;
    for k in 0..f.param_count() {
        for v in [-5.0, -1.0, 0.0, 1.0, 5.0] {
            let mut p = f.default_params();
            p[k] = v;
            if let Err(e) = Tiling::new(f, &p) {
                let msg = e.to_string();
                assert!(msg.contains(&format!("parameter v{k}=")), "{msg}");
                assert!(
                    matches!(&e, TilingError::InvalidShape { family, culprit: Culprit::Alone(ix), .. }
                        if *family == f && ix == &[(k, v)]),
                    "{e:?}"
                );
                found = true;
            }
        }
    }
    assert!(
        found,
        "some single-parameter change of IH41 must be refused"
    );
}
