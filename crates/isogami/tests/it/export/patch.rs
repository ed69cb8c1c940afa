//! The patch geometry: scale, placement, joints, outline, states, request checks.

use super::fixtures::{
    area, closed, dist, is_concave, open, COLS, CONCAVE, DESIGNS, EDGE_MM, ROWS,
};
use isogami::api::resolve_design;
use isogami::export::{
    patch_at, ExportError, PatchRequest, Scale, State, MAX_PATCH, MAX_PATCH_FRAMES,
};

fn mean_edge(polys: &[Vec<[f64; 2]>]) -> f64 {
    let (mut sum, mut count) = (0.0, 0);
    for p in polys {
        for k in 0..p.len() {
            sum += dist(p[k], p[(k + 1) % p.len()]);
            count += 1;
        }
    }
    sum / count as f64
}

#[test]
fn the_test_designs_include_concave_tiles() {
    for (p, spec) in closed().iter().zip(DESIGNS) {
        let concave = p.closed_polygons_mm.iter().any(|q| is_concave(q));
        assert_eq!(concave, CONCAVE.contains(spec), "{spec}");
    }
    assert!(CONCAVE.len() >= 3);
}

#[test]
fn the_mean_edge_length_of_the_closed_patch_is_the_asked_length() {
    for (p, spec) in closed().iter().zip(DESIGNS) {
        let m = mean_edge(&p.closed_polygons_mm);
        assert!((m - EDGE_MM).abs() <= 1e-9 * EDGE_MM, "{spec}: {m}");
        assert!((p.edge_mm - EDGE_MM).abs() <= 1e-9 * EDGE_MM);
        let tiles: Vec<_> = p.tiles.iter().map(|t| t.polygon_mm.clone()).collect();
        assert!((mean_edge(&tiles) - EDGE_MM).abs() <= 1e-9 * EDGE_MM);
    }
}

#[test]
fn a_width_scale_gives_that_width_at_the_state() {
    let design = resolve_design(DESIGNS[2]).unwrap();
    for state in [State::T(0.0), State::Open] {
        let request = PatchRequest {
            rows: 2,
            cols: 3,
            scale: Scale::WidthMm(150.0),
            state,
            // This IH44 cell is isostatic (no one-DOF sheet): the rectangle as it is.
            complete: false,
            ..PatchRequest::default()
        };
        let p = patch_at(&design, &request).unwrap();
        let xs = p
            .tiles
            .iter()
            .flat_map(|t| t.polygon_mm.iter().map(|v| v[0]));
        let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
        assert!(lo.abs() < 1e-9, "starts at 0: {lo}");
        assert!((hi - 150.0).abs() < 1e-9, "{state:?}: width {hi}");
        assert!((p.size_mm[0] - 150.0).abs() < 1e-9);
    }
}

#[test]
fn the_patch_holds_rows_times_cols_cells_of_every_tile() {
    for p in closed() {
        assert_eq!(p.tiles.len(), ROWS * COLS * p.tiles_per_cell);
        assert_eq!(p.closed_polygons_mm.len(), p.tiles.len());
        for (id, t) in p.tiles.iter().enumerate() {
            assert_eq!(t.id, id);
            let (i, j) = (t.cell[0] as usize, t.cell[1] as usize);
            assert!(t.cell[0] >= 0 && t.cell[1] >= 0);
            assert!(i < COLS && j < ROWS && t.tile < p.tiles_per_cell);
            assert!(area(&t.polygon_mm) > 0.0, "counter-clockwise");
        }
        // Each (cell, tile) once.
        let mut keys: Vec<_> = p.tiles.iter().map(|t| (t.cell, t.tile)).collect();
        keys.sort();
        keys.dedup();
        assert_eq!(keys.len(), p.tiles.len());
    }
}

/// The tiles move rigidly: every state's polygons have the closed polygons' edge lengths, and
/// the centroid and rotation of each tile place its closed shape onto its polygon.
#[test]
fn tiles_move_rigidly_and_their_pose_places_them() {
    for (p, spec) in open().iter().zip(DESIGNS) {
        assert!(p.t > 0.0, "{spec} opens");
        for t in &p.tiles {
            let c = &p.closed_polygons_mm[t.id];
            let q = &t.polygon_mm;
            let n = q.len();
            let cc = centroid(c);
            let (s, co) = t.rotation.sin_cos();
            for k in 0..n {
                let l0 = dist(c[k], c[(k + 1) % n]);
                let l1 = dist(q[k], q[(k + 1) % n]);
                assert!(
                    (l0 - l1).abs() < 1e-9 * EDGE_MM,
                    "{spec}: tile {} edge {k}",
                    t.id
                );
                let d = [c[k][0] - cc[0], c[k][1] - cc[1]];
                let placed = [
                    t.centroid_mm[0] + co * d[0] - s * d[1],
                    t.centroid_mm[1] + s * d[0] + co * d[1],
                ];
                assert!(
                    dist(placed, q[k]) < 1e-8 * EDGE_MM,
                    "{spec}: pose of {}",
                    t.id
                );
            }
        }
    }
}

fn centroid(poly: &[[f64; 2]]) -> [f64; 2] {
    let a = area(poly);
    let n = poly.len();
    let (mut x, mut y) = (0.0, 0.0);
    for k in 0..n {
        let (p, q) = (poly[k], poly[(k + 1) % n]);
        let c = p[0] * q[1] - q[0] * p[1];
        x += (p[0] + q[0]) * c;
        y += (p[1] + q[1]) * c;
    }
    [x / (6.0 * a), y / (6.0 * a)]
}

/// Both tiles of every joint have their joint vertex at the pin, to 1e-9 of the edge length,
/// closed and open.
#[test]
fn joint_vertices_coincide_to_1e9_of_the_edge() {
    for patches in [closed(), open()] {
        for (p, spec) in patches.iter().zip(DESIGNS) {
            assert!(!p.joints.is_empty());
            for j in &p.joints {
                let va = p.tiles[j.a].polygon_mm[j.vertex_a];
                let vb = p.tiles[j.b].polygon_mm[j.vertex_b];
                assert!(dist(va, vb) <= 1e-9 * EDGE_MM, "{spec}: {j:?}");
                assert!(dist(va, j.point_mm) <= 1e-9 * EDGE_MM);
                let ca = p.closed_polygons_mm[j.a][j.vertex_a];
                let cb = p.closed_polygons_mm[j.b][j.vertex_b];
                assert!(dist(ca, cb) <= 1e-9 * EDGE_MM);
                assert!(j.end == 'a' || j.end == 'b');
            }
        }
    }
}

/// rotating-squares: an R×C patch of 2×2 cells is a 2R×2C grid of squares with a joint on
/// every shared edge.
#[test]
fn rotating_squares_joints_are_the_grid_adjacencies() {
    let p = &closed()[0];
    let (r, c) = (2 * ROWS, 2 * COLS);
    assert_eq!(p.joints.len(), r * (c - 1) + (r - 1) * c);
    // And its outline is the grid's rectangle: 2(r + c) unit edges around an area r·c·L².
    assert_eq!(p.outline_mm.len(), 1);
    assert_eq!(p.outline_mm[0].len(), 2 * (r + c));
    let expected = (r * c) as f64 * EDGE_MM * EDGE_MM;
    assert!((area(&p.outline_mm[0]) - expected).abs() < 1e-9 * expected);
}

/// Only joints inside the patch: a 1×1 patch of rotating-squares has the four joints inside
/// its 2×2 block, a 1×2 patch adds the two across the shared cell side.
#[test]
fn joints_reaching_outside_the_patch_are_left_out() {
    let design = resolve_design("rotating-squares").unwrap();
    let count = |rows, cols| {
        let request = PatchRequest {
            rows,
            cols,
            ..PatchRequest::default()
        };
        patch_at(&design, &request).unwrap().joints.len()
    };
    assert_eq!(count(1, 1), 4);
    assert_eq!(count(1, 2), 10);
    assert_eq!(count(2, 1), 10);
}

/// The outline of the closed patch encloses exactly the tiles: its area is their total area.
#[test]
fn the_outline_encloses_the_closed_tiles() {
    for (p, spec) in closed().iter().zip(DESIGNS) {
        let tiles: f64 = p.closed_polygons_mm.iter().map(|q| area(q)).sum();
        let outline: f64 = p.outline_mm.iter().map(|q| area(q)).sum();
        assert!(
            (tiles - outline).abs() < 1e-9 * tiles,
            "{spec}: {tiles} {outline}"
        );
    }
}

#[test]
fn states_run_from_closed_to_the_contact_limit_and_open_is_the_widest() {
    for (p, spec) in open().iter().zip(DESIGNS) {
        let states = &p.states;
        assert!(states.len() >= 2 && states.len() <= PatchRequest::default().frames);
        assert_eq!(states[0].t, 0.0);
        assert_eq!(states.last().unwrap().t, 1.0);
        assert!(states.windows(2).all(|w| w[0].t < w[1].t), "{spec}");
        let tiles: f64 = states[0].polygons_mm.iter().map(|q| area(q)).sum();
        assert!(p.area_ratio > 1.0, "{spec} opens: {}", p.area_ratio);
        // The closed state of the series is the closed patch.
        for (a, b) in states[0].polygons_mm.iter().zip(&p.closed_polygons_mm) {
            assert!(a.iter().zip(b).all(|(u, v)| dist(*u, *v) < 1e-9 * EDGE_MM));
        }
        assert!(tiles > 0.0);
    }
    // rotating-squares opens to √2 stretch: area ratio 2.
    assert!((open()[0].area_ratio - 2.0).abs() < 1e-3);
}

#[test]
fn t_picks_the_nearest_state() {
    let design = resolve_design("rotating-squares").unwrap();
    let at = |t| {
        let request = PatchRequest {
            rows: 1,
            cols: 1,
            state: State::T(t),
            ..PatchRequest::default()
        };
        patch_at(&design, &request).unwrap()
    };
    assert_eq!(at(0.0).t, 0.0);
    assert_eq!(at(1.0).t, 1.0);
    let half = at(0.5);
    assert!((half.t - 0.5).abs() < 0.05, "{}", half.t);
    assert!(half.area_ratio > 1.0 && half.area_ratio < 2.0);
}

#[test]
fn bad_requests_are_refused_with_typed_errors() {
    let design = resolve_design("rotating-squares").unwrap();
    let with = |f: &dyn Fn(&mut PatchRequest)| {
        let mut r = PatchRequest::default();
        f(&mut r);
        patch_at(&design, &r).unwrap_err()
    };
    assert!(matches!(
        with(&|r| r.rows = 0),
        ExportError::EmptyPatch { rows: 0, .. }
    ));
    assert!(matches!(
        with(&|r| r.cols = MAX_PATCH + 1),
        ExportError::PatchTooLarge { max: MAX_PATCH, .. }
    ));
    // Sizes no machine makes: zero, negative, not finite, subnormal (its digits lost), past
    // overflow of a 40x40 patch (issue 23 item 5).
    for v in [0.0, -3.0, f64::NAN, f64::INFINITY, 1e-320, 1e-4, 1e308, 2e6] {
        let e = with(&|r| r.scale = Scale::EdgeMm(v));
        assert!(
            e.to_string()
                .contains("must be a number from 0.001 to 1000000 mm"),
            "{v}: {e}"
        );
        assert!(matches!(
            with(&|r| r.scale = Scale::EdgeMm(v)),
            ExportError::BadSize { .. }
        ));
        assert!(matches!(
            with(&|r| r.scale = Scale::WidthMm(v)),
            ExportError::BadSize { .. }
        ));
    }
    for t in [-0.1, 1.5, f64::NAN] {
        assert!(matches!(
            with(&|r| r.state = State::T(t)),
            ExportError::StatePastTrajectory { .. }
        ));
    }
    assert!(matches!(
        with(&|r| r.frames = MAX_PATCH_FRAMES + 1),
        ExportError::FrameCount { .. }
    ));
    assert!(matches!(with(&|r| r.kerf = -1.0), ExportError::Library(_)));
    for e in [with(&|r| r.rows = 0), with(&|r| r.kerf = 5.0)] {
        let msg = e.to_string();
        assert!(!msg.is_empty() && !msg.contains('\n'), "{msg}");
    }
}

/// With `complete` the patch is the rectangle's one-DOF completion, tile for tile what
/// `api::finite_sheet` makes, and says so; without, it is the rectangle and names its DOF.
#[test]
fn the_default_patch_is_the_one_dof_completion() {
    use isogami::api::{finite_sheet, SheetRequest};
    use isogami::finite::Region;
    let spec = "IH44:0.5,0.027564102564:1x2:-aaabbaa";
    let design = resolve_design(spec).unwrap();
    assert!(PatchRequest::default().complete);
    let completed = patch_at(&design, &PatchRequest::default()).unwrap();
    let raw = patch_at(
        &design,
        &PatchRequest {
            complete: false,
            ..PatchRequest::default()
        },
    )
    .unwrap();
    let sheet = finite_sheet(
        &design,
        &SheetRequest {
            region: Region::Cells { rows: 6, cols: 6 },
            ..SheetRequest::default()
        },
        &mut |_| true,
    )
    .unwrap();
    let c = sheet.completion.unwrap();
    let tiles: Vec<([i32; 2], usize)> = completed.tiles.iter().map(|t| (t.cell, t.tile)).collect();
    let want: Vec<([i32; 2], usize)> = c.sheet.tiles.iter().map(|t| (t.cell, t.tile)).collect();
    assert_eq!(tiles, want);
    assert_eq!(completed.joints.len(), c.sheet.joints.len());
    assert!(completed.finite.completed && completed.finite.dof == 1);
    assert!(completed.finite.warning().is_none());
    assert_eq!(completed.finite.added_tiles, c.report.added.len());
    // Ring tiles lie outside the rectangle's cells.
    assert!(completed
        .tiles
        .iter()
        .any(|t| t.cell[0] < 0 || t.cell[1] < 0 || t.cell[0] >= 6 || t.cell[1] >= 6));
    assert_eq!(raw.tiles.len(), 6 * 6 * raw.tiles_per_cell);
    assert!(!raw.finite.completed);
    assert_eq!(raw.finite.dof, sheet.raw_mobility.dof);
    assert!(raw
        .finite
        .warning()
        .unwrap()
        .contains(&format!("{} degrees of freedom", raw.finite.dof)));
    // A design with no one-DOF sheet: completion (the default) is refused, the raw
    // rectangle exported on request.
    let isostatic = resolve_design("IH10::2x2:--a--aa-a-bb").unwrap();
    let e = patch_at(&isostatic, &PatchRequest::default()).unwrap_err();
    assert!(e.to_string().contains("no one-DOF sheet"), "{e}");
    let raw = PatchRequest {
        complete: false,
        ..PatchRequest::default()
    };
    assert!(patch_at(&isostatic, &raw).unwrap().finite.dof > 1);
}

#[test]
fn a_patch_has_exactly_the_frames_asked_for() {
    // A design that opens in fewer accepted states than the most frames a patch takes: states
    // are inserted between them, as `deploy --frame-count` does (issue 23 item 13: 100 asked,
    // 90 written). The rectangle as it is (no completion needed for the count).
    let design =
        resolve_design("IH22:0.230769230769,0.5,0.225335752741:1x3:--ab-a-abbba-aa").unwrap();
    let states = isogami::api::deploy_path(&design, &Default::default(), &mut |_| true)
        .unwrap()
        .trajectory
        .steps
        .len();
    assert!(
        states < MAX_PATCH_FRAMES,
        "{states} states: pick a shorter design"
    );
    for frames in [2, 37, MAX_PATCH_FRAMES] {
        let request = PatchRequest {
            rows: 2,
            cols: 2,
            frames,
            complete: false,
            ..PatchRequest::default()
        };
        let patch = patch_at(&design, &request).unwrap();
        assert_eq!(patch.states.len(), frames);
        assert_eq!(patch.states[0].t, 0.0);
        assert_eq!(patch.states[frames - 1].t, 1.0);
        assert!(patch.states.windows(2).all(|w| w[0].t < w[1].t));
    }
}
