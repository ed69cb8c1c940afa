//! The export module end to end: the patch geometry and every interchange format, on
//! rotating-squares and designs of other families (concave tiles among them). Each design's
//! patch is made once and shared by the tests.

#[path = "export/fab_sizes.rs"]
mod fab_sizes;
#[path = "export/fixtures.rs"]
mod fixtures;
#[path = "export/fold.rs"]
mod fold;
#[path = "export/kirigami_sim.rs"]
mod kirigami_sim;
#[path = "export/obj.rs"]
mod obj;
#[path = "export/patch.rs"]
mod patch;
#[path = "export/print3d.rs"]
mod print3d;
#[path = "export/tile_table.rs"]
mod tile_table;
