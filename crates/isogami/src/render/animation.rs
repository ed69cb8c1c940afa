//! Rasterising SVG text (resvg) to PNG images and looping animated GIFs, in memory.
//!
//! Text needs fonts: the system fonts are loaded once per process, and the generic
//! `sans-serif` family (which every SVG of this crate uses) is pointed at an installed face,
//! preferring DejaVu Sans, so that labels do not vanish on machines without Arial. See
//! [`raster_font`].

use crate::error::{Error, Result};
use crate::math::Real;
use resvg::tiny_skia::{Color, Pixmap, Transform};
use resvg::usvg::{self, fontdb};
use std::sync::{Arc, OnceLock};

/// Sans-serif faces to use, best first, when fontdb's default (Arial) is not installed.
const SANS_CANDIDATES: [&str; 6] = [
    "DejaVu Sans",
    "Liberation Sans",
    "Noto Sans",
    "FreeSans",
    "Arial",
    "Helvetica",
];

/// Largest raster side accepted (GIF stores sizes as u16; this also bounds memory).
const MAX_SIDE: u32 = 8192;

struct Fonts {
    db: Arc<fontdb::Database>,
    sans: Option<String>,
}

fn has_family(db: &fontdb::Database, family: fontdb::Family<'_>) -> bool {
    db.query(&fontdb::Query {
        families: &[family],
        ..fontdb::Query::default()
    })
    .is_some()
}

fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(|| {
        let mut db = fontdb::Database::new();
        db.load_system_fonts();
        let sans = SANS_CANDIDATES
            .iter()
            .find(|name| has_family(&db, fontdb::Family::Name(name)))
            .map(|s| s.to_string())
            .or_else(|| {
                db.faces()
                    .find_map(|face| face.families.first().map(|(name, _)| name.clone()))
            });
        if let Some(name) = &sans {
            db.set_sans_serif_family(name.clone());
        }
        Fonts {
            db: Arc::new(db),
            sans,
        }
    })
}

/// The font family that `sans-serif` text is rasterised with, or `None` when the system has
/// no fonts at all (text is then left out of PNG and GIF output). Loads the system fonts on
/// first call.
pub fn raster_font() -> Option<String> {
    fonts().sans.clone()
}

pub(crate) fn render_error(msg: String) -> Error {
    Error::Render(msg)
}

fn parse(svg: &str) -> Result<usvg::Tree> {
    let f = fonts();
    let mut opt = usvg::Options {
        fontdb: f.db.clone(),
        ..usvg::Options::default()
    };
    if let Some(name) = &f.sans {
        opt.font_family = name.clone();
    }
    usvg::Tree::from_str(svg, &opt).map_err(|e| render_error(format!("invalid SVG: {e}")))
}

fn check_width(width_px: u32) -> Result<()> {
    if width_px == 0 || width_px > MAX_SIDE {
        return Err(render_error(format!(
            "raster width {width_px} px is outside 1..={MAX_SIDE}"
        )));
    }
    Ok(())
}

/// Draws `tree` scaled to fit a `w` × `h` canvas (centred, aspect kept) on white.
fn draw(tree: &usvg::Tree, w: u32, h: u32) -> Result<Pixmap> {
    let mut pix =
        Pixmap::new(w, h).ok_or_else(|| render_error(format!("cannot allocate {w}x{h} px")))?;
    pix.fill(Color::WHITE);
    let size = tree.size();
    let scale = (w as f32 / size.width()).min(h as f32 / size.height());
    let dx = 0.5 * (w as f32 - scale * size.width());
    let dy = 0.5 * (h as f32 - scale * size.height());
    let ts = Transform::from_scale(scale, scale).post_translate(dx, dy);
    resvg::render(tree, ts, &mut pix.as_mut());
    Ok(pix)
}

/// Raster height for `tree` drawn `width_px` wide.
fn height_for(tree: &usvg::Tree, width_px: u32) -> Result<u32> {
    let size = tree.size();
    let h = (Real::from(width_px) * Real::from(size.height()) / Real::from(size.width())).round();
    if !(1.0..=Real::from(MAX_SIDE)).contains(&h) {
        return Err(render_error(format!(
            "an SVG of {}x{} drawn {width_px} px wide would be {h} px high",
            size.width(),
            size.height()
        )));
    }
    Ok(h as u32)
}

/// Renders `svg` `width_px` pixels wide (height from its aspect ratio) on a white background
/// and encodes it as PNG.
pub fn png_from_svg(svg: &str, width_px: u32) -> Result<Vec<u8>> {
    check_width(width_px)?;
    let tree = parse(svg)?;
    let pix = draw(&tree, width_px, height_for(&tree, width_px)?)?;
    pix.encode_png()
        .map_err(|e| render_error(format!("PNG encoding failed: {e}")))
}

/// An animated GIF that loops forever, one frame per SVG, `delay_cs` hundredths of a second
/// each. The canvas is `width_px` wide with the first frame's aspect ratio; later frames are
/// scaled to fit it (centred). Each frame gets its own 256-colour palette (NeuQuant).
pub fn gif_from_svgs(frames: &[String], width_px: u32, delay_cs: u16) -> Result<Vec<u8>> {
    check_width(width_px)?;
    let Some(first) = frames.first() else {
        return Err(render_error("an animation needs at least one frame".into()));
    };
    let first = parse(first)?;
    let height = height_for(&first, width_px)?;
    let (w16, h16) = (width_px as u16, height as u16);
    let mut out = Vec::new();
    {
        let mut enc = gif::Encoder::new(&mut out, w16, h16, &[])
            .map_err(|e| render_error(format!("GIF encoder: {e}")))?;
        enc.set_repeat(gif::Repeat::Infinite)
            .map_err(|e| render_error(format!("GIF encoder: {e}")))?;
        for (k, svg) in frames.iter().enumerate() {
            let tree = if k == 0 {
                None
            } else {
                Some(parse(svg).map_err(|e| render_error(format!("frame {k}: {e}")))?)
            };
            let pix = draw(tree.as_ref().unwrap_or(&first), width_px, height)?;
            // Opaque everywhere (white background), so premultiplied RGBA equals plain RGBA.
            let mut rgba = pix.take();
            let mut frame = gif::Frame::from_rgba_speed(w16, h16, &mut rgba, 10);
            frame.delay = delay_cs;
            enc.write_frame(&frame)
                .map_err(|e| render_error(format!("GIF frame {k}: {e}")))?;
        }
    }
    Ok(out)
}
