//! What can go wrong in the mobility analysis.

use thiserror::Error;

/// A mobility analysis that could not be done.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MobilityError {
    /// The state has a NaN or infinite entry.
    #[error("numerical failure: state holds NaN or infinity")]
    NonFiniteState,
    /// The symmetric eigen-decomposition of H did not converge.
    #[error("numerical failure: eigen-decomposition did not converge")]
    Eigen,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Mechanism;
    use crate::topology::named_design;

    #[test]
    fn non_finite_state_is_refused() {
        let d = named_design("rotating-squares").unwrap();
        let mech = Mechanism::new(&d.cell().unwrap(), &d.joints).unwrap();
        let mut q = mech.rest.clone();
        q[4] = f64::NAN;
        let e = crate::mobility::analyze(&mech, &q, Default::default()).unwrap_err();
        assert_eq!(e, MobilityError::NonFiniteState);
    }
}
