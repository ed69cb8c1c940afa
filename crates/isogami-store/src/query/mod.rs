//! Catalogue queries: the typed questions a browser asks, answered with typed rows.
//!
//! A [`DesignQuery`] selects designs by facet values (family, cell, tile count, behaviour
//! class, linkage signature, end reason, origin; any of the listed values, all facets at
//! once) and numeric ranges ([`Measure`]s: expansions, area ratio, tile rotation, Poisson-like
//! ratios, steps, tile count, kerf, shape parameters), sorts by any [`SortKey`] either way, and
//! pages with limit/offset. [`Store::page`](crate::Store::page) answers with the total count of
//! the filtered set and one page of [`DesignSummary`](crate::DesignSummary) rows;
//! [`Store::facet_counts`](crate::Store::facet_counts) counts the designs per value of one
//! facet; [`Store::scatter`](crate::Store::scatter) gives any two measures of every design in
//! the set.
//!
//! Facet counts are disjunctive, as in most catalogues: the counts of a facet apply every
//! filter except that facet's own selection, so the values not (yet) ticked show how many
//! designs ticking them would add.
//!
//! The caller never writes SQL: columns come from these enums, values are bound parameters.

pub(crate) mod filter;
mod run;
mod types;

pub use types::{
    DesignQuery, Facet, FacetCount, FacetValue, Measure, Page, QueryError, RangeFilter,
    ScatterPoint, Sort, SortKey, MAX_LIMIT,
};
