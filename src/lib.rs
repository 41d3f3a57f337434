//! Umbrella crate (filled in below).
