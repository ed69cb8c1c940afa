//! Deploys one design once (rigid modes, default settings): a fixed workload for instruction
//! counts (valgrind --tool=callgrind) that do not depend on machine load.
fn main() {
    let spec = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "rotating-squares".into());
    let d = isogami::topology::Design::resolve(&spec).unwrap();
    let mech = isogami::kinematics::Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap();
    let s = isogami::deploy::DeploySettings::default();
    let traj = isogami::deploy::deploy(&mech, &s, &mut |_| true).unwrap();
    println!("{} {}", traj.steps.len(), traj.attempts);
}
