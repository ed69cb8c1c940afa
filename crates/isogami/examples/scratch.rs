use isogami::cell::{CellDims, UnitCell};
use isogami::tiling::{Family, Tiling};
fn main() {
    for f in Family::all() {
        let info = f.info();
        let t = Tiling::default_for(f);
        let c = UnitCell::new(&t, CellDims::MINIMAL);
        let status = match &c { Ok(c) => format!("m={} geom={:?}", c.edges.len(), c.check_geometry().err()), Err(e) => format!("ERR {e}") };
        println!("{} np={} nv={} na={} t1={:?} t2={:?} proto={:?} {}", info.name, info.param_count, info.vertex_count, info.aspect_count, t.t1().as_slice(), t.t2().as_slice(), if info.vertex_count==4 && info.aspect_count==1 {format!("{:?}", t.prototile().iter().map(|p| (p.x,p.y)).collect::<Vec<_>>())} else {String::new()}, status);
    }
}
