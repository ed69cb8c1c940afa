//! Per-stage counts and times of the topology enumeration (paper §4.1), printed as a table.
//!
//! ```text
//! cargo run -p isogami --release --example topology_counts -- [--budget SECONDS]
//!     [--max-edges M] [--only-minimal] [--verify M] [--family IH76 ...] [--specs]
//! ```
//!
//! First every family's 1×1 cell, then supercells in ascending order of edge count until the
//! time budget (default 600 s) is spent (a started cell is finished). `--verify M` also checks,
//! on every cell with at most M edges, that the pruned expansion finds exactly the dof = 1
//! configurations that analysing all Σ 2^k endpoint choices finds. `--specs` prints the kept
//! designs.

use isogami::cell::{CellDims, UnitCell};
use isogami::explore::{
    cells_to_explore, duplicates_across, enumerate_topologies, Expander, ReducedGraph,
};
use isogami::explore::{TopologyOptions, TopologyReport};
use isogami::kinematics::Mechanism;
use isogami::mobility::{analyze, MobilitySettings};
use isogami::tiling::{Family, Tiling};
use isogami::topology::JointChoice;
use std::time::{Duration, Instant};

#[derive(Default)]
struct Totals {
    cells: u64,
    masks: u64,
    degree: u64,
    connected: u64,
    directions: u64,
    triangles: u64,
    counting: u64,
    configs: u64,
    analyses: u64,
    certified: u64,
    unconfirmed: u64,
    mob1: u64,
    separating: u64,
    classes: u64,
    repeats: u64,
    unique: u64,
    reduced: Duration,
    expand: Duration,
    separate: Duration,
    dedup: Duration,
    total: Duration,
}

impl Totals {
    fn add(&mut self, r: &TopologyReport) {
        self.cells += 1;
        self.masks += r.masks_total;
        self.degree += r.after_degree;
        self.connected += r.after_connected;
        self.directions += r.after_directions;
        self.triangles += r.after_triangles;
        self.counting += r.after_counting;
        self.configs += r.configurations_expanded;
        self.analyses += r.expand_stats.analyses;
        self.certified += r.expand_stats.certified;
        self.unconfirmed += r.unconfirmed;
        self.mob1 += r.mobility_one;
        self.separating += r.separating;
        self.classes += r.symmetry_classes;
        self.repeats += r.after_repeats;
        self.unique += r.unique;
        self.reduced += r.timings.reduced;
        self.expand += r.timings.expand;
        self.separate += r.timings.separate;
        self.dedup += r.timings.dedup;
        self.total += r.timings.total;
    }

    fn print(&self, label: &str) {
        let pct = |a: u64, b: u64| 100.0 * (1.0 - a as f64 / (b.max(1)) as f64);
        println!(
            "TOTAL {label}: {} cells; masks {} → degree {} → connected {} → directions {} → \
             triangles {} ({:.2}% removed by the cheap checks; with Maxwell's count 2k ≥ 3n {} left, {:.2}% removed); configurations {} (leaves certified {}, \
             analysed {}) → dof=1 {} → separating {} → symmetry classes {} (unconfirmed {}) → \
             no repeats {} → unique {} ({:.3}% of configurations removed)",
            self.cells,
            self.masks,
            self.degree,
            self.connected,
            self.directions,
            self.triangles,
            pct(self.triangles, self.masks),
            self.counting,
            pct(self.counting, self.masks),
            self.configs,
            self.certified,
            self.analyses,
            self.mob1,
            self.separating,
            self.classes,
            self.unconfirmed,
            self.repeats,
            self.unique,
            pct(self.unique, self.configs),
        );
        println!(
            "TIME  {label}: reduced {:.3} s, expand {:.3} s, separate {:.3} s, dedup {:.3} s, \
             total {:.3} s",
            self.reduced.as_secs_f64(),
            self.expand.as_secs_f64(),
            self.separate.as_secs_f64(),
            self.dedup.as_secs_f64(),
            self.total.as_secs_f64()
        );
    }
}

fn row(r: &TopologyReport) {
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    println!(
        "{:<5} {:<3} {:>2} {:>2} {:>3} | {:>6} {:>6} {:>6} {:>5} {:>5} {:>4} | {:>9} {:>8} {:>7} {:>6} {:>8} {:>8} {:>6} {:>5} {:>4} | {:>7.2} {:>9.1} {:>7.1} {:>8.1} {:>9.1}",
        r.family.to_string(),
        r.dims.to_string(),
        r.tiles,
        r.edges,
        r.symmetry_group,
        r.masks_total,
        r.after_degree,
        r.after_connected,
        r.after_directions,
        r.after_triangles,
        r.masks_expanded,
        r.configurations_expanded,
        r.expand_stats.nodes,
        r.expand_stats.certified,
        r.expand_stats.analyses,
        r.mobility_one,
        r.separating,
        r.symmetry_classes,
        r.after_repeats,
        r.unique,
        ms(r.timings.reduced),
        ms(r.timings.expand),
        ms(r.timings.separate),
        ms(r.timings.dedup),
        ms(r.timings.total),
    );
}

/// Brute force: analyse every endpoint choice of every surviving mask.
fn verify(family: Family, dims: CellDims) -> (usize, bool) {
    let cell = UnitCell::new(&Tiling::default_for(family), dims).unwrap();
    let graph = ReducedGraph::new(&cell).unwrap();
    let ex = Expander::new(&cell, MobilitySettings::default()).unwrap();
    let mut brute = Vec::new();
    let mut pruned = Vec::new();
    for &mask in &graph.enumerate().survivors {
        pruned.extend(ex.expand_collect(mask).0);
        let edges: Vec<usize> = (0..cell.edges.len())
            .filter(|&k| mask >> k & 1 == 1)
            .collect();
        for bits in 0u32..(1 << edges.len()) {
            let mut j = vec![JointChoice::None; cell.edges.len()];
            for (i, &e) in edges.iter().enumerate() {
                j[e] = if bits >> i & 1 == 0 {
                    JointChoice::A
                } else {
                    JointChoice::B
                };
            }
            let mech = Mechanism::new(&cell, &j).unwrap();
            if analyze(&mech, &mech.rest, MobilitySettings::default())
                .map(|m| m.dof == 1)
                .unwrap_or(false)
            {
                brute.push(j);
            }
        }
    }
    let key = |v: &Vec<JointChoice>| v.iter().map(|j| j.to_char()).collect::<String>();
    let mut a: Vec<String> = brute.iter().map(key).collect();
    let mut b: Vec<String> = pruned.iter().map(key).collect();
    a.sort();
    b.sort();
    (a.len(), a == b)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut budget = 600.0;
    let mut options = TopologyOptions::default();
    let mut only_minimal = false;
    let mut verify_up_to = 0usize;
    let mut specs = false;
    let mut families: Vec<Family> = Vec::new();
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--budget" => {
                i += 1;
                budget = args[i].parse().expect("--budget SECONDS");
            }
            "--max-edges" => {
                i += 1;
                options.max_edges = args[i].parse().expect("--max-edges M");
            }
            "--verify" => {
                i += 1;
                verify_up_to = args[i].parse().expect("--verify M");
            }
            "--only-minimal" => only_minimal = true,
            "--specs" => specs = true,
            "--family" => {
                i += 1;
                families.push(args[i].parse().expect("--family IH#"));
            }
            other => panic!("unknown argument {other}"),
        }
        i += 1;
    }
    if families.is_empty() {
        families = Family::all().collect();
    }
    println!(
        "{:<5} {:<3} {:>2} {:>2} {:>3} | {:>6} {:>6} {:>6} {:>5} {:>5} {:>4} | {:>9} {:>8} {:>7} {:>6} {:>8} {:>8} {:>6} {:>5} {:>4} | {:>7} {:>9} {:>7} {:>8} {:>9}",
        "fam", "cel", "n", "m", "|G|", "masks", "deg", "conn", "dir", "tri", "exp", "configs",
        "nodes", "cert", "anal", "dof1", "sep", "sym", "rep", "uniq", "red ms", "expand ms", "sep ms", "dedup ms",
        "total ms"
    );
    let start = Instant::now();
    let mut minimal = Totals::default();
    let mut supercells = Totals::default();
    let mut verified = (0usize, 0usize);
    let mut reports: Vec<TopologyReport> = Vec::new();
    let mut run =
        |f: Family, d: CellDims, totals: &mut Totals| match enumerate_topologies(f, d, &options) {
            Ok(r) => {
                row(&r);
                if specs {
                    for (s, det) in r.designs.iter().zip(&r.details) {
                        println!(
                            "    {s}  joints {} gap {:.1} orbit {} merged {} unblocked {:?}",
                            det.joints,
                            det.gap_decades.unwrap_or(f64::NAN),
                            det.orbit_size,
                            det.same_motion_merged,
                            det.separation.unblocked
                        );
                    }
                }
                totals.add(&r);
                let edges = r.edges;
                let mobility_one = r.mobility_one;
                reports.push(r);
                if edges <= verify_up_to {
                    let (n, ok) = verify(f, d);
                    verified.0 += 1;
                    if !ok || n as u64 != mobility_one {
                        verified.1 += 1;
                        println!(
                            "    VERIFY MISMATCH {f} {d}: brute force finds {n}, pipeline {} \
                             (per-mask sets equal: {ok})",
                            mobility_one
                        );
                    }
                }
            }
            Err(e) => println!("{f} {d}: {e}"),
        };
    for &f in &families {
        run(f, CellDims::MINIMAL, &mut minimal);
    }
    minimal.print("1x1");
    if !only_minimal {
        let mut queue: Vec<(usize, Family, CellDims)> = families
            .iter()
            .flat_map(|&f| {
                cells_to_explore(f, &options)
                    .into_iter()
                    .filter(|(d, _)| *d != CellDims::MINIMAL)
                    .map(move |(d, m)| (m, f, d))
            })
            .collect();
        queue.sort_by_key(|&(m, f, d)| (m, f, d.a(), d.b()));
        let total_cells = queue.len();
        let mut done = 0;
        for (_, f, d) in queue {
            if start.elapsed().as_secs_f64() > budget {
                break;
            }
            run(f, d, &mut supercells);
            done += 1;
        }
        println!(
            "supercells run: {done} of {total_cells} with at most {} edges",
            options.max_edges
        );
        supercells.print("supercells");
    }
    for (label, same_family) in [("within each family", true), ("across all families", false)] {
        let dups = duplicates_across(&reports, same_family);
        let unique: usize = dups.iter().flatten().filter(|d| d.is_none()).count();
        let unique_min: usize = dups
            .iter()
            .zip(&reports)
            .filter(|(_, r)| r.dims == CellDims::MINIMAL)
            .flat_map(|(d, _)| d.iter())
            .filter(|d| d.is_none())
            .count();
        println!(
            "distinct motions {label} (cells and families compared through the motion \
             invariant): {unique} (of which on 1x1 cells: {unique_min})"
        );
    }
    if verify_up_to > 0 {
        println!(
            "verified {} cells with at most {verify_up_to} edges against brute force: {} mismatches",
            verified.0, verified.1
        );
    }
    println!("wall time {:.1} s", start.elapsed().as_secs_f64());
}
