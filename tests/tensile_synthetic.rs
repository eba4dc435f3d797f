//! Per-fibre tensile features on synthetic curves with closed-form answers
//! (MODELS.md §3, Eq. 5.1–5.4).

use tribo::extract::tensile::synthetic::{bilinear, exact_area, sample, KnottedSpec};
use tribo::extract::tensile::{
    analyze_fibre, FibreMeta, Knot, RatioMethod, ReleaseStatus, StressStrainCurve, TensileParams,
};

const RHO: f64 = 1400.0;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn linear_elastic_to_break_gives_half_sigma_epsilon_over_rho() {
    // E = 10 GPa to ε_f = 0.02: σ_f = 200 MPa, T = σ_f ε_f / 2 / ρ
    let v = bilinear(0.0, 10e9, 0.02, 10e9, 0.02);
    let c = sample(&v, 2e-5, 0.01, 0.0, 20, 1);
    let f = analyze_fibre(&c, &FibreMeta::new("lin"), &TensileParams::default());
    assert!(f.status.is_ok(), "{:?}", f.status);
    // noiseless piecewise-linear data: the trapezoid rule is exact, only
    // rounding of ~1000 sums remains (1e-12 relative)
    assert!(rel(f.strength_pa.unwrap(), 200e6) < 1e-12);
    assert!(rel(f.strain_at_break.unwrap(), 0.02) < 1e-12);
    let t = 200e6 * 0.02 / 2.0 / RHO;
    assert!(rel(f.toughness_j_per_kg.unwrap(), t) < 1e-12);
    // knot quantities (friction stress, k1) belong to knotted fibres only:
    // null for this unknotted one, not zero
    assert_eq!(
        (f.friction_stress_pa, f.friction_ratio, f.k1),
        (None, None, None)
    );
    // least squares on exact linear data recovers E to rounding
    assert!(rel(f.modulus_pa.unwrap(), 10e9) < 1e-9);
    assert_eq!(f.knot_effective, None);
    assert_eq!(f.release_status, ReleaseStatus::NotApplicable);
}

#[test]
fn bilinear_silk_integral_matches_closed_form_in_j_per_g() {
    // E = 10 GPa, ε_y = 0.02 (σ_y = 200 MPa), H = 1.5 GPa, ε_f = 0.2:
    // σ_f = 200 + 1500·0.18 = 470 MPa;
    // ∫ = 200·0.02/2 + (200 + 470)/2 · 0.18 = 2 + 60.3 = 62.3 MJ/m³;
    // T_u = 62.3 MJ/m³ / 1.4 g/cm³ = 44.5 J/g = 44 500 J/kg
    let v = bilinear(0.0, 10e9, 0.02, 1.5e9, 0.2);
    let c = sample(&v, 1e-3, 0.02, 0.0, 10, 2);
    let f = analyze_fibre(&c, &FibreMeta::new("bi"), &TensileParams::default());
    assert!(rel(f.energy_density_j_per_m3.unwrap(), 62.3e6) < 1e-12);
    assert!(rel(f.toughness_j_per_kg.unwrap(), 62.3e6 / 1400.0) < 1e-12);
    assert!(rel(f.strength_pa.unwrap(), 470e6) < 1e-12);
}

/// A knotted fibre: plateau at 100 MPa with 10 stick-slip drops of 15 MPa,
/// three unfastening peaks, release at a trough of 20 MPa, then the
/// bilinear fibre (E = 10 GPa, ε_y = 0.02, H = 2 GPa) over 0.2 of strain.
fn knotted_spec() -> KnottedSpec {
    KnottedSpec {
        plateau: 100e6,
        plateau_rise: 0.02,
        tooth_width: 0.03,
        tooth_drop: 15e6,
        teeth: 10,
        unfastening_peaks: vec![250e6, 300e6, 350e6],
        unfastening_width: 0.03,
        unfastening_trough: 20e6,
        fibre: (10e9, 0.02, 2e9, 0.2),
    }
}

fn knotted_meta() -> FibreMeta {
    FibreMeta {
        knot: Knot::Noose,
        fibre_length_m: Some(0.025),
        end_distance_m: Some(0.020),
        material: "raw".into(),
        ..FibreMeta::new("k1")
    }
}

#[test]
fn knotted_curve_gives_release_drops_and_eq_5_2_5_3() {
    let spec = knotted_spec();
    let (v, rel_idx) = spec.vertices();
    let eps_star = v[rel_idx].0;
    let eps_f = v.last().unwrap().0;
    let c = sample(&v, 1e-3, 0.03, 0.0, 10, 3);
    let f = analyze_fibre(&c, &knotted_meta(), &TensileParams::default());
    assert!(f.status.is_ok(), "{:?}", f.status);
    // σ_f = 20 + 200 + 2000·0.18 = 580 MPa
    assert!(rel(f.strength_pa.unwrap(), 580e6) < 1e-12);
    assert!(rel(f.strain_at_break.unwrap(), eps_f) < 1e-12);
    assert_eq!(f.release_status, ReleaseStatus::AfterDrop);
    assert!((f.release_strain.unwrap() - eps_star).abs() < 1e-12);
    assert_eq!(f.plateau_drops, Some(10));
    assert_eq!(f.unfastening_drops, Some(3));
    // Eq. 5.2 with k1 = (25 − 20)/25 = 0.2
    let k1 = 0.2;
    let total = exact_area(&v, 0.0, eps_f);
    assert!(rel(f.toughness_j_per_kg.unwrap(), (1.0 - k1) * total / RHO) < 1e-12);
    // after release: 20 MPa · 0.2 + bilinear area 200·0.02/2 + (200+560)/2·0.18
    let after = 20e6 * 0.2 + 2e6 + 380e6 * 0.18;
    assert!(rel(exact_area(&v, eps_star, eps_f), after) < 1e-12);
    let tu = f.toughness_after_release_j_per_kg.unwrap();
    assert!(rel(tu, (1.0 - k1) * after / RHO) < 1e-12);
    assert!(rel(f.toughness_ratio.unwrap(), total / after) < 1e-12);
    assert_eq!(f.ratio_method, Some(RatioMethod::Release));
    assert_eq!(f.knot_effective, Some(true));
    // friction stress: the mean of σ over 0 … 0.4 ε_f (strain-weighted) of
    // the piecewise-linear curve, and its ratio to σ_f = 580 MPa
    let window = 0.4 * eps_f;
    let friction = exact_area(&v, 0.0, window) / window;
    assert!(rel(f.friction_stress_pa.unwrap(), friction) < 1e-12);
    assert!(rel(f.friction_ratio.unwrap(), friction / 580e6) < 1e-12);
}

#[test]
fn knotted_features_survive_noise() {
    let spec = knotted_spec();
    let (v, rel_idx) = spec.vertices();
    let eps_star = v[rel_idx].0;
    let eps_f = v.last().unwrap().0;
    let total = exact_area(&v, 0.0, eps_f);
    for seed in 0..5 {
        // noise sd 2 MPa (0.35 % of the strength)
        let c = sample(&v, 1e-3, 0.03, 2e6, 10, seed);
        let f = analyze_fibre(&c, &knotted_meta(), &TensileParams::default());
        assert_eq!(f.plateau_drops, Some(10), "seed {seed}");
        assert_eq!(f.unfastening_drops, Some(3), "seed {seed}");
        assert_eq!(f.release_status, ReleaseStatus::AfterDrop);
        // the trough is found within two samples of the vertex
        assert!((f.release_strain.unwrap() - eps_star).abs() <= 2e-3 + 1e-12);
        // zero-mean noise on ~700 samples changes the area by ≪ 1 %; the
        // break point may move by one sample (±0.3 % of the area)
        let tk = f.toughness_j_per_kg.unwrap();
        assert!(rel(tk, 0.8 * total / RHO) < 0.01, "seed {seed}: {tk}");
        assert!(rel(f.strength_pa.unwrap(), 580e6) < 0.02);
    }
}

#[test]
fn strain_relative_to_another_length_is_converted_to_l0() {
    // the instrument's strain is relative to 25 mm (l) but Eq. 5.2 wants l0 = 20 mm
    let spec = knotted_spec();
    let (v, _) = spec.vertices();
    let mut c = sample(&v, 1e-3, 0.03, 0.0, 10, 3);
    let reference = sample(&v, 1e-3, 0.03, 0.0, 10, 3);
    for e in &mut c.strain {
        *e *= 20.0 / 25.0;
    }
    c.strain_reference_m = Some(0.025);
    let a = analyze_fibre(&c, &knotted_meta(), &TensileParams::default());
    let b = analyze_fibre(&reference, &knotted_meta(), &TensileParams::default());
    // e·25/20 after ·20/25 differs from e by rounding only
    assert!(rel(a.toughness_j_per_kg.unwrap(), b.toughness_j_per_kg.unwrap()) < 1e-12);
    assert!(rel(a.strain_at_break.unwrap(), b.strain_at_break.unwrap()) < 1e-12);
}

#[test]
fn frictionless_knot_releases_from_the_zero_floor() {
    // the loop slides out at zero stress until ε = 0.3, then the fibre loads
    let mut v = vec![(0.0, 0.0), (0.3, 0.0)];
    v.extend(bilinear(0.3, 10e9, 0.02, 2e9, 0.2).into_iter().skip(1));
    let c = sample(&v, 1e-3, 0.0, 0.0, 10, 4);
    let f = analyze_fibre(&c, &knotted_meta(), &TensileParams::default());
    assert_eq!(f.release_status, ReleaseStatus::FromFloor);
    // the floor ends where σ exceeds h = 0.02 · 560 MPa = 11.2 MPa, i.e.
    // at 1.12e-3 strain into the rise: ε* within 2e-3 of 0.3
    assert!((f.release_strain.unwrap() - 0.3).abs() < 2e-3);
    assert_eq!(f.knot_effective, Some(false));
    // T_k ≈ T_u': the knot adds (almost) nothing
    assert!((f.toughness_ratio.unwrap() - 1.0).abs() < 1e-3);
}

#[test]
fn tight_knot_without_release_is_unclear_and_uses_the_control() {
    // stress stays high and rises monotonically: no drop, no floor
    let v = vec![(0.0, 0.0), (0.01, 300e6), (0.3, 400e6), (0.5, 500e6)];
    let c = sample(&v, 1e-3, 0.0, 0.0, 10, 5);
    let mut f = analyze_fibre(&c, &knotted_meta(), &TensileParams::default());
    assert_eq!(f.release_status, ReleaseStatus::Unclear);
    assert_eq!(f.release_strain, None);
    assert_eq!(f.toughness_ratio, None);
    let tk = f.toughness_j_per_kg.unwrap();
    f.apply_control(Some(tk / 2.5), "ctrl");
    // Eq. 5.4: T_k / T_u
    assert!(rel(f.toughness_ratio.unwrap(), 2.5) < 1e-12);
    assert_eq!(f.ratio_method, Some(RatioMethod::Control));
}

#[test]
fn bad_input_gives_a_status_not_a_number() {
    let p = TensileParams::default();
    let v = bilinear(0.0, 10e9, 0.02, 1e9, 0.1);
    // NaN in the record
    let mut c = sample(&v, 1e-3, 0.0, 0.0, 5, 6);
    c.stress_pa[10] = f64::NAN;
    let f = analyze_fibre(&c, &FibreMeta::new("nan"), &p);
    assert!(
        f.status.notes()[0].code.as_str() == "non_finite",
        "{:?}",
        f.status
    );
    assert_eq!(f.toughness_j_per_kg, None);
    // no fracture: the record stops while still loading
    let c = sample(&v, 1e-3, 0.0, 0.0, 0, 6);
    let f = analyze_fibre(&c, &FibreMeta::new("nofrac"), &p);
    assert!(
        f.status.notes()[0].code.as_str() == "no_fracture",
        "{:?}",
        f.status
    );
    assert_eq!(f.strength_pa, None);
    // knotted without l, l0: no T_k, but the Eq. 5.3 ratio (k1 cancels) stays
    let (kv, _) = knotted_spec().vertices();
    let c = sample(&kv, 1e-3, 0.0, 0.0, 5, 6);
    let meta = FibreMeta {
        knot: Knot::Noose,
        ..FibreMeta::new("nolen")
    };
    let f = analyze_fibre(&c, &meta, &p);
    assert!(
        f.status.notes()[0].code.as_str() == "missing_lengths",
        "{:?}",
        f.status
    );
    assert_eq!(f.toughness_j_per_kg, None);
    assert!(f.toughness_ratio.is_some());
    // zero density
    let meta = FibreMeta {
        density_kg_per_m3: Some(0.0),
        ..FibreMeta::new("rho")
    };
    let c = sample(&v, 1e-3, 0.0, 0.0, 5, 6);
    assert!(analyze_fibre(&c, &meta, &p).status.notes()[0].code.as_str() == "bad_density");
    // zero diameter is refused when force becomes stress
    assert!(StressStrainCurve::from_force(&[0.0, 1.0], &[0.0, 1.0], 1.0, 0.0).is_err());
}
