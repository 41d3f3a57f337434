//! Generated models (filled by `lpm generate`).
