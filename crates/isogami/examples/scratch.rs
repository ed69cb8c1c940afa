use isogami::kinematics::Mechanism;
use isogami::mobility::{analyze, MobilitySettings};
use isogami::topology::{Design, JointChoice};
fn main() {
    let d = Design::resolve("rotating-squares").unwrap();
    println!("{d}");
    let cell = d.cell().unwrap();
    for e in &cell.edges {
        println!("{:?}", e);
    }
    let m = Mechanism::new(&cell, &d.joints).unwrap();
    let mob = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
    println!(
        "dof {} eig {:?} gap {:?}",
        mob.dof,
        &mob.eigenvalues[..4],
        mob.gap_decades
    );
    println!("{:?}", mob.motion.as_ref().unwrap().tiles);
    for choice in [JointChoice::Both, JointChoice::None] {
        let j = vec![choice; cell.edges.len()];
        let m = Mechanism::new(&cell, &j).unwrap();
        let mob = analyze(&m, &m.rest, MobilitySettings::default()).unwrap();
        println!("{choice:?} dof {}", mob.dof);
    }
}
