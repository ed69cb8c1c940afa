//! `isogami site`: the catalogue as a static site that works from any static file host.
//!
//! The embedded front end plus `data/site.json` (stats, families, dictionary, measures, export formats
//! for the CLI command the design page composes, inverse design's defaults and the database's
//! file name for the command the inverse-design page composes; its presence
//! switches the pages to static mode), `data/designs.json` (every catalogue row),
//! `data/motions.json` (`{computed, classes: {topology: representative}}`: the motion class
//! of every classed topology, for the mechanisms view and "same motion elsewhere"),
//! `data/design/<slug>.json` (each design view) and `thumbs/<slug>.svg`. The site is built
//! in a temporary folder beside the target and moved into place at the end, so an
//! interrupted run leaves no half-written site; an existing folder is only replaced when it
//! holds an earlier isogami site (its marker file).

use crate::assets::ASSETS;
use crate::thumbnail::thumbnail_svg;
use crate::view::DesignView;
use isogami::tiling::Family;
use isogami_store::{Check, Store, StoreError, DICTIONARY};
use serde::Serialize;
use serde_json::json;
use std::fs;
use std::path::{Path, PathBuf};

/// Marks a folder as written by `isogami site`.
pub const MARKER: &str = ".isogami-site";

/// What went wrong writing a site.
#[derive(Debug, thiserror::Error)]
pub enum SiteError {
    /// The database could not be read.
    #[error("{path}: {source}")]
    Store {
        /// The database.
        path: PathBuf,
        /// Why.
        source: StoreError,
    },
    /// A file could not be written.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The output folder exists and is not an isogami site.
    #[error("{0} exists and is not an isogami site (no {MARKER}); choose an empty or new folder")]
    NotOurs(PathBuf),
    /// A stored design could not be shown.
    #[error("design {spec}: {message}")]
    Design {
        /// Its spec.
        spec: String,
        /// Why.
        message: String,
    },
}

/// What a finished site holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SiteReport {
    /// Designs written.
    pub designs: usize,
    /// Files written.
    pub files: usize,
    /// Bytes written.
    pub bytes: u64,
}

/// The file name stem of a design's files: the spec with `:` as `_` and `,` as `~` (the
/// front end computes the same).
pub fn slug(spec: &str) -> String {
    spec.chars()
        .map(|c| match c {
            ':' => '_',
            ',' => '~',
            c if c.is_ascii_alphanumeric() || c == '.' || c == '-' => c,
            _ => '_',
        })
        .collect()
}

struct Writer {
    root: PathBuf,
    files: usize,
    bytes: u64,
}

impl Writer {
    fn put(&mut self, name: &str, bytes: &[u8]) -> Result<(), SiteError> {
        let path = self.root.join(name);
        if let Some(dir) = path.parent() {
            fs::create_dir_all(dir).map_err(|source| SiteError::Io {
                path: dir.to_path_buf(),
                source,
            })?;
        }
        fs::write(&path, bytes).map_err(|source| SiteError::Io { path, source })?;
        self.files += 1;
        self.bytes += bytes.len() as u64;
        Ok(())
    }

    fn json(&mut self, name: &str, value: &impl Serialize) -> Result<(), SiteError> {
        let text = serde_json::to_vec(value).map_err(|e| SiteError::Design {
            spec: name.to_string(),
            message: e.to_string(),
        })?;
        self.put(name, &text)
    }
}

/// Writes the catalogue of `db` as a static site into `out`; `progress(done, total)` after
/// each design.
pub fn write_site(
    db: &Path,
    out: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SiteReport, SiteError> {
    let store_err = |source| SiteError::Store {
        path: db.to_path_buf(),
        source,
    };
    if out.exists() && !out.join(MARKER).is_file() {
        let empty = fs::read_dir(out)
            .map(|mut d| d.next().is_none())
            .unwrap_or(false);
        if !empty {
            return Err(SiteError::NotOurs(out.to_path_buf()));
        }
    }
    let store = Store::open_read(db, Check::Quick).map_err(store_err)?;
    let summaries = store.summaries().map_err(store_err)?;
    let stats = store.stats().map_err(store_err)?;

    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = out
        .file_name()
        .map_or("site".into(), |n| n.to_string_lossy().to_string());
    let tmp = parent.join(format!(".{name}.tmp-{}", std::process::id()));
    let _ = fs::remove_dir_all(&tmp);
    let mut w = Writer {
        root: tmp.clone(),
        files: 0,
        bytes: 0,
    };
    let result = (|| {
        w.put(MARKER, b"written by isogami site\n")?;
        for (name, bytes) in ASSETS {
            w.put(name, bytes)?;
        }
        let mut stats_json = serde_json::to_value(&stats).map_err(|e| SiteError::Design {
            spec: "stats".into(),
            message: e.to_string(),
        })?;
        if let Some(text) = &stats.settings {
            stats_json["settings"] =
                serde_json::from_str(text).unwrap_or(serde_json::Value::String(text.clone()));
        }
        let families: Vec<_> = Family::all().map(|f| f.info()).collect();
        let db_name = db
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        w.json(
            "data/site.json",
            &json!({
                "mode": "static",
                "stats": stats_json,
                "families": families,
                "dictionary": DICTIONARY,
                // The measures the pages range, sort and plot by, as GET /api/measures.
                "measures": crate::routes::catalogue::measure_docs(),
                "export": crate::export::catalog(),
                // For the `isogami inverse` command the inverse-design page shows.
                "inverse": crate::inverse::InverseLimits::default().describe(false, &db_name),
                "tool_version": env!("CARGO_PKG_VERSION"),
            }),
        )?;
        w.json("data/designs.json", &summaries)?;
        // The mechanisms view and "same motion elsewhere" in the browser (web/src/query.js):
        // each classed topology's representative.
        let classes = store.motion_classes().map_err(store_err)?;
        let map: std::collections::BTreeMap<&str, &str> = classes
            .iter()
            .flatten()
            .flat_map(|c| {
                c.variants
                    .iter()
                    .map(|v| (v.topology.as_str(), c.representative.as_str()))
            })
            .collect();
        w.json(
            "data/motions.json",
            &json!({ "computed": classes.is_some(), "classes": map }),
        )?;
        for (k, summary) in summaries.iter().enumerate() {
            let stored = store
                .design(&summary.spec)
                .map_err(store_err)?
                .ok_or_else(|| SiteError::Design {
                    spec: summary.spec.clone(),
                    message: "listed but not readable".into(),
                })?;
            let view = DesignView::stored(stored).map_err(|e| SiteError::Design {
                spec: summary.spec.clone(),
                message: e.message,
            })?;
            let stem = slug(&summary.spec);
            w.json(&format!("data/design/{stem}.json"), &view)?;
            w.put(
                &format!("thumbs/{stem}.svg"),
                thumbnail_svg(&view).as_bytes(),
            )?;
            progress(k + 1, summaries.len());
        }
        Ok(())
    })();
    if let Err(e) = result {
        let _ = fs::remove_dir_all(&tmp);
        return Err(e);
    }
    if out.exists() {
        fs::remove_dir_all(out).map_err(|source| SiteError::Io {
            path: out.to_path_buf(),
            source,
        })?;
    }
    fs::rename(&tmp, out).map_err(|source| SiteError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    Ok(SiteReport {
        designs: summaries.len(),
        files: w.files,
        bytes: w.bytes,
    })
}

#[cfg(test)]
mod tests {
    use super::slug;

    #[test]
    fn slugs_are_file_names() {
        let s = slug("IH1:0.12,0.5:2x1:--bbb-");
        assert_eq!(s, "IH1_0.12~0.5_2x1_--bbb-");
        assert!(!slug("../../etc/passwd").contains('/'));
    }
}
