//! Supercell dimensions a×b.

use super::error::CellError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Largest supercell repetition along either tiling vector.
pub const MAX_REPEAT: u8 = 4;

/// Supercell size: the minimal cell repeated `a` times along t1 and `b` times along t2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "[u8; 2]", into = "[u8; 2]")]
pub struct CellDims {
    a: u8,
    b: u8,
}

impl CellDims {
    /// The minimal translational cell.
    pub const MINIMAL: CellDims = CellDims { a: 1, b: 1 };

    /// Checked constructor: 1 ≤ a, b ≤ 4.
    pub fn new(a: u8, b: u8) -> Result<CellDims, CellError> {
        if (1..=MAX_REPEAT).contains(&a) && (1..=MAX_REPEAT).contains(&b) {
            Ok(CellDims { a, b })
        } else {
            Err(CellError::Size { a, b })
        }
    }

    /// Repetitions along t1.
    pub fn a(self) -> u8 {
        self.a
    }

    /// Repetitions along t2.
    pub fn b(self) -> u8 {
        self.b
    }
}

impl TryFrom<[u8; 2]> for CellDims {
    type Error = CellError;
    fn try_from(v: [u8; 2]) -> Result<CellDims, CellError> {
        CellDims::new(v[0], v[1])
    }
}

impl From<CellDims> for [u8; 2] {
    fn from(d: CellDims) -> [u8; 2] {
        [d.a, d.b]
    }
}

impl fmt::Display for CellDims {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.a, self.b)
    }
}

impl FromStr for CellDims {
    type Err = CellError;
    fn from_str(s: &str) -> Result<CellDims, CellError> {
        let bad = || CellError::BadCell {
            input: crate::topology::quote_input(s),
        };
        let (a, b) = s.trim().split_once(['x', 'X']).ok_or_else(bad)?;
        let digit = |t: &str| {
            if t.len() == 1 && t.as_bytes()[0].is_ascii_digit() {
                Ok(t.as_bytes()[0] - b'0')
            } else {
                Err(bad())
            }
        };
        CellDims::new(digit(a)?, digit(b)?).map_err(|_| bad())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_and_print() {
        let d: CellDims = "2x1".parse().unwrap();
        assert_eq!((d.a(), d.b()), (2, 1));
        assert_eq!(d.to_string(), "2x1");
        for bad in [
            "0x1", "5x1", "2", "x", "2x", "ax1", "2x1x1", "22x1", " ", "-1x1",
        ] {
            assert!(bad.parse::<CellDims>().is_err(), "{bad}");
        }
    }

    #[test]
    fn errors_carry_the_input() {
        assert_eq!(CellDims::new(5, 1), Err(CellError::Size { a: 5, b: 1 }));
        assert_eq!(
            "9x\n1".parse::<CellDims>(),
            Err(CellError::BadCell {
                input: "9x\\n1".into()
            })
        );
    }
}
