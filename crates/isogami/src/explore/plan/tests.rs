//! Plans: shards, parts, counts and their text forms.

use super::*;
use std::collections::HashSet;

fn fam(name: &str) -> Family {
    name.parse().unwrap()
}

#[test]
fn shards_partition_the_plan_in_order() {
    let families = [fam("IH1"), fam("IH28"), fam("IH90")];
    let whole = ExplorePlan::new(&families, None, &TopologyOptions::default(), None).unwrap();
    assert!(whole.all.len() > 5, "{} units", whole.all.len());
    assert_eq!(whole.units(), whole.all);
    let ids: HashSet<String> = whole.all.iter().map(WorkUnit::id).collect();
    assert_eq!(ids.len(), whole.all.len(), "unit ids are unique");
    let n = 4;
    let mut seen = Vec::new();
    for i in 0..n {
        let shard = Shard::new(i, n).unwrap();
        let plan =
            ExplorePlan::new(&families, None, &TopologyOptions::default(), Some(shard)).unwrap();
        assert_eq!(plan.all, whole.all, "every shard knows the whole plan");
        let units = plan.units();
        // Positions i, i + n, …: balanced to within one unit.
        assert!(units.len().abs_diff(whole.all.len() / n) <= 1);
        for (k, u) in units.iter().enumerate() {
            assert_eq!(*u, whole.all[i + k * n]);
        }
        seen.extend(units);
    }
    assert_eq!(seen.len(), whole.all.len());
    let seen: HashSet<String> = seen.iter().map(WorkUnit::id).collect();
    assert_eq!(seen, ids);
}

#[test]
fn cells_filter_keeps_only_the_named_cells() {
    let one = CellDims::new(1, 1).unwrap();
    let plan = ExplorePlan::new(
        &[fam("IH28"), fam("IH1")],
        Some(&[one]),
        &TopologyOptions::default(),
        None,
    )
    .unwrap();
    let ids: Vec<String> = plan.all.iter().map(WorkUnit::id).collect();
    assert_eq!(ids, ["IH28/1x1", "IH1/1x1"], "families in the order given");
}

#[test]
fn requested_cells_over_the_cap_are_an_error_naming_the_cap() {
    let three = CellDims::new(3, 3).unwrap();
    let options = TopologyOptions::default();
    let e = ExplorePlan::new(&[fam("IH76")], Some(&[three]), &options, None).unwrap_err();
    match &e {
        ExploreError::CellsOverCap {
            edges,
            max_edges,
            others,
            needed,
            ..
        } => assert_eq!((*edges, *max_edges, *others, *needed), (18, 16, 0, 18)),
        other => panic!("{other:?}"),
    }
    let text = e.to_string();
    assert!(
        text.contains("IH76/3x3") && text.contains("max_edges = 16"),
        "{text}"
    );
    // Raising the cap takes the cell.
    let wide = TopologyOptions {
        max_edges: 18,
        ..options
    };
    let plan = ExplorePlan::new(&[fam("IH76")], Some(&[three]), &wide, None).unwrap();
    assert_eq!(plan.all.len(), 1);
    // Several families: every pair over the cap is counted, the largest names the cap.
    let one = CellDims::new(1, 1).unwrap();
    let e = ExplorePlan::new(
        &[fam("IH1"), fam("IH76"), fam("IH77")],
        Some(&[one, three]),
        &options,
        None,
    )
    .unwrap_err();
    let ExploreError::CellsOverCap {
        family,
        others,
        needed,
        ..
    } = e
    else {
        panic!("{e:?}");
    };
    assert_eq!(family, fam("IH1"), "the first pair in plan order");
    assert!(others >= 2, "IH76/3x3 and IH77's cells");
    assert!(needed > 18, "IH1 3x3 has more than 18 edges: {needed}");
}

#[test]
fn ih77_minimal_cell_is_planned_only_under_a_raised_cap() {
    let f = fam("IH77");
    let default = ExplorePlan::new(&[f], None, &TopologyOptions::default(), None).unwrap();
    assert!(default.all.is_empty(), "18 edges: nothing at cap 16");
    let one = CellDims::new(1, 1).unwrap();
    assert!(matches!(
        ExplorePlan::new(&[f], Some(&[one]), &TopologyOptions::default(), None),
        Err(ExploreError::CellsOverCap { edges: 18, .. })
    ));
    let cap20 = TopologyOptions {
        max_edges: 20,
        ..TopologyOptions::default()
    };
    let plan = ExplorePlan::new(&[f], None, &cap20, None).unwrap();
    assert_eq!(
        plan.all.first().map(WorkUnit::id).as_deref(),
        Some("IH77/1x1")
    );
}

#[test]
fn requested_cells_beyond_max_dims_are_an_error() {
    let quick = TopologyOptions {
        max_dims: 1,
        ..TopologyOptions::default()
    };
    let two = CellDims::new(2, 1).unwrap();
    let e = ExplorePlan::new(&[fam("IH90")], Some(&[two]), &quick, None).unwrap_err();
    assert_eq!(
        e,
        ExploreError::CellOverDims {
            dims: two,
            max_dims: 1
        }
    );
    assert!(e.to_string().contains("max_dims"), "{e}");
}

#[test]
fn longest_first_orders_by_expected_cost_and_keeps_every_unit() {
    let families = [fam("IH21"), fam("IH22"), fam("IH76"), fam("IH90")];
    let plan = ExplorePlan::new(&families, None, &TopologyOptions::default(), None).unwrap();
    let order: Vec<WorkUnit> = WorkItem::longest_first(&plan.items())
        .into_iter()
        .map(|i| i.unit)
        .collect();
    let mut a: Vec<String> = order.iter().map(WorkUnit::id).collect();
    let mut b: Vec<String> = plan.all.iter().map(WorkUnit::id).collect();
    a.sort();
    b.sort();
    assert_eq!(a, b, "a permutation of the plan");
    let costs: Vec<f64> = order.iter().map(WorkUnit::expected_cost).collect();
    assert!(costs.windows(2).all(|w| w[0] >= w[1]), "{costs:?}");
    // The slowest units of the default run (low-symmetry hexagon cells deploying
    // thousands of topologies) come before every rotating-squares cell.
    let pos = |id: &str| order.iter().position(|u| u.id() == id).unwrap();
    assert!(pos("IH21/1x1") < pos("IH76/2x4") && pos("IH22/3x1") < pos("IH76/2x4"));
    // 3^m / |G|: IH21's minimal cell has 15 edges and 6 symmetries.
    let ih21 = WorkUnit {
        family: fam("IH21"),
        dims: CellDims::new(1, 1).unwrap(),
    };
    assert_eq!(ih21.expected_cost(), 3f64.powi(15) / 6.0);
}

#[test]
fn a_unit_is_never_split_into_more_parts_than_it_has_masks() {
    use super::super::pipeline::enumerate_topology_part;
    let options = TopologyOptions::default();
    let one = CellDims::new(1, 1).unwrap();
    let families = [fam("IH90"), fam("IH28")];
    let plan = ExplorePlan::new(&families, Some(&[one]), &options, None)
        .unwrap()
        .split(MAX_PARTS)
        .unwrap();
    let items = plan.all_items();
    let mut total = 0;
    for unit in &plan.all {
        let masks = expanded_mask_count(unit.family, unit.dims);
        let whole =
            enumerate_topology_part(unit.family, unit.dims, &options, UnitPart::WHOLE).unwrap();
        assert_eq!(masks as u64, whole.masks_expanded, "{unit}");
        assert!(masks < MAX_PARTS, "{unit}: {masks} masks");
        assert_eq!(plan.parts_of(unit), masks.max(1), "{unit}");
        total += plan.parts_of(unit);
        // Every part has work: at least one mask, and the parts' masks add up.
        let mut sum = 0;
        for item in items.iter().filter(|i| i.unit == *unit) {
            assert_eq!(item.part.count(), plan.parts_of(unit));
            let r = enumerate_topology_part(unit.family, unit.dims, &options, item.part).unwrap();
            assert!(r.masks_expanded >= 1, "{} is empty", item.id());
            sum += r.masks_expanded;
        }
        assert_eq!(sum, whole.masks_expanded, "{unit}");
    }
    assert_eq!(items.len(), total);
    // Fewer parts than masks: the count asked for.
    let two = ExplorePlan::new(&families, Some(&[one]), &options, None)
        .unwrap()
        .split(2)
        .unwrap();
    let mut total = 0;
    for u in &two.all {
        let masks = expanded_mask_count(u.family, u.dims);
        assert_eq!(two.parts_of(u), masks.clamp(1, 2), "{u}");
        total += two.parts_of(u);
    }
    assert!(two.all.iter().any(|u| two.parts_of(u) == 2));
    assert_eq!(two.all_items().len(), total);
}

#[test]
fn shard_text_round_trips_and_bad_shards_are_refused() {
    let s: Shard = " 2 / 5".parse().unwrap();
    assert_eq!((s.index(), s.count()), (2, 5));
    assert_eq!(s.to_string().parse::<Shard>().unwrap(), s);
    for bad in ["3/3", "1/0", "x", "1:2", "-1/2", "0/100001", ""] {
        let e = bad.parse::<Shard>().unwrap_err();
        assert!(e.to_string().contains(&format!("'{bad}'")), "{e}");
    }
    assert!(Shard::new(0, MAX_SHARDS).is_ok());
    assert!(Shard::new(4, 4).is_err());
}
