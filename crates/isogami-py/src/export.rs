//! `isogami.export`: a patch of a design in millimetres in any of the library's export formats
//! (laser SVG/DXF, 3D-print STL/3MF, FOLD, OBJ, tile tables, kirigami_sim files, ...), through the library's one
//! export entry point. Formats are listed and parsed by the library, so a format it gains
//! appears here at once. Returns the file contents; Python writes them where it likes.

use crate::convert::{design_of, type_name};
use crate::errors;
use crate::progress::Watch;
use isogami::export::laser::{LaserSettings, Material};
use isogami::export::print3d::PrintSettings;
use isogami::export::{
    export_design, ExportError, ExportFiles, ExportOptions, Format, PatchRequest, Scale,
    SettingsGroup, State,
};
use isogami::finite::{FiniteError, Region};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

/// The Python exception of an export error.
pub(crate) fn export_error(e: ExportError, watch: Watch) -> PyErr {
    match e {
        ExportError::Library(inner) => watch.error(inner),
        e if e.is_cancelled() => watch.cancelled(|| errors::ExportError::new_err(e.to_string())),
        other => errors::ExportError::new_err(other.to_string()),
    }
}

/// Patch rows and columns from "RxC" or a pair.
fn patch_size(obj: &Bound<'_, PyAny>) -> PyResult<(usize, usize)> {
    let bad = || {
        errors::ExportError::new_err(format!(
            "patch {}: expected 'ROWSxCOLS' or (rows, cols)",
            obj.repr().map(|r| r.to_string()).unwrap_or_default()
        ))
    };
    if let Ok(text) = obj.extract::<String>() {
        let (r, c) = text.trim().split_once(['x', 'X']).ok_or_else(bad)?;
        return Ok((
            r.trim().parse().map_err(|_| bad())?,
            c.trim().parse().map_err(|_| bad())?,
        ));
    }
    // A pair of ints: a tuple, a list, a numpy array of two integers.
    match crate::convert::size_pair(obj) {
        Some(Ok(pair)) => Ok(pair),
        Some(Err(shown)) => Err(errors::ExportError::new_err(format!(
            "patch {shown}: rows and columns must be positive ints"
        ))),
        None => Err(PyTypeError::new_err(format!(
            "patch must be 'ROWSxCOLS' or a pair of ints, got {}",
            type_name(obj)
        ))),
    }
}

/// The state: a number t in [0, 1], "open" (the most open state) or "limit" (where the path
/// ends).
pub(crate) fn state_of(obj: &Bound<'_, PyAny>) -> PyResult<State> {
    if let Ok(text) = obj.extract::<String>() {
        return text.parse().map_err(errors::ExportError::new_err);
    }
    obj.extract::<f64>().map(State::T).map_err(|_| {
        PyTypeError::new_err(format!(
            "t must be a number in [0, 1], 'open' or 'limit', got {}",
            type_name(obj)
        ))
    })
}

/// The export settings a caller gave, by name; None where not given.
#[derive(Default)]
pub(crate) struct Given {
    pub(crate) material: Option<String>,
    pub(crate) hinge_mm: Option<f64>,
    pub(crate) kerf_mm: Option<f64>,
    pub(crate) thickness_mm: Option<f64>,
    pub(crate) margin_mm: Option<f64>,
    pub(crate) stroke_mm: Option<f64>,
    pub(crate) colours: [Option<String>; 3],
    pub(crate) labels: bool,
    pub(crate) gap_mm: Option<f64>,
    pub(crate) lamella_mm: Option<f64>,
    pub(crate) nozzle_mm: Option<f64>,
    /// Written into the files' metadata instead of the default.
    pub(crate) creator: Option<String>,
}

impl Given {
    /// The settings of `isogami.export`'s and `GradedRun.export`'s keywords, taken in the
    /// order of their signatures.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        material: Option<&str>,
        hinge_mm: Option<f64>,
        kerf_mm: Option<f64>,
        thickness_mm: Option<f64>,
        margin_mm: Option<f64>,
        stroke_mm: Option<f64>,
        cut_colour: Option<String>,
        score_colour: Option<String>,
        engrave_colour: Option<String>,
        labels: bool,
        gap_mm: Option<f64>,
        lamella_mm: Option<f64>,
        nozzle_mm: Option<f64>,
        creator: Option<String>,
    ) -> Given {
        Given {
            material: material.map(str::to_string),
            hinge_mm,
            kerf_mm,
            thickness_mm,
            margin_mm,
            stroke_mm,
            colours: [cut_colour, score_colour, engrave_colour],
            labels,
            gap_mm,
            lamella_mm,
            nozzle_mm,
            creator,
        }
    }

    /// Names of the given settings that only the laser group reads.
    fn laser_only(&self) -> Vec<&'static str> {
        let [cut, score, engrave] = &self.colours;
        [
            ("material", self.material.is_some()),
            ("kerf_mm", self.kerf_mm.is_some()),
            ("margin_mm", self.margin_mm.is_some()),
            ("stroke_mm", self.stroke_mm.is_some()),
            ("cut_colour", cut.is_some()),
            ("score_colour", score.is_some()),
            ("engrave_colour", engrave.is_some()),
            ("labels", self.labels),
        ]
        .into_iter()
        .filter_map(|(n, given)| given.then_some(n))
        .collect()
    }

    /// Names of the given settings that only the 3D-print group reads.
    fn print_only(&self) -> Vec<&'static str> {
        [
            ("gap_mm", self.gap_mm.is_some()),
            ("lamella_mm", self.lamella_mm.is_some()),
            ("nozzle_mm", self.nozzle_mm.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, given)| given.then_some(n))
        .collect()
    }

    /// Names of the settings both groups read.
    fn shared(&self) -> Vec<&'static str> {
        [
            ("hinge_mm", self.hinge_mm.is_some()),
            ("thickness_mm", self.thickness_mm.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, given)| given.then_some(n))
        .collect()
    }

    /// The options of `format`: the defaults, then its own group's settings as the CLI
    /// reads them, and the creator. A setting of another group is refused rather than
    /// ignored.
    pub(crate) fn options(mut self, format: Format) -> PyResult<ExportOptions> {
        let group = format.settings_group();
        let foreign: Vec<&str> = match group {
            SettingsGroup::Laser => self.print_only(),
            SettingsGroup::Print => self.laser_only(),
            SettingsGroup::None => {
                let mut all = self.laser_only();
                all.extend(self.print_only());
                all.extend(self.shared());
                all
            }
        };
        if !foreign.is_empty() {
            return Err(PyTypeError::new_err(format!(
                "{} does not apply to format {} (its settings group is {})",
                foreign.join(", "),
                format.name(),
                group.name()
            )));
        }
        let creator = self.creator.take();
        let mut options = ExportOptions::default();
        match group {
            SettingsGroup::Laser => options.laser = self.laser()?,
            SettingsGroup::Print => options.print = self.print(),
            SettingsGroup::None => {}
        }
        if let Some(c) = creator {
            options.creator = c;
        }
        Ok(options)
    }

    /// The laser settings: a material preset (or the defaults), then every value given.
    fn laser(self) -> PyResult<LaserSettings> {
        let mut s = match &self.material {
            None => LaserSettings::default(),
            Some(name) => {
                let m = Material::from_name(name.trim()).ok_or_else(|| {
                    let names: Vec<&str> = Material::ALL.iter().map(|m| m.name()).collect();
                    errors::ExportError::new_err(format!(
                        "material '{}': expected one of {}",
                        name.escape_debug(),
                        names.join(", ")
                    ))
                })?;
                LaserSettings::for_material(m)
            }
        };
        set_all([
            (&mut s.hinge_mm, self.hinge_mm),
            (&mut s.kerf_mm, self.kerf_mm),
            (&mut s.thickness_mm, self.thickness_mm),
            (&mut s.margin_mm, self.margin_mm),
            (&mut s.stroke_mm, self.stroke_mm),
        ]);
        let [cut, score, engrave] = self.colours;
        for (slot, v) in [
            (&mut s.colours.cut, cut),
            (&mut s.colours.score, score),
            (&mut s.colours.engrave, engrave),
        ] {
            if let Some(v) = v {
                *slot = v.trim().to_string();
            }
        }
        s.labels = self.labels;
        Ok(s)
    }

    /// The 3D-print settings: the defaults, then every value given.
    fn print(self) -> PrintSettings {
        let mut s = PrintSettings::default();
        set_all([
            (&mut s.hinge_mm, self.hinge_mm),
            (&mut s.thickness_mm, self.thickness_mm),
            (&mut s.gap_mm, self.gap_mm),
            (&mut s.lamella_mm, self.lamella_mm),
            (&mut s.nozzle_mm, self.nozzle_mm),
        ]);
        s
    }
}

/// Overwrites each slot with its value where one was given.
fn set_all<const N: usize>(pairs: [(&mut f64, Option<f64>); N]) {
    for (slot, v) in pairs {
        if let Some(v) = v {
            *slot = v;
        }
    }
}

/// The scale of `edge_mm` or `width_mm` (`default` when neither).
pub(crate) fn scale_of(
    edge_mm: Option<f64>,
    width_mm: Option<f64>,
    default: Scale,
) -> PyResult<Scale> {
    Ok(match (edge_mm, width_mm) {
        (Some(_), Some(_)) => {
            return Err(PyTypeError::new_err("give edge_mm or width_mm, not both"))
        }
        (_, Some(w)) => Scale::WidthMm(w),
        (Some(e), None) => Scale::EdgeMm(e),
        (None, None) => default,
    })
}

/// Export files as Python values: ``bytes`` for one file, ``{name: bytes}`` for a folder.
pub(crate) fn files_to_python(py: Python<'_>, files: ExportFiles) -> PyResult<Bound<'_, PyAny>> {
    Ok(match files {
        ExportFiles::One(bytes) => PyBytes::new(py, &bytes).into_any(),
        ExportFiles::Folder(named) => {
            let d = PyDict::new(py);
            for (name, bytes) in named {
                d.set_item(name, PyBytes::new(py, &bytes))?;
            }
            d.into_any()
        }
    })
}

/// Writes an R×C patch of ``design`` in millimetres in ``format`` and returns the file
/// contents: ``bytes`` for a single-file format, a dict ``{file name: bytes}`` for a folder of
/// files (``"kirigami-sim"``). ``export_formats()`` lists the formats.
///
/// Patch: ``patch`` (``"6x6"`` or ``(rows, cols)``, rows along w, 1..40 each), or instead
/// ``region``, read as ``finite_sheet`` reads it (``"RxC"`` cells, or in mm at ``edge_mm``
/// ``"rect:W,H"``, ``"disc:R"``, ``"polygon:x,y;x,y;…"`` centred on cell [0, 0]); the scale is
/// ``edge_mm`` (mean tile edge, default 20 mm) or ``width_mm`` (patch width at the state);
/// ``t`` is the state (a number in [0, 1], the nearest accepted state; 0 closed), ``"open"``
/// (the most open state, largest area ratio) or ``"limit"`` (where the path ends); ``kerf`` is the deployment's cut width relative to the mean edge
/// (default 0.01); ``frames`` the states animated formats keep (2..100, default 11);
/// ``complete`` (default ``True``) writes the rectangle's one-DOF completion (``FiniteError``
/// when there is none), ``complete=False`` the rectangle as it is (the CLI's ``--raw``).
///
/// Each format reads one group of settings (``export_formats()`` names it); a setting of
/// another group raises ``TypeError``. Laser formats (svg, dxf): ``material`` (``"card"``,
/// ``"felt"``, ``"pla"``) sets hinge, kerf and thickness, then ``hinge_mm``, ``kerf_mm``,
/// ``thickness_mm``, ``margin_mm``, ``stroke_mm``, ``cut_colour``, ``score_colour``,
/// ``engrave_colour`` and ``labels`` override single values. 3D-print formats (stl, 3mf):
/// ``thickness_mm`` (2), ``hinge_mm`` (0.8), ``gap_mm`` (0.4), ``lamella_mm`` (0.4),
/// ``nozzle_mm`` (0.4). ``creator`` is written into the files' metadata.
///
/// Every value is checked before the deployment runs (``ExportError``, ``SettingsError``);
/// ``progress`` and ``timeout`` as for ``deploy``; the GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (
    design, format, *, patch=None, region=None, edge_mm=None, width_mm=None, t=None, kerf=None, frames=None,
    complete=true, material=None, hinge_mm=None, kerf_mm=None, thickness_mm=None, margin_mm=None,
    stroke_mm=None, cut_colour=None, score_colour=None, engrave_colour=None, labels=false,
    gap_mm=None, lamella_mm=None, nozzle_mm=None, creator=None, progress=None, timeout=None
))]
#[allow(clippy::too_many_arguments)]
pub fn export<'py>(
    py: Python<'py>,
    design: &Bound<'py, PyAny>,
    format: &str,
    patch: Option<&Bound<'py, PyAny>>,
    region: Option<&str>,
    edge_mm: Option<f64>,
    width_mm: Option<f64>,
    t: Option<&Bound<'py, PyAny>>,
    kerf: Option<f64>,
    frames: Option<&Bound<'py, PyAny>>,
    complete: bool,
    material: Option<&str>,
    hinge_mm: Option<f64>,
    kerf_mm: Option<f64>,
    thickness_mm: Option<f64>,
    margin_mm: Option<f64>,
    stroke_mm: Option<f64>,
    cut_colour: Option<String>,
    score_colour: Option<String>,
    engrave_colour: Option<String>,
    labels: bool,
    gap_mm: Option<f64>,
    lamella_mm: Option<f64>,
    nozzle_mm: Option<f64>,
    creator: Option<String>,
    progress: Option<Bound<'py, PyAny>>,
    timeout: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let format: Format = format
        .parse()
        .map_err(|e: ExportError| errors::ExportError::new_err(e.to_string()))?;
    let defaults = PatchRequest::default();
    let patch = patch.filter(|p| !p.is_none());
    let (rows, cols) = match patch {
        Some(p) => patch_size(p)?,
        _ => (defaults.rows, defaults.cols),
    };
    let region = match region {
        Some(_) if patch.is_some() => {
            return Err(PyTypeError::new_err(
                "give patch or region, not both (a region replaces the patch)",
            ))
        }
        Some(text) => Some(
            text.parse::<Region>()
                .map_err(|e: FiniteError| errors::library(e.into()))?,
        ),
        None => None,
    };
    let scale = scale_of(edge_mm, width_mm, defaults.scale)?;
    let state = match t {
        Some(t) if !t.is_none() => state_of(t)?,
        _ => defaults.state,
    };
    let request = PatchRequest {
        rows,
        cols,
        scale,
        state,
        kerf: kerf.unwrap_or(defaults.kerf),
        frames: crate::convert::count_or("frames", frames, 0, defaults.frames)?,
        complete,
        region,
    };
    let options = Given::new(
        material,
        hinge_mm,
        kerf_mm,
        thickness_mm,
        margin_mm,
        stroke_mm,
        cut_colour,
        score_colour,
        engrave_colour,
        labels,
        gap_mm,
        lamella_mm,
        nozzle_mm,
        creator,
    )
    .options(format)?;
    request
        .validate()
        .map_err(|e| errors::ExportError::new_err(e.to_string()))?;
    options
        .validate(format)
        .map_err(|e| errors::ExportError::new_err(e.to_string()))?;
    let design = design_of(design)?;
    let mut watch = Watch::new(progress.filter(|p| !p.is_none()), timeout)?;
    let result =
        py.detach(|| export_design(&design, &request, format, &options, &mut |n| watch.tick(n)));
    let files = match result {
        Ok((_, files)) => files,
        Err(e) => return Err(export_error(e, watch)),
    };
    files_to_python(py, files)
}

/// The export formats: a list of dicts with ``name`` (what ``export`` takes),
/// ``description``, ``extension`` (None for a folder of files), ``media_type`` and
/// ``settings``, the group of settings it reads (``"laser"``, ``"print"`` or ``"none"``).
#[pyfunction]
pub fn export_formats(py: Python<'_>) -> PyResult<Vec<Bound<'_, PyDict>>> {
    Format::ALL
        .into_iter()
        .map(|f| {
            let d = PyDict::new(py);
            d.set_item("name", f.name())?;
            d.set_item("description", f.description())?;
            d.set_item("extension", f.extension())?;
            d.set_item("media_type", f.media_type())?;
            d.set_item("settings", f.settings_group().name())?;
            Ok(d)
        })
        .collect()
}
