//! The cheap screen (designs that contact locks at the start are rejected from their
//! first-order motion, before deployment) keeps exactly the designs the full assessment keeps.

use isogami::api;
use isogami::catalog::screen::{applies, cannot_reach_threshold, closing_rates, screen_rate};
use isogami::catalog::{assess, run_unit, Assessment, CatalogSettings, UnitOutcome};
use isogami::cell::CellDims;
use isogami::explore::enumerate_topologies;
use isogami::tiling::Family;

fn fam(n: u32) -> Family {
    Family::from_number(n).unwrap()
}

/// Specs and full deployment reports of the kept designs, and the stage counts.
type Content = (Vec<(String, String)>, Vec<(String, u64, u64)>);

fn content(o: &UnitOutcome) -> Content {
    (
        o.entries
            .iter()
            .map(|e| {
                (
                    e.design.to_string(),
                    serde_json::to_string(&e.report).unwrap(),
                )
            })
            .collect(),
        o.stages
            .iter()
            .map(|s| (s.stage.clone(), s.count_in, s.count_out))
            .collect(),
    )
}

/// Low-symmetry hexagon cells (most of their topologies lock or shut early), a triangle and a
/// square cell.
const UNITS: [(u32, u8, u8); 7] = [
    (28, 1, 1),
    (6, 1, 1),
    (32, 1, 1),
    (22, 2, 1),
    (2, 1, 1),
    (90, 2, 2),
    (44, 2, 2),
];

#[test]
fn screened_and_unscreened_runs_keep_the_same_designs() {
    let screened = CatalogSettings {
        samples: 3,
        ..CatalogSettings::default()
    };
    let full = CatalogSettings {
        screen: false,
        ..screened
    };
    assert!(applies(&screened));
    let mut kept = 0;
    for (f, a, b) in UNITS {
        let dims = CellDims::new(a, b).unwrap();
        let one = run_unit(fam(f), dims, &screened).unwrap();
        let two = run_unit(fam(f), dims, &full).unwrap();
        kept += one.entries.len();
        assert_eq!(content(&one), content(&two), "IH{f} {dims}");
    }
    assert!(kept > 5, "{kept} designs kept");
}

#[test]
fn every_screened_design_is_rejected_by_the_full_assessment() {
    let settings = CatalogSettings::default();
    let (mut screened, mut total) = (0, 0);
    for (f, a, b) in UNITS {
        let dims = CellDims::new(a, b).unwrap();
        let topo = enumerate_topologies(fam(f), dims, &settings.topology).unwrap();
        for (d, details) in topo.designs.iter().zip(&topo.details) {
            total += 1;
            // The exploration screens on the rates its deduplication computed: the same, bit
            // for bit, as the screen's own analysis of the design.
            let own = closing_rates(d, &settings);
            assert!(own.is_some(), "{d}");
            assert_eq!(
                details.closing.map(|r| r.map(f64::to_bits)),
                own.map(|r| r.map(f64::to_bits)),
                "{d}"
            );
            if !cannot_reach_threshold(d, &settings) {
                continue;
            }
            screened += 1;
            let rates = closing_rates(d, &settings).unwrap();
            assert!(rates.iter().all(|&r| r >= screen_rate(&settings)), "{d}");
            let verdict = assess(d, &settings, &mut |_| true).unwrap();
            assert!(
                matches!(verdict, Assessment::Rejected(_)),
                "{d} is admitted"
            );
        }
    }
    // Almost every topology of these cells locks or shuts early: the screen must catch most.
    assert!(screened * 10 > total * 9, "{screened} of {total} screened");
}

#[test]
fn admitted_designs_open_freely_along_one_sign_and_are_never_screened() {
    let settings = CatalogSettings {
        samples: 2,
        ..CatalogSettings::default()
    };
    let mut checked = 0;
    for (f, a, b) in UNITS {
        let o = run_unit(fam(f), CellDims::new(a, b).unwrap(), &settings).unwrap();
        for e in &o.entries {
            // Along the sign it opens, no cut closes at first order (roundoff only).
            let rates = closing_rates(&e.design, &settings).unwrap();
            assert!(rates.iter().any(|&r| r < 1e-9), "{}: {rates:?}", e.design);
            assert!(!cannot_reach_threshold(&e.design, &settings));
            checked += 1;
        }
    }
    assert!(checked > 5);
    let squares = isogami::topology::Design::resolve("rotating-squares").unwrap();
    assert!(
        api::analyze(&squares, settings.topology.mobility)
            .unwrap()
            .mobility
            .dof
            == 1
    );
    assert!(!cannot_reach_threshold(&squares, &settings));
    // A threshold below two kerfs turns the screen off.
    let low = CatalogSettings {
        threshold: 0.015,
        ..CatalogSettings::default()
    };
    assert!(!applies(&low));
}
