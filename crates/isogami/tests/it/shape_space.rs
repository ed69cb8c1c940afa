//! Shape-aware mobility, checked through the library's own mobility analysis and deployment
//! (`api::analyze`, `api::deploy`), which share nothing with the shape-space code but the
//! mechanism: special designs are rigid off their constraints and keep one DOF along them,
//! the constraint normals are right to first order, moved designs deploy, and rigid shapes
//! next to a special set are found back by the rank-drop search.

use isogami::api::{analyze, deploy, resolve_design, DeployRequest};
use isogami::mobility::MobilitySettings;
use isogami::shape_space::{
    classify, follow, param_scales, rank_drop, search_neighbours, ShapeClass, ShapeError,
    ShapeSettings,
};
use isogami::topology::Design;

/// The issue's four quick-database designs that no single ±2 % parameter move keeps mobile.
const SPECIAL: [&str; 4] = [
    "IH7:0.6,0.196416770201:1x1:-a-a-aaaa",
    "IH16:0.216506350946:1x1:-a-a-aaaa",
    "IH46:0.5,0.230769230769,0.5,0.5:1x1:aaaa",
    "IH53:0.5,0.102564102564,0.102564102564:1x1:aaaabbbb",
];
/// A special design whose one constraint is p2 = p3 (the tile's two equal edges).
const IH2: &str = "IH2:0.12239750492,0.5,0.225335752741,0.225335752741:1x1:aa-aa-";
/// A generic design.
const IH28: &str = "IH28:0.588675134594,0.35:1x1:a--a-b-bbb";

fn design(spec: &str) -> Design {
    resolve_design(spec).unwrap()
}

fn with(d: &Design, params: Vec<f64>) -> Design {
    Design {
        params,
        ..d.clone()
    }
}

fn dof(d: &Design) -> usize {
    analyze(d, MobilitySettings::default())
        .unwrap()
        .mobility
        .dof
}

/// √(λ_min / max(λ_max, 1)) by the mobility analysis.
fn sigma(d: &Design) -> f64 {
    let e = analyze(d, MobilitySettings::default())
        .unwrap()
        .mobility
        .eigenvalues;
    (e[0].max(0.0) / e.last().unwrap().max(1.0)).sqrt()
}

#[test]
fn the_issues_four_designs_are_special_and_rigid_at_every_single_parameter_move() {
    let settings = ShapeSettings::default();
    for spec in SPECIAL {
        let d = design(spec);
        assert_eq!(dof(&d), 1, "{spec}");
        let m = classify(&d, &settings).unwrap();
        assert_eq!(m.class, ShapeClass::Special, "{spec}");
        assert_eq!(m.samples_one_dof, 0, "{spec}");
        assert!(!m.constraints.is_empty(), "{spec}");
        let scales = param_scales(d.family);
        for i in 0..d.params.len() {
            for sign in [-1.0, 1.0] {
                let mut p = d.params.clone();
                p[i] += sign * 0.02 * scales[i];
                assert_eq!(
                    dof(&with(&d, p)),
                    0,
                    "{spec}: parameter {i} moved by {sign}·2 %"
                );
            }
        }
    }
}

#[test]
fn constraint_normals_are_right_to_first_order() {
    // Off the special set along a normal, σ grows like the distance; along a tangent only
    // like its square, so the ratio σ_tangent / σ_normal falls with the step.
    let settings = ShapeSettings::default();
    for spec in [IH2, SPECIAL[2]] {
        let d = design(spec);
        let m = classify(&d, &settings).unwrap();
        let p = d.params.len();
        // A tangent: a fixed vector with the normals projected out (they are orthonormal
        // in scaled coordinates, so project there).
        let scales = param_scales(d.family);
        let scaled: Vec<Vec<f64>> = m
            .constraints
            .iter()
            .map(|n| {
                let v: Vec<f64> = n.iter().zip(&scales).map(|(x, s)| x * s).collect();
                let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                v.iter().map(|x| x / norm).collect()
            })
            .collect();
        let mut t: Vec<f64> = (0..p).map(|i| 1.0 + i as f64).collect();
        for n in &scaled {
            let d: f64 = n.iter().zip(&t).map(|(a, b)| a * b).sum();
            t.iter_mut().zip(n).for_each(|(x, y)| *x -= d * y);
        }
        let tn = t.iter().map(|x| x * x).sum::<f64>().sqrt();
        let step = |dir: &[f64], h: f64| {
            let q: Vec<f64> = (0..p)
                .map(|i| d.params[i] + h * dir[i] * scales[i])
                .collect();
            sigma(&with(&d, q))
        };
        let tangent: Vec<f64> = t.iter().map(|x| x / tn).collect();
        // A control: 30° off the tangent towards the first normal. Wrong normals would make
        // the "tangent" as bad as this.
        let (c, s30) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let skew: Vec<f64> = (0..p)
            .map(|i| c * tangent[i] + s30 * scaled[0][i])
            .collect();
        for h in [1e-2, 1e-3] {
            let normal = step(&scaled[0], h);
            assert!(
                normal > 0.1 * h,
                "{spec}: a normal move of {h} gives σ = {normal:e}"
            );
            let along = step(&tangent, h) / normal;
            let control = step(&skew, h) / normal;
            assert!(
                along < 0.05,
                "{spec}: tangent σ / normal σ = {along:e} at {h}"
            );
            assert!(control > 0.3, "{spec}: control {control:e} at {h}");
        }
    }
}

#[test]
fn following_a_special_design_keeps_one_dof_and_it_deploys() {
    let settings = ShapeSettings::default();
    let d = design(IH2);
    let target = d.params[2] + 0.1 * param_scales(d.family)[2];
    // Moving p2 alone breaks the motion ...
    let mut alone = d.params.clone();
    alone[2] = target;
    assert_eq!(dof(&with(&d, alone)), 0);
    // ... following moves p3 with it (the constraint p2 = p3) and keeps it.
    let f = follow(&d, 2, target, &settings).unwrap();
    assert_eq!(f.class, ShapeClass::Special);
    assert!(f.steps >= 5);
    assert_eq!(f.design.params[2], target);
    assert!((f.design.params[3] - target).abs() < 1e-9, "{}", f.spec);
    assert!((f.design.params[0] - d.params[0]).abs() < 1e-9);
    assert_eq!(dof(&f.design), 1);
    let run = deploy(&f.design, &DeployRequest::default(), &mut |_| true).unwrap();
    assert_eq!(run.report.dof, 1);
    assert!(
        run.report.max_expansion > 0.05,
        "{}",
        run.report.max_expansion
    );
    // IH46: two constraints, parameter 1 drags parameter 3 along and keeps p0 = p2.
    let d = design(SPECIAL[2]);
    for value in [0.2, 0.26] {
        let f = follow(&d, 1, value, &settings).unwrap();
        assert_eq!(dof(&f.design), 1, "{}", f.spec);
        assert!((f.design.params[0] - f.design.params[2]).abs() < 1e-9);
        assert!(
            (f.design.params[3] - d.params[3]).abs() > 1e-3,
            "{}",
            f.spec
        );
    }
}

#[test]
fn generic_designs_move_freely_and_pinned_parameters_are_refused() {
    let settings = ShapeSettings::default();
    let d = design(IH28);
    let m = classify(&d, &settings).unwrap();
    assert_eq!(m.class, ShapeClass::Generic);
    assert_eq!(m.samples_one_dof, m.samples);
    assert!(m.samples >= 4 && m.constraints.is_empty());
    let f = follow(&d, 0, d.params[0] + 0.02, &settings).unwrap();
    assert_eq!((f.steps, f.class), (0, ShapeClass::Generic));
    assert_eq!(f.design.params[1], d.params[1]);
    assert_eq!(dof(&f.design), 1);
    // IH16 has one parameter and one constraint: nothing can move. IH7 is an isolated shape.
    let d = design(SPECIAL[1]);
    assert_eq!(classify(&d, &settings).unwrap().pinned, vec![0]);
    assert!(matches!(
        follow(&d, 0, 0.22, &settings),
        Err(ShapeError::Pinned { index: 0 })
    ));
    assert_eq!(
        classify(&design(SPECIAL[0]), &settings).unwrap().pinned,
        vec![0, 1]
    );
}

#[test]
fn a_rigid_shape_next_to_a_special_set_is_found_back() {
    let settings = ShapeSettings::default();
    let d = design(IH2);
    let mut off = d.params.clone();
    off[3] += 0.05 * param_scales(d.family)[3];
    let rigid = with(&d, off);
    assert_eq!(dof(&rigid), 0);
    let found = rank_drop(&rigid, &settings)
        .unwrap()
        .expect("a shape with one DOF");
    assert_eq!(dof(&found.design), 1, "{}", found.spec);
    assert!(found.sigma < 1e-6 && found.start_sigma > 1e-3);
    assert!(
        (found.design.params[2] - found.design.params[3]).abs() < 1e-8,
        "{}",
        found.spec
    );
    let run = deploy(&found.design, &DeployRequest::default(), &mut |_| true).unwrap();
    assert_eq!(run.report.dof, 1);
}

#[test]
fn bad_requests_are_typed_errors() {
    let settings = ShapeSettings::default();
    let d = design(IH2);
    assert!(matches!(
        follow(&d, 4, 0.1, &settings),
        Err(ShapeError::NoSuchParameter { index: 4, count: 4 })
    ));
    assert!(matches!(
        follow(&d, 0, f64::NAN, &settings),
        Err(ShapeError::NotFinite { .. })
    ));
    let mut rigid = d.clone();
    rigid.params[3] += 0.02;
    assert!(matches!(
        classify(&rigid, &settings),
        Err(ShapeError::NotOneDof { dof: 0 })
    ));
    // Far along the constraint the tile degenerates: an error naming it, not a bad design.
    let e = follow(&d, 2, 2.0, &settings).unwrap_err();
    assert!(
        matches!(e, ShapeError::LeavesShapes { .. } | ShapeError::Lost { .. }),
        "{e}"
    );
    let mut s = settings;
    s.radius = 0.0;
    assert!(classify(&d, &s).is_err());
}

#[test]
fn rigid_neighbours_of_a_known_design_hold_new_mechanisms() {
    // IH27 aaa-a--a-a with one more joint is rigid at the default shape, so the exploration
    // never samples its shapes; at other shapes two such neighbours move, deploy to the
    // contact limit and pass the catalogue's admission rule.
    let from = design("IH27:0.141304,0.465108,0.534891:1x1:aaa-a--a-a");
    let report = search_neighbours(
        std::slice::from_ref(&from),
        &ShapeSettings::default(),
        &isogami::catalog::CatalogSettings::default(),
    );
    assert!(report.rigid_neighbours >= 4);
    let admitted: Vec<_> = report.findings.iter().filter(|f| f.admitted).collect();
    assert!(!admitted.is_empty(), "{:?}", report.findings);
    for f in &report.findings {
        let rigid = design(&f.rigid);
        let found = design(&f.spec);
        assert_eq!(dof(&rigid), 0, "{}", f.rigid);
        assert_eq!(found.joints, rigid.joints, "same topology, another shape");
        assert_eq!(dof(&found), 1, "{}", f.spec);
    }
    for f in admitted {
        let run = deploy(&design(&f.spec), &DeployRequest::default(), &mut |_| true).unwrap();
        assert!(run.report.max_expansion > 0.1 && run.report.max_joint_residual < 1e-9);
    }
}
