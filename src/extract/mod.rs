//! Features built from ingested signals: friction, tensile, roughness.

pub mod friction;
pub mod tensile;
