//! Contact: kerf-inset collision polygons, the log barrier and its derivatives, clearance,
//! the exact overlap test and conservative advancement.

use isogami::cell::{CellDims, UnitCell};
use isogami::contact::{
    ContactError, ContactModel, ContactSettings, HessianProjection, Overlap, KEEP_FRACTION,
};
use isogami::geometry::{interiors_overlap, point_in_polygon_strict, point_segment_distance};
use isogami::kinematics::{Mechanism, StateLayout};
use isogami::math::{symmetric_eigen, vec2, DMat, DVec, Real, Vec2};
use isogami::mobility::analyze;
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice};
use std::collections::HashSet;

/// A small deterministic generator (xorshift*), so failures reproduce.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn unit(&mut self) -> Real {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as Real / (1u64 << 53) as Real
    }
    fn sym(&mut self) -> Real {
        2.0 * self.unit() - 1.0
    }
    fn vector(&mut self, n: usize, size: Real) -> DVec {
        DVec::from_fn(n, |_, _| size * self.sym())
    }
}

/// Rotating squares and its opening motion (unit vector).
fn rotating_squares() -> (Mechanism, DVec) {
    let d = Design::resolve("rotating-squares").unwrap();
    let cell = d.cell().unwrap();
    let mech = Mechanism::new(&cell, &d.joints).unwrap();
    let v = analyze(&mech, &mech.rest, Default::default())
        .unwrap()
        .motion
        .unwrap()
        .vector;
    (mech, v)
}

fn unjointed(family: Family, dims: CellDims) -> Mechanism {
    let cell = UnitCell::new(&Tiling::default_for(family), dims).unwrap();
    Mechanism::new(&cell, &vec![JointChoice::None; cell.edges.len()]).unwrap()
}

/// The state s along q0 + s·dir where the clearance first drops to `target` (bisection;
/// the clearance must start above it and be below it at s = `far`).
fn where_clearance_is(
    model: &ContactModel,
    mech: &Mechanism,
    q0: &DVec,
    dir: &DVec,
    target: Real,
    far: Real,
) -> Real {
    let (mut lo, mut hi) = (0.0, far);
    assert!(model.min_clearance(mech, &(q0 + dir * hi)) < target);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if model.min_clearance(mech, &(q0 + dir * mid)) > target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// States with active barrier terms (0 < clearance < d̂), each with its mechanism.
fn active_states() -> Vec<(&'static str, Mechanism, DVec)> {
    let settings = ContactSettings::default();
    let mut out = Vec::new();
    let mut rng = Rng::new(7);
    // Rotating squares turned the closing way until the jointed edges nearly meet, then
    // perturbed in every coordinate (tiles and lattice).
    let (mech, v) = rotating_squares();
    let model = ContactModel::new(&mech, settings).unwrap();
    for (k, frac) in [0.3, 0.6, 0.9].into_iter().enumerate() {
        let s = where_clearance_is(&model, &mech, &mech.rest, &-&v, frac * settings.dhat, 0.5);
        let q = &mech.rest - &v * s + rng.vector(mech.layout.len(), 1e-5 * (k as Real + 1.0));
        out.push(("rotating squares, closing", mech.clone(), q));
    }
    // One square per cell: the lattice squeezed so a tile meets its own translates (pairs of
    // a tile with itself across cells, k_u and k_w ≠ 0), slightly turned.
    let mech = unjointed(Family::from_number(76).unwrap(), CellDims::MINIMAL);
    assert_eq!(mech.layout.tiles, 1);
    let mut q = mech.rest.clone();
    let l = mech.layout;
    q[2] = 2e-3;
    let squeeze = 1.0 - (settings.kerf - 0.4 * settings.dhat) / q.rows(l.u(), 2).norm();
    for k in l.u()..l.len() {
        q[k] *= squeeze;
    }
    q += rng.vector(l.len(), 1e-5);
    out.push(("squeezed square lattice", mech, q));
    // Two tiles of IH28 pushed together: tile 1 moved toward tile 0 and turned a little.
    let mech = unjointed(
        Family::from_number(28).unwrap(),
        CellDims::new(2, 1).unwrap(),
    );
    let model = ContactModel::new(&mech, settings).unwrap();
    let (p0, _) = mech.pose(&mech.rest, 0);
    let (p1, _) = mech.pose(&mech.rest, 1);
    let mut dir = DVec::zeros(mech.layout.len());
    let toward = (p0 - p1).normalize();
    dir[3] = toward.x;
    dir[4] = toward.y;
    dir[5] = 0.3;
    let s = where_clearance_is(&model, &mech, &mech.rest, &dir, 0.5 * settings.dhat, 0.5);
    let q = &mech.rest + &dir * s + rng.vector(mech.layout.len(), 2e-5);
    out.push(("IH28 2x1, tiles pushed together", mech, q));
    for (name, mech, q) in &out {
        let model = ContactModel::new(mech, settings).unwrap();
        let c = model.min_clearance(mech, q);
        assert!(c > 0.0 && c < settings.dhat, "{name}: clearance {c}");
        assert!(model.energy(mech, q) > 0.0, "{name}");
    }
    out
}

fn derivatives(
    model: &ContactModel,
    mech: &Mechanism,
    q: &DVec,
    projection: HessianProjection,
) -> (DVec, DMat) {
    let n = mech.layout.len();
    let (mut g, mut h) = (DVec::zeros(n), DMat::zeros(n, n));
    model.add_derivatives(mech, q, &mut g, &mut h, projection);
    (g, h)
}

fn max_abs(m: impl IntoIterator<Item = Real>) -> Real {
    m.into_iter().fold(0.0, |a, x| a.max(x.abs()))
}

#[test]
fn closed_state_of_every_family_is_a_kerf_apart() {
    let settings = ContactSettings::default();
    for family in Family::all() {
        let mech = unjointed(family, CellDims::MINIMAL);
        let model = ContactModel::new(&mech, settings).unwrap_or_else(|e| panic!("{family}: {e}"));
        let q = &mech.rest;
        let c = model.min_clearance(&mech, q);
        assert!(
            (c - settings.kerf).abs() <= 1e-9 * settings.kerf,
            "{family}: closed-state clearance {c}, kerf {}",
            settings.kerf
        );
        assert_eq!(model.energy(&mech, q), 0.0, "{family}");
        assert_eq!(model.overlapping_pair(&mech, q), None, "{family}");
        assert_eq!(model.max_safe_step(&mech, q, &DVec::zeros(q.len())), 1.0);
    }
}

#[test]
fn collision_polygons_are_the_tiles_inset_by_half_the_kerf() {
    let settings = ContactSettings::with_kerf(0.04);
    let h = 0.5 * settings.kerf;
    for family in [1, 28, 41, 76, 84].map(|n| Family::from_number(n).unwrap()) {
        let mech = unjointed(family, CellDims::new(2, 1).unwrap());
        let model = ContactModel::new(&mech, settings).unwrap();
        let mut rng = Rng::new(u64::from(family.number()));
        let q = &mech.rest + rng.vector(mech.layout.len(), 0.1);
        let polys = model.collision_polygons(&mech, &q);
        assert_eq!(polys.len(), 9 * mech.layout.tiles);
        for (tile, offset, poly) in &polys {
            let outer = mech.tile_polygon(&q, *tile, *offset);
            assert_eq!(poly.len(), outer.len());
            let n = outer.len();
            for (k, p) in poly.iter().enumerate() {
                assert!(point_in_polygon_strict(p, &outer, 0.9 * h), "{family}");
                // Vertex k lies on the offsets of both edge lines through tile vertex k.
                for e in [(k + n - 1) % n, k] {
                    let (a, b) = (outer[e], outer[(e + 1) % n]);
                    let normal = Vec2::new(a.y - b.y, b.x - a.x).normalize();
                    assert!(((p - a).dot(&normal) - h).abs() < 1e-12, "{family}");
                }
                // And no closer than h to any edge of the tile.
                for e in 0..n {
                    let d = point_segment_distance(p, &outer[e], &outer[(e + 1) % n]);
                    assert!(d > h - 1e-12, "{family}: {d}");
                }
            }
        }
    }
}

#[test]
fn energy_is_zero_beyond_dhat_and_grows_as_tiles_close() {
    let (mech, v) = rotating_squares();
    let settings = ContactSettings::default();
    let model = ContactModel::new(&mech, settings).unwrap();
    let mut last = (Real::INFINITY, 0.0);
    for k in 0..=200 {
        let q = &mech.rest - &v * (Real::from(k) * 2e-4);
        let (c, e) = (model.min_clearance(&mech, &q), model.energy(&mech, &q));
        if c >= settings.dhat {
            assert_eq!(e, 0.0, "clearance {c}");
        } else if c > 0.0 {
            assert!(e > 0.0 && e.is_finite(), "clearance {c}, energy {e}");
            assert!(
                c < last.0 && e > last.1,
                "not monotone: {c} {e} after {last:?}"
            );
        }
        last = (c, e);
    }
    // The path ends deep in contact.
    assert!(last.1 == Real::INFINITY);
}

#[test]
fn gradient_matches_finite_differences_of_energy() {
    for (name, mech, q) in active_states() {
        let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
        let (g, _) = derivatives(&model, &mech, &q, HessianProjection::Exact);
        let scale = max_abs(g.iter().copied());
        assert!(scale > 1e-6, "{name}: gradient {scale}");
        let h = 1e-7;
        for k in 0..q.len() {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[k] += h;
            qm[k] -= h;
            let fd = (model.energy(&mech, &qp) - model.energy(&mech, &qm)) / (2.0 * h);
            assert!(
                (fd - g[k]).abs() <= 1e-6 * scale,
                "{name}: ∂E/∂q[{k}] = {} but finite differences give {fd}",
                g[k]
            );
        }
        // The projected variant has the same (exact) gradient.
        let (gp, _) = derivatives(&model, &mech, &q, HessianProjection::PerTermPsd);
        assert!((gp - &g).norm() <= 1e-15 * scale * (q.len() as Real));
    }
}

#[test]
fn exact_hessian_matches_finite_differences_of_gradient() {
    for (name, mech, q) in active_states() {
        let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
        let (_, hess) = derivatives(&model, &mech, &q, HessianProjection::Exact);
        let scale = max_abs(hess.iter().copied());
        assert!(scale > 1e-3, "{name}: Hessian {scale}");
        assert!((&hess - hess.transpose()).norm() <= 1e-12 * scale);
        let h = 1e-8;
        for k in 0..q.len() {
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[k] += h;
            qm[k] -= h;
            let (gp, _) = derivatives(&model, &mech, &qp, HessianProjection::Exact);
            let (gm, _) = derivatives(&model, &mech, &qm, HessianProjection::Exact);
            let fd = (gp - gm) / (2.0 * h);
            for j in 0..q.len() {
                assert!(
                    (fd[j] - hess[(j, k)]).abs() <= 1e-5 * scale,
                    "{name}: H[{j},{k}] = {} but finite differences give {}",
                    hess[(j, k)],
                    fd[j]
                );
            }
        }
    }
}

#[test]
fn projected_hessians_are_psd_and_only_add_curvature() {
    let mut some_term_was_indefinite = false;
    for (name, mech, q) in active_states() {
        let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
        let (g, exact) = derivatives(&model, &mech, &q, HessianProjection::Exact);
        let scale = max_abs(exact.iter().copied());
        let mut per_term = DMat::zeros(q.len(), q.len());
        let mut grad = DVec::zeros(q.len());
        model.add_gradient_hessian(&mech, &q, &mut grad, &mut per_term);
        assert!((&grad - &g).norm() <= 1e-12 * g.norm());
        let (_, per_pair) = derivatives(&model, &mech, &q, HessianProjection::PerPairPsd);
        for (kind, proj) in [("per term", &per_term), ("per pair", &per_pair)] {
            let p = symmetric_eigen(proj.clone()).unwrap();
            assert!(
                p.values[0] >= -1e-12 * scale,
                "{name}, {kind}: {:?}",
                p.values
            );
            // Projection removes negative eigenvalues only: P(H) − H is PSD too.
            let diff = symmetric_eigen(proj - &exact).unwrap();
            assert!(
                diff.values[0] >= -1e-12 * scale,
                "{name}, {kind}: {:?}",
                diff.values
            );
            some_term_was_indefinite |= diff.values.last().unwrap() > &(1e-9 * scale);
        }
        // Projecting sums of terms discards less curvature than projecting each term.
        let lost = |p: &DMat| (p - &exact).trace();
        assert!(lost(&per_pair) <= lost(&per_term) * (1.0 + 1e-12) + 1e-12 * scale);
    }
    // The test would be vacuous if no term ever needed the projection.
    assert!(some_term_was_indefinite);
}

#[test]
fn max_safe_step_never_lets_a_sampled_path_overlap() {
    let (mech, v) = rotating_squares();
    let settings = ContactSettings::default();
    let model = ContactModel::new(&mech, settings).unwrap();
    let n = mech.layout.len();
    let mut rng = Rng::new(11);
    let mut starts = vec![mech.rest.clone(), &mech.rest + &v * 0.3];
    for (_, m, q) in active_states().into_iter().take(3) {
        assert_eq!(m.layout, mech.layout);
        starts.push(q);
    }
    let mut blocked = 0;
    for q in &starts {
        let c0 = model.min_clearance(&mech, q);
        assert!(c0 > 0.0);
        for trial in 0..40 {
            let size = [0.003, 0.03, 0.3, 3.0][trial % 4];
            let mut dq = rng.vector(n, 1.0);
            if trial % 5 == 0 {
                // Mostly the closing motion: contact ahead.
                dq = &dq * 0.1 - &v;
            }
            let dq = dq.normalize() * size;
            let alpha = model.max_safe_step(&mech, q, &dq);
            assert!((0.0..=1.0).contains(&alpha));
            if alpha < 1.0 {
                blocked += 1;
            }
            for k in 0..=100 {
                let qs = q + &dq * (alpha * Real::from(k) / 100.0);
                assert_eq!(model.overlapping_pair(&mech, &qs), None, "α = {alpha}");
                let c = model.min_clearance(&mech, &qs);
                assert!(c >= KEEP_FRACTION * c0 * (1.0 - 1e-9), "{c} < 10% of {c0}");
                assert!(model.energy(&mech, &qs).is_finite());
            }
        }
    }
    assert!(blocked > 20, "only {blocked} steps were limited by contact");
}

#[test]
fn max_safe_step_is_not_needlessly_small() {
    // Closing rotating squares: the clearance falls to 10 % of its start at some s*; the
    // advancement must get most of the way there (the bound is loose for rotations, which
    // is what the repeated rounds are for).
    let (mech, v) = rotating_squares();
    let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
    let q = mech.rest.clone();
    let c0 = model.min_clearance(&mech, &q);
    let dq = -&v * 0.1;
    let s_star = where_clearance_is(&model, &mech, &q, &dq, KEEP_FRACTION * c0, 1.0);
    let alpha = model.max_safe_step(&mech, &q, &dq);
    assert!(alpha <= s_star * (1.0 + 1e-9), "{alpha} > {s_star}");
    assert!(alpha >= 0.9 * s_star, "α = {alpha}, limit {s_star}");
    // Opening with a modest step is not limited at all.
    assert_eq!(model.max_safe_step(&mech, &q, &(&v * 0.1)), 1.0);
}

#[test]
fn overlapping_pair_detects_overlap_the_barrier_cannot_see() {
    let (mech, _) = rotating_squares();
    let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
    // Tile 1 put on top of tile 0, turned 45°: every vertex is far from every edge (the
    // barrier alone would see nothing), yet the squares overlap.
    let mut q = mech.rest.clone();
    let (p0, _) = mech.pose(&q, 0);
    q[3] = p0.x;
    q[4] = p0.y;
    q[5] = std::f64::consts::FRAC_PI_4;
    let Some(Overlap::Tiles(found)) = model.overlapping_pair(&mech, &q) else {
        panic!("overlap not found");
    };
    assert_eq!((found.a, found.b), (0, 1));
    assert_eq!(model.energy(&mech, &q), Real::INFINITY);
    assert_eq!(model.min_clearance(&mech, &q), 0.0);
    assert_eq!(model.max_safe_step(&mech, &q, &DVec::zeros(q.len())), 0.0);
    // A tile overlapping a neighbour's translate across the cell boundary: the lattice
    // squeezed by more than a kerf.
    let mut q = mech.rest.clone();
    let l = mech.layout;
    for k in l.u()..l.len() {
        q[k] *= 0.98;
    }
    let Some(Overlap::Tiles(found)) = model.overlapping_pair(&mech, &q) else {
        panic!("overlap not found");
    };
    assert_ne!(found.offset, [0, 0], "tiles {}, {}", found.a, found.b);
    assert_eq!(model.energy(&mech, &q), Real::INFINITY);
}

#[test]
fn settings_and_insets_are_validated() {
    let (mech, _) = rotating_squares();
    for bad in [
        ContactSettings::with_kerf(0.0),
        ContactSettings::with_kerf(0.3),
        ContactSettings {
            dhat: 0.02,
            ..ContactSettings::default()
        },
        ContactSettings::default().with_stiffness(-1.0),
    ] {
        assert!(ContactModel::new(&mech, bad).is_err(), "{bad:?}");
    }
    // A mechanism whose second tile is a sliver narrower than the kerf.
    let square = vec![
        vec2(-0.5, -0.5),
        vec2(0.5, -0.5),
        vec2(0.5, 0.5),
        vec2(-0.5, 0.5),
    ];
    let sliver = vec![
        vec2(-0.5, -0.02),
        vec2(0.5, -0.02),
        vec2(0.5, 0.02),
        vec2(-0.5, 0.02),
    ];
    let layout = StateLayout { tiles: 2 };
    let thin = Mechanism {
        layout,
        joints: Vec::new(),
        tile_shapes: vec![square, sliver],
        length_scale: 1.0,
        rest: DVec::zeros(layout.len()),
    };
    let err = ContactModel::new(&thin, ContactSettings::with_kerf(0.1)).unwrap_err();
    assert!(err.to_string().contains("tile 1"), "{err}");
    assert!(
        matches!(err, ContactError::Inset { tile: 1, inset, .. } if inset == 0.05),
        "{err:?}"
    );
    assert!(ContactModel::new(&thin, ContactSettings::with_kerf(0.02)).is_ok());
}

#[test]
fn inputs_that_do_not_fit_get_conservative_answers() {
    let (mech, v) = rotating_squares();
    let model = ContactModel::new(&mech, ContactSettings::default()).unwrap();
    let n = mech.layout.len();
    let short = DVec::zeros(n - 1);
    let mut nan = mech.rest.clone();
    nan[4] = Real::NAN;
    let other = unjointed(Family::from_number(76).unwrap(), CellDims::MINIMAL);
    for (m, q) in [(&mech, &short), (&mech, &nan), (&other, &other.rest)] {
        assert!(model.check(m, q).is_err());
        assert_eq!(model.energy(m, q), Real::INFINITY);
        assert_eq!(model.min_clearance(m, q), 0.0);
        assert_eq!(model.max_safe_step(m, q, &v), 0.0);
        assert!(model.collision_polygons(m, q).is_empty());
        let (mut g, mut h) = (DVec::zeros(n), DMat::zeros(n, n));
        model.add_gradient_hessian(m, q, &mut g, &mut h);
        assert_eq!((g.norm(), h.norm()), (0.0, 0.0));
    }
    // Gradient and Hessian of the wrong size are left alone; a NaN step is refused.
    let (_, _, q) = active_states().swap_remove(0);
    let (mut g, mut h) = (DVec::zeros(n + 1), DMat::zeros(n, n));
    model.add_gradient_hessian(&mech, &q, &mut g, &mut h);
    assert_eq!((g.norm(), h.norm()), (0.0, 0.0));
    let mut dq = v.clone();
    dq[0] = Real::NAN;
    assert_eq!(model.max_safe_step(&mech, &q, &dq), 0.0);
    // A step whose motion bound overflows is refused too.
    assert_eq!(model.max_safe_step(&mech, &q, &(&v * 1e308)), 0.0);
}

#[test]
fn results_do_not_depend_on_units_or_orientation() {
    // The same design built from a cell scaled by 37 and turned by 0.7 rad: the closing
    // motion meets contact at the same step, with the same energy.
    let d = Design::resolve("rotating-squares").unwrap();
    let cell = d.cell().unwrap();
    let settings = ContactSettings::default();
    let mut limits = Vec::new();
    for c in [cell.clone(), cell.transformed(37.0, 0.7)] {
        let mech = Mechanism::new(&c, &d.joints).unwrap();
        let v = analyze(&mech, &mech.rest, Default::default())
            .unwrap()
            .motion
            .unwrap()
            .vector;
        let model = ContactModel::new(&mech, settings).unwrap();
        let s = where_clearance_is(&model, &mech, &mech.rest, &-&v, 0.5 * settings.dhat, 0.5);
        let e = model.energy(&mech, &(&mech.rest - &v * (0.99 * s)));
        limits.push((s, e));
    }
    let ((s0, e0), (s1, e1)) = (limits[0], limits[1]);
    assert!((s0 - s1).abs() < 1e-9 * s0, "{s0} vs {s1}");
    assert!((e0 - e1).abs() < 1e-6 * e0, "{e0} vs {e1}");
}

/// Brute force: the smallest distance between a collision polygon of the centre cell and
/// any other collision polygon of the 7×7 block (0 on overlap), without the model's pairs.
fn brute_force_clearance(model: &ContactModel, mech: &Mechanism, q: &DVec) -> Real {
    let (u, w) = mech.lattice(q);
    let place = |i: usize, o: [i32; 2]| -> Vec<Vec2> {
        let (p, th) = mech.pose(q, i);
        let shift = p + u * Real::from(o[0]) + w * Real::from(o[1]);
        let r = isogami::math::rotation(th);
        model.collision_shapes()[i]
            .iter()
            .map(|s| r * s + shift)
            .collect()
    };
    let mut best = Real::INFINITY;
    for a in 0..mech.layout.tiles {
        let pa = place(a, [0, 0]);
        for b in 0..mech.layout.tiles {
            for ku in -3..=3 {
                for kw in -3..=3 {
                    if a == b && [ku, kw] == [0, 0] {
                        continue;
                    }
                    let pb = place(b, [ku, kw]);
                    if interiors_overlap(&pa, &pb, 1e-12) {
                        return 0.0;
                    }
                    best = best.min(pairwise_distance(&pa, &pb));
                }
            }
        }
    }
    best
}

#[test]
fn candidate_pairs_include_every_tile_that_comes_near() {
    // Every tile of the 9×9 block either is listed against each centre tile by the broad
    // phase with a margin of half an edge length, or keeps at least that far from it. In
    // IH38–IH40 a tile shares a vertex with a tile two cells away, which a fixed 3×3 block of
    // cells would miss.
    let settings = ContactSettings::default();
    let margin = 0.5;
    let mut beyond_block = Vec::new();
    for family in Family::all() {
        for dims in [CellDims::MINIMAL, CellDims::new(2, 1).unwrap()] {
            let mech = unjointed(family, dims);
            let model = ContactModel::new(&mech, settings).unwrap();
            let q = &mech.rest;
            let listed_pairs = model.pairs_at(&mech, q, margin).unwrap();
            let pairs: HashSet<_> = listed_pairs.iter().map(|p| (p.a, p.b, p.offset)).collect();
            let n = mech.layout.tiles;
            let polygon = |i: usize, o: [i32; 2]| -> Vec<Vec2> {
                let (p, th) = mech.pose(q, i);
                let (u, w) = mech.lattice(q);
                let shift = p + u * Real::from(o[0]) + w * Real::from(o[1]);
                let r = isogami::math::rotation(th);
                model.collision_shapes()[i]
                    .iter()
                    .map(|s| r * s + shift)
                    .collect()
            };
            for a in 0..n {
                let pa = polygon(a, [0, 0]);
                for b in 0..n {
                    for ku in -4..=4 {
                        for kw in -4..=4 {
                            let o = [ku, kw];
                            if a == b && o == [0, 0] {
                                continue;
                            }
                            let listed =
                                pairs.contains(&(a, b, o)) || pairs.contains(&(b, a, [-ku, -kw]));
                            let d = pairwise_distance(&pa, &polygon(b, o));
                            assert!(
                                listed || d >= margin,
                                "{family} {dims}: tiles {a} and {b} at {o:?} are {d} apart"
                            );
                            let touching = pairwise_distance(
                                &mech.tile_polygon(q, a, [0, 0]),
                                &mech.tile_polygon(q, b, o),
                            ) <= 1e-7;
                            if listed && touching && o.iter().any(|k| k.abs() > 1) {
                                beyond_block.push(format!("{family} {dims}"));
                            }
                        }
                    }
                }
            }
        }
    }
    beyond_block.dedup();
    assert_eq!(
        beyond_block,
        ["IH38 1x1", "IH38 2x1", "IH39 1x1", "IH39 2x1", "IH40 1x1", "IH40 2x1"]
    );
}

/// Smallest vertex–edge distance between two polygons, both directions.
fn pairwise_distance(a: &[Vec2], b: &[Vec2]) -> Real {
    let mut best = Real::INFINITY;
    for (x, y) in [(a, b), (b, a)] {
        for v in x {
            for e in 0..y.len() {
                best = best.min(point_segment_distance(v, &y[e], &y[(e + 1) % y.len()]));
            }
        }
    }
    best
}

#[test]
fn min_clearance_agrees_with_brute_force_near_the_closed_state() {
    let settings = ContactSettings::default();
    let mut rng = Rng::new(5);
    for family in Family::all() {
        let mech = unjointed(family, CellDims::MINIMAL);
        let model = ContactModel::new(&mech, settings).unwrap();
        for _ in 0..4 {
            let mut q = mech.rest.clone();
            for i in 0..mech.layout.tiles {
                let k = mech.layout.tile(i);
                q[k] += 0.002 * rng.sym();
                q[k + 1] += 0.002 * rng.sym();
                q[k + 2] += 0.006 * rng.sym();
            }
            let got = model.min_clearance(&mech, &q);
            let want = brute_force_clearance(&model, &mech, &q);
            assert!(
                (got - want).abs() <= 1e-12,
                "{family}: clearance {got}, brute force {want}"
            );
        }
    }
}
