//! Linkage analysis (paper §5.1) — placeholder, being written.
