//! Query strings → store queries. Repeated keys select several values of one facet
//! (`family=IH1&family=IH2`); every parameter is checked and an unknown one is refused, so a
//! typo never silently shows the whole catalogue.

use crate::error::{ApiError, ApiResult};
use isogami_store::query::MAX_LIMIT;
use isogami_store::query::{QueryError, RangeFilter, Sort};
use isogami_store::{DesignQuery, Facet, Measure};

/// Most rows one API page returns (the store allows more; the browser pages).
pub const MAX_PAGE: u32 = 500;
/// Most points one scatter answer holds.
pub const MAX_SCATTER: u32 = 100_000;

/// The `key=value` pairs of a raw query string, percent-decoded.
pub fn pairs(raw: Option<&str>) -> Vec<(String, String)> {
    form_urlencoded::parse(raw.unwrap_or("").as_bytes())
        .map(|(k, v)| (k.into_owned(), v.into_owned()))
        .collect()
}

/// What a designs/facets/scatter request asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// Filters, sort and page.
    pub query: DesignQuery,
    /// Scatter axes, when given.
    pub x: Option<Measure>,
    /// Second scatter axis.
    pub y: Option<Measure>,
}

/// Reads filters, sort, page and axes; `extra` lists further keys the endpoint accepts.
pub fn parse(pairs: &[(String, String)], extra: &[&str]) -> ApiResult<Request> {
    let mut query = DesignQuery::default();
    let (mut x, mut y) = (None, None);
    for (key, value) in pairs {
        let facet = |f: Facet| {
            f.value(value)
                .map_err(|e| ApiError::bad_parameter(format!("{key}: {e}")))
        };
        match key.as_str() {
            "family" => {
                query.select(facet(Facet::Family)?);
            }
            "cell" => {
                query.select(facet(Facet::Cell)?);
            }
            "tiles" => {
                query.select(facet(Facet::TileCount)?);
            }
            "behaviour" => {
                query.select(facet(Facet::Behaviour)?);
            }
            "linkage" => {
                query.select(facet(Facet::LinkageSignature)?);
            }
            "end" => {
                query.select(facet(Facet::EndReason)?);
            }
            "origin" => {
                query.select(facet(Facet::Origin)?);
            }
            "range" => {
                let r: RangeFilter = value.parse().map_err(|e| match e {
                    QueryError::RangeForm(_) | QueryError::RangeBound { .. } => {
                        ApiError::bad_parameter(e.to_string())
                    }
                    e => ApiError::bad_parameter(format!("range: {e}")),
                })?;
                query.range(r.measure, r.min, r.max);
            }
            "sort" => {
                let sort: Sort = value
                    .parse()
                    .map_err(|e| ApiError::bad_parameter(format!("sort: {e}")))?;
                query.sort_by(sort.key, sort.descending);
            }
            "lead" => {
                query
                    .lead(value)
                    .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
            }
            "limit" => {
                let n: u32 = number(key, value)?;
                if !(1..=MAX_PAGE.min(MAX_LIMIT)).contains(&n) {
                    return Err(ApiError::bad_parameter(format!(
                        "limit {n} outside 1..={MAX_PAGE}"
                    )));
                }
                query.limit = n;
            }
            "offset" => query.offset = number(key, value)?,
            "x" => x = Some(measure(key, value)?),
            "y" => y = Some(measure(key, value)?),
            k if extra.contains(&k) => {}
            k => {
                return Err(ApiError::bad_parameter(format!(
                    "unknown parameter {:?}",
                    truncate(k)
                )))
            }
        }
    }
    Ok(Request { query, x, y })
}

/// The value of the first `key`, if present.
pub fn get<'a>(pairs: &'a [(String, String)], key: &str) -> Option<&'a str> {
    pairs
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

fn measure(key: &str, value: &str) -> ApiResult<Measure> {
    value
        .parse()
        .map_err(|e| ApiError::bad_parameter(format!("{key}: {e}")))
}

fn number<T: std::str::FromStr>(key: &str, value: &str) -> ApiResult<T> {
    value.parse().map_err(|_| {
        ApiError::bad_parameter(format!(
            "{key} must be a non-negative integer, got {:?}",
            truncate(value)
        ))
    })
}

/// At most 60 characters of user text, for messages.
pub fn truncate(s: &str) -> String {
    let mut out: String = s.chars().take(60).collect();
    if s.chars().count() > 60 {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(q: &str) -> ApiResult<Request> {
        parse(&pairs(Some(q)), &[])
    }

    #[test]
    fn lead_buildable_puts_buildable_designs_first() {
        assert!(parsed("lead=buildable").unwrap().query.buildable_first);
        assert!(!parsed("lead=all").unwrap().query.buildable_first);
        assert!(!parsed("").unwrap().query.buildable_first);
    }

    #[test]
    fn repeated_keys_select_several_values() {
        let r = parsed("family=IH1&family=IH28&cell=2x1&range=max_area_ratio:1.5:&sort=-steps&limit=20&offset=40").unwrap();
        assert_eq!(r.query.families.len(), 2);
        assert_eq!(r.query.cells.len(), 1);
        assert_eq!(r.query.ranges.len(), 1);
        assert_eq!(r.query.ranges[0].min, Some(1.5));
        assert_eq!(r.query.ranges[0].max, None);
        assert!(r.query.sort.unwrap().descending);
        assert_eq!((r.query.limit, r.query.offset), (20, 40));
    }

    #[test]
    fn bad_values_are_refused_with_the_key_named() {
        for (q, needle) in [
            ("family=IH999", "family"),
            ("range=max_area_ratio:NaN:", "not a finite"),
            ("range=max_area_ratio:inf:", "not a finite"),
            ("range=nope:1:2", "unknown measure"),
            ("range=max_area_ratio", "measure:min:max"),
            ("limit=0", "limit"),
            ("limit=100000", "limit"),
            ("offset=-1", "offset"),
            ("sort=-", "sort"),
            ("lead=first", "lead"),
            ("colour=red", "unknown parameter"),
            ("x=v9", "x"),
        ] {
            let e = parsed(q).unwrap_err();
            assert_eq!(e.status, 400, "{q}");
            assert!(e.message.contains(needle), "{q}: {}", e.message);
        }
    }
}
