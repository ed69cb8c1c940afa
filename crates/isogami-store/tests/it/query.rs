//! Catalogue queries checked against a brute-force evaluation over every stored summary:
//! filters, sort orders, pages, totals, facet counts, scatter points, and refused queries.

use crate::common;

use common::synthetic::{self, Rng, SIGNATURES};
use common::{entry, run, temp};
use isogami::cell::CellDims;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use isogami_store::query::{QueryError, RangeFilter, Sort};
use isogami_store::{
    Check, DesignQuery, DesignRecord, DesignSummary, Facet, FacetValue, Measure, Origin, SortKey,
    Store, StoreError, StoreWriter,
};
use std::cmp::Ordering;
use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::OnceLock;

const N: usize = 600;

/// A database of N synthetic designs plus two user designs, and the insertion order.
fn fixture() -> &'static (PathBuf, HashMap<String, usize>) {
    static CELL: OnceLock<(PathBuf, HashMap<String, usize>)> = OnceLock::new();
    CELL.get_or_init(|| {
        // Kept for the whole process (a static is never dropped): inside cargo's per-target
        // scratch folder, not the system's temporary directory.
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("store-query-fixture");
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("db");
        let mut w = StoreWriter::open(&path, Some(run()), Check::Quick).unwrap();
        let mut order = HashMap::new();
        for u in synthetic::units(entry(), N, 7) {
            w.commit_unit(&u).unwrap();
            for d in &u.designs {
                order.insert(d.summary().spec.clone(), order.len());
            }
        }
        let e = entry();
        for k in 0..2 {
            let mut params = e.design.params.clone();
            params[0] *= 1.0 + 0.01 * f64::from(k + 1);
            let design = e.design.at_params(&params);
            let rec =
                DesignRecord::from_parts(&design, "user", Origin::User, &e.report, None).unwrap();
            w.save_user_design(&rec).unwrap();
            order.insert(rec.summary().spec.clone(), order.len());
        }
        (path, order)
    })
}

fn store() -> Store {
    Store::open_read(&fixture().0, Check::Quick).unwrap()
}

fn measure(s: &DesignSummary, m: Measure) -> Option<f64> {
    match m {
        Measure::MaxExpansion => Some(s.max_expansion),
        Measure::MinExpansion => Some(s.min_expansion),
        Measure::MaxAreaRatio => Some(s.max_area_ratio),
        Measure::MaxTileRotation => Some(s.max_tile_rotation),
        Measure::PoissonMin => s.poisson_min,
        Measure::PoissonMax => s.poisson_max,
        Measure::Steps => Some(s.steps as f64),
        Measure::TileCount => Some(f64::from(s.tile_count)),
        Measure::Kerf => Some(s.kerf),
        Measure::FiniteRawDof => s.finite_raw_dof.map(f64::from),
        Measure::FiniteCovered => s.finite_covered,
        Measure::OpenT => s.open_t,
        Measure::EndAreaRatio => s.end_area_ratio,
        Measure::ShapeTolerance => s.shape_tolerance,
        Measure::FabricationKept => s.fabrication_kept,
        Measure::Param(k) => s.params.get(usize::from(k)).copied(),
    }
}

/// The brute-force filter.
fn matches(q: &DesignQuery, s: &DesignSummary, skip: Option<Facet>) -> bool {
    let facet = |f: Facet, ok: bool| skip == Some(f) || ok;
    facet(
        Facet::Family,
        q.families.is_empty() || q.families.contains(&s.family),
    ) && facet(Facet::Cell, q.cells.is_empty() || q.cells.contains(&s.cell))
        && facet(
            Facet::TileCount,
            q.tile_counts.is_empty() || q.tile_counts.contains(&s.tile_count),
        )
        && facet(
            Facet::Behaviour,
            q.behaviours.is_empty() || q.behaviours.contains(&s.behaviour),
        )
        && facet(
            Facet::LinkageSignature,
            q.linkage_signatures.is_empty() || q.linkage_signatures.contains(&s.linkage_signature),
        )
        && facet(
            Facet::EndReason,
            q.end_reasons.is_empty() || q.end_reasons.contains(&s.end_reason),
        )
        && facet(
            Facet::Origin,
            q.origins.is_empty() || q.origins.contains(&s.origin),
        )
        && q.ranges.iter().all(|r| match measure(s, r.measure) {
            None => false,
            Some(v) => r.min.is_none_or(|m| v >= m) && r.max.is_none_or(|m| v <= m),
        })
}

/// The brute-force order: key (missing values last in both directions), then insertion
/// order in the same direction.
fn compare(
    sort: Sort,
    a: &DesignSummary,
    b: &DesignSummary,
    order: &HashMap<String, usize>,
) -> Ordering {
    fn nulls_last<T: PartialOrd>(a: Option<T>, b: Option<T>, desc: bool) -> Ordering {
        match (a, b) {
            (None, None) => Ordering::Equal,
            (None, Some(_)) => Ordering::Greater,
            (Some(_), None) => Ordering::Less,
            (Some(x), Some(y)) => {
                let o = x.partial_cmp(&y).unwrap();
                if desc {
                    o.reverse()
                } else {
                    o
                }
            }
        }
    }
    let d = sort.descending;
    let dir = |o: Ordering| if d { o.reverse() } else { o };
    let key = match sort.key {
        SortKey::Spec => dir(a.spec.cmp(&b.spec)),
        SortKey::Family => dir(a.family.number().cmp(&b.family.number())),
        SortKey::Cell => dir((a.cell.a(), a.cell.b()).cmp(&(b.cell.a(), b.cell.b()))),
        SortKey::Behaviour => nulls_last(
            a.behaviour.map(BehaviourClass::as_str),
            b.behaviour.map(BehaviourClass::as_str),
            d,
        ),
        SortKey::LinkageSignature => nulls_last(
            a.linkage_signature.as_deref(),
            b.linkage_signature.as_deref(),
            d,
        ),
        SortKey::EndReason => dir(a.end_reason.cmp(&b.end_reason)),
        SortKey::Origin => dir(a.origin.as_str().cmp(b.origin.as_str())),
        SortKey::Measure(m) => nulls_last(measure(a, m), measure(b, m), d),
    };
    key.then_with(|| dir(order[&a.spec].cmp(&order[&b.spec])))
}

/// A random query over the fixture's value ranges.
fn random_query(rng: &mut Rng, all: &[DesignSummary]) -> DesignQuery {
    let mut q = DesignQuery::default();
    let pick = |rng: &mut Rng| all[(rng.next() % all.len() as u64) as usize].clone();
    if rng.one_in(3) {
        for _ in 0..1 + rng.next() % 6 {
            q.families.push(pick(rng).family);
        }
    }
    if rng.one_in(4) {
        q.cells.push(pick(rng).cell);
    }
    if rng.one_in(5) {
        q.tile_counts.push(pick(rng).tile_count);
    }
    if rng.one_in(3) {
        q.behaviours.push(pick(rng).behaviour);
        q.behaviours.push(pick(rng).behaviour);
    }
    if rng.one_in(4) {
        q.linkage_signatures
            .push(Some(rng.pick(&SIGNATURES).to_string()));
    }
    if rng.one_in(5) {
        q.end_reasons.push(pick(rng).end_reason);
    }
    if rng.one_in(6) {
        q.origins.push(rng.pick(&[Origin::Explored, Origin::User]));
    }
    let measures: Vec<Measure> = Measure::all().collect();
    for _ in 0..rng.next() % 3 {
        let m = rng.pick(&measures);
        let values: Vec<f64> = all.iter().filter_map(|s| measure(s, m)).collect();
        if values.is_empty() {
            continue;
        }
        let a = rng.pick(&values);
        let b = rng.pick(&values);
        let (lo, hi) = (a.min(b), a.max(b));
        let (min, max) = match rng.next() % 3 {
            0 => (Some(lo), None),
            1 => (None, Some(hi)),
            _ => (Some(lo), Some(hi)),
        };
        q.ranges.push(RangeFilter {
            measure: m,
            min,
            max,
        });
    }
    let keys = [
        SortKey::Spec,
        SortKey::Family,
        SortKey::Cell,
        SortKey::Behaviour,
        SortKey::LinkageSignature,
        SortKey::EndReason,
        SortKey::Origin,
        SortKey::Measure(rng.pick(&measures)),
    ];
    if !rng.one_in(5) {
        q.sort = Some(Sort {
            key: rng.pick(&keys),
            descending: rng.one_in(2),
        });
    }
    q.buildable_first = rng.one_in(3);
    q.limit = rng.pick(&[1, 7, 50, 1000]);
    q.offset = if rng.one_in(2) { 0 } else { rng.next() % 40 };
    q
}

#[test]
fn pages_equal_a_brute_force_filter_sort_and_slice() {
    let s = store();
    let all = s.summaries().unwrap();
    assert_eq!(all.len(), N + 2);
    let order = &fixture().1;
    let mut rng = Rng::new(99);
    let mut nonempty = 0;
    for _ in 0..300 {
        let q = random_query(&mut rng, &all);
        let mut expected: Vec<&DesignSummary> =
            all.iter().filter(|d| matches(&q, d, None)).collect();
        expected.sort_by(|a, b| {
            // Buildable designs first when asked (DesignSummary::buildable, whose rule the
            // SQL repeats), then the sort.
            let lead = if q.buildable_first {
                b.buildable().cmp(&a.buildable())
            } else {
                Ordering::Equal
            };
            lead.then_with(|| {
                compare(
                    q.sort.unwrap_or(Sort {
                        key: SortKey::Spec,
                        descending: false,
                    }),
                    a,
                    b,
                    order,
                )
            })
        });
        let page = s.page(&q).unwrap();
        assert_eq!(page.total as usize, expected.len(), "{q:?}");
        let want: Vec<&DesignSummary> = expected
            .into_iter()
            .skip(q.offset as usize)
            .take(q.limit as usize)
            .collect();
        let got: Vec<&DesignSummary> = page.rows.iter().collect();
        assert_eq!(got, want, "{q:?}");
        nonempty += usize::from(!page.rows.is_empty());
    }
    assert!(nonempty > 100, "{nonempty} non-empty pages");
    let buildable = all.iter().filter(|d| d.buildable()).count();
    assert!(
        buildable > 0 && buildable < all.len(),
        "{buildable} buildable designs of {}: the order's lead is tested",
        all.len()
    );
}

#[test]
fn facet_counts_apply_every_filter_but_their_own() {
    let s = store();
    let all = s.summaries().unwrap();
    let mut rng = Rng::new(5);
    for _ in 0..60 {
        let q = random_query(&mut rng, &all);
        for (facet, counts) in s.all_facet_counts(&q).unwrap() {
            let mut expected: HashMap<String, u64> = HashMap::new();
            for d in all.iter().filter(|d| matches(&q, d, Some(facet))) {
                let v = match facet {
                    Facet::Family => FacetValue::Family(d.family),
                    Facet::Cell => FacetValue::Cell(d.cell),
                    Facet::TileCount => FacetValue::TileCount(d.tile_count),
                    Facet::Behaviour => FacetValue::Behaviour(d.behaviour),
                    Facet::LinkageSignature => {
                        FacetValue::LinkageSignature(d.linkage_signature.clone())
                    }
                    Facet::EndReason => FacetValue::EndReason(d.end_reason.clone()),
                    Facet::Origin => FacetValue::Origin(d.origin),
                };
                *expected.entry(format!("{v:?}")).or_default() += 1;
            }
            let got: HashMap<String, u64> = counts
                .iter()
                .map(|c| (format!("{:?}", c.value), c.count))
                .collect();
            assert_eq!(got, expected, "{facet:?} under {q:?}");
            assert!(counts.windows(2).all(|w| w[0].count >= w[1].count));
            assert!(counts.iter().all(|c| c.value.facet() == facet));
        }
    }
}

#[test]
fn ticking_a_facet_value_gives_as_many_designs_as_its_count() {
    let s = store();
    let mut q = DesignQuery::default();
    q.range(Measure::MaxExpansion, Some(0.4), None);
    for facet in Facet::ALL {
        for c in s.facet_counts(&q, facet).unwrap() {
            let mut ticked = q.clone();
            ticked.select(c.value.clone());
            assert_eq!(s.page(&ticked).unwrap().total, c.count, "{:?}", c.value);
        }
    }
}

#[test]
fn scatter_points_are_the_filtered_designs_that_have_both_measures() {
    let s = store();
    let all = s.summaries().unwrap();
    let order = &fixture().1;
    let q = DesignQuery {
        behaviours: vec![Some(BehaviourClass::IsotropicAuxetic), None],
        ..DesignQuery::default()
    };
    for (x, y) in [
        (Measure::MaxExpansion, Measure::MinExpansion),
        (Measure::PoissonMin, Measure::Param(2)),
        (Measure::Steps, Measure::MaxAreaRatio),
    ] {
        let mut expected: Vec<&DesignSummary> = all
            .iter()
            .filter(|d| matches(&q, d, None) && measure(d, x).is_some() && measure(d, y).is_some())
            .collect();
        expected.sort_by_key(|d| order[&d.spec]);
        let points = s.scatter(&q, x, y, 100_000).unwrap();
        assert_eq!(points.len(), expected.len());
        for (p, d) in points.iter().zip(expected) {
            assert_eq!(
                (&p.spec, Some(p.x), Some(p.y), p.family, p.behaviour),
                (&d.spec, measure(d, x), measure(d, y), d.family, d.behaviour)
            );
        }
        assert_eq!(s.scatter(&q, x, y, 3).unwrap().len(), points.len().min(3));
    }
}

#[test]
fn bad_queries_are_refused_with_a_typed_error() {
    let s = store();
    let bad = |f: &dyn Fn(&mut DesignQuery)| {
        let mut q = DesignQuery::default();
        f(&mut q);
        match s.page(&q) {
            Err(StoreError::InvalidQuery(e)) => e,
            other => panic!("{q:?}: {other:?}"),
        }
    };
    assert!(matches!(
        bad(&|q| {
            q.range(Measure::MaxExpansion, Some(f64::NAN), None);
        }),
        QueryError::NotFinite { .. }
    ));
    assert!(matches!(
        bad(&|q| {
            q.range(Measure::Kerf, Some(2.0), Some(1.0));
        }),
        QueryError::EmptyRange { .. }
    ));
    assert_eq!(bad(&|q| q.limit = 0), QueryError::Limit(0));
    assert_eq!(bad(&|q| q.limit = 1001), QueryError::Limit(1001));
    assert_eq!(bad(&|q| q.offset = u64::MAX), QueryError::Offset(u64::MAX));
    assert_eq!(
        bad(&|q| {
            q.range(Measure::Param(6), Some(0.0), None);
        }),
        QueryError::ParamSlot(6)
    );
    assert!(s
        .scatter(
            &DesignQuery::default(),
            Measure::Param(9),
            Measure::Kerf,
            10
        )
        .is_err());
}

#[test]
fn filter_values_are_data_never_sql() {
    let s = store();
    let q = DesignQuery {
        linkage_signatures: vec![Some("x') OR 1=1; DROP TABLE designs; --".into())],
        end_reasons: vec!["' OR ''='".into()],
        ..DesignQuery::default()
    };
    assert_eq!(s.page(&q).unwrap().total, 0);
    assert_eq!(s.design_count().unwrap() as usize, N + 2);
}

#[test]
fn names_read_back() {
    for m in Measure::all() {
        assert_eq!(m.to_string().parse::<Measure>().unwrap(), m);
        let json = serde_json::to_string(&m).unwrap();
        assert_eq!(serde_json::from_str::<Measure>(&json).unwrap(), m);
    }
    assert!("v6".parse::<Measure>().is_err());
    assert!("area".parse::<Measure>().is_err());
    assert_eq!(
        Facet::Family.value("IH28").unwrap(),
        FacetValue::Family(Family::from_number(28).unwrap())
    );
    assert_eq!(
        Facet::Cell.value("2x1").unwrap(),
        FacetValue::Cell(CellDims::new(2, 1).unwrap())
    );
    assert_eq!(
        Facet::Behaviour.value("none").unwrap(),
        FacetValue::Behaviour(None)
    );
    assert!(Facet::Behaviour.value("wobbly").is_err());
    assert!(Facet::Origin.value("found").is_err());
    // A query travels as JSON (the browser's URL state) and back.
    let mut q = DesignQuery::default();
    q.select(FacetValue::Behaviour(Some(
        BehaviourClass::AnisotropicAuxetic,
    )))
    .range(Measure::Param(1), Some(0.1), Some(0.9))
    .sort_by(SortKey::Measure(Measure::MaxAreaRatio), true);
    let json = serde_json::to_string(&q).unwrap();
    assert_eq!(serde_json::from_str::<DesignQuery>(&json).unwrap(), q);
    assert_eq!(
        serde_json::from_str::<DesignQuery>("{}").unwrap(),
        DesignQuery::default()
    );
}

#[test]
fn rows_are_verified_as_they_are_listed() {
    // A page reads through the row checksums: a changed value in a listed row is reported.
    let dir_guard = temp("listed");
    let dir = dir_guard.path();
    let path = dir.join("db");
    std::fs::copy(&fixture().0, &path).unwrap();
    let c = rusqlite::Connection::open(&path).unwrap();
    c.execute("UPDATE designs SET steps = steps + 1 WHERE id = 5", [])
        .unwrap();
    drop(c);
    let s = Store::open_read(&path, Check::Quick).unwrap();
    let q = DesignQuery {
        limit: 1000,
        ..DesignQuery::default()
    };
    assert!(matches!(s.page(&q), Err(StoreError::Damaged(_))));
    assert!(matches!(
        Store::open_read(&path, Check::Full),
        Err(StoreError::Damaged(_))
    ));
}

#[test]
fn every_sort_key_orders_alike_whether_an_index_is_walked_or_rows_sorted() {
    let s = store();
    let all = s.summaries().unwrap();
    let order = &fixture().1;
    let mut keys = vec![
        SortKey::Spec,
        SortKey::Family,
        SortKey::Cell,
        SortKey::Behaviour,
        SortKey::LinkageSignature,
        SortKey::EndReason,
        SortKey::Origin,
    ];
    keys.extend(Measure::all().map(SortKey::Measure));
    for key in keys {
        for descending in [false, true] {
            // Unfiltered small pages walk the key's index (if it has one); a selective filter
            // or a deep page sorts the matching rows.
            let mut walk = DesignQuery::default();
            walk.sort_by(key, descending);
            walk.limit = 7;
            walk.offset = 3;
            let mut deep = walk.clone();
            deep.offset = 590;
            let mut selective = walk.clone();
            selective.offset = 0;
            selective.range(Measure::MaxExpansion, Some(1.3), None);
            for q in [walk, deep, selective] {
                let sort = q.sort.unwrap();
                let mut expected: Vec<&DesignSummary> =
                    all.iter().filter(|d| matches(&q, d, None)).collect();
                expected.sort_by(|a, b| compare(sort, a, b, order));
                let want: Vec<&DesignSummary> = expected
                    .into_iter()
                    .skip(q.offset as usize)
                    .take(q.limit as usize)
                    .collect();
                let page = s.page(&q).unwrap();
                assert!(!want.is_empty());
                assert_eq!(page.rows.iter().collect::<Vec<_>>(), want, "{q:?}");
            }
        }
    }
}

#[test]
fn finite_sheet_columns_filter_and_sort_with_missing_values_last() {
    let s = store();
    let all = s.summaries().unwrap();
    let mut q = DesignQuery::default();
    q.range(Measure::FiniteRawDof, Some(1.0), Some(1.0))
        .sort_by(SortKey::Measure(Measure::FiniteCovered), true);
    q.limit = 1000;
    let page = s.page(&q).unwrap();
    let want = all.iter().filter(|d| d.finite_raw_dof == Some(1)).count();
    assert!(want > 10 && want < all.len(), "{want}");
    assert_eq!(page.total as usize, want);
    let covered: Vec<Option<f64>> = page.rows.iter().map(|r| r.finite_covered).collect();
    let known = covered.iter().take_while(|c| c.is_some()).count();
    assert!(known > 0 && known < covered.len(), "both kinds on the page");
    assert!(covered[known..].iter().all(Option::is_none), "missing last");
    assert!(
        covered[..known].windows(2).all(|w| w[0] >= w[1]),
        "descending"
    );
    // Names as the URL and Python give them.
    assert_eq!(
        "finite_covered".parse::<Measure>().unwrap(),
        Measure::FiniteCovered
    );
    assert_eq!(
        "finite_raw_dof".parse::<SortKey>().unwrap(),
        SortKey::Measure(Measure::FiniteRawDof)
    );
    // User designs have neither figure and never pass a range on them.
    let mut users = DesignQuery::default();
    users.select(FacetValue::Origin(Origin::User));
    users.range(Measure::FiniteCovered, Some(0.0), None);
    assert_eq!(s.page(&users).unwrap().total, 0);
}
