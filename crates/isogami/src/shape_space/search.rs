//! Rank-dropping designs the paper's screening cannot find: topologies that are rigid at the
//! default shape but gain one degree of freedom at another valid shape.
//!
//! Every rigid joint topology of a cell is a candidate, far too many to search. This driver
//! searches the natural ones next to known mechanisms: the *neighbours* of each given
//! design, with one joint added on a cut edge or one joint moved to the edge's other end.
//! These are one constraint away from a mechanism, so a shape where the extra constraint is
//! compatible is the typical rank drop. Each rigid neighbour goes through [`rank_drop`]; each
//! shape found is assessed by the catalogue's own admission rule ([`crate::catalog::assess`]:
//! one DOF, not locked at the start, largest expansion past the threshold), which deploys it
//! with frame checks. Runs in parallel (rayon).

use super::kernel::dof;
use super::rank_drop::rank_drop;
use super::ShapeSettings;
use crate::catalog::{assess, Assessment, CatalogSettings};
use crate::math::Real;
use crate::topology::{Design, JointChoice};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeSet;

/// A rank-dropping design found next to a known one.
#[derive(Debug, Clone, Serialize)]
pub struct Finding {
    /// The known design it was found next to.
    pub from: String,
    /// The rigid neighbour topology at the default shape of `from`.
    pub rigid: String,
    /// The shape with one DOF.
    pub spec: String,
    /// Admitted by the catalogue's rule (one DOF, opens, reaches the threshold).
    pub admitted: bool,
    /// Largest principal expansion of its deployment (when it deployed).
    pub max_expansion: Option<Real>,
    /// Why it was not admitted.
    pub rejection: Option<String>,
}

/// What a search did.
#[derive(Debug, Clone, Serialize)]
pub struct SearchReport {
    /// Designs given.
    pub designs: usize,
    /// Rigid neighbours searched.
    pub rigid_neighbours: usize,
    /// Shapes with one DOF found, one per neighbour topology.
    pub findings: Vec<Finding>,
}

/// The neighbours of `design`: one joint added on a cut edge (either end), or one joint moved
/// to the other end of its edge; only those whose cell builds.
pub fn neighbours(design: &Design) -> Vec<Design> {
    let mut out = Vec::new();
    for (k, j) in design.joints.iter().enumerate() {
        let choices: &[JointChoice] = match j {
            JointChoice::None => &[JointChoice::A, JointChoice::B],
            JointChoice::A => &[JointChoice::B],
            JointChoice::B => &[JointChoice::A],
            JointChoice::Both => &[],
        };
        for &c in choices {
            let mut d = design.clone();
            d.joints[k] = c;
            if d.cell().is_ok() {
                out.push(d);
            }
        }
    }
    out
}

/// Searches the rigid neighbours of `designs` for rank-dropping shapes.
pub fn search_neighbours(
    designs: &[Design],
    settings: &ShapeSettings,
    catalog: &CatalogSettings,
) -> SearchReport {
    let mut seen = BTreeSet::new();
    let mut rigid: Vec<(String, Design)> = Vec::new();
    for d in designs {
        for n in neighbours(d) {
            if !n.params.is_empty()
                && matches!(dof(&n, settings.mobility), Ok((0, _)))
                && seen.insert(n.to_string())
            {
                rigid.push((d.to_string(), n));
            }
        }
    }
    let findings: Vec<Finding> = rigid
        .par_iter()
        .filter_map(|(from, n)| {
            let found = rank_drop(n, settings).ok()??;
            let (admitted, max_expansion, rejection) =
                match assess(&found.design, catalog, &mut |_| true) {
                    Ok(Assessment::Admitted(r)) => (true, Some(r.max_expansion), None),
                    Ok(Assessment::Rejected(why)) => (false, None, Some(why.to_string())),
                    Err(e) => (false, None, Some(e.to_string())),
                };
            Some(Finding {
                from: from.clone(),
                rigid: n.to_string(),
                spec: found.spec,
                admitted,
                max_expansion,
                rejection,
            })
        })
        .collect();
    SearchReport {
        designs: designs.len(),
        rigid_neighbours: rigid.len(),
        findings,
    }
}
