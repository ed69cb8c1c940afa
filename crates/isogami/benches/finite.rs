//! Finite sheets of 10×10 cells (issue 22's goals: mobility ≤ 50 ms, completion ≤ 200 ms,
//! finite deployment of the completed sheet ≤ 1 s).
//!
//! `cargo bench -p isogami --bench finite`. Per design: the raw region's free-boundary
//! mobility at an opened state (sparse kernel, floppy modes), its completion to one DOF, and
//! the completed sheet's deployment with contact among its own tiles plus the DOF checks
//! along the way. The periodic deployment that finds the opened state is made once, outside
//! the timings.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use isogami::api::deploy_path;
use isogami::deploy::{deploy_with, DeploySettings};
use isogami::finite::{
    check_states, complete, periodic_velocity, sheet_mobility, sheet_pairs, Context, FiniteSheet,
    Region,
};
use isogami::kinematics::Mechanism;
use isogami::mobility::analyze;
use isogami::topology::Design;
use std::hint::black_box;

const DESIGNS: [(&str, &str); 3] = [
    ("rotating-squares", "rotating-squares"),
    ("IH44-1x2", "IH44:0.5,0.027564102564:1x2:-aaabbaa"),
    (
        "IH9-1x2",
        "IH9:0.04739750492,0.35,0.225335752741:1x2:--aaabb--aa-",
    ),
];

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("finite-10x10");
    group.sample_size(10);
    let settings = DeploySettings::default();
    for (name, spec) in DESIGNS {
        let design = Design::resolve(spec).unwrap();
        let cell = design.cell().unwrap();
        let mech = Mechanism::new(&cell, &design.joints).unwrap();
        let path = deploy_path(&design, &settings, &mut |_| true).unwrap();
        let traj = &path.trajectory;
        let k = (1..traj.steps.len())
            .min_by(|&a, &b| (traj.t(a) - 0.3).abs().total_cmp(&(traj.t(b) - 0.3).abs()))
            .unwrap();
        let q = traj.steps[k].q.clone();
        let motion = analyze(&mech, &q, settings.mobility)
            .unwrap()
            .motion
            .unwrap()
            .vector;
        let region = Region::Cells { rows: 10, cols: 10 };
        let raw = FiniteSheet::new(&cell, &mech, region.tiles(&mech, 20.0).unwrap());
        let ctx = Context {
            cell: &cell,
            mech: &mech,
            q: &q,
            motion: &motion,
            // IH9 keeps 49.2 % of a 10×10 region: below the default 50 %, still a completion.
            min_covered: 0.0,
            keep_going: isogami::stop::NEVER,
        };
        group.bench_with_input(BenchmarkId::new("mobility", name), &raw, |b, raw| {
            b.iter(|| {
                let poses = raw.poses(&mech, &q);
                let periodic = periodic_velocity(raw, &mech, &motion);
                black_box(sheet_mobility(
                    raw,
                    &mech,
                    &poses,
                    Some(&periodic),
                    isogami::stop::NEVER,
                ))
            })
        });
        group.bench_with_input(BenchmarkId::new("completion", name), &raw, |b, raw| {
            b.iter(|| black_box(complete(&ctx, raw).unwrap()))
        });
        let sheet = complete(&ctx, &raw).unwrap().sheet;
        group.bench_with_input(BenchmarkId::new("deployment", name), &sheet, |b, sheet| {
            b.iter(|| {
                let contact = path
                    .contact
                    .clone()
                    .restricted_to(sheet_pairs(sheet).iter().copied());
                let traj = deploy_with(&mech, &contact, &settings, &mut |_| true).unwrap();
                black_box(check_states(sheet, &mech, &traj, 8, settings.mobility).unwrap())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
