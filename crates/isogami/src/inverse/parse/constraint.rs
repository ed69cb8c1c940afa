//! Constraints of the text form: `families=…`, `cells=…`, `tiles<=N`, `rotation>=DEG`,
//! `kerf>=K`, `hinge>=H`.

use super::number;
use crate::inverse::error::InverseError;
use crate::inverse::target::Constraints;
use crate::math::Real;
use crate::topology::quote_input;

const CONSTRAINTS: &str = "families, cells, tiles, rotation, kerf, hinge";

/// Reads one constraint into `c`.
pub(super) fn constraint(text: &str, c: &mut Constraints) -> Result<(), InverseError> {
    let t = text.trim();
    let bad = |problem: &str| InverseError::BadConstraint {
        text: quote_input(t),
        problem: problem.to_string(),
    };
    let (key, op, value) = ["<=", ">=", "="]
        .iter()
        .find_map(|op| t.split_once(op).map(|(k, v)| (k, *op, v)))
        .ok_or_else(|| bad("expected KEY=VALUE, KEY>=VALUE or KEY<=VALUE"))?;
    let key = key.trim().to_ascii_lowercase();
    let value = value.trim();
    let at_least = |name: &'static str, slot: &mut Option<Real>| -> Result<(), InverseError> {
        if op != ">=" {
            return Err(bad(&format!("{name} takes '>=' (a lower bound)")));
        }
        if slot.is_some() {
            return Err(InverseError::RepeatedConstraint { key: name });
        }
        *slot = Some(number(name, value)?);
        Ok(())
    };
    match key.as_str() {
        "families" | "family" => {
            if op != "=" || !c.families.is_empty() {
                return Err(bad("families=IH1,IH28 (once)"));
            }
            c.families = value
                .split(',')
                .map(|f| {
                    f.trim()
                        .parse()
                        .map_err(|e: crate::tiling::TilingError| bad(&e.to_string()))
                })
                .collect::<Result<_, _>>()?;
        }
        "cells" | "cell" => {
            if op != "=" || !c.cells.is_empty() {
                return Err(bad("cells=1x1,2x1 (once)"));
            }
            c.cells = value
                .split(',')
                .map(|d| {
                    d.trim()
                        .parse()
                        .map_err(|e: crate::cell::CellError| bad(&e.to_string()))
                })
                .collect::<Result<_, _>>()?;
        }
        "tiles" => {
            let n: u32 = value
                .parse()
                .map_err(|_| bad("the tile count must be a whole number"))?;
            let (lo, hi) = match op {
                ">=" => (Some(n), None),
                "<=" => (None, Some(n)),
                _ => (Some(n), Some(n)),
            };
            for (slot, v) in [(&mut c.min_tiles, lo), (&mut c.max_tiles, hi)] {
                if let Some(v) = v {
                    if slot.is_some() {
                        return Err(InverseError::RepeatedConstraint { key: "tiles" });
                    }
                    *slot = Some(v);
                }
            }
        }
        "rotation" => at_least("rotation", &mut c.min_rotation_deg)?,
        "kerf" => at_least("kerf", &mut c.min_kerf)?,
        "hinge" => at_least("hinge", &mut c.min_hinge)?,
        _ => {
            return Err(InverseError::UnknownConstraint {
                key: quote_input(&key),
                known: CONSTRAINTS,
            })
        }
    }
    Ok(())
}
