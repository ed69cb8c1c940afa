//! The export formats by name: what each writes, its file extension and media type. Every
//! front end (CLI flags, the server's export endpoint, the Python bindings) lists and parses
//! formats from here, so a new format appears everywhere at once.

use super::error::ExportError;
use std::fmt;
use std::str::FromStr;

/// A file format `export` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(into = "&'static str")]
pub enum Format {
    /// Laser-cutting SVG of the closed sheet (mm; cut, score, engrave groups).
    Svg,
    /// Laser-cutting DXF of the closed sheet (R12, mm; layers CUT, SCORE, OUTLINE).
    Dxf,
    /// FOLD 1.1 JSON, every deployment state a frame.
    Fold,
    /// Wavefront OBJ of the state, one object per tile.
    Obj,
    /// The tile table as CSV.
    TilesCsv,
    /// The tile table as JSON.
    TilesJson,
    /// kirigami_sim's text files (vertices, constraints, hull tiles, hull vertices): a
    /// folder of files.
    KirigamiSim,
    /// 3D printing: binary STL of the sheet as one solid (mm; STL has no units).
    Stl,
    /// 3D printing: 3MF package of the sheet as one solid, in millimetres, with metadata.
    ThreeMf,
}

/// Which group of settings a format is laid out with, so front ends show the right fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SettingsGroup {
    /// [`LaserSettings`](super::laser::LaserSettings): hinge, kerf, thickness, colours...
    Laser,
    /// [`PrintSettings`](super::print3d::PrintSettings): thickness, gap, hinge, lamella,
    /// nozzle.
    Print,
    /// Only the patch request.
    None,
}

impl SettingsGroup {
    /// `laser`, `print` or `none`.
    pub fn name(self) -> &'static str {
        match self {
            SettingsGroup::Laser => "laser",
            SettingsGroup::Print => "print",
            SettingsGroup::None => "none",
        }
    }
}

impl Format {
    /// Every format, in the order front ends list them.
    pub const ALL: [Format; 9] = [
        Format::Svg,
        Format::Dxf,
        Format::Fold,
        Format::Obj,
        Format::TilesCsv,
        Format::TilesJson,
        Format::KirigamiSim,
        Format::Stl,
        Format::ThreeMf,
    ];

    /// The name used on the command line, in URLs and in Python (`tiles-csv`).
    pub fn name(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Dxf => "dxf",
            Format::Fold => "fold",
            Format::Obj => "obj",
            Format::TilesCsv => "tiles-csv",
            Format::TilesJson => "tiles-json",
            Format::KirigamiSim => "kirigami-sim",
            Format::Stl => "stl",
            Format::ThreeMf => "3mf",
        }
    }

    /// One line saying what the file is for.
    pub fn description(self) -> &'static str {
        match self {
            Format::Svg => "laser cutting: SVG in mm with cut, score and engrave groups",
            Format::Dxf => "laser cutting: DXF R12 in mm with layers CUT, SCORE, OUTLINE",
            Format::Fold => "FOLD 1.1 (JSON) with every deployment state as a frame",
            Format::Obj => "Wavefront OBJ of the state, one object per tile",
            Format::TilesCsv => "tile table (CSV): polygon, pose, rotation, neighbours",
            Format::TilesJson => "tile table (JSON): polygon, pose, rotation, neighbours",
            Format::KirigamiSim => "the spring simulator kirigami_sim's input files",
            Format::Stl => "3D printing: binary STL (mm) of the sheet with lamella hinges",
            Format::ThreeMf => {
                "3D printing: 3MF (mm, with metadata) of the sheet with lamella hinges"
            }
        }
    }

    /// The file name extension (without the dot) of a single-file format; `None` for a
    /// folder of files.
    pub fn extension(self) -> Option<&'static str> {
        match self {
            Format::Svg => Some("svg"),
            Format::Dxf => Some("dxf"),
            Format::Fold => Some("fold"),
            Format::Obj => Some("obj"),
            Format::TilesCsv => Some("csv"),
            Format::TilesJson => Some("json"),
            Format::KirigamiSim => None,
            Format::Stl => Some("stl"),
            Format::ThreeMf => Some("3mf"),
        }
    }

    /// The media type of a single-file format's content.
    pub fn media_type(self) -> &'static str {
        match self {
            Format::Svg => "image/svg+xml",
            Format::Dxf => "image/vnd.dxf",
            Format::Fold | Format::TilesJson => "application/json",
            Format::Obj => "model/obj",
            Format::TilesCsv => "text/csv",
            Format::KirigamiSim => "text/plain",
            Format::Stl => "model/stl",
            Format::ThreeMf => "model/3mf",
        }
    }

    /// The settings group the format's files are laid out with.
    pub fn settings_group(self) -> SettingsGroup {
        match self {
            Format::Svg | Format::Dxf => SettingsGroup::Laser,
            Format::Stl | Format::ThreeMf => SettingsGroup::Print,
            Format::Fold
            | Format::Obj
            | Format::TilesCsv
            | Format::TilesJson
            | Format::KirigamiSim => SettingsGroup::None,
        }
    }

    /// Whether the format's files are laid out with the laser settings.
    pub fn uses_laser_settings(self) -> bool {
        self.settings_group() == SettingsGroup::Laser
    }

    /// Whether the format's files are built with the 3D-print settings.
    pub fn uses_print_settings(self) -> bool {
        self.settings_group() == SettingsGroup::Print
    }

    /// Whether the patch request's state (t, open) changes the file. A laser cuts the flat
    /// sheet, so SVG and DXF are always drawn from the closed state, whatever state is asked
    /// for; front ends say so instead of offering a choice that does nothing.
    pub fn uses_state(self) -> bool {
        !matches!(self, Format::Svg | Format::Dxf)
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl From<Format> for &'static str {
    fn from(format: Format) -> &'static str {
        format.name()
    }
}

impl FromStr for Format {
    type Err = ExportError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let wanted = text.trim().to_ascii_lowercase();
        Format::ALL
            .into_iter()
            .find(|f| f.name() == wanted)
            .ok_or_else(|| ExportError::UnknownFormat {
                given: text.to_string(),
                known: Format::ALL.map(Format::name).join(", "),
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_parses_back_and_names_are_unique() {
        for f in Format::ALL {
            assert_eq!(f.name().parse::<Format>().unwrap(), f);
            assert_eq!(f.to_string().to_uppercase().parse::<Format>().unwrap(), f);
            assert_eq!(
                Format::ALL.iter().filter(|g| g.name() == f.name()).count(),
                1
            );
        }
    }

    #[test]
    fn each_format_has_one_settings_group() {
        for f in Format::ALL {
            let g = f.settings_group();
            assert_eq!(f.uses_laser_settings(), g == SettingsGroup::Laser, "{f}");
            assert_eq!(f.uses_print_settings(), g == SettingsGroup::Print, "{f}");
        }
        assert_eq!(Format::Stl.settings_group().name(), "print");
        assert_eq!("3MF".parse::<Format>().unwrap(), Format::ThreeMf);
        assert_eq!(Format::ThreeMf.extension(), Some("3mf"));
    }

    /// `uses_state` is what the files do: exported closed and open, exactly the formats that
    /// do not use the state give the same bytes (issue 24: the page offered t = 0, 0.5 and
    /// open for laser files, which came out byte-identical).
    #[test]
    fn a_format_uses_the_state_exactly_when_its_files_change_with_it() {
        use crate::export::{export_design, ExportFiles, ExportOptions, PatchRequest, State};
        let design = crate::api::resolve_design("rotating-squares").unwrap();
        let bytes = |format: Format, state: State| {
            let request = PatchRequest {
                rows: 2,
                cols: 2,
                state,
                ..PatchRequest::default()
            };
            let options = ExportOptions {
                creator: "test".into(),
                ..ExportOptions::default()
            };
            match export_design(&design, &request, format, &options, &mut |_| true)
                .unwrap()
                .1
            {
                ExportFiles::One(b) => b,
                ExportFiles::Folder(files) => files.into_iter().flat_map(|(_, b)| b).collect(),
            }
        };
        for f in Format::ALL {
            let same = bytes(f, State::T(0.0)) == bytes(f, State::Open);
            assert_eq!(same, !f.uses_state(), "{f}");
        }
    }

    #[test]
    fn an_unknown_name_lists_the_known_ones() {
        let e = "stp".parse::<Format>().unwrap_err().to_string();
        assert!(
            e.contains("'stp'") && e.contains("tiles-csv") && !e.contains('\n'),
            "{e}"
        );
    }
}
