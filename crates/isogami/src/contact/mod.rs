//! Contact between tiles: kerf-inset collision polygons and an IPC-style log barrier.
//!
//! What it is for: keeping the deployment solver's states physically possible. Each tile's
//! collision polygon is the tile inset by half the kerf (a real cut width, default 1 % of
//! the mean edge length L), so in the closed state neighbouring collision polygons are a
//! kerf apart while the pin joints stay at the tiling vertices. Contact is checked between
//! every tile of the centre cell and every lattice translate of every tile that can come
//! within reach, each physical pair once: the broad phase (`pairs`, on a reduced basis of
//! the current lattice, `lattice`) is exact at every state, so a sheet that shears or
//! stretches far from its closed cell still sees every neighbour. A solver keeps Verlet
//! lists of those pairs (`verlet`: listed with a skin, reused while a closed-form bound
//! shows that no other pair can have come near) so that it does not enumerate the lattice
//! at every evaluation. The module provides:
//!
//! - E_coll(q): a log barrier b(d) = −κ (d − d̂)² ln(d/d̂) on the unsigned (unsquared)
//!   distance d of every vertex–edge pair (both directions) closer than d̂ < kerf, with its
//!   exact gradient and a Hessian whose per-term blocks are projected to PSD;
//! - the smallest clearance, an exact overlap test independent of the barrier, and a
//!   conservative-advancement step bound for line searches that must stay intersection-free,
//!   with a cheap clearance tracker in front of it ([`ClearanceTracker`]);
//! - the kerf inset itself ([`inset_polygon`]), for fabrication export;
//! - the world collision polygons of the 3×3 block, for rendering.
//!
//! Everything is non-dimensional (units of L) like the mechanism's state. A bounding-box
//! broad phase makes far-apart pairs nearly free.
//!
//! ```
//! use isogami::contact::{ContactModel, ContactSettings};
//! use isogami::kinematics::Mechanism;
//! use isogami::math::DVec;
//! use isogami::topology::Design;
//!
//! let design = Design::resolve("rotating-squares")?;
//! let mech = Mechanism::new(&design.cell()?, &design.joints)?;
//! let contact = ContactModel::new(&mech, ContactSettings::default())?;
//! let q = &mech.rest;
//! // Closed state: collision polygons exactly a kerf apart, the barrier inactive.
//! assert!((contact.min_clearance(&mech, q) - 0.01).abs() < 1e-12);
//! assert_eq!(contact.energy(&mech, q), 0.0);
//! // A line search keeps its trial states intersection-free.
//! let mut dq = DVec::zeros(q.len());
//! dq[5] = 1.0; // turn tile 1 by a radian: it hits its neighbours long before that
//! let alpha = contact.max_safe_step(&mech, q, &dq);
//! assert!(alpha > 0.0 && alpha < 0.02);
//! assert!(contact.overlapping_pair(&mech, &(q + &dq * alpha)).is_none());
//! # Ok::<(), isogami::Error>(())
//! ```
//!
//! What it must not do: move joints or change tile shapes, solve anything (the deployment
//! solver owns Newton, line search and step control), do I/O, or panic on bad input
//! (invalid settings and unusable insets are typed errors; states that do not fit get
//! conservative answers, see [`ContactModel`]).

mod aabb;
mod advance;
mod barrier;
mod clearance;
mod derivatives;
mod distance;
mod energy;
mod error;
pub(crate) mod inset;
mod lattice;
mod local;
mod model;
mod narrow;
/// The distance between two polygons as sets (0 when they overlap), for other stages that
/// keep polygons apart (the print export's gaps).
pub(crate) use narrow::polygon_distance;
mod pairs;
mod placement;
mod psd;
mod reach;
mod settings;
mod tracker;
mod verlet;

pub use advance::KEEP_FRACTION;
pub use clearance::{Overlap, CLEARANCE_REACH};
pub use derivatives::HessianProjection;
pub use error::ContactError;
pub use inset::{inset_polygon, InsetProblem};
pub use model::ContactModel;
pub use pairs::CandidatePair;
pub use settings::{ContactSettings, MAX_KERF, MIN_KERF};
pub use tracker::ClearanceTracker;
pub(crate) use verlet::PairCache;
