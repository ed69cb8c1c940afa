//! Cheap screens before a full deployment (issue 13, "cheap screens first"): a design whose
//! cuts shut, along both signs of its motion, before it can open past the expansion threshold
//! is recognised from its first-order motion in microseconds instead of a deployment that
//! tries both signs, halving its step until it gives up or marching to the contact limit.
//!
//! Every cut starts a kerf wide (each tile's collision polygon is inset by half the kerf), and
//! across a unique edge the two tiles approach at the first-order rate −opening (the edge
//! endpoints' relative normal velocity per unit of arc length along the unit motion vector,
//! [`edge_rates`]): with a largest closing rate r the first cut shuts after about kerf / r of
//! arc, and the sheet has opened by at most about [`REACH`] · kerf / r by then. A design is
//! screened out when both signs close some cut at a rate of at least [`screen_rate`] =
//! max([`MIN_SCREEN_RATE`], REACH · kerf / threshold) (0.1 with the default kerf 0.01 and
//! threshold 0.1), i.e. when neither sign can reach the threshold, and only when the threshold
//! is at least [`THRESHOLD_KERFS`] kerfs. A design with more than one degree of freedom, or
//! whose analysis fails, is not screened: the full assessment decides it.
//!
//! The floor is there because the first-order picture is not the whole story: a cut can close
//! at first order and open again as the motion turns. Of the 841 designs of the default run,
//! two deploy along a sign on which some cut closes at first order: at 0.0007, and
//! `IH6:0.04739750492,0.5,0.150335752741,0.625,0.35:1x1:--a-b-bb-ba-` (a shape sample) at
//! 0.044, which opens to 0.89 although REACH · kerf / r is 0.09. REACH alone (0.04) drops
//! that design; the floor keeps 2.3 times the largest closing rate of any admitted design
//! measured (those 841 and the 61 topologies below).
//!
//! Why this never drops a design the assessment admits. Measured with the
//! `screen_calibration` example on 19,130 unique topologies of 27 units (the hexagon cells IH21
//! 1x1, IH23 3x1, IH22 2x1 and 3x1, IH26 3x1, IH27, IH28, IH6, IH32 1x1, IH2, IH3 2x1, IH1, IH7,
//! IH16, IH24, IH25, IH12, IH13 2x1; squares IH41 4x2, IH44, IH45 2x2, IH54 2x1, IH10 2x2,
//! IH76 2x2; triangles IH83, IH90 2x2, IH93), deploying every one of them:
//!
//! - every one of the 61 admitted designs has a sign along which no cut closes at all (its
//!   smaller closing rate is at most 3e-13, roundoff);
//! - over the designs that are not locked although both signs close some cut (rate above
//!   0.01), the expansion reached is at most 0.19 · kerf / r (r the smaller rate): `REACH` is
//!   twice that;
//! - on the first 16 of these units (10,309 topologies) the rule screens out 9,747 (the first
//!   version of the screen, both signs closing at 1/4 or more: 6,533), none of them admitted;
//!   the largest expansion any of them reaches is 0.016, a sixth of the threshold. Their
//!   deployments were 94 % of the deployment time (64 % before); screening one costs one
//!   mobility analysis (tens of µs).
//!
//! The exploration keeps the same designs with and without the screen (tested on a set of
//! units; `CatalogSettings::screen` turns it off). It screens the topologies it enumerated on
//! the closing rates its deduplication measured on the same analysis ([`screens_out`]), so
//! for them the screen costs nothing; shape samples are analysed here ([`closing_rates`]).
//! Plain data in and out; no I/O.

use super::settings::CatalogSettings;
use crate::explore::{self, edge_rates};
use crate::kinematics::Mechanism;
use crate::mobility::analyze;
use crate::topology::Design;

/// Bound on how far a design opens before a cut closing at first-order rate r shuts: at most
/// `REACH` · kerf / r of largest principal expansion (measured at most 0.19 with the
/// calibration example; twice that for margin). See the module docs.
pub const REACH: f64 = 0.4;

/// The screen's rate is never below this (see the module docs: a cut closing at first order
/// can open again; the largest such rate of an admitted design measured is 0.044).
pub const MIN_SCREEN_RATE: f64 = 0.1;

/// The screen applies only when the expansion threshold is at least this many kerfs (see the
/// module docs: a design whose cuts shut within the probe expands by less than 0.8 kerf).
pub const THRESHOLD_KERFS: f64 = 2.0;

/// Largest first-order closing rate over every edge endpoint, for the motion as signed by the
/// mobility analysis (+) and its reverse (−); 0 when nothing closes. `None` when the design
/// does not build or does not have one degree of freedom. The exploration has these rates from
/// its deduplication already (`DesignDetails::closing`, the same analysis of the same design).
pub fn closing_rates(design: &Design, settings: &CatalogSettings) -> Option<[f64; 2]> {
    let cell = design.cell().ok()?;
    let mech = Mechanism::new(&cell, &design.joints).ok()?;
    let mob = analyze(&mech, &mech.rest, settings.topology.mobility).ok()?;
    if mob.dof != 1 {
        return None;
    }
    let v = &mob.motion.as_ref()?.vector;
    explore::closing_rates(&edge_rates(&cell, &mech, v))
}

/// Whether the screen may decide under `settings`: the threshold is at least
/// [`THRESHOLD_KERFS`] kerfs.
pub fn applies(settings: &CatalogSettings) -> bool {
    settings.threshold >= THRESHOLD_KERFS * settings.deploy.contact.kerf
}

/// The closing rate at and above which a sign cannot open past the threshold before the cut
/// shuts: max([`MIN_SCREEN_RATE`], [`REACH`] · kerf / threshold), 0.1 with the defaults and at
/// most 0.2 where the screen applies.
pub fn screen_rate(settings: &CatalogSettings) -> f64 {
    MIN_SCREEN_RATE.max(REACH * settings.deploy.contact.kerf / settings.threshold)
}

/// True when `design` is screened out: along both signs of its motion some cut closes at a
/// first-order rate of at least [`screen_rate`], and the screen applies under `settings`
/// (see the module docs).
pub fn cannot_reach_threshold(design: &Design, settings: &CatalogSettings) -> bool {
    applies(settings) && screens_out(closing_rates(design, settings), settings)
}

/// The screen's verdict from closing rates already known (as [`closing_rates`] gives them),
/// whether or not the screen applies under `settings`.
pub fn screens_out(closing: Option<[f64; 2]>, settings: &CatalogSettings) -> bool {
    let rate = screen_rate(settings);
    closing.is_some_and(|c| c.iter().all(|&r| r >= rate))
}
