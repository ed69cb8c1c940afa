//! Catalogue queries on 10^4 realistic designs.
//!
//! `cargo bench -p isogami-store`. The database holds 10,000 designs, each with a real
//! deployment report (40 frames) and linkage analysis of an explored design, re-labelled with
//! families, cells, joints and measures spread over the exploration's ranges (about 0.4 GB,
//! built once into the temporary directory and reused). Query shapes:
//!
//! - `page/no-filter`: the first page of 50 in spec order, with the total count;
//! - `page/one-facet`: behaviour = isotropic auxetic, sorted by largest expansion, descending;
//! - `page/two-ranges-facet-sort`: max expansion in [0.3, 1.0], area ratio ≥ 1.5, one of
//!   two linkage signatures, sorted by tile rotation descending, third page;
//! - `page/param-range-family`: one family, v0 in a range, sorted by v0;
//! - `page/selective-range-sort`: max expansion ≥ 1.45 (a few % of designs), sorted by area
//!   ratio descending;
//! - `page/no-filter-nullable-sort-offset-5000`: sorted by the smallest Poisson-like ratio
//!   (no index: missing values last), page at offset 5000;
//! - `facets/all-under-range`: counts of all seven facets under a range filter;
//! - `scatter/all`: two measures of every design;
//! - `design/by-spec`: one design with its report and linkages parsed into the library types;
//! - `open/quick` and `open/full`: opening with quick_check, and with integrity_check, every
//!   row's checksum and every document parsed.

#[path = "../tests/it/common/synthetic.rs"]
#[allow(dead_code)]
mod synthetic;

use criterion::{criterion_group, criterion_main, Criterion};
use isogami::catalog::{run_unit, CatalogSettings};
use isogami::cell::CellDims;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use isogami_store::{Check, DesignQuery, Facet, Measure, RunInfo, SortKey, Store, StoreWriter};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Duration;

const DESIGNS: usize = 10_000;

/// Builds the database once (about a minute) and reuses it afterwards.
fn database() -> PathBuf {
    let path = std::env::temp_dir().join(format!(
        "isogami-store-bench-v{}-{DESIGNS}.db",
        isogami_store::SCHEMA_VERSION
    ));
    if Store::open_read(&path, Check::Quick)
        .and_then(|s| s.design_count())
        .is_ok_and(|n| n as usize == DESIGNS)
    {
        return path;
    }
    let _ = std::fs::remove_file(&path);
    let mut settings = CatalogSettings::default();
    settings.topology.max_dims = 1;
    settings.topology.max_edges = 12;
    settings.samples = 4;
    let base = run_unit(
        Family::from_number(83).unwrap(),
        CellDims::MINIMAL,
        &settings,
    )
    .unwrap()
    .entries
    .remove(0);
    let fingerprint = settings.fingerprint();
    let run = RunInfo {
        tool_version: "bench",
        settings: &fingerprint,
    };
    let mut w = StoreWriter::open(&path, Some(run), Check::Quick).unwrap();
    for u in synthetic::units(&base, DESIGNS, 2024) {
        w.commit_unit(&u).unwrap();
    }
    path
}

fn queries() -> Vec<(&'static str, DesignQuery)> {
    let mut one_facet = DesignQuery::default();
    one_facet
        .select(isogami_store::FacetValue::Behaviour(Some(
            BehaviourClass::IsotropicAuxetic,
        )))
        .sort_by(SortKey::Measure(Measure::MaxExpansion), true);
    let mut combined = DesignQuery::default();
    combined
        .range(Measure::MaxExpansion, Some(0.3), Some(1.0))
        .range(Measure::MaxAreaRatio, Some(1.5), None)
        .sort_by(SortKey::Measure(Measure::MaxTileRotation), true);
    combined.linkage_signatures = vec![Some("2×4-bar".into()), Some("1×6-bar".into())];
    combined.offset = 100;
    let mut param = DesignQuery::default();
    param
        .range(Measure::Param(0), Some(0.1), Some(0.5))
        .sort_by(SortKey::Measure(Measure::Param(0)), false);
    param.families = vec![Family::from_number(28).unwrap()];
    let mut selective = DesignQuery::default();
    selective
        .range(Measure::MaxExpansion, Some(1.45), None)
        .sort_by(SortKey::Measure(Measure::MaxAreaRatio), true);
    let mut deep = DesignQuery::default();
    deep.sort_by(SortKey::Measure(Measure::PoissonMin), false);
    deep.offset = 5000;
    vec![
        ("page/no-filter", DesignQuery::default()),
        ("page/selective-range-sort", selective),
        ("page/no-filter-nullable-sort-offset-5000", deep),
        ("page/one-facet", one_facet),
        ("page/two-ranges-facet-sort", combined),
        ("page/param-range-family", param),
    ]
}

fn bench(c: &mut Criterion) {
    let path = database();
    let store = Store::open_read(&path, Check::Quick).unwrap();
    for (name, q) in queries() {
        let page = store.page(&q).unwrap();
        eprintln!("{name}: {} rows of {}", page.rows.len(), page.total);
        c.bench_function(name, |b| {
            b.iter(|| black_box(store.page(black_box(&q)).unwrap()))
        });
    }
    let mut ranged = DesignQuery::default();
    ranged.range(Measure::MaxExpansion, Some(0.5), None);
    c.bench_function("facets/all-under-range", |b| {
        b.iter(|| black_box(store.all_facet_counts(&ranged).unwrap()))
    });
    let _ = Facet::ALL;
    c.bench_function("scatter/all", |b| {
        b.iter(|| {
            black_box(
                store
                    .scatter(
                        &DesignQuery::default(),
                        Measure::MaxExpansion,
                        Measure::PoissonMin,
                        100_000,
                    )
                    .unwrap(),
            )
        })
    });
    let spec = store.page(&DesignQuery::default()).unwrap().rows[17]
        .spec
        .clone();
    c.bench_function("design/by-spec", |b| {
        b.iter(|| black_box(store.design(&spec).unwrap().unwrap()))
    });
    let mut slow = c.benchmark_group("open");
    slow.sample_size(10)
        .measurement_time(Duration::from_secs(20));
    slow.bench_function("quick", |b| {
        b.iter(|| black_box(Store::open_read(&path, Check::Quick).unwrap()))
    });
    slow.bench_function("full", |b| {
        b.iter(|| black_box(Store::open_read(&path, Check::Full).unwrap()))
    });
    slow.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
