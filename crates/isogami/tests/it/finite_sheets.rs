//! Finite sheets (issue 22): the free-boundary mobility against an independent dense rank
//! count, rotating squares' known counts, completion to one DOF, refusals and regions.

use isogami::api::{deploy_path, finite_sheet, resolve_design, SheetRequest};
use isogami::deploy::DeploySettings;
use isogami::finite::{periodic_velocity, FiniteError, FiniteSheet, Region, SheetTile};
use isogami::kinematics::Mechanism;
use isogami::math::{DMat, DVec, Real, Vec2};
use isogami::Error;

/// A tile index of the sheet for a cell and tile.
fn cells(rows: i32, cols: i32, n: usize) -> Vec<SheetTile> {
    (0..rows)
        .flat_map(|j| {
            (0..cols).flat_map(move |i| {
                (0..n).map(move |k| SheetTile {
                    cell: [i, j],
                    tile: k,
                })
            })
        })
        .collect()
}

/// The sheet's joint Jacobian written out densely here, from the joints' attachment points
/// (not the library's sparse H): rows r = R(θa)·sa + pa − R(θb)·sb − pb per pin.
fn dense_jacobian(sheet: &FiniteSheet, mech: &Mechanism, poses: &[(Vec2, Real)]) -> DMat {
    let mut j = DMat::zeros(2 * sheet.joints.len(), 3 * sheet.len());
    for (r, pin) in sheet.joints.iter().enumerate() {
        let joint = &mech.joints[pin.joint];
        for (tile, s, sign) in [(pin.a, joint.s_a, 1.0), (pin.b, joint.s_b, -1.0)] {
            let th = poses[tile].1;
            // d/dθ of R(θ)s = (−sin θ sx − cos θ sy, cos θ sx − sin θ sy).
            let d = Vec2::new(
                -th.sin() * s.x - th.cos() * s.y,
                th.cos() * s.x - th.sin() * s.y,
            );
            j[(2 * r, 3 * tile)] += sign;
            j[(2 * r + 1, 3 * tile + 1)] += sign;
            j[(2 * r, 3 * tile + 2)] += sign * d.x;
            j[(2 * r + 1, 3 * tile + 2)] += sign * d.y;
        }
    }
    j
}

/// Degrees of freedom of a sheet in one piece by a dense SVD: 3n − 3 − rank J, with the
/// rank counted against a gap (singular values below 1e-6 of the largest are zero).
fn dense_dof(sheet: &FiniteSheet, mech: &Mechanism, poses: &[(Vec2, Real)]) -> usize {
    let j = dense_jacobian(sheet, mech, poses);
    let s = j.svd(false, false).singular_values;
    let top = s.iter().copied().fold(0.0, Real::max);
    let rank = s.iter().filter(|&&v| v > 1e-6 * top).count();
    3 * sheet.len() - 3 - rank
}

/// The opened periodic state nearest t = 0.3 and the periodic motion there.
fn opened(design: &isogami::api::Design, mech: &Mechanism) -> (DVec, DVec) {
    let path = deploy_path(design, &DeploySettings::default(), &mut |_| true).unwrap();
    let traj = &path.trajectory;
    let k = (1..traj.steps.len())
        .min_by(|&a, &b| (traj.t(a) - 0.3).abs().total_cmp(&(traj.t(b) - 0.3).abs()))
        .unwrap();
    let q = traj.steps[k].q.clone();
    let motion = isogami::mobility::analyze(mech, &q, Default::default())
        .unwrap()
        .motion
        .unwrap()
        .vector;
    (q, motion)
}

#[test]
fn rotating_squares_is_one_dof_opened_and_4k_minus_2_closed() {
    let design = resolve_design("rotating-squares").unwrap();
    for k in 2..=5 {
        let request = SheetRequest {
            region: Region::Cells { rows: k, cols: k },
            ..SheetRequest::default()
        };
        let out = finite_sheet(&design, &request, &mut |_| true).unwrap();
        assert_eq!(out.raw_mobility.dof, 1, "{k}x{k}");
        assert!(out.raw_mobility.follows_periodic);
        assert!(out.raw_mobility.floppy.is_empty());
        assert_eq!(out.raw_closed_dof, 4 * k - 2, "{k}x{k} closed");
        let c = out.completion.unwrap();
        assert_eq!(c.sheet, out.raw, "nothing to complete");
        assert_eq!(c.report.covered_fraction, 1.0);
    }
}

#[test]
fn free_boundary_dof_equals_an_independent_dense_rank_count() {
    // Small sheets take the dense path, larger ones (over 90 unknowns) the sparse one.
    let designs = [
        "rotating-squares",
        "IH44:0.5,0.027564102564:1x2:-aaabbaa",
        "IH2:0.04739750492,0.35,0.150335752741,0.150335752741:1x1:aa-aa-",
        "IH10::1x2:-aaaa-",
        "IH31::1x1:-baaaaabbb-a",
        "IH10::2x2:--a--aa-a-bb",
    ];
    for spec in designs {
        let design = resolve_design(spec).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let (q, motion) = opened(&design, &mech);
        for size in [1, 2, 4] {
            let sheet = FiniteSheet::new(&cell, &mech, cells(size, size, mech.tile_count()));
            if sheet.pieces().1 != 1 {
                continue;
            }
            for state in [&q, &mech.rest] {
                let poses = sheet.poses(&mech, state);
                let periodic = periodic_velocity(&sheet, &mech, &motion);
                let m = isogami::finite::sheet_mobility(
                    &sheet,
                    &mech,
                    &poses,
                    Some(&periodic),
                    isogami::stop::NEVER,
                )
                .unwrap();
                assert_eq!(
                    m.dof,
                    dense_dof(&sheet, &mech, &poses),
                    "{spec} {size}x{size}"
                );
                assert_eq!(
                    m.floppy.len() + usize::from(m.follows_periodic),
                    m.dof,
                    "{spec}"
                );
            }
            // The periodic motion restricted to the sheet is a motion of the sheet.
            let poses = sheet.poses(&mech, &q);
            let v = periodic_velocity(&sheet, &mech, &motion);
            let residual = dense_jacobian(&sheet, &mech, &poses) * &v;
            assert!(
                residual.amax() < 1e-6 * v.amax(),
                "{spec}: {}",
                residual.amax()
            );
        }
    }
}

#[test]
fn completion_leaves_one_dof_moving_with_the_periodic_sheet() {
    for spec in [
        "IH44:0.5,0.027564102564:1x2:-aaabbaa",
        "IH2:0.04739750492,0.35,0.150335752741,0.150335752741:1x1:aa-aa-",
        "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-",
    ] {
        let design = resolve_design(spec).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let out = finite_sheet(&design, &SheetRequest::default(), &mut |_| true).unwrap();
        assert!(out.raw_mobility.dof > 1, "{spec}: the raw 6x6 patch flops");
        let c = out.completion.unwrap();
        assert_eq!(c.mobility.dof, 1, "{spec}");
        assert!(c.mobility.follows_periodic && c.mobility.floppy.is_empty());
        assert_eq!(c.sheet.pieces().1, 1);
        assert!(
            c.sheet.pins().iter().all(|&p| p >= 2),
            "{spec}: no loose tile"
        );
        let r = &c.report;
        assert!(r.covered_fraction >= 0.5 && r.covered_fraction <= 1.0);
        assert_eq!(r.kept + r.removed.len(), r.requested);
        assert_eq!(c.sheet.len(), r.kept + r.added.len());
        // Independently: the completed sheet's dense rank count is one DOF at the opened state.
        let (q, _) = opened(&design, &mech);
        assert_eq!(
            dense_dof(&c.sheet, &mech, &c.sheet.poses(&mech, &q)),
            1,
            "{spec}"
        );
    }
}

#[test]
fn an_isostatic_design_is_refused_with_its_count() {
    let design = resolve_design("IH10::2x2:--a--aa-a-bb").unwrap();
    let err = finite_sheet(&design, &SheetRequest::default(), &mut |_| true).unwrap_err();
    let Error::Finite(FiniteError::NoOneDofSheet { reason }) = &err else {
        panic!("{err}");
    };
    assert!(
        reason.contains("4 tiles and 6 pins (3n − 2p = 0"),
        "{reason}"
    );
    // The raw analysis still answers.
    let raw = SheetRequest {
        complete: false,
        ..SheetRequest::default()
    };
    let out = finite_sheet(&design, &raw, &mut |_| true).unwrap();
    assert!(out.raw_mobility.dof > 10);
    assert!(!out.raw_mobility.loose_tiles.is_empty());
    // Asked to keep the raw region on a refusal, the same request answers with it and the
    // refusal's reason.
    let kept = SheetRequest {
        keep_raw_on_refusal: true,
        ..SheetRequest::default()
    };
    let out = finite_sheet(&design, &kept, &mut |_| true).unwrap();
    assert!(out.completion.is_none());
    assert_eq!(out.refusal.as_deref(), Some(err.to_string().as_str()));
}

/// Regions of an isostatic cell, square and long, are refused by counting tiles and pins
/// alone, before the periodic deployment starts (its progress is never called) and so before
/// any factorisation; the count named is the least any sheet keeping the share can have.
#[test]
fn an_isostatic_region_is_refused_by_counting_before_any_work() {
    let design = resolve_design("IH10::2x2:--a--aa-a-bb").unwrap();
    for (rows, cols) in [(4, 4), (10, 10), (20, 20), (2, 30)] {
        let request = SheetRequest {
            region: Region::Cells { rows, cols },
            ..SheetRequest::default()
        };
        let mut called = false;
        let err = finite_sheet(&design, &request, &mut |_| {
            called = true;
            true
        })
        .unwrap_err();
        assert!(
            !called,
            "{rows}x{cols}: the deployment ran before the refusal"
        );
        let Error::Finite(FiniteError::NoOneDofSheet { reason }) = &err else {
            panic!("{err}");
        };
        let count: usize = reason
            .split(" has at least ")
            .nth(1)
            .and_then(|r| r.split(" DOF").next())
            .and_then(|n| n.trim().parse().ok())
            .unwrap_or_else(|| panic!("{rows}x{cols}: no count in {reason}"));
        assert!(count >= 2, "{reason}");
    }
}

#[test]
fn regions_in_mm_hold_the_tiles_whose_centroid_is_inside() {
    let design = resolve_design("rotating-squares").unwrap();
    let cell = design.cell().unwrap();
    let mech = Mechanism::new(&cell, &design.joints).unwrap();
    let edge_mm = 10.0;
    let disc: Region = "disc:55".parse().unwrap();
    let tiles = disc.tiles(&mech, edge_mm).unwrap();
    let n = mech.tile_count();
    let origin = (0..n).fold(Vec2::zeros(), |a, k| a + mech.pose(&mech.rest, k).0) / n as Real;
    let sheet = FiniteSheet::new(&cell, &mech, tiles.clone());
    assert_eq!(sheet.len(), tiles.len());
    let poses = sheet.poses(&mech, &mech.rest);
    let r = 55.0 / edge_mm;
    for (p, _) in &poses {
        assert!((p - origin).norm() < r);
    }
    // Every square of the lattice within the disc (less one edge, clear of the boundary).
    let area = poses.len() as Real;
    assert!(
        area > 0.9 * std::f64::consts::PI * (r - 1.0).powi(2),
        "{area}"
    );
    let out = finite_sheet(
        &design,
        &SheetRequest {
            region: disc,
            edge_mm,
            ..SheetRequest::default()
        },
        &mut |_| true,
    )
    .unwrap();
    assert_eq!(out.completion.unwrap().mobility.dof, 1);
    for bad in [
        "0x3",
        "3x",
        "disc:-1",
        "disc:nan",
        "rect:4",
        "polygon:0,0;1,0",
        "polygon:0,0;1,1;0,0;1,1",
        "41x2",
    ] {
        assert!(bad.parse::<Region>().is_err(), "{bad}");
    }
    let square: Region = "polygon:0,0;30,0;30,30;0,30".parse().unwrap();
    assert_eq!(square.to_string().parse::<Region>().unwrap(), square);
}

/// A shape a hair away is the same finite sheet: the same tiles and pins (identity is
/// combinatorial), the same counts and the same completion. Shapes where the labels before
/// issue 21 jumped (IH9 at p1 = 0.5, IH44 at p0 = 0.5).
#[test]
fn a_shape_a_hair_away_is_the_same_finite_sheet() {
    let cases = [
        "IH9:0.12239750492,{},0.225335752741:2x1:---abb--a-bb",
        "IH44:{},0.027564102564:1x2:-aaabbaa",
    ];
    let mut completed = 0;
    for template in cases {
        let at = |p: &str, complete: bool| {
            let spec = template.replace("{}", p);
            let design = resolve_design(&spec).unwrap();
            let request = SheetRequest {
                complete,
                ..SheetRequest::default()
            };
            finite_sheet(&design, &request, &mut |_| true).map_err(|e| e.to_string())
        };
        let raw = at("0.5", false).unwrap();
        let done = at("0.5", true);
        for p in ["0.499999999", "0.500000001"] {
            let near = at(p, false).unwrap();
            assert_eq!(raw.raw, near.raw, "{template} {p}: same tiles and pins");
            assert_eq!(
                raw.raw_mobility.dof, near.raw_mobility.dof,
                "{template} {p}"
            );
            assert_eq!(raw.raw_closed_dof, near.raw_closed_dof, "{template} {p}");
            match (&done, at(p, true)) {
                (Ok(a), Ok(b)) => {
                    let (ca, cb) = (a.completion.as_ref().unwrap(), b.completion.unwrap());
                    assert_eq!(ca.sheet, cb.sheet, "{template} {p}: same completion");
                    assert_eq!(cb.mobility.dof, 1);
                    completed += 1;
                }
                (Err(a), Err(b)) => assert_eq!(a, &b, "{template} {p}"),
                (a, b) => panic!("{template} {p}: {a:?} vs {b:?}"),
            }
        }
    }
    assert!(completed > 0, "at least one case completes");
}

#[test]
fn giving_up_below_the_smallest_share_never_changes_a_verdict() {
    // Completion stops pruning a candidate once it covers less than `min_covered`; with
    // `min_covered` 0 it prunes to the end. The kept sheet is the same, and a refusal is a
    // sheet that, pruned to the end, keeps less than the share (or none at all).
    for spec in [
        "rotating-squares",
        "IH10::2x2:--a--aa-a-bb",
        "IH44:0.5,0.027564102564:1x2:-aaabbaa",
        "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-",
    ] {
        let design = resolve_design(spec).unwrap();
        let request = |min_covered| SheetRequest {
            region: Region::Cells { rows: 4, cols: 4 },
            min_covered,
            ..SheetRequest::default()
        };
        let early = finite_sheet(&design, &request(0.5), &mut |_| true);
        let full = finite_sheet(&design, &request(0.0), &mut |_| true);
        match (early, full) {
            (Ok(a), Ok(b)) => {
                let (a, b) = (a.completion.unwrap(), b.completion.unwrap());
                assert_eq!(a.sheet, b.sheet, "{spec}");
                assert!(a.report.covered_fraction >= 0.5, "{spec}");
            }
            (Err(a), Ok(b)) => {
                assert!(
                    matches!(a, Error::Finite(FiniteError::NoOneDofSheet { .. })),
                    "{spec}: {a}"
                );
                let share = b.completion.unwrap().report.covered_fraction;
                assert!(share < 0.5, "{spec}: refused, yet pruning keeps {share}");
            }
            (Err(_), Err(_)) => {}
            (Ok(_), Err(b)) => panic!("{spec}: accepted only when giving up early ({b})"),
        }
    }
}

#[test]
fn a_stop_check_stops_completion_between_its_rounds() {
    use isogami::finite::{complete, Context};
    use std::sync::atomic::{AtomicUsize, Ordering};
    let spec = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";
    let design = resolve_design(spec).unwrap();
    let cell = design.cell().unwrap();
    let mech = Mechanism::new(&cell, &design.joints).unwrap();
    let (q, motion) = opened(&design, &mech);
    let region = Region::Cells { rows: 6, cols: 6 };
    let raw = FiniteSheet::new(&cell, &mech, region.tiles(&mech, 20.0).unwrap());
    let asked = AtomicUsize::new(0);
    // Goes on for the first round of each candidate, then says stop.
    let check = || asked.fetch_add(1, Ordering::SeqCst) < 2;
    let ctx = |keep_going| Context {
        cell: &cell,
        mech: &mech,
        q: &q,
        motion: &motion,
        min_covered: 0.5,
        keep_going,
    };
    let whole = complete(&ctx(isogami::stop::NEVER), &raw).unwrap();
    assert!(whole.report.removed.len() > 2, "prunes over several rounds");
    let stopped = complete(&ctx(&check), &raw);
    assert!(
        matches!(stopped, Err(FiniteError::Cancelled)),
        "{stopped:?}"
    );
    // Each candidate stops at its first poll past the second: no round runs on.
    assert!(asked.load(Ordering::SeqCst) <= 4, "{asked:?}");
}

#[test]
fn a_progress_callback_stops_the_completion_after_the_deployment() {
    let design = resolve_design("IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-").unwrap();
    // The deployment reports each count once; the completion is asked on with the last count
    // again: saying stop then ends the work with a cancelled error, not a sheet.
    let mut last = 0;
    let mut repeats = 0;
    let err = finite_sheet(
        &design,
        &SheetRequest {
            region: Region::Cells { rows: 8, cols: 8 },
            ..SheetRequest::default()
        },
        &mut |n| {
            if n == last {
                repeats += 1;
                return false;
            }
            last = n;
            true
        },
    )
    .unwrap_err();
    assert!(err.is_cancelled(), "{err}");
    assert_eq!(repeats, 1, "asked once more after saying stop");
}
