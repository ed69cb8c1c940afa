//! Contact between kerf-inset tile polygons (placeholder, being written).
