//! Deployment cost: a whole rigid-modes trajectory per design, on rotating squares and on
//! designs from eleven families (`SAMPLE_OPENING_DESIGNS`).
//!
//! `cargo bench -p isogami --bench deploy`. Time per frame = trajectory time / accepted
//! states (printed once per design before measuring). Group `deploy/trajectory` times the
//! solver alone; group `deploy/api` the library entry point `api::deploy` with its default
//! request (cell, mechanism, contact model, trajectory, 60 checked frames, report): the same
//! work as one `isogami.deploy(design)` call from Python, which
//! `crates/isogami-py/bench/deploy_overhead.py` times to give the Python overhead.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use isogami::api::{self, DeployRequest};
use isogami::deploy::{deploy, DeploySettings};
use isogami::kinematics::Mechanism;
use isogami::topology::{Design, SAMPLE_OPENING_DESIGNS};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("deploy");
    group.sample_size(20);
    for spec in SAMPLE_OPENING_DESIGNS {
        let d = Design::resolve(spec).unwrap();
        let mech = Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap();
        let settings = DeploySettings::default();
        let traj = deploy(&mech, &settings, &mut |_| true).unwrap();
        eprintln!(
            "{spec}: {} states, {} attempts, {}",
            traj.steps.len(),
            traj.attempts,
            traj.end_reason
        );
        let name = format!("{}-{}", d.family, d.joints.len());
        group.bench_with_input(BenchmarkId::new("trajectory", &name), &mech, |b, mech| {
            b.iter(|| black_box(deploy(mech, &settings, &mut |_| true).unwrap().steps.len()))
        });
        let request = DeployRequest::default();
        group.bench_with_input(BenchmarkId::new("api", &name), &d, |b, d| {
            b.iter(|| {
                black_box(
                    api::deploy(d, &request, &mut |_| true)
                        .unwrap()
                        .frames
                        .len(),
                )
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
