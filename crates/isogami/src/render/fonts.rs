//! The fonts that text is rasterised with, as an explicit value: the caller decides whether
//! to scan the system's font directories ([`Fonts::system`], file I/O over every installed
//! font) or to rasterise without text ([`Fonts::empty`]). No library call loads fonts behind
//! the caller's back.
//!
//! Every SVG of this crate sets `font-family="sans-serif"`; fontdb maps that generic family
//! to Arial, which many Linux machines lack, so [`Fonts::system`] points it at an installed
//! face, preferring DejaVu Sans, so that labels do not vanish.

use resvg::usvg::fontdb;
use std::sync::Arc;

/// Sans-serif faces to use, best first, when fontdb's default (Arial) is not installed.
const SANS_CANDIDATES: [&str; 6] = [
    "DejaVu Sans",
    "Liberation Sans",
    "Noto Sans",
    "FreeSans",
    "Arial",
    "Helvetica",
];

/// A font database for rasterising SVG text, and the face that `sans-serif` resolves to.
/// Cheap to clone (shared).
#[derive(Clone)]
pub struct Fonts {
    pub(super) db: Arc<fontdb::Database>,
    pub(super) sans: Option<String>,
}

impl std::fmt::Debug for Fonts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Fonts")
            .field("faces", &self.db.len())
            .field("sans", &self.sans)
            .finish()
    }
}

fn has_family(db: &fontdb::Database, family: fontdb::Family<'_>) -> bool {
    db.query(&fontdb::Query {
        families: &[family],
        ..fontdb::Query::default()
    })
    .is_some()
}

impl Fonts {
    /// No fonts: text elements are left out of rasters; everything else is drawn.
    pub fn empty() -> Fonts {
        Fonts {
            db: Arc::new(fontdb::Database::new()),
            sans: None,
        }
    }

    /// The fonts installed on this machine (scans the system font directories once, now).
    /// `sans-serif` is the first installed face of DejaVu Sans, Liberation Sans, Noto Sans,
    /// FreeSans, Arial, Helvetica, else any installed face.
    pub fn system() -> Fonts {
        let mut db = fontdb::Database::new();
        db.load_system_fonts();
        let sans = SANS_CANDIDATES
            .iter()
            .find(|name| has_family(&db, fontdb::Family::Name(name)))
            .map(|s| s.to_string())
            .or_else(|| {
                db.faces()
                    .find_map(|face| face.families.first().map(|(name, _)| name.clone()))
            });
        if let Some(name) = &sans {
            db.set_sans_serif_family(name.clone());
        }
        Fonts {
            db: Arc::new(db),
            sans,
        }
    }

    /// The family that `sans-serif` text is drawn with, or `None` when there are no fonts
    /// (text is then left out of PNG and GIF output).
    pub fn sans_family(&self) -> Option<&str> {
        self.sans.as_deref()
    }

    /// Number of font faces loaded.
    pub fn face_count(&self) -> usize {
        self.db.len()
    }
}
