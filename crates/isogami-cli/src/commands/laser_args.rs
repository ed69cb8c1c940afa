//! The laser flags of `isogami export` (formats svg and dxf): a material preset, then any
//! value overridden, checked by the library before anything is deployed or written.
//! `--hinge-mm` and `--thickness-mm` are shared with the 3D-print formats
//! ([`super::print_args`]), whose defaults differ.

use isogami::export::laser::{LaserSettings, Material};

/// Laser-cutting flags.
#[derive(Debug, clap::Args)]
pub struct LaserArgs {
    /// Material preset for svg/dxf: card (hinge 1.0, kerf 0.1, 0.3 mm), felt (1.5, 0.2,
    /// 2 mm) or pla (0.8, 0.15, 2 mm). Without it: hinge 1.5, kerf 0.2, thickness 2.
    #[arg(long)]
    material: Option<String>,
    /// Hinge width at each joint, mm: the bridge of uncut material for svg/dxf [default: 1.5
    /// or the preset's], the lamella's width along the edge for stl/3mf [default: 0.8, at
    /// least --nozzle-mm].
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) hinge_mm: Option<f64>,
    /// Width of the laser's cut, mm: cut paths are compensated by half of it.
    #[arg(long, allow_hyphen_values = true)]
    kerf_mm: Option<f64>,
    /// Sheet thickness, mm: written in the metadata of svg/dxf [default: 2 or the preset's];
    /// the height of the printed tiles for stl/3mf [default: 2].
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) thickness_mm: Option<f64>,
    /// Empty margin round the sheet, mm [default: 5].
    #[arg(long, allow_hyphen_values = true)]
    margin_mm: Option<f64>,
    /// Stroke width of the SVG's lines, mm [default: 0.1, a hairline].
    #[arg(long, allow_hyphen_values = true)]
    stroke_mm: Option<f64>,
    /// Colour of the cut group / layer [default: #000000].
    #[arg(long)]
    cut_colour: Option<String>,
    /// Colour of the score group / layer [default: #0000ff].
    #[arg(long)]
    score_colour: Option<String>,
    /// Colour of the engrave group / layer [default: #ff0000].
    #[arg(long)]
    engrave_colour: Option<String>,
    /// Engrave each tile's number at its centre.
    #[arg(long)]
    labels: bool,
}

impl LaserArgs {
    /// The validated settings: the preset (or defaults), then every flag given.
    pub fn settings(&self) -> Result<LaserSettings, String> {
        let mut s = match &self.material {
            None => LaserSettings::default(),
            Some(name) => {
                let m = Material::from_name(name.trim()).ok_or_else(|| {
                    let names: Vec<&str> = Material::ALL.iter().map(|m| m.name()).collect();
                    format!("--material '{name}': expected one of {}", names.join(", "))
                })?;
                LaserSettings::for_material(m)
            }
        };
        let set = |slot: &mut f64, v: Option<f64>| {
            if let Some(v) = v {
                *slot = v;
            }
        };
        set(&mut s.hinge_mm, self.hinge_mm);
        set(&mut s.kerf_mm, self.kerf_mm);
        set(&mut s.thickness_mm, self.thickness_mm);
        set(&mut s.margin_mm, self.margin_mm);
        set(&mut s.stroke_mm, self.stroke_mm);
        for (slot, v) in [
            (&mut s.colours.cut, &self.cut_colour),
            (&mut s.colours.score, &self.score_colour),
            (&mut s.colours.engrave, &self.engrave_colour),
        ] {
            if let Some(v) = v {
                *slot = v.trim().to_string();
            }
        }
        s.labels = self.labels;
        s.validate().map_err(|e| e.to_string())?;
        Ok(s)
    }
}
