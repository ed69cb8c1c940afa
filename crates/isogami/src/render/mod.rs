//! Rendering of pipeline data. Returns strings and bytes; the caller writes files.
//!
//! Always built: the dependency-free SVG drawings of a cell, a deployment frame and the
//! linkages ([`cell_svg`], [`frame_svg`], [`linkage_svg`]). With the `render` cargo feature
//! (on by default): plots (plotters), PNG and GIF rasters (resvg, gif) and the `Fonts` they
//! draw text with, which the caller creates explicitly. A consumer of the core pipeline (a
//! server, Python bindings) builds with `default-features = false` and gets none of these
//! dependencies.

#[cfg(feature = "render")]
mod animation;
mod cell_svg;
mod deployment_svg;
#[cfg(feature = "render")]
mod error;
#[cfg(feature = "render")]
mod fonts;
mod frame_svg;
mod linkage_svg;
#[cfg(feature = "render")]
mod plots;
#[cfg(feature = "render")]
mod raster;
mod svg;

#[cfg(feature = "render")]
pub use animation::gif_from_svgs;
pub use cell_svg::cell_svg;
pub use deployment_svg::deployment_frame_svgs;
#[cfg(feature = "render")]
pub use error::{RenderError, RenderResult};
#[cfg(feature = "render")]
pub use fonts::Fonts;
pub use frame_svg::{frame_svg, view_box_for, FrameStyle, ViewBox};
pub use linkage_svg::{linkage_colour, linkage_svg};
#[cfg(feature = "render")]
pub use plots::{expansion_plot_svg, polar_plot_svg};
#[cfg(feature = "render")]
pub use raster::png_from_svg;
