//! The data dictionary of a catalogue row: every field of [`DesignSummary`] with its type,
//! unit and meaning, for the browser's CSV/JSON downloads and the API's `/api/dictionary`.

use serde::Serialize;

/// One field of a catalogue row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct FieldDoc {
    /// Name as serialised (JSON key, CSV column).
    pub field: &'static str,
    /// JSON type; `|null` when it can be missing.
    #[serde(rename = "type")]
    pub kind: &'static str,
    /// Unit, or "" for counts and names.
    pub unit: &'static str,
    /// What it means.
    pub meaning: &'static str,
}

const fn doc(
    field: &'static str,
    kind: &'static str,
    unit: &'static str,
    meaning: &'static str,
) -> FieldDoc {
    FieldDoc {
        field,
        kind,
        unit,
        meaning,
    }
}

/// Every field of [`DesignSummary`](crate::DesignSummary), in serialisation order.
pub const DICTIONARY: &[FieldDoc] = &[
    doc("spec", "string", "", "Design spec FAMILY:PARAMS:CELL:JOINTS; unique in a database"),
    doc("origin", "string", "", "explored (found by the exploration) or user (saved from the browser)"),
    doc("family", "string", "", "Isohedral tiling family IH1..IH93 (Kaplan's numbering)"),
    doc("cell", "[integer, integer]", "", "Supercell size [a, b]: the minimal cell repeated a times along t1, b along t2"),
    doc("tile_count", "integer", "", "Tiles in the (super)cell"),
    doc("joints", "string", "", "One character per unique edge of the cell: - cut, a/b pin joint at that end"),
    doc("topology", "string", "", "Spec of the joint topology at the family's default parameters this design was sampled from"),
    doc("params", "number[]", "", "Shape parameters v0.. of the family (tactile's parameterisation)"),
    doc("behaviour", "string|null", "", "isotropic, anisotropic or orthotropic expansion; null when the sheet does not expand"),
    doc("linkage_signature", "string|null", "", "Linkages of the sheet by bar count, e.g. 2×4-bar + 1×6-bar"),
    doc("end_reason", "string", "", "Why deployment stopped: contact_limit, locked, step_size_exhausted, stalled, max_steps, diverged or solver_failure"),
    doc("method", "string", "", "Deployment method: rigid-modes, ncm or springs"),
    doc("dof", "integer", "", "Degrees of freedom of the closed state (1 = deploys by one motion)"),
    doc("kerf", "number", "L", "Cut width relative to the cell's mean edge length L"),
    doc("max_expansion", "number", "1", "Largest principal expansion reached (singular value of F minus 1)"),
    doc("min_expansion", "number", "1", "Smallest principal expansion reached (singular value of F minus 1)"),
    doc("max_area_ratio", "number", "1", "Largest area ratio det F reached (open area / closed area)"),
    doc("max_tile_rotation", "number", "rad", "Largest tile rotation from the closed state"),
    doc("poisson_min", "number|null", "1", "Smallest Poisson-like ratio -ε_min/ε_max over the open frames; null when the sheet never opens"),
    doc("poisson_max", "number|null", "1", "Largest Poisson-like ratio over the open frames"),
    doc("steps", "integer", "", "Accepted deployment states, the closed one included"),
    doc("finite_raw_dof", "integer|null", "", "Degrees of freedom of the raw 6×6-cell patch as cut (free boundary, at the opened state t = 0.3; 1 = it opens with the design's one motion); null for user designs"),
    doc("finite_covered", "number|null", "1", "Fraction of the 6×6-cell patch's area kept by its completion to a one-DOF sheet (0.5 to 1); null when no such sheet exists (e.g. isostatic cells) or for user designs"),
    doc("open_t", "number|null", "1", "t of the most open state (largest area ratio) along the path, 0 closed to 1 where the path ends; export's `--t open` writes it; null for user designs"),
    doc("end_area_ratio", "number|null", "1", "Area ratio where the path ends (the contact limit, export's `--t limit`); below max_area_ratio when the sheet closes again past its most open state; null for user designs"),
    doc("shape_tolerance", "number|null", "L", "Largest vertex displacement, relative to the mean edge length L, under which shapes moved both ways along a fixed direction of the shape parameters keep 95 % of the largest area ratio (levels 1e-6 to 2.5e-2; 0.0025 = ±0.05 mm at 20 mm edges); 0 for a special design, which opens only at its exact shape; null when the family has no shape parameters, or for user designs"),
    doc("fabrication_kept", "number|null", "1", "Largest area ratio of the shapes moved by the fabrication tolerance (±0.0025 L, ±0.05 mm at 20 mm edges), as a fraction of the design's (the smaller of the two moves; above 1 when both open further); null like shape_tolerance"),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::records::{DesignSummary, Origin};

    /// The dictionary lists exactly the serialised fields, in order, and types agree with
    /// the JSON values of a real summary.
    #[test]
    fn dictionary_matches_the_serialised_summary() {
        let design = isogami::api::resolve_design("rotating-squares").unwrap();
        let summary = DesignSummary {
            spec: design.to_string(),
            origin: Origin::Explored,
            family: design.family,
            cell: design.dims,
            tile_count: 2,
            joints: "ab".into(),
            topology: design.to_string(),
            params: vec![0.5],
            behaviour: None,
            linkage_signature: Some("1×4-bar".into()),
            end_reason: "contact_limit".into(),
            method: isogami::deploy::Method::RigidModes,
            dof: 1,
            kerf: 0.01,
            max_expansion: 0.4,
            min_expansion: 0.4,
            max_area_ratio: 2.0,
            max_tile_rotation: 0.7,
            poisson_min: None,
            poisson_max: Some(-1.0),
            steps: 100,
            finite_raw_dof: Some(3),
            finite_covered: None,
            open_t: Some(0.5),
            end_area_ratio: Some(1.0),
            shape_tolerance: Some(0.0),
            fabrication_kept: Some(0.3),
        };
        let json = serde_json::to_value(&summary).unwrap();
        let object = json.as_object().unwrap();
        let keys: Vec<&str> = object.keys().map(String::as_str).collect();
        let fields: Vec<&str> = DICTIONARY.iter().map(|d| d.field).collect();
        let mut sorted = fields.clone();
        sorted.sort();
        let mut sorted_keys = keys.clone();
        sorted_keys.sort();
        assert_eq!(sorted, sorted_keys);
        for d in DICTIONARY {
            let v = &object[d.field];
            let ok = d.kind.split('|').any(|k| match k {
                "string" => v.is_string(),
                "integer" => v.is_u64() || v.is_i64(),
                "number" => v.is_number(),
                "null" => v.is_null(),
                t if t.ends_with("[]") || t.starts_with('[') => v.is_array(),
                _ => false,
            });
            assert!(ok, "{}: {} is not {}", d.field, v, d.kind);
        }
    }
}
