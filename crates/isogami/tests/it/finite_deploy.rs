//! Finite deployment (issue 22): a completed sheet opens with the periodic motion until
//! contact, its end state is checked here with other code than the solver's (joints closed
//! from the tiles' attachment points, kerf-inset tiles disjoint by `geo`), and a floppy raw
//! region is refused with its count. Pulled sheets: a one-DOF sheet pulled apart by two
//! tiles follows the periodic motion, a floppy raw one leaves it through its extra modes, a
//! completed one only at a branch point of its motion.

use geo::{Coord, Intersects, LineString, Polygon};
use isogami::api::{
    deploy_path, deploy_sheet, pull_sheet, resolve_design, SheetDeployRequest, SheetPull,
    SheetPullRequest, SheetRequest,
};
use isogami::contact::inset_polygon;
use isogami::deploy::{DeploySettings, EndReason, TilePose};
use isogami::finite::{FiniteSheet, Region, LEAVE_TOLERANCE};
use isogami::kinematics::Mechanism;
use isogami::math::{rotation, Real, Vec2};
use isogami::Error;

const DESIGNS: [&str; 3] = [
    "rotating-squares",
    "IH44:0.5,0.027564102564:1x2:-aaabbaa",
    "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-",
];

fn request(rows: usize) -> SheetDeployRequest {
    SheetDeployRequest {
        sheet: SheetRequest {
            region: Region::Cells { rows, cols: rows },
            ..SheetRequest::default()
        },
        ..SheetDeployRequest::default()
    }
}

#[test]
fn a_completed_sheet_moves_with_the_periodic_sheet_until_contact() {
    let settings = DeploySettings::default();
    for spec in DESIGNS {
        let design = resolve_design(spec).unwrap();
        let out = deploy_sheet(&design, &request(4), &mut |_| true).unwrap();
        assert!(out.one_dof_throughout, "{spec}: {:?}", out.checks);
        assert!(!out.checks.is_empty());
        // Every state before the periodic sheet's first contact is compared.
        let periodic = deploy_path(&design, &settings, &mut |_| true).unwrap();
        let before_contact = periodic
            .trajectory
            .steps
            .iter()
            .take_while(|s| s.min_clearance >= settings.contact.dhat)
            .count();
        let a = out.agreement;
        assert!(
            a.compared_steps >= before_contact.min(out.steps) && a.compared_steps >= 2,
            "{spec}: compared {} of {before_contact} contact-free periodic states",
            a.compared_steps
        );
        assert!(
            a.max_position_deviation <= 1e-6 && a.max_angle_deviation <= 1e-6,
            "{spec}: {a:?}"
        );
        // The sheet opens: as far as the periodic sheet, or further where it lacks the pair
        // that stops the periodic sheet (the finite deployment's contact is a subset).
        assert!(out.max_hull_area_ratio > 1.05, "{spec}");
        assert!(
            out.max_hull_area_ratio >= out.periodic.measures.hull_area_ratio * (1.0 - 1e-3),
            "{spec}: finite {} < periodic {}",
            out.max_hull_area_ratio,
            out.periodic.measures.hull_area_ratio
        );
        let frames = &out.frames;
        assert_eq!(frames.first().unwrap().step, 0);
        assert_eq!(frames.last().unwrap().step, out.steps - 1);
        assert!(frames
            .iter()
            .all(|f| f.poses.len() == out.analysis.sheet().len()));
    }
}

/// A frame rebuilt from its poses (tiling units, as the API gives them) with the design's
/// tile shapes: every pin of the sheet closed to `tolerance` L, and no two kerf-inset tiles
/// touching (`geo`'s intersection test).
fn check_frame(
    spec: &str,
    mech: &Mechanism,
    sheet: &FiniteSheet,
    poses: &[TilePose],
    tolerance: Real,
) {
    let scale = mech.length_scale;
    let pose = |k: usize| {
        let p = &poses[k];
        (Vec2::new(p.x / scale, p.y / scale), p.theta)
    };
    let mut worst: Real = 0.0;
    for pin in &sheet.joints {
        let j = &mech.joints[pin.joint];
        let (pa, ta) = pose(pin.a);
        let (pb, tb) = pose(pin.b);
        worst = worst.max((pa + rotation(ta) * j.s_a - pb - rotation(tb) * j.s_b).norm());
    }
    assert!(worst <= tolerance, "{spec}: a pin opens by {worst:e} L");
    let kerf = DeploySettings::default().contact.kerf;
    let polygons: Vec<Polygon> = sheet
        .tiles
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let inset = inset_polygon(&mech.tile_shapes[t.tile], 0.5 * kerf).unwrap();
            let (p, th) = pose(k);
            let ring: Vec<Coord> = inset
                .iter()
                .map(|v| {
                    let w = p + rotation(th) * v;
                    Coord { x: w.x, y: w.y }
                })
                .collect();
            Polygon::new(LineString::from(ring), Vec::new())
        })
        .collect();
    for a in 0..polygons.len() {
        for b in a + 1..polygons.len() {
            assert!(
                !polygons[a].intersects(&polygons[b]),
                "{spec}: tiles {a} and {b} touch"
            );
        }
    }
}

#[test]
fn the_end_state_has_closed_joints_and_no_overlap() {
    for spec in DESIGNS {
        let design = resolve_design(spec).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let out = deploy_sheet(&design, &request(4), &mut |_| true).unwrap();
        let last = out.frames.last().unwrap();
        check_frame(spec, &mech, out.analysis.sheet(), &last.poses, 1e-9);
    }
}

#[test]
fn a_floppy_raw_region_is_refused_with_its_count() {
    let design = resolve_design(DESIGNS[1]).unwrap();
    let mut req = request(6);
    req.sheet.complete = false;
    match deploy_sheet(&design, &req, &mut |_| true) {
        Err(Error::Finite(e)) => {
            let msg = e.to_string();
            assert!(
                msg.contains("degrees of freedom") && msg.contains("complete it"),
                "{msg}"
            );
        }
        other => panic!("expected a refusal, got {:?}", other.map(|d| d.steps)),
    }
    // Rotating squares' raw region is one-DOF already and deploys as it is.
    let squares = resolve_design("rotating-squares").unwrap();
    let mut req = request(3);
    req.sheet.complete = false;
    let out = deploy_sheet(&squares, &req, &mut |_| true).unwrap();
    assert!(out.analysis.completion.is_none() && out.one_dof_throughout);
}

#[test]
fn too_few_frames_is_a_bad_request() {
    let design = resolve_design("rotating-squares").unwrap();
    let mut req = request(2);
    req.frames = 1;
    assert!(matches!(
        deploy_sheet(&design, &req, &mut |_| true),
        Err(Error::Finite(_))
    ));
}

#[test]
fn a_sheet_without_the_blocking_pair_moves_past_the_periodic_limit() {
    // One loop of IH27's four tiles: the pair of tiles that stops the periodic sheet is not
    // in it, so it keeps moving (with the full contact model it would stop with the periodic
    // sheet); a 2×2 sheet holds that pair and stops where the periodic sheet stops.
    let design = resolve_design("IH27:0.066304,0.465108,0.534891:1x1:-aaaaaaaa-").unwrap();
    let one = deploy_sheet(&design, &request(1), &mut |_| true).unwrap();
    assert!(
        one.steps > one.periodic.steps + 10,
        "{} states, periodic {}",
        one.steps,
        one.periodic.steps
    );
    assert!(one.one_dof_throughout);
    let a = one.agreement;
    assert!(
        a.compared_steps >= 2 && a.max_position_deviation <= 1e-6,
        "{a:?}"
    );
    let two = deploy_sheet(&design, &request(2), &mut |_| true).unwrap();
    assert_eq!(two.steps, two.periodic.steps);
    assert_eq!(two.end, two.periodic.measures);
}

const IH9: &str = "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-";

fn pull(spec: &str, rows: usize, complete: bool) -> SheetPull {
    let design = resolve_design(spec).unwrap();
    let request = SheetPullRequest {
        sheet: SheetRequest {
            region: Region::Cells { rows, cols: rows },
            complete,
            ..SheetRequest::default()
        },
        ..SheetPullRequest::default()
    };
    let out = pull_sheet(&design, &request, &mut |_| true).unwrap();
    // Every frame rebuilt from its poses: pins closed, no two tiles touching.
    let mech = Mechanism::new(&design.cell().unwrap(), &design.joints).unwrap();
    for f in &out.frames {
        check_frame(spec, &mech, out.analysis.sheet(), &f.poses, 1e-8);
    }
    out
}

#[test]
fn a_one_dof_sheet_pulled_apart_follows_the_periodic_motion() {
    // Rotating squares, 3x3 cells as they are (one DOF): every tile where the periodic motion
    // puts it, until the pull stalls where the squares stand at 45°, when the distance
    // between any two square centres has grown by cos 45° + sin 45° = √2.
    let out = pull("rotating-squares", 3, false);
    assert_eq!(out.dof, 1);
    assert!(out.leaves.is_none() && out.leaving.is_empty());
    assert!(out.max_deviation <= 1e-6, "{}", out.max_deviation);
    assert_eq!(out.end_reason, EndReason::Stalled);
    assert!(
        (out.extension - 2f64.sqrt()).abs() < 1e-3,
        "{}",
        out.extension
    );
}

#[test]
fn a_floppy_raw_sheet_pulled_apart_leaves_the_periodic_motion() {
    let out = pull(IH9, 2, false);
    assert!(out.dof > 1, "{}", out.dof);
    assert!(out.max_deviation > LEAVE_TOLERANCE, "{}", out.max_deviation);
    assert!(!out.leaving.is_empty());
    let leaves = out.leaves.expect("leaves the motion");
    assert!(leaves.dof > 1, "{leaves:?}");
    // The same design's completed 3x3 sheet follows the motion to the end of the pull.
    let done = pull(IH9, 3, true);
    assert_eq!(done.dof, 1);
    assert!(done.leaves.is_none(), "{:?}", done.leaves);
    assert!(
        done.max_deviation <= LEAVE_TOLERANCE,
        "{}",
        done.max_deviation
    );
    assert!(done.extension > 1.05, "{}", done.extension);
}

#[test]
fn a_completed_sheet_leaves_the_motion_only_at_a_branch_point() {
    // IH9's completed 2x2 sheet is one DOF at the counting state, but at t ≈ 0.03 of the
    // periodic motion it has a second motion (a singular state of its path, where the
    // count at the accepted states around it is still one); pulled, it takes that branch.
    let out = pull(IH9, 2, true);
    assert_eq!(out.dof, 1);
    let leaves = out.leaves.expect("leaves at the branch point");
    assert!(leaves.before_periodic_t < 0.1, "{leaves:?}");
    let design = resolve_design(IH9).unwrap();
    let mech = Mechanism::new(&design.cell().unwrap(), &design.joints).unwrap();
    let path = isogami::api::deploy_path(&design, &Default::default(), &mut |_| true).unwrap();
    let singular = isogami::finite::sheet_singular_states(
        out.analysis.sheet(),
        &mech,
        &path.trajectory,
        1,
        &Default::default(),
        isogami::stop::NEVER,
    )
    .unwrap();
    let (lo, hi) = (leaves.after_periodic_t, leaves.before_periodic_t);
    assert!(
        singular
            .iter()
            .any(|s| s.t >= lo.min(hi) - 0.02 && s.t <= lo.max(hi) + 0.02),
        "{leaves:?} {singular:?}"
    );
}

#[test]
fn bad_grips_and_frames_are_bad_requests() {
    let design = resolve_design("rotating-squares").unwrap();
    for (grips, frames) in [(Some([0, 0]), 24), (Some([0, 999]), 24), (None, 1)] {
        let request = SheetPullRequest {
            sheet: SheetRequest {
                region: Region::Cells { rows: 2, cols: 2 },
                ..SheetRequest::default()
            },
            grips,
            frames,
        };
        match pull_sheet(&design, &request, &mut |_| true) {
            Err(Error::Finite(e)) => assert!(!e.to_string().is_empty()),
            other => panic!("{grips:?}/{frames}: {:?}", other.map(|p| p.steps)),
        }
    }
}
