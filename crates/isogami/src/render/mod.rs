//! Rendering of pipeline data as SVG text. Returns strings; the caller writes files.

mod animation;
mod cell_svg;
mod frame_svg;
mod linkage_svg;
mod plots;
mod svg;

pub use animation::{gif_from_svgs, png_from_svg, raster_font};
pub use cell_svg::cell_svg;
pub use frame_svg::{frame_svg, view_box_for, FrameStyle, ViewBox};
pub use linkage_svg::{linkage_colour, linkage_svg};
pub use plots::{expansion_plot_svg, polar_plot_svg};
