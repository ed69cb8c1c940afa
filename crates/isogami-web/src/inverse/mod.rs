//! Inverse design as server jobs (`/api/inverse`): a posted target and search sizes become
//! one run of the library's `inverse::inverse_design` over the database's candidates, on the
//! blocking pool; clients poll its progress (stage, counts, the best objective and the
//! leading topologies' best designs so far), stop it, and save its refined designs.
//!
//! Polling, not a push channel: the job outlives any one connection (a page reload or a
//! dropped network finds it again by id), every answer is a plain JSON GET that proxies and
//! static hosts pass unchanged, and a few polls a second are plenty for a run of seconds to
//! minutes. The polls double as the heartbeat: a job nobody asks about for
//! [`InverseLimits::abandon`] stops.
//!
//! One job at a time per server (a second is refused with 409 `busy`); every count has a
//! server cap and every run a wall-time cap ([`InverseLimits`]); ended jobs are forgotten
//! after [`InverseLimits::keep`].
//!
//! | module | what |
//! |---|---|
//! | [`limits`] | the caps and what `GET /api/inverse` tells the page |
//! | [`body`] | the posted JSON → the library's `InverseRequest`, checked against the caps |
//! | [`job`] | one run: progress snapshot, stop reasons, the result as the CLI prints it; the kind of job ([`crate::jobs`]: the registry, one running at a time, ended ones forgotten) |
//! | [`view`] | what a poll answers |

pub mod body;
pub mod job;
pub mod limits;
pub mod view;

pub use body::InverseBody;
pub use job::{Job, Jobs};
pub use limits::InverseLimits;
pub use view::JobView;
