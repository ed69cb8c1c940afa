//! What can go wrong when plotting or rasterising: one typed error for the [`super`] module's
//! plot, PNG and GIF functions, each variant carrying the offending value.

use crate::math::Real;
use thiserror::Error;

/// A plot, raster or animation that could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum RenderError {
    /// A raster width of zero or above the largest side accepted.
    #[error("raster width {width} px is outside 1..={max}")]
    Width {
        /// The width asked for.
        width: u32,
        /// The largest side accepted.
        max: u32,
    },
    /// An SVG whose aspect ratio gives an unusable raster height at the width asked for.
    #[error("an SVG of {svg_width}x{svg_height} drawn {width} px wide would be {height} px high (1..={max})")]
    Height {
        /// The SVG's own width.
        svg_width: f32,
        /// The SVG's own height.
        svg_height: f32,
        /// The raster width asked for.
        width: u32,
        /// The raster height that would result.
        height: Real,
        /// The largest side accepted.
        max: u32,
    },
    /// The pixel buffer could not be allocated.
    #[error("cannot allocate a {width}x{height} px raster")]
    Allocation {
        /// Raster width.
        width: u32,
        /// Raster height.
        height: u32,
    },
    /// SVG text that does not parse (`frame`: its index in an animation).
    #[error("invalid SVG{}: {message}", frame.map_or(String::new(), |k| format!(" (frame {k})")))]
    InvalidSvg {
        /// Index of the frame in an animation, if any.
        frame: Option<usize>,
        /// The parser's message.
        message: String,
    },
    /// The PNG encoder failed.
    #[error("PNG encoding failed: {0}")]
    Png(String),
    /// The GIF encoder failed (`frame`: the frame being written, if any).
    #[error("GIF encoding failed{}: {message}", frame.map_or(String::new(), |k| format!(" at frame {k}")))]
    Gif {
        /// Index of the frame being written, if any.
        frame: Option<usize>,
        /// The encoder's message.
        message: String,
    },
    /// An animation without frames.
    #[error("an animation needs at least one frame")]
    NoFrames,
    /// Plot series of different or zero lengths.
    #[error(
        "expansion plot needs equally long, non-empty series: t has {t}, min {min}, max {max}"
    )]
    SeriesLengths {
        /// Length of the t series.
        t: usize,
        /// Length of the min series.
        min: usize,
        /// Length of the max series.
        max: usize,
    },
    /// A NaN or infinity in a plotted series.
    #[error("{series}[{index}] is {value} (plots need finite numbers)")]
    NotFinite {
        /// Name of the series ("t", "min", "max").
        series: &'static str,
        /// Index of the sample.
        index: usize,
        /// The offending value.
        value: Real,
    },
    /// A polar profile without samples.
    #[error("polar profile '{label}' has no samples")]
    EmptyProfile {
        /// The profile's label.
        label: String,
    },
    /// A polar profile sample that is not finite.
    #[error("polar profile '{label}' sample {index} is (θ = {theta}, ε = {eps}): not finite")]
    ProfileNotFinite {
        /// The profile's label.
        label: String,
        /// Index of the sample.
        index: usize,
        /// Its angle.
        theta: Real,
        /// Its expansion.
        eps: Real,
    },
    /// A polar profile sample with 1 + ε < 0.
    #[error("polar profile '{label}' sample {index} has radius 1 + ε = {radius} < 0")]
    NegativeRadius {
        /// The profile's label.
        label: String,
        /// Index of the sample.
        index: usize,
        /// The radius 1 + ε.
        radius: Real,
    },
    /// The plotting library failed, or produced SVG that fails the output checks.
    #[error("plot: {0}")]
    Plot(String),
}

/// Result of the rendering functions.
pub type RenderResult<T> = Result<T, RenderError>;
