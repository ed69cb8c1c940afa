//! Saving inverse design's refined designs as user designs: the one way every front end (the
//! CLI's `inverse --save`, the server, Python) stores them.

use crate::error::{StoreError, StoreResult};
use crate::open::StoreWriter;
use crate::records::{DesignRecord, Origin};
use isogami::api::linkages;
use isogami::inverse::InverseResult;
use serde::Serialize;

/// What happened to one refined design.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct SavedDesign {
    /// The refined design's spec.
    pub spec: String,
    /// True when this call stored it; false when the database already held the spec.
    pub saved: bool,
    /// "saved" or "already in the database".
    pub note: String,
}

impl StoreWriter {
    /// Saves every refined design of `result` (origin `user`, with its verified report and
    /// its linkage analysis), in rank order. A spec already in the database is kept as it was
    /// and reported with `saved: false`; any other error stops at that design.
    pub fn save_inverse_results(
        &mut self,
        result: &InverseResult,
    ) -> StoreResult<Vec<SavedDesign>> {
        let mut out = Vec::with_capacity(result.results.len());
        for r in &result.results {
            let refined = &r.after;
            let analysis = linkages(&refined.design).ok();
            let record = DesignRecord::from_parts(
                &refined.design,
                &r.topology,
                Origin::User,
                &refined.report,
                analysis.as_ref(),
            )?;
            let saved = match self.save_user_design(&record) {
                Ok(()) => true,
                Err(StoreError::DuplicateSpec(_)) => false,
                Err(e) => return Err(e),
            };
            out.push(SavedDesign {
                spec: refined.spec.clone(),
                saved,
                note: if saved {
                    "saved"
                } else {
                    "already in the database"
                }
                .to_string(),
            });
        }
        Ok(out)
    }
}
