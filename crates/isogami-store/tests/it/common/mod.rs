//! Shared fixtures: real catalogue entries, temporary directories, file snapshots.
#![allow(dead_code)]

pub mod synthetic;

use isogami::catalog::{run_unit, CatalogEntry, CatalogSettings};
use isogami::cell::CellDims;
use isogami::tiling::Family;
use isogami_store::{sidecar_paths, Check, ExploreRequest, RunInfo, StoreWriter, UnitRecords};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use tempfile::TempDir;

/// The quick exploration's settings.
pub fn quick_settings() -> CatalogSettings {
    CatalogSettings::default().quick()
}

/// The quick exploration of two cheap families (IH83 and IH90, minimal cells).
pub fn two_family_request(jobs: usize) -> ExploreRequest {
    ExploreRequest {
        settings: quick_settings(),
        families: vec![
            Family::from_number(83).unwrap(),
            Family::from_number(90).unwrap(),
        ],
        cells: None,
        shard: None,
        jobs,
        parts: 1,
    }
}

/// Real outcomes of two small work units (IH83 and IH90 on their minimal cells), computed
/// once per test binary.
pub fn outcomes() -> &'static [UnitRecords] {
    static CELL: OnceLock<Vec<UnitRecords>> = OnceLock::new();
    CELL.get_or_init(|| {
        [83, 90]
            .iter()
            .map(|&n| {
                let o = run_unit(
                    Family::from_number(n).unwrap(),
                    CellDims::MINIMAL,
                    &quick_settings(),
                )
                .unwrap();
                assert!(!o.entries.is_empty(), "IH{n} keeps designs");
                UnitRecords::from_outcome(&o, 0.5).unwrap()
            })
            .collect()
    })
}

/// A real catalogue entry (the first design IH83 keeps).
pub fn entry() -> &'static CatalogEntry {
    static CELL: OnceLock<CatalogEntry> = OnceLock::new();
    CELL.get_or_init(|| {
        run_unit(
            Family::from_number(83).unwrap(),
            CellDims::MINIMAL,
            &quick_settings(),
        )
        .unwrap()
        .entries
        .remove(0)
    })
}

/// A fresh directory for one test.
/// Removed with everything in it when the returned guard drops.
pub fn temp(name: &str) -> TempDir {
    tempfile::Builder::new()
        .prefix(&format!("isogami-store-{name}-"))
        .tempdir()
        .unwrap()
}

pub const SETTINGS: &str = "{\"threshold\":0.1}";

pub fn run() -> RunInfo<'static> {
    RunInfo {
        tool_version: "0.1.0",
        settings: SETTINGS,
    }
}

/// A real small database with both units committed.
pub fn real_db(path: &Path) {
    let mut w = StoreWriter::open(path, Some(run()), Check::Full).unwrap();
    for u in outcomes() {
        w.commit_unit(u).unwrap();
    }
}

/// The bytes of a file and which files lie beside it.
#[derive(Debug, PartialEq)]
pub struct Snapshot {
    bytes: Vec<u8>,
    sidecars: Vec<PathBuf>,
}

impl Snapshot {
    pub fn bytes_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    pub fn len(&self) -> usize {
        self.bytes.len()
    }
}

pub fn snapshot(path: &Path) -> Snapshot {
    Snapshot {
        bytes: std::fs::read(path).unwrap(),
        sidecars: sidecar_paths(path)
            .into_iter()
            .filter(|p| p.exists())
            .collect(),
    }
}
