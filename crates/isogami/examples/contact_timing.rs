//! Rough timings of the contact model's queries (medians over many calls), on rotating
//! squares (4 tiles) and on an IH28 2×1 cell (8 tiles), with and without active barrier
//! terms. Run with `cargo run --release --example contact_timing`.

use isogami::cell::{CellDims, UnitCell};
use isogami::contact::{ContactModel, ContactSettings, HessianProjection};
use isogami::kinematics::Mechanism;
use isogami::math::{DMat, DVec, Real};
use isogami::mobility::analyze;
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice};
use std::hint::black_box;
use std::time::Instant;

const REPEATS: usize = 2000;

/// Median time of one call of `f`, in microseconds.
fn median_us(mut f: impl FnMut()) -> Real {
    let mut times: Vec<Real> = (0..REPEATS)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(Real::total_cmp);
    times[REPEATS / 2]
}

fn report(name: &str, mech: &Mechanism, model: &ContactModel, q: &DVec, dq: &DVec) {
    let n = mech.layout.len();
    let (mut g, mut h) = (DVec::zeros(n), DMat::zeros(n, n));
    let derivs = median_us(|| {
        g.fill(0.0);
        h.fill(0.0);
        model.add_gradient_hessian(mech, q, &mut g, &mut h);
        black_box((&g, &h));
    });
    let per_pair = median_us(|| {
        g.fill(0.0);
        h.fill(0.0);
        model.add_derivatives(mech, q, &mut g, &mut h, HessianProjection::PerPairPsd);
        black_box((&g, &h));
    });
    let energy = median_us(|| {
        black_box(model.energy(mech, q));
    });
    let clearance = median_us(|| {
        black_box(model.min_clearance(mech, q));
    });
    let overlap = median_us(|| {
        black_box(model.overlapping_pair(mech, q));
    });
    let step = median_us(|| {
        black_box(model.max_safe_step(mech, q, dq));
    });
    println!(
        "{name:<38} clearance {:>8.2e}  E {:>8.2e}  α {:>5.3} | add_gradient_hessian {derivs:>5.1} µs \
         (per-pair PSD {per_pair:>5.1} µs)  \
         energy {energy:>5.1} µs  min_clearance {clearance:>5.1} µs  overlapping_pair \
         {overlap:>5.1} µs  max_safe_step {step:>6.1} µs",
        model.min_clearance(mech, q),
        model.energy(mech, q),
        model.max_safe_step(mech, q, dq),
    );
}

/// xorshift, so the run is reproducible.
fn noise(seed: &mut u64) -> Real {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as Real / (1u64 << 53) as Real * 2.0 - 1.0
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let settings = ContactSettings::default();

    let d = Design::resolve("rotating-squares")?;
    let mech = Mechanism::new(&d.cell()?, &d.joints)?;
    let model = ContactModel::new(&mech, settings)?;
    println!(
        "rotating squares: {} pairs within d̂ at rest",
        model
            .pairs_at(&mech, &mech.rest, settings.dhat)
            .map_or(0, |p| p.len())
    );
    let v = analyze(&mech, &mech.rest, Default::default())?
        .motion
        .ok_or("rotating squares has no motion")?
        .vector;
    report(
        "rotating squares, closed",
        &mech,
        &model,
        &mech.rest,
        &(&v * 0.1),
    );
    // Turned the closing way until the clearance is about d̂/2.
    let (mut lo, mut hi) = (0.0, 0.1);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if model.min_clearance(&mech, &(&mech.rest - &v * mid)) > 0.5 * settings.dhat {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let q = &mech.rest - &v * lo;
    report(
        "rotating squares, closing (active)",
        &mech,
        &model,
        &q,
        &(-&v * 0.1),
    );

    let cell = UnitCell::new(
        &Tiling::default_for(Family::from_number(28)?),
        CellDims::new(2, 1)?,
    )?;
    let mech = Mechanism::new(&cell, &vec![JointChoice::None; cell.edges.len()])?;
    let model = ContactModel::new(&mech, settings)?;
    let build = median_us(|| {
        black_box(ContactModel::new(&mech, settings).ok());
    });
    println!(
        "IH28 2x1: {} pairs within d̂ at rest, ContactModel::new {build:.1} µs",
        model
            .pairs_at(&mech, &mech.rest, settings.dhat)
            .map_or(0, |p| p.len())
    );
    let n = mech.layout.len();
    let mut seed = 0x2545_F491_4F6C_DD1D_u64;
    let dq = DVec::from_fn(n, |_, _| 0.05 * noise(&mut seed));
    report(
        &format!("IH28 2x1 ({} tiles), closed", mech.layout.tiles),
        &mech,
        &model,
        &mech.rest,
        &dq,
    );
    // Random small turns and shifts until some pairs are inside d̂ without overlap.
    let q = loop {
        let q = &mech.rest + DVec::from_fn(n, |_, _| 0.004 * noise(&mut seed));
        let c = model.min_clearance(&mech, &q);
        if c > 0.0 && c < settings.dhat && model.energy(&mech, &q).is_finite() {
            break q;
        }
    };
    report("IH28 2x1, perturbed (active)", &mech, &model, &q, &dq);
    Ok(())
}
