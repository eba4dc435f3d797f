//! Anisotropic Lattice Spring Friction Model (ALSFM), thesis Ch. 1–2 and
//! MODELS.md §5.

pub mod closed_form;
