//! Realistic synthetic designs for query tests and benchmarks: real deployment reports and
//! linkage analyses of one explored design, re-labelled with varied families, cells, joints
//! and measures drawn from the ranges the exploration produces.

use isogami::catalog::{CatalogEntry, FiniteFigures, Margins, TOLERANCE_LEVELS};
use isogami::cell::CellDims;
use isogami::deploy::EndReason;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use isogami::topology::{Design, JointChoice};
use isogami_store::{DesignRecord, Origin, StageCount, UnitRecords, WorkUnitRecord};
use std::collections::BTreeMap;

/// Deterministic pseudo-random numbers (xorshift64*), no dependency needed.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }

    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// True with probability 1/n.
    pub fn one_in(&mut self, n: u64) -> bool {
        self.next().is_multiple_of(n)
    }

    /// Uniform in [lo, hi).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }

    pub fn pick<T: Clone>(&mut self, items: &[T]) -> T {
        items[(self.next() % items.len() as u64) as usize].clone()
    }
}

pub const SIGNATURES: [&str; 5] = [
    "2×4-bar",
    "4×4-bar",
    "1×6-bar",
    "2×4-bar + 1×6-bar",
    "6×4-bar + 1×6-bar",
];

const CELLS: [(u8, u8); 5] = [(1, 1), (2, 1), (1, 2), (2, 2), (3, 1)];

/// The `i`-th synthetic design: unique spec (its joints spell `i` in base 3).
pub fn design(base: &CatalogEntry, i: usize, rng: &mut Rng) -> DesignRecord {
    let families: Vec<Family> = Family::all().collect();
    let family = rng.pick(&families);
    let (a, b) = rng.pick(&CELLS);
    let dims = CellDims::new(a, b).unwrap();
    let params: Vec<f64> = family
        .default_params()
        .iter()
        .map(|p| p * rng.uniform(0.7, 1.3))
        .collect();
    let mut joints = Vec::new();
    let mut k = i;
    for _ in 0..12 {
        joints.push([JointChoice::None, JointChoice::A, JointChoice::B][k % 3]);
        k /= 3;
    }
    let design = Design::new(family, &params, dims, joints);
    let mut report = base.report.clone();
    report.design = design.to_string();
    report.max_expansion = rng.uniform(0.1, 1.5);
    report.min_expansion = rng.uniform(-0.5, report.max_expansion);
    report.max_area_ratio = (1.0 + report.max_expansion) * (1.0 + report.min_expansion.max(0.0));
    report.max_tile_rotation = rng.uniform(0.0, 2.1);
    report.steps = (rng.next() % 2000) as usize + 20;
    report.behaviour = rng.pick(&[
        Some(BehaviourClass::IsotropicAuxetic),
        Some(BehaviourClass::AnisotropicAuxetic),
        Some(BehaviourClass::OrthotropicPositivePoisson),
        None,
    ]);
    report.end_reason = rng.pick(&[
        EndReason::ContactLimit,
        EndReason::ContactLimit,
        EndReason::StepSizeExhausted,
        EndReason::MaxSteps,
    ]);
    let shrink = rng.uniform(-1.0, 1.0);
    for f in &mut report.frames {
        f.measures.min_expansion = shrink * f.measures.max_expansion.abs();
    }
    let mut linkages = base.linkages.clone();
    linkages.signature = rng.pick(&SIGNATURES).to_string();
    let raw_dof = rng.pick(&[1, 1, 2, 3, 7, 20]);
    let share = rng.uniform(0.5, 1.0);
    let covered = rng.pick(&[None, Some(1.0), Some(1.0), Some(share)]);
    let level = TOLERANCE_LEVELS[(rng.next() % TOLERANCE_LEVELS.len() as u64) as usize];
    let shape_tolerance = rng.pick(&[None, Some(0.0), Some(level), Some(level)]);
    let margins = Margins {
        open_t: rng.uniform(0.0, 1.0),
        end_area_ratio: rng.uniform(0.9, 3.0),
        shape_tolerance,
        fabrication_kept: shape_tolerance.map(|_| rng.uniform(0.3, 1.1)),
    };
    DesignRecord::from_parts(
        &design,
        &design.to_string(),
        Origin::Explored,
        &report,
        Some(&linkages),
    )
    .unwrap()
    .with_finite(Some(&FiniteFigures { raw_dof, covered }))
    .unwrap()
    .with_margins(Some(&margins))
    .unwrap()
}

/// `n` synthetic designs grouped into work units by family and cell.
pub fn units(base: &CatalogEntry, n: usize, seed: u64) -> Vec<UnitRecords> {
    let mut rng = Rng::new(seed);
    let mut by_unit: BTreeMap<String, Vec<DesignRecord>> = BTreeMap::new();
    for i in 0..n {
        let d = design(base, i, &mut rng);
        let s = d.summary();
        by_unit
            .entry(format!("{}/{}", s.family, s.cell))
            .or_default()
            .push(d);
    }
    by_unit
        .into_iter()
        .map(|(id, designs)| {
            let (family, cell) = id.split_once('/').unwrap();
            UnitRecords {
                unit: WorkUnitRecord {
                    id: id.clone(),
                    family: family.into(),
                    cell: cell.into(),
                    kind: "topology+shapes".into(),
                    seconds: 0.25,
                    peak_rss_bytes: (id.len() % 2 == 0).then_some(64 << 20),
                },
                stages: vec![StageCount {
                    stage: "degree".into(),
                    count_in: 64,
                    count_out: designs.len() as u64,
                    seconds: 0.01,
                }],
                designs,
            }
        })
        .collect()
}
