//! The finite 6×6 patch's figures the catalogue stores (issue 22, item 5): computed from the
//! admission's own deployment, they equal `api::finite_sheet` on the same request.

use isogami::api::{finite_sheet, resolve_design};
use isogami::catalog::{finite_figures, finite_request, run_unit, CatalogSettings, FiniteFigures};
use isogami::cell::CellDims;
use isogami::finite::Region;
use isogami::tiling::Family;
use isogami::topology::Design;

fn settings() -> CatalogSettings {
    CatalogSettings {
        samples: 1,
        ..CatalogSettings::default()
    }
}

/// The figures as `api::finite_sheet` gives them (deployed on its own).
fn independent(design: &Design) -> FiniteFigures {
    let request = finite_request(&settings());
    assert_eq!(request.region, Region::Cells { rows: 6, cols: 6 });
    match finite_sheet(design, &request, &mut |_| true) {
        Ok(a) => FiniteFigures {
            raw_dof: a.raw_mobility.dof,
            covered: a.completion.map(|c| c.report.covered_fraction),
        },
        Err(e) => {
            assert!(e.to_string().contains("no one-DOF sheet"), "{design}: {e}");
            let mut raw = request.clone();
            raw.complete = false;
            let a = finite_sheet(design, &raw, &mut |_| true).unwrap();
            FiniteFigures {
                raw_dof: a.raw_mobility.dof,
                covered: None,
            }
        }
    }
}

#[test]
fn rotating_squares_entries_carry_one_dof_fully_covered_patches() {
    let o = run_unit(
        Family::from_number(76).unwrap(),
        CellDims::new(2, 2).unwrap(),
        &settings(),
    )
    .unwrap();
    assert!(!o.entries.is_empty());
    for e in &o.entries {
        let stored = e.finite.expect("every new entry has its figures");
        assert_eq!(stored, independent(&e.design), "{}", e.design);
        assert_eq!(stored, finite_figures(&e.design, &settings()).unwrap());
    }
    let squares = o
        .entries
        .iter()
        .find(|e| e.design.joints.iter().all(|j| j.ends().len() == 1))
        .expect("the fully hinged squares");
    let f = squares.finite.unwrap();
    assert_eq!(f.raw_dof, 1, "{}", squares.design);
    assert_eq!(f.covered, Some(1.0));
}

#[test]
fn named_designs_get_the_figures_finite_sheet_gives() {
    let squares = resolve_design("rotating-squares").unwrap();
    let f = finite_figures(&squares, &settings()).unwrap();
    assert_eq!(f, independent(&squares));
    assert_eq!((f.raw_dof, f.covered), (1, Some(1.0)));

    // An isostatic cell: its pruned patch falls apart, so no covered fraction.
    let isostatic = resolve_design("IH10::2x2:--a--aa-a-bb").unwrap();
    let f = finite_figures(&isostatic, &settings()).unwrap();
    assert_eq!(f, independent(&isostatic));
    assert_eq!(f.covered, None, "{f:?}");
    assert!(f.raw_dof >= 1);

    // Floppy as cut, completed to (nearly) the whole region.
    let floppy = resolve_design("IH44:0.5,0.027564102564:1x2:-aaabbaa").unwrap();
    let f = finite_figures(&floppy, &settings()).unwrap();
    assert_eq!(f, independent(&floppy));
    assert!(f.raw_dof > 1, "{f:?}");
    let covered = f.covered.expect("completes");
    assert!(covered > 0.9 && covered <= 1.0, "{f:?}");
}
