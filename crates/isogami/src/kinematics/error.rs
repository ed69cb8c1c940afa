//! What can be wrong when assembling a mechanism.

use thiserror::Error;

/// A mechanism that cannot be assembled.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum KinematicsError {
    /// A joint list whose length is not the cell's unique edge count.
    #[error("bad design spec: {given} joint choices for a cell with {edges} edges")]
    JointCount {
        /// Joint choices given.
        given: usize,
        /// Unique edges of the cell.
        edges: usize,
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::Mechanism;
    use crate::topology::named_design;

    #[test]
    fn joint_count_is_carried() {
        let d = named_design("rotating-squares").unwrap();
        let cell = d.cell().unwrap();
        let e = Mechanism::new(&cell, &d.joints[..3]).unwrap_err();
        assert_eq!(
            e,
            KinematicsError::JointCount {
                given: 3,
                edges: cell.edges.len()
            }
        );
    }
}
