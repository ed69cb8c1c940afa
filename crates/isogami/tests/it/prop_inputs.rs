//! Property tests over everything a user can type or load: spec strings, design JSON and
//! shape parameters. On any input the library must not panic, must not hand back a NaN or
//! an infinity, and must explain a refusal in one line.

use isogami::cell::{CellDims, UnitCell};
use isogami::kinematics::Mechanism;
use isogami::math::{cross, Real};
use isogami::mobility::{analyze, MobilitySettings};
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, DesignJson, JointChoice, SAMPLE_OPENING_DESIGNS};
use proptest::prelude::*;

/// A refusal is one non-empty line, whatever the input holds (quoted input is escaped).
fn assert_one_line(e: &impl std::fmt::Display, input: &str) {
    let msg = e.to_string();
    assert!(!msg.trim().is_empty(), "empty error for {input:?}");
    assert!(
        !msg.contains(['\n', '\r']),
        "multi-line error for {input:?}: {msg:?}"
    );
}

/// Found by `any_text_resolves_or_is_refused_in_one_line`: `BadCell` and `UnknownFamily`
/// used to quote the user's text unescaped, so a line break in it broke the message.
#[test]
fn errors_escape_line_breaks_in_the_input() {
    for text in ["IH1::\nx1:-", "IH\n28::1x1:-"] {
        let msg = Design::resolve(text).expect_err("invalid").to_string();
        assert!(!msg.contains('\n'), "{text:?}: {msg:?}");
    }
}

/// Every coordinate of the cell is finite and the lattice is not degenerate.
fn assert_cell_finite(cell: &UnitCell, what: &str) {
    for (i, t) in cell.tiles.iter().enumerate() {
        assert!(
            t.polygon.iter().all(|p| p.x.is_finite() && p.y.is_finite()),
            "{what}: tile {i} has a non-finite vertex"
        );
        assert!(
            t.centroid.x.is_finite() && t.centroid.y.is_finite(),
            "{what}"
        );
    }
    assert!(
        cell.u.iter().chain(cell.w.iter()).all(|x| x.is_finite()),
        "{what}"
    );
    let area = cross(&cell.u, &cell.w).abs();
    let l = cell.mean_edge_length();
    assert!(l.is_finite() && l > 0.0, "{what}: mean edge length {l}");
    assert!(
        area > 1e-9 * l * l,
        "{what}: degenerate lattice, area {area}"
    );
}

/// A number as a user might type it: ordinary values, extremes, non-finite values.
fn number() -> impl Strategy<Value = Real> {
    prop_oneof![
        6 => -2.0..2.0f64,
        1 => any::<f64>(),
        1 => prop::sample::select(vec![
            0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, Real::MAX, Real::MIN_POSITIVE,
            Real::NAN, Real::INFINITY, Real::NEG_INFINITY,
        ]),
    ]
}

/// A family number, mostly valid (1..=93 holds some unrealizable numbers too).
fn family_number() -> impl Strategy<Value = u32> {
    prop_oneof![9 => 1u32..=93, 1 => any::<u32>()]
}

/// Text that looks like a spec, with the field separators and joint letters over-weighted,
/// and known designs with a character changed.
fn spec_like() -> impl Strategy<Value = String> {
    let known = (
        prop::sample::select(SAMPLE_OPENING_DESIGNS),
        any::<prop::sample::Index>(),
        any::<char>(),
    )
        .prop_map(|(spec, at, c)| {
            let mut chars: Vec<char> = spec.chars().collect();
            let k = at.index(chars.len());
            chars[k] = c;
            chars.into_iter().collect()
        });
    prop_oneof![
        ".{0,40}",
        "(IH[0-9]{1,3}|rotating-squares|default)?(:[-0-9.,eEnaif]{0,12}){0,2}(:[0-9]x[0-9])?(:[-abxy]{0,20})?",
        prop::sample::select(SAMPLE_OPENING_DESIGNS).prop_map(str::to_string),
        known,
    ]
}

fn joint_string() -> impl Strategy<Value = String> {
    "[-abx]{0,40}"
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    #[test]
    fn any_text_resolves_or_is_refused_in_one_line(text in spec_like()) {
        match Design::resolve(&text) {
            Ok(d) => {
                // What was accepted prints back to a spec that reads the same.
                let again: Design = d.to_string().parse().expect("printed spec parses");
                prop_assert_eq!(again, d);
            }
            Err(e) => assert_one_line(&e, &text),
        }
    }

    #[test]
    fn structured_specs_round_trip_and_build_finite_cells(
        n in family_number(),
        params in prop::collection::vec(number(), 0..4),
        defaults in any::<bool>(),
        a in 0u8..6,
        b in 0u8..6,
        joints in joint_string(),
        fit in any::<bool>(),
    ) {
        let params = match Family::from_number(n) {
            Ok(f) if defaults => f.default_params(),
            _ => params,
        };
        let text_params: Vec<String> = params.iter().map(|p| p.to_string()).collect();
        // Half the cases give exactly as many joint characters as the cell has edges (when
        // the cell builds), so that the whole spec is valid.
        let mut joints = joints;
        if let (true, Ok(f), Ok(dims)) = (fit, Family::from_number(n), CellDims::new(a, b)) {
            if let Some(cell) = Tiling::new(f, &params)
                .ok()
                .and_then(|t| UnitCell::new(&t, dims).ok())
            {
                joints = joints.chars().cycle().chain(std::iter::repeat('-')).take(cell.edges.len()).collect();
            }
        }
        let spec = format!("IH{n}:{}:{a}x{b}:{joints}", text_params.join(","));
        let d: Design = match spec.parse() {
            Ok(d) => d,
            Err(e) => {
                assert_one_line(&e, &spec);
                return Ok(());
            }
        };
        prop_assert!(d.params.iter().all(|p| p.is_finite()), "{spec}");
        let again: Design = d.to_string().parse().expect("printed spec parses");
        prop_assert_eq!(&again, &d);
        match d.cell() {
            Ok(cell) => {
                assert_cell_finite(&cell, &spec);
                prop_assert_eq!(cell.edges.len(), d.joints.len());
            }
            Err(e) => assert_one_line(&e, &spec),
        }
    }

    #[test]
    fn shape_parameters_give_a_finite_tile_or_a_named_refusal(
        n in 1u32..=93,
        offsets in prop::collection::vec(number(), 0..7),
        near in any::<bool>(),
    ) {
        let Ok(family) = Family::from_number(n) else { return Ok(()) };
        // Half the cases perturb the defaults a little (mostly valid shapes), half replace
        // them (often invalid, sometimes the wrong count).
        let params: Vec<Real> = if near {
            family
                .default_params()
                .iter()
                .zip(offsets.iter().chain(std::iter::repeat(&0.0)))
                .map(|(p, o)| p + 0.1 * o)
                .collect()
        } else {
            offsets.clone()
        };
        let what = format!("{family} {params:?}");
        match Tiling::new(family, &params) {
            Ok(t) => {
                prop_assert!(t.prototile().iter().all(|p| p.x.is_finite() && p.y.is_finite()), "{what}");
                let (t1, t2) = (t.t1(), t.t2());
                prop_assert!(cross(&t1, &t2).abs() > 0.0 && cross(&t1, &t2).is_finite(), "{what}");
                for dims in [CellDims::MINIMAL, CellDims::new(2, 1).expect("valid")] {
                    match UnitCell::new(&t, dims) {
                        Ok(cell) => assert_cell_finite(&cell, &what),
                        Err(e) => assert_one_line(&e, &what),
                    }
                }
            }
            Err(e) => assert_one_line(&e, &what),
        }
    }

    #[test]
    fn valid_designs_have_a_finite_spectrum(
        n in 1u32..=93,
        joints in prop::collection::vec(0u8..4, 0..40),
    ) {
        let Ok(family) = Family::from_number(n) else { return Ok(()) };
        let tiling = Tiling::default_for(family);
        let cell = UnitCell::new(&tiling, CellDims::MINIMAL).expect("default cell");
        let choices = [JointChoice::None, JointChoice::A, JointChoice::B, JointChoice::Both];
        let joints: Vec<JointChoice> = (0..cell.edges.len())
            .map(|e| choices[usize::from(joints.get(e).copied().unwrap_or(0))])
            .collect();
        let mech = match Mechanism::new(&cell, &joints) {
            Ok(m) => m,
            Err(e) => {
                assert_one_line(&e, &family.to_string());
                return Ok(());
            }
        };
        match analyze(&mech, &mech.rest, MobilitySettings::default()) {
            Ok(m) => {
                prop_assert!(m.eigenvalues.iter().all(|l| l.is_finite()), "{family}");
                prop_assert!(m.dof <= m.eigenvalues.len());
                for motion in m.motion.iter().chain(&m.modes) {
                    prop_assert!(motion.vector.iter().all(|x| x.is_finite()), "{family}");
                    prop_assert!(motion.area_rate.is_finite(), "{family}");
                }
            }
            Err(e) => assert_one_line(&e, &family.to_string()),
        }
    }
}

/// Design JSON as a user might hand-write it: the right keys with odd values, wrong types,
/// extra keys, duplicate edges.
fn json_like() -> impl Strategy<Value = String> {
    let family = prop_oneof![
        8 => family_number().prop_map(|n| format!("\"IH{n}\"")),
        1 => Just("28".to_string()),
        1 => Just("null".to_string()),
        1 => "\"[A-Za-z0-9]{0,6}\"",
    ];
    let params = prop_oneof![
        prop::collection::vec(-2.0..2.0f64, 0..4).prop_map(|v| format!("{v:?}")),
        Just("[1e999]".to_string()),
        Just("\"0.5\"".to_string()),
        Just("null".to_string()),
    ];
    let cell = prop_oneof![
        4 => (1u32..=4, 1u32..=4),
        1 => (0u32..300, 0u32..6),
    ]
    .prop_map(|(a, b)| format!("[{a}, {b}]"));
    let at = prop_oneof![
        8 => prop::sample::select(vec!["\"a\"", "\"b\"", "\"both\""]),
        1 => prop::sample::select(vec!["\"c\"", "1", "null"]),
    ];
    let joint = (prop_oneof![8 => 0usize..8, 1 => any::<usize>()], at)
        .prop_map(|(e, at)| format!("{{\"edge\": {e}, \"at\": {at}}}"));
    let joints = prop::collection::vec(joint, 0..5).prop_map(|v| format!("[{}]", v.join(", ")));
    let extra = prop::bool::weighted(0.1);
    (
        family,
        prop::option::weighted(0.3, params),
        cell,
        joints,
        extra,
    )
        .prop_map(|(f, p, c, j, extra)| {
            let params = p.map_or(String::new(), |p| format!(", \"params\": {p}"));
            let extra = if extra { ", \"colour\": 1" } else { "" };
            format!("{{\"family\": {f}{params}, \"cell\": {c}, \"joints\": {j}{extra}}}")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1024))]

    #[test]
    fn design_json_is_read_or_refused_in_one_line(text in prop_oneof![json_like(), "\\{.{0,40}"]) {
        match Design::from_json(&text) {
            Ok(d) => {
                prop_assert!(d.params.iter().all(|p| p.is_finite()), "{text}");
                let cell = d.cell().expect("a design read from JSON builds its cell");
                assert_cell_finite(&cell, &text);
                // The JSON written back reads as the same design.
                let back: DesignJson = d.to_json();
                let again = Design::from_json(&serde_json::to_string(&back).expect("serialises"))
                    .expect("written JSON reads back");
                prop_assert_eq!(again, d);
            }
            Err(e) => assert_one_line(&e, &text),
        }
    }
}
