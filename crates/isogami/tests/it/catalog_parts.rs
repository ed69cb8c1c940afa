//! A unit split into parts and joined (`catalog::combine_parts`) equals the unit run whole:
//! the same designs with the same reports and the same stage counts, for 3 and 7 parts, with
//! motion classes that span parts; the parts survive a JSON round trip (how they wait in a
//! database); and parts that are not one unit's are refused.

use isogami::catalog::{combine_parts, run_unit, run_unit_part, CatalogSettings, PartOutcome};
use isogami::cell::CellDims;
use isogami::explore::{ExploreError, UnitPart};
use isogami::tiling::Family;

fn fam(n: u32) -> Family {
    Family::from_number(n).unwrap()
}

fn settings() -> CatalogSettings {
    CatalogSettings {
        samples: 3,
        ..CatalogSettings::default()
    }
}

type Content = (Vec<(String, String)>, Vec<(String, u64, u64)>);

fn content(o: &isogami::catalog::UnitOutcome) -> Content {
    (
        o.entries
            .iter()
            .map(|e| {
                (
                    e.design.to_string(),
                    serde_json::to_string(&(&e.design.params, &e.report, &e.linkages)).unwrap(),
                )
            })
            .collect(),
        o.stages
            .iter()
            .map(|s| (s.stage.clone(), s.count_in, s.count_out))
            .collect(),
    )
}

fn parts(f: Family, dims: CellDims, count: usize) -> Vec<PartOutcome> {
    (0..count)
        .map(|k| run_unit_part(f, dims, UnitPart::new(k, count).unwrap(), &settings()).unwrap())
        .collect()
}

/// A hexagon cell with many motion classes, a square and a triangle supercell.
const UNITS: [(u32, u8, u8); 3] = [(28, 1, 1), (44, 2, 2), (90, 2, 1)];

#[test]
fn parts_joined_equal_the_whole_unit() {
    let mut spanning = 0;
    let mut kept = 0;
    for (f, a, b) in UNITS {
        let dims = CellDims::new(a, b).unwrap();
        let whole = run_unit(fam(f), dims, &settings()).unwrap();
        kept += whole.entries.len();
        for count in [3, 7] {
            let ps = parts(fam(f), dims, count);
            let classes: usize = ps.iter().map(|p| p.classes.len()).sum();
            let unique = whole.stages.iter().find(|s| s.stage == "unique").unwrap();
            // Classes that more than one part found: the join merged them.
            spanning += classes - unique.count_out as usize;
            // Joined in any order, and after a JSON round trip.
            let mut shuffled: Vec<PartOutcome> = ps
                .iter()
                .map(|p| serde_json::from_str(&serde_json::to_string(p).unwrap()).unwrap())
                .collect();
            shuffled.reverse();
            let joined = combine_parts(shuffled).unwrap();
            assert_eq!(
                content(&joined),
                content(&whole),
                "IH{f} {dims} in {count} parts"
            );
        }
    }
    assert!(kept > 5, "{kept} designs kept");
    assert!(
        spanning > 0,
        "no motion class spans parts: the join is not tested"
    );
}

#[test]
fn parts_of_different_units_or_counts_or_missing_are_refused() {
    let dims = CellDims::new(1, 1).unwrap();
    let three = parts(fam(28), dims, 3);
    let refused = |ps: Vec<PartOutcome>, word: &str| {
        let e = combine_parts(ps).unwrap_err();
        assert!(matches!(&e, ExploreError::PartsMismatch { .. }), "{e:?}");
        assert!(e.to_string().contains(word), "{e}");
    };
    refused(three[..2].to_vec(), "part 2/3 is missing");
    refused(
        vec![three[0].clone(), three[1].clone(), three[1].clone()],
        "given twice",
    );
    let other = run_unit_part(fam(6), dims, UnitPart::new(2, 3).unwrap(), &settings()).unwrap();
    refused(
        vec![three[0].clone(), three[1].clone(), other],
        "parts of IH28/1x1 and IH6/1x1",
    );
    let halves = parts(fam(28), dims, 2);
    refused(
        vec![three[0].clone(), three[1].clone(), halves[1].clone()],
        "split into 3 and into 2 parts",
    );
    refused(Vec::new(), "no parts");
    assert!(UnitPart::new(3, 3).is_err() && UnitPart::new(0, 0).is_err());
}
