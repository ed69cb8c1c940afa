//! Rows as column values: the one place that maps records to the columns of the schema and
//! back, so the values that are checksummed at insert are exactly the values read back.

use crate::checksum;
use crate::error::{StoreError, StoreResult};
use crate::records::{DesignSummary, Origin, StageCount, WorkUnitRecord};
use crate::schema::PARAM_SLOTS;
use isogami::cell::CellDims;
use isogami::deploy::Method;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use rusqlite::types::Value;
use rusqlite::Row;

/// Columns of a `designs` row, in the order of [`design_values`] (checksum excluded).
pub(crate) const DESIGN_COLUMNS: &str = "spec, origin, work_unit, family, cell, cell_a, cell_b, \
    tile_count, joints, topology, param_count, p0, p1, p2, p3, p4, p5, behaviour, \
    linkage_signature, end_reason, method, dof, kerf, max_expansion, min_expansion, max_area_ratio, \
    max_tile_rotation, poisson_min, poisson_max, steps, finite_raw_dof, finite_covered, open_t, \
    end_area_ratio, shape_tolerance, fabrication_kept";

/// Number of columns in [`DESIGN_COLUMNS`].
pub(crate) const DESIGN_COLUMN_COUNT: usize = 36;

/// The columns of a schema-4 `designs` row (the first [`DESIGN_COLUMNS`], without the
/// margin ones), which its checksum covers: read by the migration.
pub(crate) const DESIGN_COLUMN_COUNT_V4: usize = 32;

/// The columns of a schema-3 `designs` row (the first [`DESIGN_COLUMNS`], without the
/// finite-sheet ones), which its checksum covers: read by the migration.
pub(crate) const DESIGN_COLUMN_COUNT_V3: usize = 30;

fn text(s: &str) -> Value {
    Value::Text(s.to_string())
}

fn opt_text(s: Option<&str>) -> Value {
    s.map_or(Value::Null, text)
}

fn opt_real(x: Option<f64>) -> Value {
    x.map_or(Value::Null, Value::Real)
}

/// The values of a `designs` row.
pub(crate) fn design_values(s: &DesignSummary, work_unit: Option<&str>) -> Vec<Value> {
    let mut v = vec![
        text(&s.spec),
        text(s.origin.as_str()),
        opt_text(work_unit),
        Value::Integer(i64::from(s.family.number())),
        text(&s.cell.to_string()),
        Value::Integer(i64::from(s.cell.a())),
        Value::Integer(i64::from(s.cell.b())),
        Value::Integer(i64::from(s.tile_count)),
        text(&s.joints),
        text(&s.topology),
        Value::Integer(s.params.len() as i64),
    ];
    v.extend((0..PARAM_SLOTS).map(|k| opt_real(s.params.get(k).copied())));
    v.extend([
        opt_text(s.behaviour.map(BehaviourClass::as_str)),
        opt_text(s.linkage_signature.as_deref()),
        text(&s.end_reason),
        text(&s.method.to_string()),
        Value::Integer(i64::from(s.dof)),
        Value::Real(s.kerf),
        Value::Real(s.max_expansion),
        Value::Real(s.min_expansion),
        Value::Real(s.max_area_ratio),
        Value::Real(s.max_tile_rotation),
        opt_real(s.poisson_min),
        opt_real(s.poisson_max),
        Value::Integer(s.steps as i64),
        s.finite_raw_dof
            .map_or(Value::Null, |n| Value::Integer(i64::from(n))),
        opt_real(s.finite_covered),
        opt_real(s.open_t),
        opt_real(s.end_area_ratio),
        opt_real(s.shape_tolerance),
        opt_real(s.fabrication_kept),
    ]);
    debug_assert_eq!(v.len(), DESIGN_COLUMN_COUNT);
    v
}

/// Reads `n` columns starting at `first` as raw values.
pub(crate) fn raw_values(row: &Row<'_>, first: usize, n: usize) -> rusqlite::Result<Vec<Value>> {
    (first..first + n).map(|i| row.get::<_, Value>(i)).collect()
}

/// Checks a row's values against its stored checksum.
pub(crate) fn verify(
    values: &[Value],
    stored: i64,
    what: impl FnOnce() -> String,
) -> StoreResult<()> {
    if checksum::of_values(values) == stored {
        Ok(())
    } else {
        Err(StoreError::Damaged(format!(
            "{} fails its checksum",
            what()
        )))
    }
}

/// Typed access to a row's values; every mismatch is damage.
struct Reader<'a> {
    values: &'a [Value],
    at: usize,
}

fn wrong(at: usize, v: &Value, wanted: &str) -> String {
    format!("column {at} is {:?}, not {wanted}", v.data_type())
}

impl<'a> Reader<'a> {
    fn next(&mut self) -> (usize, &'a Value) {
        let at = self.at;
        self.at += 1;
        (at, self.values.get(at).unwrap_or(&Value::Null))
    }

    fn text(&mut self) -> Result<String, String> {
        match self.next() {
            (_, Value::Text(s)) => Ok(s.clone()),
            (at, v) => Err(wrong(at, v, "text")),
        }
    }

    fn opt_text(&mut self) -> Result<Option<String>, String> {
        match self.next() {
            (_, Value::Null) => Ok(None),
            (_, Value::Text(s)) => Ok(Some(s.clone())),
            (at, v) => Err(wrong(at, v, "text")),
        }
    }

    fn int(&mut self) -> Result<i64, String> {
        match self.next() {
            (_, Value::Integer(i)) => Ok(*i),
            (at, v) => Err(wrong(at, v, "an integer")),
        }
    }

    fn opt_int(&mut self) -> Result<Option<i64>, String> {
        match self.next() {
            (_, Value::Null) => Ok(None),
            (_, Value::Integer(i)) => Ok(Some(*i)),
            (at, v) => Err(wrong(at, v, "an integer")),
        }
    }

    fn real(&mut self) -> Result<f64, String> {
        match self.next() {
            (_, Value::Real(x)) => Ok(*x),
            (at, v) => Err(wrong(at, v, "a number")),
        }
    }

    fn opt_real(&mut self) -> Result<Option<f64>, String> {
        match self.next() {
            (_, Value::Null) => Ok(None),
            (_, Value::Real(x)) => Ok(Some(*x)),
            (at, v) => Err(wrong(at, v, "a number")),
        }
    }
}

fn small<T: TryFrom<i64>>(x: i64, what: &str) -> Result<T, String> {
    T::try_from(x).map_err(|_| format!("{what} {x} out of range"))
}

/// The summary of a `designs` row read as [`DESIGN_COLUMNS`]; the work unit is returned apart.
pub(crate) fn design_from_values(
    values: &[Value],
) -> Result<(DesignSummary, Option<String>), String> {
    let mut r = Reader { values, at: 0 };
    let spec = r.text()?;
    let origin_name = r.text()?;
    let origin =
        Origin::from_name(&origin_name).ok_or(format!("unknown origin '{origin_name}'"))?;
    let work_unit = r.opt_text()?;
    let family = Family::from_number(small(r.int()?, "family")?).map_err(|e| e.to_string())?;
    let cell_text = r.text()?;
    let cell: CellDims = cell_text
        .parse()
        .map_err(|e: isogami::cell::CellError| e.to_string())?;
    let (a, b) = (r.int()?, r.int()?);
    if (a, b) != (i64::from(cell.a()), i64::from(cell.b())) {
        return Err(format!("cell {cell_text} but dimensions {a}x{b}"));
    }
    let tile_count = small(r.int()?, "tile count")?;
    let joints = r.text()?;
    let topology = r.text()?;
    let param_count: usize = small(r.int()?, "parameter count")?;
    if param_count > PARAM_SLOTS {
        return Err(format!("{param_count} shape parameters"));
    }
    let mut params = Vec::with_capacity(param_count);
    for k in 0..PARAM_SLOTS {
        match (k < param_count, r.opt_real()?) {
            (true, Some(x)) => params.push(x),
            (false, None) => {}
            _ => {
                return Err(format!(
                    "shape parameter slot p{k} disagrees with the count"
                ))
            }
        }
    }
    let behaviour = match r.opt_text()? {
        None => None,
        Some(name) => Some(
            serde_json::from_value::<BehaviourClass>(serde_json::Value::String(name.clone()))
                .map_err(|_| format!("unknown behaviour class '{name}'"))?,
        ),
    };
    let linkage_signature = r.opt_text()?;
    let end_reason = r.text()?;
    let method_name = r.text()?;
    let method: Method = method_name
        .parse()
        .map_err(|e: isogami::error::SettingsError| e.to_string())?;
    let dof = small(r.int()?, "dof")?;
    Ok((
        DesignSummary {
            spec,
            origin,
            family,
            cell,
            tile_count,
            joints,
            topology,
            params,
            behaviour,
            linkage_signature,
            end_reason,
            method,
            dof,
            kerf: r.real()?,
            max_expansion: r.real()?,
            min_expansion: r.real()?,
            max_area_ratio: r.real()?,
            max_tile_rotation: r.real()?,
            poisson_min: r.opt_real()?,
            poisson_max: r.opt_real()?,
            steps: small(r.int()?, "steps")?,
            finite_raw_dof: r
                .opt_int()?
                .map(|n| small(n, "finite raw dof"))
                .transpose()?,
            finite_covered: r.opt_real()?,
            open_t: r.opt_real()?,
            end_area_ratio: r.opt_real()?,
            shape_tolerance: r.opt_real()?,
            fabrication_kept: r.opt_real()?,
        },
        work_unit,
    ))
}

/// Reads a `designs` row selected as [`DESIGN_COLUMNS`] followed by `checksum`, starting at
/// column `first`, and verifies it.
pub(crate) fn read_design(
    row: &Row<'_>,
    first: usize,
) -> StoreResult<(DesignSummary, Option<String>)> {
    let values = raw_values(row, first, DESIGN_COLUMN_COUNT)?;
    let stored: i64 = row.get(first + DESIGN_COLUMN_COUNT)?;
    let spec = match values.first() {
        Some(Value::Text(s)) => s.clone(),
        _ => "?".into(),
    };
    verify(&values, stored, || format!("design row {spec}"))?;
    design_from_values(&values).map_err(|e| StoreError::Damaged(format!("design row {spec}: {e}")))
}

/// The values of a `design_data` row covered by its checksum: the spec binds the documents to
/// their design.
pub(crate) fn data_values(spec: &str, report: &str, linkages: Option<&str>) -> [Value; 3] {
    [text(spec), text(report), opt_text(linkages)]
}

/// The values of a work unit and its stages covered by the unit's checksum.
pub(crate) fn unit_values(unit: &WorkUnitRecord, stages: &[StageCount]) -> Vec<Value> {
    let mut v = vec![
        text(&unit.id),
        text(&unit.family),
        text(&unit.cell),
        text(&unit.kind),
        Value::Real(unit.seconds),
    ];
    for s in stages {
        v.extend([
            text(&s.stage),
            Value::Integer(s.count_in as i64),
            Value::Integer(s.count_out as i64),
            Value::Real(s.seconds),
        ]);
    }
    v
}

/// The values of a `unit_memory` row covered by its checksum.
pub(crate) fn unit_memory_values(unit: &str, peak_rss_bytes: i64) -> [Value; 2] {
    [text(unit), Value::Integer(peak_rss_bytes)]
}

/// The values of a `motion_classes` row covered by its checksum.
pub(crate) fn motion_class_values(topology: &str, representative: &str) -> [Value; 2] {
    [text(topology), text(representative)]
}

/// The values of a `cell_twins` row covered by its checksum.
pub(crate) fn cell_twin_values(spec: &str, kept: &str) -> [Value; 2] {
    [text(spec), text(kept)]
}

/// The values of a `meta` row covered by its checksum.
pub(crate) fn meta_values(key: &str, value: &str) -> [Value; 2] {
    [text(key), text(value)]
}
