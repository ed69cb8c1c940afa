//! The full check behind [`Check::Full`](crate::Check::Full): every row against its checksum,
//! every stored document parsed into the library's types, no design without its data.

use crate::error::{StoreError, StoreResult};
use crate::open::Store;
use crate::read::typed;
use crate::rows::DESIGN_COLUMNS;

impl Store {
    /// Verifies every row of the database (SQLite's own check runs when opening).
    pub(crate) fn verify_rows(&self) -> StoreResult<()> {
        self.work_units()?;
        self.motion_classes()?;
        self.cell_twins()?;
        self.parts()?;
        let orphans: i64 = self.conn.query_row(
            "SELECT (SELECT count(*) FROM designs WHERE id NOT IN (SELECT design FROM design_data))
                  + (SELECT count(*) FROM design_data WHERE design NOT IN (SELECT id FROM designs))
                  + (SELECT count(*) FROM designs WHERE work_unit IS NOT NULL
                        AND work_unit NOT IN (SELECT id FROM work_units))",
            [],
            |r| r.get(0),
        )?;
        if orphans > 0 {
            return Err(StoreError::Damaged(format!(
                "{orphans} design rows without their data, unit or design"
            )));
        }
        let mut stmt = self.conn.prepare(&format!(
            "SELECT {DESIGN_COLUMNS}, d.checksum, x.report, x.linkages, x.checksum
             FROM designs d JOIN design_data x ON x.design = d.id ORDER BY d.id"
        ))?;
        let mut rows = stmt.query([])?;
        while let Some(row) = rows.next()? {
            let record = crate::read::record_from_row(row)?;
            typed(record)?;
        }
        Ok(())
    }
}
