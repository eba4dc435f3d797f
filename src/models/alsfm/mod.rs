//! Anisotropic Lattice Spring Friction Model (ALSFM), thesis Ch. 1–2 and
//! MODELS.md §5.
//!
//! Two periodic surfaces, z1 below and z2 above, interact through vertical
//! springs; half are attached to each body and each slides on the other
//! surface with the local Coulomb law μ0 on the tangent plane. The global
//! coefficient is μ = |(R_x, R_y)| / R_z (Eq. 1.13).
//!
//! | module | job |
//! |---|---|
//! | [`local_law`] | one spring on a facet: S, D, H_x, H_y (Eq. 1.27, 1.28, 1.41, 1.42) |
//! | [`closed_form`] | wedge closed forms (Eq. 1.10–1.22) and hierarchy power laws (Eq. 2.17) |
//! | [`surface`] | flat, wedges, sinusoids, sampled profiles and maps |
//! | [`separation`] | the separation that carries the load (exact by sorting) |
//! | [`instant`] | one instant of the lattice: forces and reactions |
//! | [`series`] | μ(t) over one period and its averages |
//! | [`numeric_1d`] | surfaces extruded along y (Sec. 1.3) |
//! | [`numeric_2d`] | 2-D surfaces with the local tangent plane (Sec. 1.4) |
//! | [`wear`] | Archard wear: B(t), T_w (Sec. 2.2) |
//! | [`hierarchy`] | levels with μ_{i−1} as local coefficient (Sec. 2.3, 2.4) |
//! | [`exactness`] | where the Case 2 closed form is exact (light-load boundary) |
//! | [`solver`] | picks the cheapest exact path and reports it |

pub mod closed_form;
pub mod exactness;
pub mod hierarchy;
pub mod instant;
pub mod local_law;
pub mod numeric_1d;
pub mod numeric_2d;
pub mod separation;
pub mod series;
pub mod solver;
pub mod surface;
pub mod wear;
