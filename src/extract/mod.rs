//! Features built from ingested signals: friction, tensile, roughness.

pub mod friction;
pub mod roughness;
pub mod tensile;
