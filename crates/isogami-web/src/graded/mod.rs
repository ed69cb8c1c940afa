//! Graded sheets as server jobs (`/api/graded`, issue 25): a posted design, region and target
//! outline become one run of the library's `api::graded_sheet` on the blocking pool; clients
//! poll its progress (iteration, cost, stage and, throttled, the opened polygons of the sheet
//! as it stands), stop it, and download the graded sheet as `isogami graded --out` writes it.
//!
//! The design follows the inverse-design jobs ([`crate::inverse`]): polling rather than a push
//! channel, the polls doing as the heartbeat (a job nobody asks about for
//! [`GradedLimits::abandon`] stops), caps on sizes, wall time and jobs running at once, ended
//! jobs forgotten after [`GradedLimits::keep`]. No pipeline logic here: the body is read into
//! the library's `GradedRequest` (the outline by the library's own parser), and everything
//! else is the library's.
//!
//! | module | what |
//! |---|---|
//! | [`limits`] | the caps and what `GET /api/graded` tells the page |
//! | [`body`] | the posted JSON → the library's `GradedRequest`, checked against the caps, then by the library's setup (its refusals: 400s) |
//! | [`job`] | one run: progress, snapshots, stop reasons, the result as the CLI writes it; the kind of job ([`crate::jobs`]: the registry, a few running at a time, ended ones forgotten) |

pub mod body;
pub mod job;
pub mod limits;

pub use body::{outline_view, GradedBody};
pub use job::{GradedJob, GradedJobs, GradedView};
pub use limits::GradedLimits;
