//! Expansion measures along a deployment (placeholder, being written).
