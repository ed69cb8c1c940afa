//! Temporary: first-order closing rates vs deployment outcome, to calibrate a screen.
use isogami::api;
use isogami::catalog::CatalogSettings;
use isogami::cell::CellDims;
use isogami::deploy::EndReason;
use isogami::explore::{edge_rates, enumerate_topologies};
use isogami::kinematics::Mechanism;
use isogami::tiling::Family;
use rayon::prelude::*;
use std::time::Instant;
fn main() {
    let settings = CatalogSettings::default();
    let args: Vec<String> = std::env::args().skip(1).collect();
    for a in &args {
        let (f, d) = a.split_once('/').unwrap();
        let f: Family = f.parse().unwrap();
        let d: CellDims = d.parse().unwrap();
        let topo = enumerate_topologies(f, d, &settings.topology).unwrap();
        let rows: Vec<String> = topo.designs.par_iter().map(|des| {
            let cell = des.cell().unwrap();
            let mech = Mechanism::new(&cell, &des.joints).unwrap();
            let an = api::analyze(des, settings.topology.mobility).unwrap();
            let v = &an.mobility.motion.as_ref().unwrap().vector;
            let rates = edge_rates(&cell, &mech, v);
            let mut close = [0.0f64; 2];
            for r in &rates { for k in 0..2 { let o = r.opening[k];
                close[0] = close[0].max(-o); close[1] = close[1].max(o); } }
            let t = Instant::now();
            let rep = api::deploy(des, &settings.deploy_request(), &mut |_| true).unwrap().report;
            let dt = t.elapsed().as_secs_f64();
            let locked = matches!(rep.end_reason, EndReason::Locked) || rep.steps < 2;
            format!("{} {:.6e} {:.6e} {} {} {:.4} {:.4} {:.5}", des, close[0], close[1], locked as u8, rep.steps, rep.max_expansion, dt, an.mobility.gap_decades.unwrap_or(0.0))
        }).collect();
        for r in rows { println!("{a} {r}"); }
    }
}
