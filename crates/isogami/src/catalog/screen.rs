//! Cheap screens before a full deployment (issue 13, "cheap screens first"): a design that
//! contact locks at the start is recognised from its first-order motion in microseconds
//! instead of a deployment that tries both signs and halves its step until it gives up.
//!
//! Deployment tries both signs ±v of the closed state's motion and calls a sign opening when
//! it travels a probe of 4 kerfs of arc length (deploy's `opening` module); a design where
//! neither does is locked. Every cut starts a kerf wide (each tile's collision polygon is
//! inset by half the kerf), and across a unique edge the two tiles approach at the first-order
//! rate −opening (the edge endpoints' relative normal velocity per unit of arc length along
//! the unit motion vector, [`edge_rates`]): with a closing rate r the cut shuts after about
//! kerf / r of arc. A sign is **blocked** when some edge closes at a rate of at least
//! [`BLOCKING_RATE`] = 1/4, i.e. shuts within the probe; a design is screened out when both
//! signs are blocked, and only when the expansion threshold is at least
//! [`THRESHOLD_KERFS`] kerfs (see below). A design with more than one degree of freedom, or
//! whose analysis fails, is not screened: the full assessment decides it.
//!
//! Why this never drops a design the assessment admits. Measured on the 10,467 unique
//! topologies of 16 units of the default run (the hexagon cells IH21 1x1, IH23 3x1, IH22 2x1,
//! IH27, IH28, IH6, IH32 1x1, IH2, IH3 2x1, squares IH41 4x2, IH44, IH45 2x2, IH54 2x1, IH10 2x2,
//! triangles IH83, IH90 2x2): every admitted design has a sign along which no edge closes at
//! all (its smaller closing rate is 1e-13, roundoff); 6,624 designs have both signs blocked,
//! 6,533 of them deploy as locked and the other 91 stop after 2–6 tiny steps, the largest
//! expansion any of them reaches is 1e-4 (0.01 kerf). Over the designs of the sample whose
//! two signs both close some cut (rate above 0.01) but which are not locked, the expansion
//! reached is at most 0.19 per kerf / r of arc, so a design whose cuts shut within the probe
//! (4 kerfs) expands by less than 0.8 kerf: the screen applies only
//! when the threshold is at least [`THRESHOLD_KERFS`] = 2 kerfs (0.02 with the default kerf;
//! the default threshold is 0.1). These 6,624 designs took 47.5 s of the 74.4 s their
//! deployments cost (64 %); screening one costs one mobility analysis (tens of µs).
//!
//! The exploration keeps the same designs with and without the screen (tested on a set of
//! units; `CatalogSettings::screen` turns it off). Plain data in and out; no I/O.

use super::settings::CatalogSettings;
use crate::explore::edge_rates;
use crate::kinematics::Mechanism;
use crate::mobility::analyze;
use crate::topology::Design;

/// A closing rate (units of L per unit of arc length) at which a kerf-wide cut shuts within
/// deployment's probe of 4 kerfs: a sign with such an edge does not open.
pub const BLOCKING_RATE: f64 = 0.25;

/// The screen applies only when the expansion threshold is at least this many kerfs (see the
/// module docs: a design whose cuts shut within the probe expands by less than 0.8 kerf).
pub const THRESHOLD_KERFS: f64 = 2.0;

/// Largest first-order closing rate over every edge endpoint, for the motion as signed by the
/// mobility analysis (+) and its reverse (−); 0 when nothing closes.
pub fn closing_rates(design: &Design, settings: &CatalogSettings) -> Option<[f64; 2]> {
    let cell = design.cell().ok()?;
    let mech = Mechanism::new(&cell, &design.joints).ok()?;
    let mob = analyze(&mech, &mech.rest, settings.topology.mobility).ok()?;
    if mob.dof != 1 {
        return None;
    }
    let v = &mob.motion.as_ref()?.vector;
    let mut close = [0.0f64; 2];
    for r in edge_rates(&cell, &mech, v) {
        for o in r.opening {
            close[0] = close[0].max(-o);
            close[1] = close[1].max(o);
        }
    }
    close.iter().all(|c| c.is_finite()).then_some(close)
}

/// Whether the screen may decide under `settings`: the threshold is at least
/// [`THRESHOLD_KERFS`] kerfs.
pub fn applies(settings: &CatalogSettings) -> bool {
    settings.threshold >= THRESHOLD_KERFS * settings.deploy.contact.kerf
}

/// True when `design` is screened out: both signs of its motion are blocked at first order
/// and the screen applies under `settings` (see the module docs).
pub fn locked_at_start(design: &Design, settings: &CatalogSettings) -> bool {
    applies(settings)
        && closing_rates(design, settings).is_some_and(|c| c.iter().all(|&r| r >= BLOCKING_RATE))
}
