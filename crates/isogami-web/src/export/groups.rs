//! Settings groups of the export formats: which query keys set which [`ExportOptions`], with
//! a description of every field (kind, unit, default, presets) that the formats endpoint
//! serves so the browser builds its form from it.
//!
//! A format uses a group when the group's `uses` says so; the browser shows a group's fields
//! only for formats that use it. Adding a group is one more entry
//! in [`GROUPS`]: a description and a function that applies its query values.

use crate::error::{ApiError, ApiResult};
use crate::filters::truncate;
use isogami::export::laser::{LaserSettings, Material};
use isogami::export::print3d::PrintSettings;
use isogami::export::{ExportOptions, Format, SettingsGroup};
use serde::Serialize;
use serde_json::{json, Value};

/// A settings group: its fields and how their query values change the options.
pub struct Group {
    /// Name used in the formats list (`laser`).
    pub name: &'static str,
    /// Heading in the form.
    pub label: &'static str,
    /// Whether `format` is laid out with this group's settings.
    pub uses: fn(Format) -> bool,
    /// The fields, for the form.
    pub fields: fn() -> Vec<Field>,
    /// Applies the group's keys of a query (each at most once) to the options.
    pub apply: fn(&mut ExportOptions, &Values<'_>) -> ApiResult<()>,
}

/// Every settings group, in form order.
pub const GROUPS: &[Group] = &[
    Group {
        name: "laser",
        label: "Laser cutting",
        uses: Format::uses_laser_settings,
        fields: laser_fields,
        apply: apply_laser,
    },
    Group {
        name: "print",
        label: "3D printing",
        uses: uses_print_settings,
        fields: print_fields,
        apply: apply_print,
    },
];

fn uses_print_settings(format: Format) -> bool {
    format.settings_group() == SettingsGroup::Print
}

/// The groups `format` uses, by name.
pub fn groups_of(format: Format) -> Vec<&'static str> {
    GROUPS
        .iter()
        .filter(|g| (g.uses)(format))
        .map(|g| g.name)
        .collect()
}

/// Every query key some group reads (a key shared by groups once).
pub fn group_keys() -> Vec<&'static str> {
    let mut keys: Vec<&'static str> = GROUPS
        .iter()
        .flat_map(|g| (g.fields)().into_iter().map(|f| f.name))
        .collect();
    keys.sort_unstable();
    keys.dedup();
    keys
}

/// One field of a group's form, named as its query key and CLI flag (`hinge_mm` is
/// `--hinge-mm`).
#[derive(Debug, Clone, Serialize)]
pub struct Field {
    /// Query key.
    pub name: &'static str,
    /// Label in the form.
    pub label: &'static str,
    /// `number`, `choice`, `flag` or `colour`.
    pub kind: &'static str,
    /// Unit of a number.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<&'static str>,
    /// The value used when the key is absent (null: none).
    pub default: Value,
    /// Whether zero is allowed (numbers; otherwise they must be above zero).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zero_ok: Option<bool>,
    /// The values of a choice: `{value, label, sets}`, where `sets` maps other fields of the
    /// group to the values the choice gives them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub choices: Vec<Value>,
    /// One line of help.
    pub help: &'static str,
}

fn number(name: &'static str, label: &'static str, default: f64, help: &'static str) -> Field {
    Field {
        name,
        label,
        kind: "number",
        unit: Some("mm"),
        default: json!(default),
        zero_ok: Some(false),
        choices: Vec::new(),
        help,
    }
}

fn colour(name: &'static str, label: &'static str, default: &str, help: &'static str) -> Field {
    Field {
        name,
        label,
        kind: "colour",
        unit: None,
        default: json!(default),
        zero_ok: None,
        choices: Vec::new(),
        help,
    }
}

fn laser_fields() -> Vec<Field> {
    let d = LaserSettings::default();
    let presets = Material::ALL
        .iter()
        .map(|m| {
            let n = m.numbers();
            json!({
                "value": m.name(),
                "label": format!(
                    "{} (hinge {} mm, kerf {} mm, {} mm thick)",
                    m.name(), n.hinge_mm, n.kerf_mm, n.thickness_mm
                ),
                "sets": {
                    "hinge_mm": n.hinge_mm,
                    "kerf_mm": n.kerf_mm,
                    "thickness_mm": n.thickness_mm,
                },
            })
        })
        .collect();
    vec![
        Field {
            name: "material",
            label: "material preset",
            kind: "choice",
            unit: None,
            default: Value::Null,
            zero_ok: None,
            choices: presets,
            help: "sets hinge, kerf and thickness; any of them can still be changed",
        },
        number(
            "hinge_mm",
            "hinge width",
            d.hinge_mm,
            "bridge of material left at each joint",
        ),
        number(
            "kerf_mm",
            "laser kerf",
            d.kerf_mm,
            "width of the laser's cut: cut paths are compensated by half of it",
        ),
        number(
            "thickness_mm",
            "sheet thickness",
            d.thickness_mm,
            "written in the file's metadata",
        ),
        Field {
            zero_ok: Some(true),
            ..number(
                "margin_mm",
                "margin",
                d.margin_mm,
                "empty margin round the sheet",
            )
        },
        number(
            "stroke_mm",
            "line width",
            d.stroke_mm,
            "stroke width of the SVG's lines (a hairline)",
        ),
        colour(
            "cut_colour",
            "cut colour",
            &d.colours.cut,
            "colour of the cut group / layer",
        ),
        colour(
            "score_colour",
            "score colour",
            &d.colours.score,
            "colour of the score group / layer",
        ),
        colour(
            "engrave_colour",
            "engrave colour",
            &d.colours.engrave,
            "colour of the engrave group / layer (tile labels)",
        ),
        Field {
            name: "labels",
            label: "engrave tile numbers",
            kind: "flag",
            unit: None,
            default: json!(d.labels),
            zero_ok: None,
            choices: Vec::new(),
            help: "engrave each tile's number at its centre",
        },
    ]
}

fn print_fields() -> Vec<Field> {
    let d = PrintSettings::default();
    vec![
        number(
            "thickness_mm",
            "tile thickness",
            d.thickness_mm,
            "height of the printed tiles",
        ),
        number(
            "hinge_mm",
            "hinge width",
            d.hinge_mm,
            "width of the lamella hinge at each joint, along the edge (at least the nozzle width)",
        ),
        number(
            "lamella_mm",
            "lamella thickness",
            d.lamella_mm,
            "thickness of the hinges at the bottom face (thinner than the tiles)",
        ),
        number(
            "gap_mm",
            "gap",
            d.gap_mm,
            "clearance between neighbouring tiles; the outline keeps its size",
        ),
        number(
            "nozzle_mm",
            "nozzle width",
            d.nozzle_mm,
            "the printer's extrusion width: a narrower hinge is refused",
        ),
    ]
}

/// The 3D-print settings of a query: the defaults, then every value given; as `isogami
/// export`'s print flags (`hinge_mm` and `thickness_mm` are shared with the laser group,
/// as the CLI's flags are).
fn apply_print(options: &mut ExportOptions, values: &Values<'_>) -> ApiResult<()> {
    let mut s = PrintSettings::default();
    for (key, slot) in [
        ("thickness_mm", &mut s.thickness_mm),
        ("hinge_mm", &mut s.hinge_mm),
        ("lamella_mm", &mut s.lamella_mm),
        ("gap_mm", &mut s.gap_mm),
        ("nozzle_mm", &mut s.nozzle_mm),
    ] {
        if let Some(v) = values.number(key)? {
            *slot = v;
        }
    }
    options.print = s;
    Ok(())
}

/// The query values of one request, each key at most once.
pub struct Values<'a>(pub &'a [(String, String)]);

/// Longest design text (a spec, a name or design JSON) a request may carry: a query's
/// `design` ([`Values::design`]), a live deployment's or saved design's posted one and the
/// shape endpoints' (each through [`check_design_text`]).
pub const MAX_DESIGN: usize = 16 * 1024;

/// `text` if it is at most [`MAX_DESIGN`] bytes, else 400 `bad_parameter`: the one length
/// check of a design's text, wherever the text comes from.
pub fn check_design_text(text: &str) -> ApiResult<&str> {
    if text.len() > MAX_DESIGN {
        return Err(ApiError::bad_parameter("design text longer than 16 KiB"));
    }
    Ok(text)
}

impl Values<'_> {
    /// The value of `key`, if given.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| v.trim())
    }

    /// The `design` parameter: required, not empty, at most [`MAX_DESIGN`] bytes.
    pub fn design(&self) -> ApiResult<&str> {
        let design = self
            .get("design")
            .filter(|d| !d.is_empty())
            .ok_or_else(|| ApiError::bad_parameter("missing parameter design"))?;
        check_design_text(design)
    }

    /// A number (any finite or non-finite value the library then judges), if given.
    pub fn number(&self, key: &str) -> ApiResult<Option<f64>> {
        self.get(key)
            .map(|text| {
                text.parse::<f64>().map_err(|_| {
                    ApiError::bad_parameter(format!(
                        "{key} {:?}: expected a number",
                        truncate(text)
                    ))
                })
            })
            .transpose()
    }

    /// A flag: `true`/`1` or `false`/`0`, if given.
    pub fn flag(&self, key: &str) -> ApiResult<Option<bool>> {
        self.get(key)
            .map(|text| match text {
                "true" | "1" => Ok(true),
                "false" | "0" => Ok(false),
                _ => Err(ApiError::bad_parameter(format!(
                    "{key} {:?}: expected true or false",
                    truncate(text)
                ))),
            })
            .transpose()
    }
}

/// The laser settings of a query: the preset (or the defaults), then every value given; as
/// `isogami export`'s laser flags.
fn apply_laser(options: &mut ExportOptions, values: &Values<'_>) -> ApiResult<()> {
    let mut s = match values.get("material") {
        None | Some("") => LaserSettings::default(),
        Some(name) => {
            let m = Material::from_name(name).ok_or_else(|| {
                let names: Vec<&str> = Material::ALL.iter().map(|m| m.name()).collect();
                ApiError::bad_parameter(format!(
                    "material {:?}: expected one of {}",
                    truncate(name),
                    names.join(", ")
                ))
            })?;
            LaserSettings::for_material(m)
        }
    };
    for (key, slot) in [
        ("hinge_mm", &mut s.hinge_mm),
        ("kerf_mm", &mut s.kerf_mm),
        ("thickness_mm", &mut s.thickness_mm),
        ("margin_mm", &mut s.margin_mm),
        ("stroke_mm", &mut s.stroke_mm),
    ] {
        if let Some(v) = values.number(key)? {
            *slot = v;
        }
    }
    for (key, slot) in [
        ("cut_colour", &mut s.colours.cut),
        ("score_colour", &mut s.colours.score),
        ("engrave_colour", &mut s.colours.engrave),
    ] {
        if let Some(v) = values.get(key) {
            *slot = v.to_string();
        }
    }
    if let Some(labels) = values.flag("labels")? {
        s.labels = labels;
    }
    options.laser = s;
    Ok(())
}
