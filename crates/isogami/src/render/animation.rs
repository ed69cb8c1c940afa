//! Looping animated GIFs from a sequence of SVG frames, in memory.

use super::error::{RenderError, RenderResult};
use super::fonts::Fonts;
use super::raster::{check_width, draw, height_for, parse};

fn gif_error(frame: Option<usize>) -> impl Fn(gif::EncodingError) -> RenderError {
    move |e| RenderError::Gif {
        frame,
        message: e.to_string(),
    }
}

/// An animated GIF that loops forever, one frame per SVG, `delay_cs` hundredths of a second
/// each. The canvas is `width_px` wide with the first frame's aspect ratio; later frames are
/// scaled to fit it (centred). Each frame gets its own 256-colour palette (NeuQuant). Text is
/// drawn with `fonts` (left out if it has none).
pub fn gif_from_svgs(
    frames: &[String],
    width_px: u32,
    delay_cs: u16,
    fonts: &Fonts,
) -> RenderResult<Vec<u8>> {
    check_width(width_px)?;
    let Some(first) = frames.first() else {
        return Err(RenderError::NoFrames);
    };
    let first = parse(first, fonts, Some(0))?;
    let height = height_for(&first, width_px)?;
    // Both sides are at most MAX_SIDE (8192), so they fit in u16.
    let (w16, h16) = (width_px as u16, height as u16);
    let mut out = Vec::new();
    {
        let mut enc = gif::Encoder::new(&mut out, w16, h16, &[]).map_err(gif_error(None))?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(gif_error(None))?;
        for (k, svg) in frames.iter().enumerate() {
            let tree = if k == 0 {
                None
            } else {
                Some(parse(svg, fonts, Some(k))?)
            };
            let pix = draw(tree.as_ref().unwrap_or(&first), width_px, height)?;
            // Opaque everywhere (white background), so premultiplied RGBA equals plain RGBA.
            let mut rgba = pix.take();
            let mut frame = gif::Frame::from_rgba_speed(w16, h16, &mut rgba, 10);
            frame.delay = delay_cs;
            enc.write_frame(&frame).map_err(gif_error(Some(k)))?;
        }
    }
    Ok(out)
}
