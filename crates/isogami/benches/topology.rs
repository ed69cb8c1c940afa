//! Topology enumeration cost (paper §4.1; the paper reports ~20 ms for its reduced-topology
//! filter).
//!
//! `cargo bench -p isogami --bench topology`. Two groups: the four cheap checks over all 2^16
//! joint masks of 16-edge cells (adjacency precomputation included), and the whole
//! `enumerate_topologies` (reduced checks, expansion with certified mobility, separation,
//! deduplication) on a few cells.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use isogami::cell::{CellDims, UnitCell};
use isogami::explore::{enumerate_topologies, ReducedGraph, TopologyOptions};
use isogami::tiling::{Family, Tiling};
use std::hint::black_box;
use std::time::Duration;

fn cell(n: u32, a: u8, b: u8) -> UnitCell {
    let f = Family::from_number(n).unwrap();
    UnitCell::new(&Tiling::default_for(f), CellDims::new(a, b).unwrap()).unwrap()
}

fn reduced(c: &mut Criterion) {
    let mut group = c.benchmark_group("reduced-filter");
    for (n, a, b) in [(56, 1, 1), (76, 4, 2), (41, 2, 4)] {
        let cell = cell(n, a, b);
        let name = format!("IH{n}-{a}x{b}/m{}", cell.edges.len());
        group.bench_with_input(BenchmarkId::new("all-masks", &name), &cell, |bch, cell| {
            bch.iter(|| {
                let g = ReducedGraph::new(cell).unwrap();
                black_box(g.enumerate().after_triangles)
            })
        });
    }
    group.finish();
}

fn full(c: &mut Criterion) {
    let mut group = c.benchmark_group("enumerate-topologies");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    for (n, a, b) in [(76, 2, 2), (28, 1, 1), (30, 1, 1), (21, 1, 1)] {
        let f = Family::from_number(n).unwrap();
        let dims = CellDims::new(a, b).unwrap();
        let m = cell(n, a, b).edges.len();
        let name = format!("IH{n}-{a}x{b}/m{m}");
        group.bench_with_input(BenchmarkId::new("full", &name), &dims, |bch, &dims| {
            bch.iter(|| {
                black_box(
                    enumerate_topologies(f, dims, &TopologyOptions::default())
                        .unwrap()
                        .unique,
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, reduced, full);
criterion_main!(benches);
