//! The kinematic model: rigid tiles joined by pin joints on a periodic lattice.
//!
//! State q = [x₀, y₀, θ₀, …, x_{n−1}, y_{n−1}, θ_{n−1}, u_x, u_y, w_x, w_y]. Geometry is
//! non-dimensionalised by the cell's mean edge length L, so positions are in units of L and
//! a rotation's lever arms are O(1): one tolerance serves every family and scale. A joint
//! between tile i (cell 0) and tile j in cell (k_u, k_w) has residual
//! R(θ_i)s_a + p_i − (R(θ_j)s_b + p_j + k_u u + k_w w). Residuals, the exact Jacobian and the
//! exact Hessian of E_joints = ½|c|² live here; no eigen-analysis, no contact.

mod error;
mod mechanism;

pub use error::KinematicsError;
pub use mechanism::{Joint, Mechanism, StateLayout};
