//! Rendering of pipeline data as SVG text. Returns strings; the caller writes files.

mod cell_svg;
mod svg;

pub use cell_svg::cell_svg;
