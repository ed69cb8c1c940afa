//! Mobility analysis cost per design, on cells with 8 to 16 unique edges.
//!
//! `cargo bench -p isogami --bench analyze`. Two measurements per design: the analysis alone
//! (mechanism assembly + Jacobian + eigen-decomposition, what topology enumeration pays per
//! joint configuration) and the whole path from a spec string (tiling, cell, edges, analysis).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use isogami::kinematics::Mechanism;
use isogami::mobility::{analyze, MobilitySettings};
use isogami::topology::{Design, JointChoice};
use std::hint::black_box;

/// Designs with 8, 10, 12, 15 and 16 unique edges; joints alternate a/b with every third edge
/// cut, a fixed pattern so that runs compare.
fn designs() -> Vec<(String, Design)> {
    let mut out = vec![(
        "rotating-squares/m8".to_string(),
        Design::resolve("rotating-squares").unwrap(),
    )];
    for (fam, dims) in [
        ("IH28", "1x1"),
        ("IH5", "1x1"),
        ("IH21", "1x1"),
        ("IH56", "1x1"),
        ("IH41", "2x4"),
    ] {
        let d = Design::resolve(&format!("{fam}:default:{dims}:-")).unwrap();
        let m = isogami::cell::UnitCell::new(&d.tiling().unwrap(), d.dims)
            .unwrap()
            .edges
            .len();
        let joints = (0..m)
            .map(|k| match k % 3 {
                0 => JointChoice::A,
                1 => JointChoice::B,
                _ => JointChoice::None,
            })
            .collect();
        out.push((format!("{fam}-{dims}/m{m}"), Design { joints, ..d }));
    }
    out
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("analyze");
    for (name, design) in designs() {
        let cell = design.cell().unwrap();
        group.bench_with_input(BenchmarkId::new("mobility", &name), &cell, |b, cell| {
            b.iter(|| {
                let m = Mechanism::new(cell, &design.joints).unwrap();
                black_box(
                    analyze(&m, &m.rest, MobilitySettings::default())
                        .unwrap()
                        .dof,
                )
            })
        });
        let spec = design.to_string();
        group.bench_with_input(BenchmarkId::new("from-spec", &name), &spec, |b, spec| {
            b.iter(|| {
                let d = Design::resolve(spec).unwrap();
                let cell = d.cell().unwrap();
                let m = Mechanism::new(&cell, &d.joints).unwrap();
                black_box(
                    analyze(&m, &m.rest, MobilitySettings::default())
                        .unwrap()
                        .dof,
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
