//! Why a run found nothing: which constraint removed the candidates, and what made the
//! screened designs invalid, in words a user can act on.

use super::error::InverseError;
use super::evaluate::{Evaluation, Invalidity, Outcome};
use super::target::Constraints;
use super::Candidate;
use crate::catalog::Rejection;
use crate::math::Real;
use crate::topology::Design;
use std::collections::BTreeSet;
use std::fmt::Display;

/// Tiles in a design's cell.
pub(crate) fn tile_count(d: &Design) -> usize {
    d.family.info().aspect_count * usize::from(d.dims.a()) * usize::from(d.dims.b())
}

/// "a, b and 3 more" for the first few of a list.
fn some_of<T: Display>(items: &BTreeSet<T>) -> String {
    let shown: Vec<String> = items.iter().take(6).map(|x| x.to_string()).collect();
    match items.len().saturating_sub(shown.len()) {
        0 => shown.join(", "),
        more => format!("{} and {more} more", shown.join(", ")),
    }
}

/// The error for candidates none of which passes `constraints`' family, cell and tile
/// bounds: each constraint that removes some, with how many and what the candidates offer
/// instead.
pub(crate) fn none_admitted(candidates: &[Candidate], constraints: &Constraints) -> InverseError {
    let c = constraints;
    let designs = || candidates.iter().map(|x| &x.design);
    let tiles: BTreeSet<usize> = designs().map(tile_count).collect();
    let tile_range = match (tiles.first(), tiles.last()) {
        (Some(lo), Some(hi)) if lo != hi => format!("their cells have {lo} to {hi} tiles"),
        (Some(n), _) => format!("their cells have {n} tiles"),
        _ => String::new(),
    };
    let mut removed = Vec::new();
    let mut count = |name: String, gone: usize, offer: String| {
        if gone > 0 {
            removed.push(format!("{name} removes {gone} ({offer})"));
        }
    };
    if !c.families.is_empty() {
        let names: Vec<String> = c.families.iter().map(|f| f.to_string()).collect();
        let have: BTreeSet<_> = designs().map(|d| d.family).collect();
        let gone = designs()
            .filter(|d| !c.families.contains(&d.family))
            .count();
        count(
            format!("families={}", names.join(",")),
            gone,
            format!("they are of {}", some_of(&have)),
        );
    }
    if !c.cells.is_empty() {
        let names: Vec<String> = c.cells.iter().map(|d| d.to_string()).collect();
        let have: BTreeSet<String> = designs().map(|d| d.dims.to_string()).collect();
        let gone = designs().filter(|d| !c.cells.contains(&d.dims)).count();
        count(
            format!("cells={}", names.join(",")),
            gone,
            format!("their cells are {}", some_of(&have)),
        );
    }
    if let Some(m) = c.min_tiles {
        let gone = designs().filter(|d| tile_count(d) < m as usize).count();
        count(format!("tiles>={m}"), gone, tile_range.clone());
    }
    if let Some(m) = c.max_tiles {
        let gone = designs().filter(|d| tile_count(d) > m as usize).count();
        count(format!("tiles<={m}"), gone, tile_range);
    }
    if removed.is_empty() {
        // Each constraint alone leaves some, but not together.
        removed.push("each constraint leaves some, but no design passes all of them".into());
    }
    InverseError::NoneAdmitted {
        total: candidates.len(),
        removed: removed.join("; "),
    }
}

/// What made the screened designs invalid, most common reason first: "40 turn their tiles by
/// less than rotation>=30 (at most 22.1°); 8 fail hinge>=0.2 (…)".
pub(crate) fn invalid_reasons<'a>(
    evaluations: impl Iterator<Item = &'a Evaluation>,
    constraints: &Constraints,
) -> String {
    // (reason, count, an example or the largest rotation reached)
    let mut reasons: Vec<(String, usize, String)> = Vec::new();
    let mut most_rotation = Real::NEG_INFINITY;
    for e in evaluations {
        let Outcome::Invalid(why) = &e.outcome else {
            continue;
        };
        let reason = match why {
            Invalidity::Rotation { reached_deg, .. } => {
                most_rotation = most_rotation.max(*reached_deg);
                format!(
                    "turn their tiles by less than rotation>={}",
                    constraints.min_rotation_deg.unwrap_or(0.0)
                )
            }
            Invalidity::Hinge { .. } => format!(
                "leave no room for a hinge>={}",
                constraints.min_hinge.unwrap_or(0.0)
            ),
            Invalidity::Excluded { what } => format!("are excluded by the {what} constraint"),
            Invalidity::Kerf { .. } => "have a kerf outside the allowed range".into(),
            Invalidity::Shape { .. } => "have a tile shape that is refused".into(),
            Invalidity::Build { .. } => "do not build a cell".into(),
            Invalidity::Rejected { rejection } => match rejection {
                Rejection::Mobility { .. } => "do not move with one degree of freedom".into(),
                Rejection::Locked => "are locked by contact at the start".into(),
                Rejection::BelowThreshold { .. } => "open less than the expansion threshold".into(),
            },
            Invalidity::Failed { .. } => "fail to deploy".into(),
            Invalidity::Unmet { .. } => "cannot be scored for the target".into(),
        };
        match reasons.iter_mut().find(|(r, ..)| *r == reason) {
            Some((_, n, _)) => *n += 1,
            None => reasons.push((reason, 1, why.to_string())),
        }
    }
    reasons.sort_by_key(|r| std::cmp::Reverse(r.1));
    if reasons.is_empty() {
        return "no design was deployed".into();
    }
    reasons
        .into_iter()
        .map(|(reason, n, example)| {
            if reason.starts_with("turn their tiles") {
                format!("{n} {reason} (at most {most_rotation:.1}°)")
            } else {
                format!("{n} {reason} (e.g. {example})")
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}
