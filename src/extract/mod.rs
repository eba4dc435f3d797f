//! Features built from ingested signals: friction, tensile, roughness, wear.

pub mod friction;
pub mod roughness;
pub mod tensile;
pub mod wear;
