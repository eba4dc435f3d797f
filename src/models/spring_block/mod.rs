//! 2-D spring-block model of a patterned elastic surface sliding on a rigid
//! plane (thesis Ch. 4 §4.3, Costagliola et al. 2018; MODELS.md §7, which is
//! authoritative where the thesis is ambiguous).
//!
//! # Model
//! The surface is a square lattice of N_x × N_y blocks of mass m = ρ l³. For
//! block i at displacement u_i from its rest position,
//!
//! m ü_i = Σ_j F_int^(ij) + K_s (v t − u_i) − m γ u̇_i + F_fr^(i),
//!
//! - internal springs to the 8 neighbours, F_int^(ij) = k_ij (r_ij − l_ij)
//!   (r_j − r_i)/r_ij, k_ij = K_int = c E l_z on the axes and K_int/2 on the
//!   diagonals (c = 3/8, the thesis's convention: effective modulus E/2,
//!   Poisson's ratio 1/3; see [`StiffnessConvention`]);
//! - shear springs to the slider, K_s = K_int (l/l_z)², the slider moving at
//!   v = |v| (cos α, sin α);
//! - damping −m γ u̇ (γ is not given by the thesis; a named parameter);
//! - Amontons–Coulomb friction with normal force F_n = p l²: a stuck block
//!   stays stuck while |F_mot| ≤ μ_s^i F_n + F_ad (F_mot = internal + shear);
//!   a sliding block feels −μ_d^i F_n along its velocity and sticks again
//!   when its velocity vanishes (reverses) with |F_mot| below the threshold.
//!   Holes have μ = 0.
//!
//! The friction force measured on the slider is T_tot(t) = Σ_i K_s (v t − u_i);
//! the macroscopic coefficient is T/N with N = N_x N_y p l² (nominal load).
//!
//! | symbol | field | unit | default |
//! |---|---|---|---|
//! | E | [`SpringBlockParams::youngs_modulus`] | Pa | 0.8e6 |
//! | ρ | [`SpringBlockParams::density`] | kg/m³ | 1012 |
//! | l | [`SpringBlockParams::spacing`] | m | 5e-6 |
//! | l_z | [`SpringBlockParams::thickness`] | m | = l |
//! | N_x, N_y | `nx`, `ny` | 1 | 85 |
//! | (μ_s)_m, σ_s | [`LocalFriction`] | 1 | 4.5, 0.2 |
//! | (μ_d)_m, σ_d | [`LocalFriction`] | 1 | 3.0, 0.2 |
//! | F_ad/l² | [`SpringBlockParams::adhesion`] | Pa | 23.8e3 |
//! | γ | [`SpringBlockParams::damping`] | 1/s | 2e6 |
//! | v | [`SpringBlockParams::slider_speed`] | m/s | 2e-4 |
//!
//! # Assumptions and range
//! Quasi-static normal load (F_n constant and equal on every block, holes
//! included, as in the thesis); small strains are not assumed (springs are
//! geometrically nonlinear). Patterns are drawn on the lattice
//! ([`pattern`]). The model is meant for slow sliding and low to intermediate
//! pressures (3–25 kPa in the thesis).

pub mod forces;
pub mod interface;
pub mod lattice;
pub mod params;
pub mod pattern;

pub use interface::Interface;
pub use lattice::Lattice;
pub use params::{LocalFriction, SpringBlockParams, StiffnessConvention};
pub use pattern::{contact_fraction, Pattern};
