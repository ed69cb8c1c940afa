//! The JSON boundary check: a serde `Serializer` that writes nothing and fails on the first
//! NaN or infinite `f32`/`f64`, naming where it sits (`frames[3].measures.area_ratio`).
//!
//! serde_json writes a non-finite number as `null` without complaint, so a value is walked
//! with this serializer before it is printed or written; a violation becomes a one-line
//! error instead of output.

use serde::ser::{self, Serialize};
use std::fmt;

/// Why a value cannot be written as JSON.
#[derive(Debug, Clone, PartialEq)]
pub enum JsonCheckError {
    /// A NaN or infinite number at `path` (empty: the value itself).
    NonFinite {
        /// Field path, e.g. `frames[3].measures.area_ratio`.
        path: String,
        /// The offending number.
        value: f64,
    },
    /// A `Serialize` implementation that failed on its own.
    Custom(String),
}

impl fmt::Display for JsonCheckError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JsonCheckError::NonFinite { path, value } if path.is_empty() => {
                write!(f, "the value is {value} (not a finite number)")
            }
            JsonCheckError::NonFinite { path, value } => {
                write!(f, "{path} is {value} (not a finite number)")
            }
            JsonCheckError::Custom(msg) => f.write_str(msg),
        }
    }
}

impl std::error::Error for JsonCheckError {}

impl ser::Error for JsonCheckError {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        JsonCheckError::Custom(msg.to_string())
    }
}

/// Walks `value` as serde would serialise it; `Err` names the first non-finite number.
pub fn check_finite<T: Serialize + ?Sized>(value: &T) -> Result<(), JsonCheckError> {
    let mut path = String::new();
    value.serialize(Checker { path: &mut path })
}

/// The serializer: `path` is the location of the value being visited.
struct Checker<'a> {
    path: &'a mut String,
}

/// A sequence, tuple, map or struct being visited: children extend `path` and restore it.
struct Compound<'a> {
    path: &'a mut String,
    base: usize,
    index: usize,
}

impl<'a> Compound<'a> {
    fn new(path: &'a mut String) -> Self {
        let base = path.len();
        Compound {
            path,
            base,
            index: 0,
        }
    }

    fn child<T: Serialize + ?Sized>(
        &mut self,
        label: &str,
        value: &T,
    ) -> Result<(), JsonCheckError> {
        if label.starts_with('[') || self.path.is_empty() {
            self.path.push_str(label);
        } else {
            self.path.push('.');
            self.path.push_str(label);
        }
        let r = value.serialize(Checker {
            path: &mut *self.path,
        });
        if r.is_ok() {
            self.path.truncate(self.base);
        }
        r
    }

    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), JsonCheckError> {
        let label = format!("[{}]", self.index);
        self.index += 1;
        self.child(&label, value)
    }
}

fn non_finite(path: &str, value: f64) -> Result<(), JsonCheckError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(JsonCheckError::NonFinite {
            path: path.to_string(),
            value,
        })
    }
}

macro_rules! accept {
    ($($name:ident: $ty:ty),* $(,)?) => {
        $(fn $name(self, _: $ty) -> Result<(), JsonCheckError> {
            Ok(())
        })*
    };
}

impl<'a> ser::Serializer for Checker<'a> {
    type Ok = ();
    type Error = JsonCheckError;
    type SerializeSeq = Compound<'a>;
    type SerializeTuple = Compound<'a>;
    type SerializeTupleStruct = Compound<'a>;
    type SerializeTupleVariant = Compound<'a>;
    type SerializeMap = MapCompound<'a>;
    type SerializeStruct = Compound<'a>;
    type SerializeStructVariant = Compound<'a>;

    accept!(
        serialize_bool: bool,
        serialize_i8: i8,
        serialize_i16: i16,
        serialize_i32: i32,
        serialize_i64: i64,
        serialize_i128: i128,
        serialize_u8: u8,
        serialize_u16: u16,
        serialize_u32: u32,
        serialize_u64: u64,
        serialize_u128: u128,
        serialize_char: char,
        serialize_str: &str,
        serialize_bytes: &[u8],
        serialize_unit_struct: &'static str,
    );

    fn serialize_f32(self, v: f32) -> Result<(), JsonCheckError> {
        non_finite(self.path, f64::from(v))
    }

    fn serialize_f64(self, v: f64) -> Result<(), JsonCheckError> {
        non_finite(self.path, v)
    }

    fn serialize_none(self) -> Result<(), JsonCheckError> {
        Ok(())
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), JsonCheckError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<(), JsonCheckError> {
        Ok(())
    }

    fn serialize_unit_variant(
        self,
        _: &'static str,
        _: u32,
        _: &'static str,
    ) -> Result<(), JsonCheckError> {
        Ok(())
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        value: &T,
    ) -> Result<(), JsonCheckError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), JsonCheckError> {
        Compound::new(self.path).child(variant, value)
    }

    fn serialize_seq(self, _: Option<usize>) -> Result<Compound<'a>, JsonCheckError> {
        Ok(Compound::new(self.path))
    }

    fn serialize_tuple(self, _: usize) -> Result<Compound<'a>, JsonCheckError> {
        Ok(Compound::new(self.path))
    }

    fn serialize_tuple_struct(
        self,
        _: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, JsonCheckError> {
        Ok(Compound::new(self.path))
    }

    fn serialize_tuple_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, JsonCheckError> {
        push_label(self.path, variant);
        Ok(Compound::new(self.path))
    }

    fn serialize_map(self, _: Option<usize>) -> Result<MapCompound<'a>, JsonCheckError> {
        Ok(MapCompound {
            inner: Compound::new(self.path),
            key: String::new(),
        })
    }

    fn serialize_struct(self, _: &'static str, _: usize) -> Result<Compound<'a>, JsonCheckError> {
        Ok(Compound::new(self.path))
    }

    fn serialize_struct_variant(
        self,
        _: &'static str,
        _: u32,
        variant: &'static str,
        _: usize,
    ) -> Result<Compound<'a>, JsonCheckError> {
        push_label(self.path, variant);
        Ok(Compound::new(self.path))
    }
}

fn push_label(path: &mut String, label: &str) {
    if !path.is_empty() {
        path.push('.');
    }
    path.push_str(label);
}

/// The element-wise compounds (sequences, tuples): each element is labelled `[i]`.
macro_rules! elements {
    ($($trait:ident::$method:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = JsonCheckError;
            fn $method<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), JsonCheckError> {
                self.element(v)
            }
            fn end(self) -> Result<(), JsonCheckError> {
                Ok(())
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field
);

/// The field-wise compounds (structs, struct variants): each field is labelled by its name.
macro_rules! fields {
    ($($trait:ident),*) => {$(
        impl ser::$trait for Compound<'_> {
            type Ok = ();
            type Error = JsonCheckError;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                v: &T,
            ) -> Result<(), JsonCheckError> {
                self.child(key, v)
            }
            fn end(self) -> Result<(), JsonCheckError> {
                Ok(())
            }
        }
    )*};
}

fields!(SerializeStruct, SerializeStructVariant);

/// A map being visited: keys become path labels (as serde_json would write them).
struct MapCompound<'a> {
    inner: Compound<'a>,
    key: String,
}

impl ser::SerializeMap for MapCompound<'_> {
    type Ok = ();
    type Error = JsonCheckError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), JsonCheckError> {
        // Keys that serde_json cannot write fail there; here they only name the path.
        self.key = match serde_json::to_value(key) {
            Ok(serde_json::Value::String(s)) => s,
            Ok(other) => other.to_string(),
            Err(e) => return Err(JsonCheckError::Custom(format!("map key: {e}"))),
        };
        Ok(())
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, v: &T) -> Result<(), JsonCheckError> {
        let key = std::mem::take(&mut self.key);
        self.inner.child(&key, v)
    }
    fn end(self) -> Result<(), JsonCheckError> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    #[derive(serde::Serialize)]
    struct Measures {
        area_ratio: f64,
        stretch: Option<f32>,
    }

    #[derive(serde::Serialize)]
    struct Frame {
        t: f64,
        measures: Measures,
    }

    #[derive(serde::Serialize)]
    enum End {
        Diverged { at: f64 },
        Stopped(f64),
    }

    fn frame(area_ratio: f64, stretch: Option<f32>) -> Frame {
        Frame {
            t: 0.5,
            measures: Measures {
                area_ratio,
                stretch,
            },
        }
    }

    #[test]
    fn finite_values_pass() {
        let frames = vec![frame(1.0, Some(2.0)), frame(1.5, None)];
        assert_eq!(check_finite(&frames), Ok(()));
        assert_eq!(check_finite(&(1.0, "x", [0u8; 3], None::<f64>)), Ok(()));
        assert_eq!(check_finite(&f64::MAX), Ok(()));
    }

    #[test]
    fn nan_and_infinity_are_named_by_path() {
        let frames = vec![frame(1.0, None), frame(f64::NAN, None)];
        let e = check_finite(&frames).unwrap_err();
        assert!(matches!(&e, JsonCheckError::NonFinite { path, value }
            if path == "[1].measures.area_ratio" && value.is_nan()));
        assert_eq!(
            e.to_string(),
            "[1].measures.area_ratio is NaN (not a finite number)"
        );
        let e = check_finite(&vec![frame(1.0, Some(f32::INFINITY))]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "[0].measures.stretch is inf (not a finite number)"
        );
        let e = check_finite(&f64::NEG_INFINITY).unwrap_err();
        assert_eq!(e.to_string(), "the value is -inf (not a finite number)");
    }

    #[test]
    fn maps_and_variants_extend_the_path() {
        let mut m = BTreeMap::new();
        m.insert("ok", vec![1.0]);
        m.insert("bad", vec![0.0, 0.0, f64::NAN]);
        let e = check_finite(&m).unwrap_err();
        assert!(e.to_string().starts_with("bad[2] is NaN"), "{e}");
        let e = check_finite(&vec![End::Stopped(1.0), End::Diverged { at: f64::NAN }]);
        assert!(e
            .unwrap_err()
            .to_string()
            .starts_with("[1].Diverged.at is NaN"));
        let e = check_finite(&End::Stopped(f64::INFINITY)).unwrap_err();
        assert!(e.to_string().starts_with("Stopped is inf"), "{e}");
        // serde_json itself would have written `null` here.
        let nan = vec![frame(f64::NAN, None)];
        assert!(serde_json::to_string(&nan).unwrap().contains("null"));
    }
}
