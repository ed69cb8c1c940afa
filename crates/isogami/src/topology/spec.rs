//! The compact spec string `FAMILY:PARAMS:CELL:JOINTS`, e.g. `IH28:0.1,0.2:2x1:ab-ba-ab-b`.
//!
//! PARAMS are comma-separated numbers (empty for families without parameters, or `default`),
//! read into and written in their canonical form (12 significant digits, see
//! [`crate::tiling::canonical_param`]) so that equal shapes have equal specs; JOINTS has one
//! character per unique edge: `-` none, `a`/`b` a pin at that endpoint, `x` both. Parsing
//! then formatting gives the canonical spec, and formatting then parsing a design made by the
//! library (whose parameters are canonical) gives back the same design bit for bit.

use super::design::{Design, JointChoice};
use super::error::DesignError;
use crate::cell::CellDims;
use crate::tiling::TilingError;
use crate::tiling::{canonical_param, Family};
use std::fmt;
use std::str::FromStr;

impl fmt::Display for Design {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let params: Vec<String> = self
            .params
            .iter()
            .map(|&p| format!("{}", canonical_param(p)))
            .collect();
        let joints: String = self.joints.iter().map(|j| j.to_char()).collect();
        write!(
            f,
            "{}:{}:{}:{}",
            self.family,
            params.join(","),
            self.dims,
            joints
        )
    }
}

impl FromStr for Design {
    type Err = DesignError;

    /// Reads a spec; its parameters become canonical.
    fn from_str(s: &str) -> Result<Design, DesignError> {
        let raw = parse_exact(s)?;
        Ok(raw.at_params(&raw.params))
    }
}

/// Reads a spec keeping its parameters exactly as written (not canonical): for translating
/// old specs, whose joint labels depended on the exact shape.
pub(super) fn parse_exact(s: &str) -> Result<Design, DesignError> {
    let fields: Vec<&str> = s.trim().split(':').collect();
    if fields.len() != 4 {
        return Err(DesignError::FieldCount {
            fields: fields.len(),
            input: truncate(s),
        });
    }
    let family: Family = fields[0].parse()?;
    let params = parse_params(family, fields[1])?;
    let dims: CellDims = fields[2].parse()?;
    let joints = fields[3]
        .chars()
        .enumerate()
        .map(|(i, c)| {
            JointChoice::from_char(c).ok_or(DesignError::JointChar { index: i, found: c })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Design {
        family,
        params,
        dims,
        joints,
    })
}

fn parse_params(family: Family, text: &str) -> Result<Vec<f64>, DesignError> {
    let t = text.trim();
    if t == "default" {
        return Ok(family.default_params());
    }
    if t.is_empty() {
        return Ok(Vec::new());
    }
    t.split(',')
        .enumerate()
        .map(|(i, p)| {
            let v: f64 = p.trim().parse().map_err(|_| DesignError::ParamNotNumber {
                index: i,
                input: truncate(p),
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(TilingError::ParamNotFinite { index: i, value: v }.into())
            }
        })
        .collect()
}

/// At most 40 characters of user input, for error messages.
/// User input as it may appear inside a one-line message: at most 40 characters, control
/// characters and line breaks escaped.
pub(crate) fn truncate(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out.escape_debug().to_string()
}
