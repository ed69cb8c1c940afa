//! The catalogue's query semantics evaluated in plain Rust over the store's summaries, as
//! the README states them (OR within a facet, AND across facets, inclusive ranges that
//! designs without the measure never pass, missing values last in either sort direction,
//! ties in insertion order), to check the server's SQL answers against.

use isogami_store::DesignSummary;
use std::cmp::Ordering;

/// Every measure name the API accepts.
pub const MEASURES: [&str; 15] = [
    "max_expansion",
    "min_expansion",
    "max_area_ratio",
    "max_tile_rotation",
    "poisson_min",
    "poisson_max",
    "steps",
    "tile_count",
    "kerf",
    "v0",
    "v1",
    "v2",
    "v3",
    "v4",
    "v5",
];

/// Every non-measure sort key.
pub const ORDER_KEYS: [&str; 7] = [
    "spec",
    "family",
    "cell",
    "behaviour",
    "linkage_signature",
    "end_reason",
    "origin",
];

/// Facet query keys and the facet names `/api/facets` answers with.
pub const FACETS: [(&str, &str); 7] = [
    ("family", "family"),
    ("cell", "cell"),
    ("tiles", "tile_count"),
    ("behaviour", "behaviour"),
    ("linkage", "linkage_signature"),
    ("end", "end_reason"),
    ("origin", "origin"),
];

/// The value of measure `name` of `s`, if it has one.
pub fn measure(s: &DesignSummary, name: &str) -> Option<f64> {
    Some(match name {
        "max_expansion" => s.max_expansion,
        "min_expansion" => s.min_expansion,
        "max_area_ratio" => s.max_area_ratio,
        "max_tile_rotation" => s.max_tile_rotation,
        "poisson_min" => return s.poisson_min,
        "poisson_max" => return s.poisson_max,
        "steps" => s.steps as f64,
        "tile_count" => f64::from(s.tile_count),
        "kerf" => s.kerf,
        v => {
            let k: usize = v.strip_prefix('v').unwrap().parse().unwrap();
            return s.params.get(k).copied();
        }
    })
}

/// A sort key's value: text, a number, a cell, or missing.
#[derive(Debug, Clone, PartialEq)]
pub enum Key {
    Text(String),
    Number(f64),
    Cell(u8, u8),
    Missing,
}

/// The value `s` is sorted by under `key`.
pub fn sort_key(s: &DesignSummary, key: &str) -> Key {
    match key {
        "spec" => Key::Text(s.spec.clone()),
        "family" => Key::Number(f64::from(s.family.number())),
        "cell" => Key::Cell(s.cell.a(), s.cell.b()),
        "behaviour" => s
            .behaviour
            .map_or(Key::Missing, |b| Key::Text(b.as_str().into())),
        "linkage_signature" => s.linkage_signature.clone().map_or(Key::Missing, Key::Text),
        "end_reason" => Key::Text(s.end_reason.clone()),
        "origin" => Key::Text(s.origin.as_str().into()),
        m => measure(s, m).map_or(Key::Missing, Key::Number),
    }
}

/// The order of two present keys (byte order for text, as SQLite's BINARY collation).
fn compare(a: &Key, b: &Key) -> Ordering {
    match (a, b) {
        (Key::Text(a), Key::Text(b)) => a.as_bytes().cmp(b.as_bytes()),
        (Key::Number(a), Key::Number(b)) => a.partial_cmp(b).unwrap(),
        (Key::Cell(a0, a1), Key::Cell(b0, b1)) => (a0, a1).cmp(&(b0, b1)),
        _ => panic!("keys of different kinds: {a:?} {b:?}"),
    }
}

/// Whether `first` (inserted at `i`) may come before `second` (inserted at `j`) in a list
/// sorted by key, `descending` or not: missing keys last, ties by insertion in the sort's
/// direction.
pub fn in_order(first: (&Key, usize), second: (&Key, usize), descending: bool) -> bool {
    let tie = if descending {
        first.1 > second.1
    } else {
        first.1 < second.1
    };
    match (first.0, second.0) {
        (Key::Missing, Key::Missing) => tie,
        (Key::Missing, _) => false,
        (_, Key::Missing) => true,
        (a, b) => match compare(a, b) {
            Ordering::Equal => tie,
            Ordering::Less => !descending,
            Ordering::Greater => descending,
        },
    }
}

/// The URL text of `s`'s value of the facet with query key `facet`, or None when that value
/// cannot be selected in a URL (a missing linkage signature).
pub fn facet_text(s: &DesignSummary, facet: &str) -> Option<String> {
    Some(match facet {
        "family" => s.family.to_string(),
        "cell" => s.cell.to_string(),
        "tiles" => s.tile_count.to_string(),
        "behaviour" => s.behaviour.map_or("none".into(), |b| b.as_str().into()),
        "linkage" => return s.linkage_signature.clone(),
        "end" => s.end_reason.clone(),
        "origin" => s.origin.as_str().into(),
        other => panic!("no facet {other}"),
    })
}

/// The URL text of a facet value as `/api/facets` serialises it.
pub fn facet_value_text(value: &serde_json::Value) -> Option<String> {
    match value {
        serde_json::Value::Null => Some("none".into()),
        serde_json::Value::String(s) => Some(s.clone()),
        serde_json::Value::Number(n) => Some(n.to_string()),
        serde_json::Value::Array(ab) => Some(format!("{}x{}", ab[0], ab[1])),
        _ => None,
    }
}

/// Filters as a catalogue URL holds them.
#[derive(Debug, Clone, Default)]
pub struct Filter {
    /// (facet query key, selected values).
    pub facets: Vec<(String, Vec<String>)>,
    /// (measure, min, max).
    pub ranges: Vec<(String, Option<f64>, Option<f64>)>,
}

impl Filter {
    /// Adds a selected facet value.
    pub fn select(mut self, facet: &str, value: &str) -> Filter {
        match self.facets.iter_mut().find(|(f, _)| f == facet) {
            Some((_, values)) => values.push(value.into()),
            None => self.facets.push((facet.into(), vec![value.into()])),
        }
        self
    }

    /// Adds a range.
    pub fn range(mut self, measure: &str, min: Option<f64>, max: Option<f64>) -> Filter {
        self.ranges.push((measure.into(), min, max));
        self
    }

    /// The same filters without `facet`'s selection.
    pub fn without(&self, facet: &str) -> Filter {
        let mut out = self.clone();
        out.facets.retain(|(f, _)| f != facet);
        out
    }

    /// The query string (no leading `?`), repeated keys for several values.
    pub fn query(&self) -> String {
        let mut parts = Vec::new();
        for (facet, values) in &self.facets {
            for v in values {
                parts.push(format!("{facet}={}", super::enc(v)));
            }
        }
        for (m, lo, hi) in &self.ranges {
            let b = |x: &Option<f64>| x.map_or(String::new(), |x| format!("{x:?}"));
            parts.push(format!(
                "range={}",
                super::enc(&format!("{m}:{}:{}", b(lo), b(hi)))
            ));
        }
        parts.join("&")
    }

    /// Whether `s` passes every filter.
    pub fn matches(&self, s: &DesignSummary) -> bool {
        let facets = self
            .facets
            .iter()
            .all(|(facet, values)| facet_text(s, facet).is_some_and(|text| values.contains(&text)));
        let ranges = self.ranges.iter().all(|(m, lo, hi)| {
            measure(s, m)
                .is_some_and(|v| lo.is_none_or(|lo| v >= lo) && hi.is_none_or(|hi| v <= hi))
        });
        facets && ranges
    }

    /// How many of `all` pass.
    pub fn count(&self, all: &[DesignSummary]) -> usize {
        all.iter().filter(|s| self.matches(s)).count()
    }
}
