//! Shared fixtures for the integration tests.
#![allow(dead_code)]

use isogami::cell::{CellDims, UnitCell};
use isogami::kinematics::Mechanism;
use isogami::math::DVec;
use isogami::tiling::{Family, Tiling};
use isogami::topology::{Design, JointChoice};

/// A small deterministic generator (xorshift*), so failures reproduce.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [-1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.unit() - 1.0
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}

pub fn cell_of(family: Family, params: &[f64], dims: CellDims) -> UnitCell {
    let t = Tiling::new(family, params).unwrap_or_else(|e| panic!("{family}: {e}"));
    UnitCell::new(&t, dims).unwrap_or_else(|e| panic!("{family} {dims}: {e}"))
}

pub fn random_joints(rng: &mut Rng, m: usize) -> Vec<JointChoice> {
    (0..m)
        .map(|_| match rng.below(3) {
            0 => JointChoice::None,
            1 => JointChoice::A,
            _ => JointChoice::B,
        })
        .collect()
}

pub fn rotating_squares() -> (Design, UnitCell, Mechanism) {
    let d = Design::resolve("rotating-squares").unwrap();
    let c = d.cell().unwrap();
    let m = Mechanism::new(&c, &d.joints).unwrap();
    (d, c, m)
}

/// A state near rest: every coordinate moved by up to `size`.
pub fn perturbed(rng: &mut Rng, q: &DVec, size: f64) -> DVec {
    DVec::from_iterator(q.len(), q.iter().map(|x| x + size * rng.sym()))
}

/// Small-perturbation parameters that stay valid, for families with parameters.
pub fn perturbed_params(rng: &mut Rng, family: Family, rel: f64) -> Vec<f64> {
    let d = family.default_params();
    for _ in 0..50 {
        let p: Vec<f64> = d
            .iter()
            .map(|v| v + rel * (v.abs() + 0.1) * rng.sym())
            .collect();
        if Tiling::new(family, &p).is_ok() {
            return p;
        }
    }
    panic!("{family}: no valid perturbation of size {rel} found in 50 tries");
}
pub mod overlap;
