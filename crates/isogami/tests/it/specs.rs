//! Design specs: exact round trips, the JSON form, and a parser that never panics.

use crate::common;

use isogami::cell::CellDims;
use isogami::cell::CellError;
use isogami::tiling::Family;
use isogami::tiling::TilingError;
use isogami::topology::DesignError;
use isogami::topology::{Design, JointChoice, NAMED_DESIGNS};
use proptest::prelude::*;

fn family_strategy() -> impl Strategy<Value = Family> {
    let all: Vec<Family> = Family::all().collect();
    (0..all.len()).prop_map(move |i| all[i])
}

fn joint_strategy() -> impl Strategy<Value = JointChoice> {
    prop_oneof![
        Just(JointChoice::None),
        Just(JointChoice::A),
        Just(JointChoice::B),
        Just(JointChoice::Both)
    ]
}

fn design_strategy() -> impl Strategy<Value = Design> {
    (
        family_strategy(),
        1u8..=4,
        1u8..=4,
        prop::collection::vec(joint_strategy(), 0..60),
        prop::collection::vec(any::<f64>().prop_filter("finite", |v| v.is_finite()), 6),
    )
        .prop_map(|(family, a, b, joints, raw)| {
            Design::new(
                family,
                &raw[..family.param_count()],
                CellDims::new(a, b).unwrap(),
                joints,
            )
        })
}

fn same_bits(a: &Design, b: &Design) -> bool {
    a.family == b.family
        && a.dims == b.dims
        && a.joints == b.joints
        && a.params.len() == b.params.len()
        && a.params
            .iter()
            .zip(&b.params)
            .all(|(x, y)| x.to_bits() == y.to_bits())
}

proptest! {
    #[test]
    fn spec_strings_round_trip_exactly(d in design_strategy()) {
        let s = d.to_string();
        let back: Design = s.parse().unwrap();
        prop_assert!(same_bits(&d, &back), "{s}");
        prop_assert_eq!(back.to_string(), s);
    }

    #[test]
    fn any_numbers_print_canonically_and_read_back_to_the_same_spec(
        d in design_strategy(),
        noise in prop::collection::vec(-4i64..=4, 6),
    ) {
        // Parameters off their canonical form by a few ulps name the same design.
        let mut raw = d.clone();
        for (p, n) in raw.params.iter_mut().zip(&noise) {
            let moved = f64::from_bits((p.to_bits() as i64 + n) as u64);
            // A few ulps are a relative change only for normal numbers (not at 0).
            if moved.is_finite() && p.abs() > 1e-300 {
                *p = moved;
            }
        }
        let s = raw.to_string();
        let back: Design = s.parse().unwrap();
        prop_assert!(back.is_canonical(), "{s}");
        prop_assert_eq!(back.to_string(), d.to_string());
    }

    #[test]
    fn random_strings_never_panic(s in "\\PC{0,80}") {
        let _ = s.parse::<Design>();
        let _ = Design::resolve(&s);
    }

    #[test]
    fn near_valid_strings_never_panic(
        fam in "(IH|ih)?[0-9]{0,3}",
        params in "[-0-9.,eE+naifNI]{0,30}",
        cell in "[0-9xX]{0,4}",
        joints in "[-abxAB0-9?]{0,20}",
        sep in prop::sample::select(vec![":", "::", ";", ""]),
    ) {
        let s = format!("{fam}{sep}{params}{sep}{cell}{sep}{joints}");
        if let Ok(d) = Design::resolve(&s) {
            // Whatever parses must build its cell or fail with an error, not a panic.
            let _ = d.cell();
        }
    }

    #[test]
    fn json_round_trips_for_valid_designs(
        family in family_strategy(),
        a in 1u8..=2, b in 1u8..=2,
        seed in any::<u64>(),
    ) {
        let dims = CellDims::new(a, b).unwrap();
        let cell = isogami::cell::UnitCell::new(
            &isogami::tiling::Tiling::default_for(family), dims).unwrap();
        let mut rng = common::Rng::new(seed);
        let joints = common::random_joints(&mut rng, cell.edges.len());
        let d = Design::with_defaults(family, dims, joints);
        let text = serde_json::to_string(&d.to_json()).unwrap();
        let back = Design::from_json(&text).unwrap();
        prop_assert!(same_bits(&d, &back), "{text}");
        prop_assert_eq!(Design::resolve(&text).unwrap(), d);
    }
}

#[test]
fn named_designs_resolve_and_build() {
    for name in NAMED_DESIGNS {
        let d = Design::resolve(name).unwrap();
        let cell = d.cell().unwrap();
        assert_eq!(d.joints.len(), cell.edges.len());
        assert_eq!(Design::resolve(&d.to_string()).unwrap(), d);
    }
}

#[test]
fn malformed_specs_give_specific_errors() {
    let rs = Design::resolve("rotating-squares").unwrap().to_string();
    let bad_family = rs.replace("IH76", "IH19");
    assert!(matches!(
        Design::resolve(&bad_family),
        Err(DesignError::Tiling(TilingError::UnknownFamily { input })) if input == "IH19"
    ));
    assert!(Design::resolve("IH28:0.1:1x1:-").is_ok());
    assert!(matches!(
        Design::resolve("IH28:0.1:1x1:-").unwrap().cell(),
        Err(DesignError::Tiling(TilingError::ParamCount {
            expected: 2,
            got: 1,
            ..
        }))
    ));
    assert!(matches!(
        Design::resolve("IH28:0.1,nan:1x1:-"),
        Err(DesignError::Tiling(TilingError::ParamNotFinite { index: 1, value })) if value.is_nan()
    ));
    assert!(matches!(
        Design::resolve("IH28:0.1,zz:1x1:-"),
        Err(DesignError::ParamNotNumber { index: 1, input }) if input == "zz"
    ));
    assert!(matches!(
        Design::resolve("IH28:default:5x1:-"),
        Err(DesignError::Cell(CellError::BadCell { input })) if input == "5x1"
    ));
    assert!(matches!(
        Design::resolve("IH28:default:1x1:ab?"),
        Err(DesignError::JointChar {
            index: 2,
            found: '?'
        })
    ));
    assert!(matches!(
        Design::resolve("IH28:default:1x1"),
        Err(DesignError::FieldCount { fields: 3, .. })
    ));
    assert!(matches!(
        Design::resolve("IH28:default:1x1:ab").unwrap().cell(),
        Err(DesignError::JointCount { given: 2, .. })
    ));
    let json = r#"{"family":"IH76","cell":[2,2],"joints":[{"edge":8,"at":"a"}]}"#;
    assert!(matches!(
        Design::resolve(json),
        Err(DesignError::JointIndex { index: 8, edges: 8 })
    ));
    let json =
        r#"{"family":"IH76","cell":[2,2],"joints":[{"edge":1,"at":"a"},{"edge":1,"at":"b"}]}"#;
    assert!(matches!(
        Design::resolve(json),
        Err(DesignError::DuplicateEdge { edge: 1 })
    ));
    let json = r#"{"family":"IH76","cell":[0,2],"joints":[]}"#;
    assert!(matches!(
        Design::resolve(json),
        Err(DesignError::Json { .. })
    ));
    for e in [
        Design::resolve("nonsense").unwrap_err(),
        Design::resolve("{").unwrap_err(),
    ] {
        assert!(!e.to_string().contains('\n'), "one line: {e}");
    }
}

/// Issue 21: for 200 random valid shapes per family, spec → string → spec is the identity,
/// and two shapes equal to 12 significant digits give one spec.
#[test]
fn random_valid_shapes_have_one_canonical_spec() {
    let mut rng = common::Rng::new(2121);
    for family in Family::all() {
        let ranges = isogami::tiling::param_ranges(family, 0.6);
        let mut found = 0;
        let mut twins = 0;
        for _ in 0..20_000 {
            if found == 200 || ranges.is_empty() {
                break;
            }
            let p: Vec<f64> = ranges
                .iter()
                .map(|&(lo, hi)| lo + (hi - lo) * rng.unit())
                .collect();
            if isogami::tiling::Tiling::new(family, &p).is_err() {
                continue;
            }
            found += 1;
            let d = Design::new(family, &p, CellDims::MINIMAL, vec![JointChoice::A]);
            let s = d.to_string();
            let back: Design = s.parse().unwrap();
            assert!(same_bits(&d, &back), "{s}");
            // The same shape to 12 significant digits, reached another way (1e-14 apart).
            let twin: Vec<f64> = p
                .iter()
                .map(|&x| x * (1.0 + 1e-14 * (rng.unit() - 0.5)))
                .collect();
            let digits = |v: &[f64]| v.iter().map(|x| format!("{x:.11e}")).collect::<Vec<_>>();
            if digits(&twin) == digits(&p) {
                let twin = Design::new(family, &twin, CellDims::MINIMAL, vec![JointChoice::A]);
                assert_eq!(twin.to_string(), s);
                twins += 1;
            }
            // Long decimal noise typed by a user reads as the same shape.
            let noisy: Vec<String> = d.params.iter().map(|x| format!("{x:.17}")).collect();
            let typed = format!("{}:{}:1x1:a", family, noisy.join(","));
            assert_eq!(typed.parse::<Design>().unwrap().to_string(), s, "{typed}");
        }
        if family.param_count() > 0 {
            assert_eq!(found, 200, "{family}: 200 random valid shapes");
            assert!(twins > 150, "{family}: {twins} twins at 12 digits");
        }
    }
}
