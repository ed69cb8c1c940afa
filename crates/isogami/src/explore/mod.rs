//! Design-space exploration (paper §4.1–4.2) — placeholder, being written.
