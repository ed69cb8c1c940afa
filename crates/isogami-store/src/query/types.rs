//! The query vocabulary: filters, measures, sort keys, facets, and the answers.

use crate::records::{DesignSummary, Origin};
use crate::schema::PARAM_SLOTS;
use isogami::cell::CellDims;
use isogami::measure::BehaviourClass;
use isogami::tiling::Family;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Largest page.
pub const MAX_LIMIT: u32 = 1000;

/// A numeric column: range filters, sorting and scatter axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Measure {
    /// Largest principal expansion reached.
    MaxExpansion,
    /// Smallest principal expansion reached.
    MinExpansion,
    /// Largest area ratio reached.
    MaxAreaRatio,
    /// Largest tile rotation reached (radians).
    MaxTileRotation,
    /// Smallest Poisson-like ratio over the open frames.
    PoissonMin,
    /// Largest Poisson-like ratio over the open frames.
    PoissonMax,
    /// Accepted deployment states.
    Steps,
    /// Tiles in the cell.
    TileCount,
    /// Kerf relative to the mean edge length.
    Kerf,
    /// Degrees of freedom of the raw 6×6-cell patch (missing for user designs).
    FiniteRawDof,
    /// Covered fraction of the completed 6×6-cell patch (missing when it has no one-DOF
    /// sheet, and for user designs).
    FiniteCovered,
    /// t of the most open state (missing for user designs).
    OpenT,
    /// Area ratio where the path ends (missing for user designs).
    EndAreaRatio,
    /// Shape tolerance: vertex displacement relative to the mean edge length that keeps 95 %
    /// of the opening (missing for families without shape parameters and user designs).
    ShapeTolerance,
    /// Fraction of the largest area ratio kept at the fabrication tolerance (missing like
    /// the shape tolerance).
    FabricationKept,
    /// Shape parameter v_k (0 ≤ k < 6; designs of families with fewer parameters have none).
    Param(u8),
}

impl Measure {
    /// Every measure with a fixed name, then the six parameter slots.
    pub fn all() -> impl Iterator<Item = Measure> {
        [
            Measure::MaxExpansion,
            Measure::MinExpansion,
            Measure::MaxAreaRatio,
            Measure::MaxTileRotation,
            Measure::PoissonMin,
            Measure::PoissonMax,
            Measure::Steps,
            Measure::TileCount,
            Measure::Kerf,
            Measure::FiniteRawDof,
            Measure::FiniteCovered,
            Measure::OpenT,
            Measure::EndAreaRatio,
            Measure::ShapeTolerance,
            Measure::FabricationKept,
        ]
        .into_iter()
        .chain((0..PARAM_SLOTS as u8).map(Measure::Param))
    }

    /// The column it is stored in.
    pub(crate) fn column(self) -> Result<&'static str, QueryError> {
        Ok(match self {
            Measure::MaxExpansion => "max_expansion",
            Measure::MinExpansion => "min_expansion",
            Measure::MaxAreaRatio => "max_area_ratio",
            Measure::MaxTileRotation => "max_tile_rotation",
            Measure::PoissonMin => "poisson_min",
            Measure::PoissonMax => "poisson_max",
            Measure::Steps => "steps",
            Measure::TileCount => "tile_count",
            Measure::Kerf => "kerf",
            Measure::FiniteRawDof => "finite_raw_dof",
            Measure::FiniteCovered => "finite_covered",
            Measure::OpenT => "open_t",
            Measure::EndAreaRatio => "end_area_ratio",
            Measure::ShapeTolerance => "shape_tolerance",
            Measure::FabricationKept => "fabrication_kept",
            Measure::Param(k) => {
                const SLOTS: [&str; PARAM_SLOTS] = ["p0", "p1", "p2", "p3", "p4", "p5"];
                SLOTS
                    .get(usize::from(k))
                    .copied()
                    .ok_or(QueryError::ParamSlot(k))?
            }
        })
    }

    /// True when some designs may lack it.
    pub(crate) fn nullable(self) -> bool {
        matches!(
            self,
            Measure::PoissonMin
                | Measure::PoissonMax
                | Measure::FiniteRawDof
                | Measure::FiniteCovered
                | Measure::OpenT
                | Measure::EndAreaRatio
                | Measure::ShapeTolerance
                | Measure::FabricationKept
                | Measure::Param(_)
        )
    }
}

impl fmt::Display for Measure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Measure::Param(k) => write!(f, "v{k}"),
            m => f.write_str(m.column().unwrap_or("?")),
        }
    }
}

impl FromStr for Measure {
    type Err = QueryError;
    /// Column names (`max_expansion`, …) and `v0`…`v5` for shape parameters.
    fn from_str(s: &str) -> Result<Measure, QueryError> {
        if let Some(k) = s.strip_prefix('v') {
            let k: u8 = k
                .parse()
                .map_err(|_| QueryError::UnknownName(s.to_string()))?;
            Measure::Param(k).column()?;
            return Ok(Measure::Param(k));
        }
        Measure::all()
            .find(|m| m.to_string() == s)
            .ok_or_else(|| QueryError::UnknownName(s.to_string()))
    }
}

impl TryFrom<String> for Measure {
    type Error = QueryError;
    fn try_from(s: String) -> Result<Measure, QueryError> {
        s.parse()
    }
}

impl From<Measure> for String {
    fn from(m: Measure) -> String {
        m.to_string()
    }
}

/// Inclusive bounds on a measure; a missing bound is open. Designs without the measure (no
/// Poisson-like ratio, no such shape parameter, no finite-sheet figure) never pass a range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RangeFilter {
    /// The measure.
    pub measure: Measure,
    /// Lower bound.
    pub min: Option<f64>,
    /// Upper bound.
    pub max: Option<f64>,
}

/// What rows can be sorted by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SortKey {
    /// Spec string.
    Spec,
    /// Family number (IH2 before IH10).
    Family,
    /// Cell a, then b.
    Cell,
    /// Behaviour class name (unclassified last).
    Behaviour,
    /// Linkage signature text (missing last).
    LinkageSignature,
    /// End reason.
    EndReason,
    /// Origin.
    Origin,
    /// Any measure (missing values last).
    Measure(Measure),
}

impl FromStr for SortKey {
    type Err = QueryError;
    /// `spec`, `family`, `cell`, `behaviour`, `linkage_signature`, `end_reason`, `origin`, or
    /// any measure name.
    fn from_str(s: &str) -> Result<SortKey, QueryError> {
        Ok(match s {
            "spec" => SortKey::Spec,
            "family" => SortKey::Family,
            "cell" => SortKey::Cell,
            "behaviour" => SortKey::Behaviour,
            "linkage_signature" => SortKey::LinkageSignature,
            "end_reason" => SortKey::EndReason,
            "origin" => SortKey::Origin,
            m => SortKey::Measure(m.parse()?),
        })
    }
}

/// A sort key and a direction; ties are broken by insertion order in the same direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Sort {
    /// Key.
    pub key: SortKey,
    /// Largest first.
    pub descending: bool,
}

impl FromStr for Sort {
    type Err = QueryError;
    /// A sort key's name, `-` first for largest first (`-max_area_ratio`).
    fn from_str(s: &str) -> Result<Sort, QueryError> {
        let (name, descending) = match s.strip_prefix('-') {
            Some(rest) => (rest, true),
            None => (s, false),
        };
        Ok(Sort {
            key: name.parse()?,
            descending,
        })
    }
}

impl FromStr for RangeFilter {
    type Err = QueryError;
    /// `measure:min:max`, either bound empty for none; bounds must be finite (their order is
    /// checked when the query runs).
    fn from_str(s: &str) -> Result<RangeFilter, QueryError> {
        let parts: Vec<&str> = s.split(':').collect();
        let [m, lo, hi] = parts[..] else {
            return Err(QueryError::RangeForm(clipped(s)));
        };
        let measure: Measure = m.parse()?;
        let bound = |text: &str| -> Result<Option<f64>, QueryError> {
            if text.is_empty() {
                return Ok(None);
            }
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(QueryError::RangeBound {
                    measure,
                    text: clipped(text),
                }),
            }
        };
        Ok(RangeFilter {
            measure,
            min: bound(lo)?,
            max: bound(hi)?,
        })
    }
}

/// A facet: a column whose distinct values are listed with counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Facet {
    /// Tiling family.
    Family,
    /// Supercell.
    Cell,
    /// Tiles in the cell.
    TileCount,
    /// Behaviour class.
    Behaviour,
    /// Linkage signature.
    LinkageSignature,
    /// End reason of the deployment.
    EndReason,
    /// Explored or saved by a user.
    Origin,
}

impl Facet {
    /// Every facet.
    pub const ALL: [Facet; 7] = [
        Facet::Family,
        Facet::Cell,
        Facet::TileCount,
        Facet::Behaviour,
        Facet::LinkageSignature,
        Facet::EndReason,
        Facet::Origin,
    ];
}

/// One value of a facet. Serialises as the bare value (`"IH28"`, `[2, 1]`, `4`, `null`, …);
/// read one back with [`Facet::value`], which knows which facet it belongs to.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum FacetValue {
    /// A family.
    Family(Family),
    /// A cell.
    Cell(CellDims),
    /// A tile count.
    TileCount(u32),
    /// A behaviour class, None for unclassified designs.
    Behaviour(Option<BehaviourClass>),
    /// A linkage signature, None for designs stored without a linkage analysis.
    LinkageSignature(Option<String>),
    /// An end reason.
    EndReason(String),
    /// An origin.
    Origin(Origin),
}

impl Facet {
    /// Reads a value of this facet from text as a URL or command line gives it: `IH28`,
    /// `2x1`, `4`, `isotropic_auxetic` (or `none` for unclassified), a linkage signature,
    /// an end reason, `explored` or `user`.
    pub fn value(self, text: &str) -> Result<FacetValue, QueryError> {
        let bad = || QueryError::FacetValue {
            facet: self,
            text: text.to_string(),
        };
        Ok(match self {
            Facet::Family => FacetValue::Family(text.parse().map_err(|_| bad())?),
            Facet::Cell => FacetValue::Cell(text.parse().map_err(|_| bad())?),
            Facet::TileCount => FacetValue::TileCount(text.parse().map_err(|_| bad())?),
            Facet::Behaviour => FacetValue::Behaviour(match text {
                "none" => None,
                name => Some(
                    serde_json::from_value(serde_json::Value::String(name.to_string()))
                        .map_err(|_| bad())?,
                ),
            }),
            Facet::LinkageSignature => FacetValue::LinkageSignature(Some(text.to_string())),
            Facet::EndReason => FacetValue::EndReason(text.to_string()),
            Facet::Origin => FacetValue::Origin(Origin::from_name(text).ok_or_else(bad)?),
        })
    }
}

impl Facet {
    /// The facet's name (also the column it is stored in).
    pub fn name(self) -> &'static str {
        match self {
            Facet::Family => "family",
            Facet::Cell => "cell",
            Facet::TileCount => "tile_count",
            Facet::Behaviour => "behaviour",
            Facet::LinkageSignature => "linkage_signature",
            Facet::EndReason => "end_reason",
            Facet::Origin => "origin",
        }
    }
}

impl fmt::Display for Facet {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FacetValue {
    /// The facet this value belongs to.
    pub fn facet(&self) -> Facet {
        match self {
            FacetValue::Family(_) => Facet::Family,
            FacetValue::Cell(_) => Facet::Cell,
            FacetValue::TileCount(_) => Facet::TileCount,
            FacetValue::Behaviour(_) => Facet::Behaviour,
            FacetValue::LinkageSignature(_) => Facet::LinkageSignature,
            FacetValue::EndReason(_) => Facet::EndReason,
            FacetValue::Origin(_) => Facet::Origin,
        }
    }
}

/// How many designs of the filtered set have a facet value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FacetCount {
    /// The value.
    pub value: FacetValue,
    /// Designs with it.
    pub count: u64,
}

/// A filtered, sorted page request. Empty lists do not filter; a list keeps designs with any
/// of its values; all filters hold together.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct DesignQuery {
    /// Families.
    pub families: Vec<Family>,
    /// Cells.
    pub cells: Vec<CellDims>,
    /// Tile counts.
    pub tile_counts: Vec<u32>,
    /// Behaviour classes (None: unclassified).
    pub behaviours: Vec<Option<BehaviourClass>>,
    /// Linkage signatures (None: no linkage analysis stored).
    pub linkage_signatures: Vec<Option<String>>,
    /// End reasons (`contact_limit`, …).
    pub end_reasons: Vec<String>,
    /// Origins.
    pub origins: Vec<Origin>,
    /// Numeric ranges.
    pub ranges: Vec<RangeFilter>,
    /// Order (default: spec, ascending).
    pub sort: Option<Sort>,
    /// Buildable designs first (see [`DesignSummary::buildable`]), each part in the sort's
    /// order: how a catalogue leads with what can be made.
    pub buildable_first: bool,
    /// Rows per page, 1…[`MAX_LIMIT`].
    pub limit: u32,
    /// Rows skipped.
    pub offset: u64,
}

impl Default for DesignQuery {
    fn default() -> DesignQuery {
        DesignQuery {
            families: Vec::new(),
            cells: Vec::new(),
            tile_counts: Vec::new(),
            behaviours: Vec::new(),
            linkage_signatures: Vec::new(),
            end_reasons: Vec::new(),
            origins: Vec::new(),
            ranges: Vec::new(),
            sort: None,
            buildable_first: false,
            limit: 50,
            offset: 0,
        }
    }
}

impl DesignQuery {
    /// Adds a facet value to the selection (as ticking it in a catalogue would).
    pub fn select(&mut self, value: FacetValue) -> &mut DesignQuery {
        match value {
            FacetValue::Family(v) => self.families.push(v),
            FacetValue::Cell(v) => self.cells.push(v),
            FacetValue::TileCount(v) => self.tile_counts.push(v),
            FacetValue::Behaviour(v) => self.behaviours.push(v),
            FacetValue::LinkageSignature(v) => self.linkage_signatures.push(v),
            FacetValue::EndReason(v) => self.end_reasons.push(v),
            FacetValue::Origin(v) => self.origins.push(v),
        }
        self
    }

    /// Adds a range filter.
    pub fn range(
        &mut self,
        measure: Measure,
        min: Option<f64>,
        max: Option<f64>,
    ) -> &mut DesignQuery {
        self.ranges.push(RangeFilter { measure, min, max });
        self
    }

    /// Sets the order.
    pub fn sort_by(&mut self, key: SortKey, descending: bool) -> &mut DesignQuery {
        self.sort = Some(Sort { key, descending });
        self
    }

    /// Sets [`DesignQuery::buildable_first`] from its text: `buildable` (first) or `all`.
    pub fn lead(&mut self, text: &str) -> Result<&mut DesignQuery, QueryError> {
        self.buildable_first = match text {
            "buildable" => true,
            "all" => false,
            other => return Err(QueryError::Lead(other.chars().take(60).collect())),
        };
        Ok(self)
    }
}

/// One page of a query.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Page {
    /// Designs in the whole filtered set.
    pub total: u64,
    /// Offset of the first row.
    pub offset: u64,
    /// The rows.
    pub rows: Vec<DesignSummary>,
}

/// One design as a point of a scatter plot, with what a plot colours it by.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScatterPoint {
    /// Spec.
    pub spec: String,
    /// x value.
    pub x: f64,
    /// y value.
    pub y: f64,
    /// Tiling family.
    pub family: Family,
    /// Behaviour class (None when the sheet does not expand).
    pub behaviour: Option<BehaviourClass>,
}

/// A query that cannot be run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum QueryError {
    /// A NaN or infinite bound.
    #[error("bound {value} on {measure} is not a finite number")]
    NotFinite {
        /// The measure.
        measure: Measure,
        /// The bound.
        value: f64,
    },
    /// min > max.
    #[error("empty range on {measure}: {min} > {max}")]
    EmptyRange {
        /// The measure.
        measure: Measure,
        /// Lower bound.
        min: f64,
        /// Upper bound.
        max: f64,
    },
    /// Limit outside 1…MAX_LIMIT.
    #[error("limit {0} outside 1..={MAX_LIMIT}")]
    Limit(u32),
    /// Offset beyond what SQLite counts.
    #[error("offset {0} too large")]
    Offset(u64),
    /// A shape parameter slot that no family has.
    #[error("shape parameter v{0} does not exist (families have at most six, v0…v5)")]
    ParamSlot(u8),
    /// Text that is not a value of the facet.
    #[error("'{text}' is not a value of facet {facet}")]
    FacetValue {
        /// The facet.
        facet: Facet,
        /// The text.
        text: String,
    },
    /// A measure name that does not exist.
    #[error("unknown measure '{0}'")]
    UnknownName(String),
    /// A `lead` that is neither `buildable` nor `all`.
    #[error("lead '{0}': expected 'buildable' (buildable designs first) or 'all'")]
    Lead(String),
    /// A range text that is not `measure:min:max` (at most 60 characters of it).
    #[error("range must be measure:min:max, got {0:?}")]
    RangeForm(String),
    /// A range bound that is not a finite number (at most 60 characters of it).
    #[error("range bound {text:?} on {measure} is not a finite number")]
    RangeBound {
        /// The measure.
        measure: Measure,
        /// The bound's text.
        text: String,
    },
}

/// At most 60 characters of user text, for messages.
fn clipped(s: &str) -> String {
    let mut out: String = s.chars().take(60).collect();
    if s.chars().count() > 60 {
        out.push('…');
    }
    out
}
