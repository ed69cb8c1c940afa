//! The one error every settings struct (contact, deploy, mobility, exploration, frame
//! selection) gives for a field outside its range: the setting's name, the value given and
//! what it must be, as typed values.

use crate::math::Real;
use std::fmt;
use thiserror::Error;

/// A setting outside its allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("invalid setting: {name} {value} must {requirement}{}", note_suffix(.note))]
#[non_exhaustive]
pub struct SettingsError {
    /// The setting's name, e.g. "kerf" or "max_halvings".
    pub name: &'static str,
    /// The value given.
    pub value: SettingValue,
    /// What the value must be.
    pub requirement: Requirement,
    /// Why the range is what it is, when that helps the user ("" when not).
    pub note: &'static str,
}

impl SettingsError {
    /// A setting `name` whose `value` does not meet `requirement`.
    pub fn new(
        name: &'static str,
        value: impl Into<SettingValue>,
        requirement: Requirement,
    ) -> SettingsError {
        SettingsError {
            name,
            value: value.into(),
            requirement,
            note: "",
        }
    }

    /// The same error with an explanation appended in parentheses.
    pub fn with_note(self, note: &'static str) -> SettingsError {
        SettingsError { note, ..self }
    }
}

fn note_suffix(note: &str) -> String {
    if note.is_empty() {
        String::new()
    } else {
        format!(" ({note})")
    }
}

/// The value a setting was given.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue {
    /// A real number.
    Number(Real),
    /// A count or index.
    Count(u64),
    /// A word (a method name); escaped for a one-line message.
    Text(String),
}

impl From<Real> for SettingValue {
    fn from(v: Real) -> Self {
        SettingValue::Number(v)
    }
}

impl From<usize> for SettingValue {
    fn from(v: usize) -> Self {
        SettingValue::Count(v as u64)
    }
}

impl From<u32> for SettingValue {
    fn from(v: u32) -> Self {
        SettingValue::Count(u64::from(v))
    }
}

impl fmt::Display for SettingValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SettingValue::Number(v) => f.write_str(&short_real(*v)),
            SettingValue::Count(n) => write!(f, "{n}"),
            SettingValue::Text(s) => write!(f, "'{s}'"),
        }
    }
}

/// A number as the shortest text that reads back to it: plain for everyday magnitudes,
/// scientific (`1e300`, `-2.5e-9`) for huge and tiny ones, so a message stays one short line.
pub(crate) fn short_real(v: Real) -> String {
    let magnitude = v.abs();
    if v != 0.0 && v.is_finite() && !(1e-4..1e9).contains(&magnitude) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// What a setting must be.
#[derive(Debug, Clone, PartialEq)]
pub enum Requirement {
    /// A finite number above zero.
    Positive,
    /// A finite number strictly above this bound.
    Above(Real),
    /// A finite number at least this bound.
    AtLeast(Real),
    /// At most this bound.
    AtMost(Real),
    /// A finite number in an interval; the flags say whether each end is excluded.
    Within {
        /// Lower end.
        low: Real,
        /// Upper end.
        high: Real,
        /// The lower end itself is not allowed.
        open_low: bool,
        /// The upper end itself is not allowed.
        open_high: bool,
    },
    /// An integer in `low..=high`.
    CountIn {
        /// Smallest allowed.
        low: u64,
        /// Largest allowed.
        high: u64,
    },
    /// One of these words.
    OneOf(&'static [&'static str]),
}

impl Requirement {
    /// The closed interval [low, high].
    pub fn closed(low: Real, high: Real) -> Requirement {
        Requirement::Within {
            low,
            high,
            open_low: false,
            open_high: false,
        }
    }
}

impl fmt::Display for Requirement {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Requirement::Positive => f.write_str("be a finite number above 0"),
            Requirement::Above(b) => write!(f, "be a finite number above {}", short_real(*b)),
            Requirement::AtLeast(b) => write!(f, "be a finite number >= {}", short_real(*b)),
            Requirement::AtMost(b) => write!(f, "be at most {}", short_real(*b)),
            Requirement::Within {
                low,
                high,
                open_low,
                open_high,
            } => write!(
                f,
                "lie in {}{}, {}{}",
                if *open_low { '(' } else { '[' },
                short_real(*low),
                short_real(*high),
                if *open_high { ')' } else { ']' }
            ),
            Requirement::CountIn { low, high } => write!(f, "lie in {low}..={high}"),
            Requirement::OneOf(words) => write!(f, "be one of {}", words.join(", ")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn carries_name_value_and_range() {
        let e = SettingsError::new("kerf", 0.5, Requirement::closed(1e-4, 0.2)).with_note("why");
        assert_eq!(e.name, "kerf");
        assert_eq!(e.value, SettingValue::Number(0.5));
        assert_eq!(
            e.to_string(),
            "invalid setting: kerf 0.5 must lie in [0.0001, 0.2] (why)"
        );
        let e = SettingsError::new("samples", 0usize, Requirement::CountIn { low: 1, high: 9 });
        assert_eq!(
            e.to_string(),
            "invalid setting: samples 0 must lie in 1..=9"
        );
    }

    #[test]
    fn extreme_values_print_short_and_read_back_exactly() {
        for v in [1e300, -2.5e-9, 1e9, 123456789.0, 1e-4, 0.5, 0.0, -0.0, 7.0] {
            let text = short_real(v);
            assert!(text.len() <= 12, "{v}: {text}");
            assert_eq!(text.parse::<Real>().unwrap(), v, "{text}");
        }
        let e = SettingsError::new("kerf", 1e300, Requirement::closed(1e-4, 0.2));
        assert_eq!(
            e.to_string(),
            "invalid setting: kerf 1e300 must lie in [0.0001, 0.2]"
        );
        assert_eq!(short_real(Real::NAN), "NaN");
        assert_eq!(short_real(Real::NEG_INFINITY), "-inf");
    }
}

#[cfg(test)]
mod ground_floor {
    /// The settings error sits below every stage: it imports nothing of the crate but
    /// `math`, and no module reaches it through the error union (which imports every stage's
    /// error), so the import arrows run one way (issue 23 item 26: a 27-file circle).
    #[test]
    fn the_settings_error_is_imported_from_the_ground_floor_only() {
        let src = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let me = std::fs::read_to_string(src.join("settings_error.rs")).unwrap();
        for line in me
            .lines()
            .filter(|l| l.trim_start().starts_with("use crate::"))
        {
            assert!(
                line.contains("crate::math"),
                "settings_error imports {line}"
            );
        }
        let mut stack = vec![src];
        let mut offenders = Vec::new();
        while let Some(dir) = stack.pop() {
            for entry in std::fs::read_dir(&dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    stack.push(path);
                    continue;
                }
                let text = std::fs::read_to_string(&path).unwrap();
                let through_union = text.lines().any(|l| {
                    l.contains("crate::error::")
                        && ["SettingsError", "Requirement", "SettingValue"]
                            .iter()
                            .any(|n| l.contains(n))
                });
                if through_union && !path.ends_with("error/mod.rs") {
                    offenders.push(path.display().to_string());
                }
            }
        }
        assert!(offenders.is_empty(), "through crate::error: {offenders:?}");
    }
}
