//! Nanotensile fibre analysis: strength, toughness and slip-knot energy
//! dissipation (thesis Ch. 5; MODELS.md §3, which is authoritative).
//!
//! # Model
//!
//! Stress σ = F / A with A = π d² / 4. Strain ε is engineering strain.
//!
//! - Unknotted toughness modulus (Eq. 5.1): T_u = (1/ρ) ∫_0^{ε_f} σ dε,
//!   strain relative to the fibre length l.
//! - Knotted toughness modulus (Eq. 5.2): T_k = (1 − k1)/ρ ∫_0^{ε_f*} σ dε,
//!   strain relative to l0 (distance between the fibre ends),
//!   k1 = (l − l0)/l.
//! - After release (Eq. 5.3): T_u' = (1 − k1)/ρ ∫_{ε*}^{ε_f*} σ dε and
//!   T_k / T_u' = ∫_0^{ε_f*} σ dε / ∫_{ε*}^{ε_f*} σ dε.
//! - Against the adjacent control fibre (Eq. 5.4): T_k / T_u.
//! - Friction stress: mean σ over 0 … 0.4 ε_f; the knot is *effective* when
//!   friction stress / strength > 8 % (Table 5.1).
//!
//! | symbol | field | unit inside tribo | unit in tables |
//! |---|---|---|---|
//! | d | [`FibreMeta::diameter_m`] | m | µm |
//! | l | [`FibreMeta::fibre_length_m`] | m | mm |
//! | l0 | [`FibreMeta::end_distance_m`] | m | mm |
//! | ρ | [`FibreMeta::density_kg_per_m3`] | kg/m³ | g/cm³ |
//! | σ | [`StressStrainCurve::stress_pa`] | Pa | MPa |
//! | ε, ε_f, ε* | [`StressStrainCurve::strain`] | 1 | 1 |
//! | T_u, T_k, T_u' | [`FibreFeatures`] | J/kg | J/g |
//!
//! σ in MPa integrated over ε gives MJ/m³; divided by ρ in g/cm³ it gives
//! J/g (the same number as Pa·1 / (kg/m³) / 1000).
//!
//! # Assumptions and valid range
//! - Circular cross-section of constant diameter (thesis §5.2).
//! - Slack (negative strain) is excluded: integrals start at ε = 0.
//! - The break point is the last point before the final drop to near zero
//!   ([`fracture`]); ε* is the start of the final monotone rise
//!   ([`release`]); both are noise-tolerant and say when they fail.
//! - Strain must increase through the test (a tensile test); a record that
//!   goes back in strain integrates as a line integral.
//!
//! # Example
//! ```
//! use tribo::extract::tensile::{analyze_fibre, synthetic, FibreMeta, TensileParams};
//! // linear-elastic to break: T = σ_f ε_f / 2 / ρ
//! let v = synthetic::bilinear(0.0, 10e9, 0.02, 10e9, 0.02);
//! let curve = synthetic::sample(&v, 1e-4, 0.01, 0.0, 5, 1);
//! let f = analyze_fibre(&curve, &FibreMeta::new("a"), &TensileParams::default());
//! let t = f.toughness_j_per_kg.unwrap();
//! assert!((t - 200e6 * 0.02 / 2.0 / 1400.0).abs() < 1e-6 * t);
//! ```

pub mod analyze;
pub mod checks;
pub mod class;
pub mod curve;
pub mod facts;
pub mod fracture;
pub mod general;
pub mod modulus;
pub mod params;
pub mod release;
pub mod synthetic;

pub use analyze::{analyze_fibre, FibreFeatures, RatioMethod};
pub use class::{Direction, MaterialClass};
pub use curve::{FibreMeta, Knot, StressStrainCurve, DEFAULT_DENSITY_KG_PER_M3};
pub use params::TensileParams;
pub use release::ReleaseStatus;
pub mod records;
pub mod summary;

pub use records::{
    apply_controls, apply_controls_table, tensile_table, FibreRecord, InstrumentResults,
};
pub use summary::{groups_table, rows_from_table, summarize, FibreRow, GroupSummary};
pub mod batch;
pub mod from_dataset;

pub use batch::{analyze_dataset, analyze_file, analyze_files, analyze_planned};
