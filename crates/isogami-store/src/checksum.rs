//! Row checksums: CRC-32 over the exact values a row stores.
//!
//! SQLite's quick_check verifies the file's structure (b-trees, page ownership, record
//! headers), not the bytes inside a record: a flipped bit in a stored number or in a JSON
//! document passes it. Every row this crate writes therefore carries a checksum over its
//! values, computed from the values bound at insert and recomputed from the values read back.
//! Each value is hashed with its type and length, so no two different rows hash the same
//! sequence of bytes. CRC-32 detects every change of up to 32 consecutive bits and misses a
//! random larger change with probability 2⁻³².

use rusqlite::types::Value;

/// Checksum of a sequence of column values, as stored in a `checksum` column.
pub(crate) fn of_values<'a>(values: impl IntoIterator<Item = &'a Value>) -> i64 {
    let mut h = crc32fast::Hasher::new();
    for v in values {
        match v {
            Value::Null => h.update(&[0]),
            Value::Integer(i) => {
                h.update(&[1]);
                h.update(&i.to_le_bytes());
            }
            Value::Real(x) => {
                h.update(&[2]);
                h.update(&x.to_bits().to_le_bytes());
            }
            Value::Text(s) => {
                h.update(&[3]);
                h.update(&(s.len() as u64).to_le_bytes());
                h.update(s.as_bytes());
            }
            Value::Blob(b) => {
                h.update(&[4]);
                h.update(&(b.len() as u64).to_le_bytes());
                h.update(b);
            }
        }
    }
    i64::from(h.finalize())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn types_and_boundaries_change_the_checksum() {
        let a = of_values(&[Value::Text("ab".into()), Value::Text("c".into())]);
        let b = of_values(&[Value::Text("a".into()), Value::Text("bc".into())]);
        assert_ne!(a, b);
        assert_ne!(
            of_values(&[Value::Integer(1)]),
            of_values(&[Value::Real(1.0)])
        );
        assert_ne!(of_values(&[Value::Null]), of_values(&[]));
        let x = of_values(&[Value::Real(0.5)]);
        assert_eq!(x, of_values(&[Value::Real(0.5)]));
        assert_ne!(x, of_values(&[Value::Real(0.5f64.next_up())]));
    }
}
