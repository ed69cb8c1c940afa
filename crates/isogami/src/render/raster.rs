//! Rasterising SVG text (resvg) to PNG images, in memory, with the caller's [`Fonts`].

use super::error::{RenderError, RenderResult};
use super::fonts::Fonts;
use crate::math::Real;
use resvg::tiny_skia::{Color, Pixmap, Transform};
use resvg::usvg;

/// Largest raster side accepted (GIF stores sizes as u16; this also bounds memory).
pub(super) const MAX_SIDE: u32 = 8192;

/// Parses `svg` with `fonts` (`frame`: its index in an animation, for the error).
pub(super) fn parse(svg: &str, fonts: &Fonts, frame: Option<usize>) -> RenderResult<usvg::Tree> {
    let mut opt = usvg::Options {
        fontdb: fonts.db.clone(),
        ..usvg::Options::default()
    };
    if let Some(name) = &fonts.sans {
        opt.font_family = name.clone();
    }
    usvg::Tree::from_str(svg, &opt).map_err(|e| RenderError::InvalidSvg {
        frame,
        message: e.to_string(),
    })
}

pub(super) fn check_width(width: u32) -> RenderResult<()> {
    if width == 0 || width > MAX_SIDE {
        return Err(RenderError::Width {
            width,
            max: MAX_SIDE,
        });
    }
    Ok(())
}

/// Draws `tree` scaled to fit a `w` × `h` canvas (centred, aspect kept) on white.
pub(super) fn draw(tree: &usvg::Tree, w: u32, h: u32) -> RenderResult<Pixmap> {
    let mut pix = Pixmap::new(w, h).ok_or(RenderError::Allocation {
        width: w,
        height: h,
    })?;
    pix.fill(Color::WHITE);
    let size = tree.size();
    let scale = (w as f32 / size.width()).min(h as f32 / size.height());
    let dx = 0.5 * (w as f32 - scale * size.width());
    let dy = 0.5 * (h as f32 - scale * size.height());
    let ts = Transform::from_scale(scale, scale).post_translate(dx, dy);
    resvg::render(tree, ts, &mut pix.as_mut());
    Ok(pix)
}

/// Raster height for `tree` drawn `width` pixels wide.
pub(super) fn height_for(tree: &usvg::Tree, width: u32) -> RenderResult<u32> {
    let size = tree.size();
    let h = (Real::from(width) * Real::from(size.height()) / Real::from(size.width())).round();
    if !(1.0..=Real::from(MAX_SIDE)).contains(&h) {
        return Err(RenderError::Height {
            svg_width: size.width(),
            svg_height: size.height(),
            width,
            height: h,
            max: MAX_SIDE,
        });
    }
    Ok(h as u32)
}

/// Renders `svg` `width_px` pixels wide (height from its aspect ratio) on a white background
/// and encodes it as PNG. Text is drawn with `fonts` (left out if it has none).
pub fn png_from_svg(svg: &str, width_px: u32, fonts: &Fonts) -> RenderResult<Vec<u8>> {
    check_width(width_px)?;
    let tree = parse(svg, fonts, None)?;
    let pix = draw(&tree, width_px, height_for(&tree, width_px)?)?;
    pix.encode_png()
        .map_err(|e| RenderError::Png(e.to_string()))
}
