//! Roughness parameters of analytic profiles against their closed forms
//! (MODELS.md §4 checks), and the bad-input edge cases.
#![deny(clippy::float_cmp)]

use std::f64::consts::PI;

use tribo::extract::roughness::amplitude::rms_slope;
use tribo::extract::roughness::*;
use tribo::signal::gaussian_filter::{FilterEnds, GaussianFilterParams};
use tribo::status::Code;
use tribo::Error;

const A: f64 = 1e-6; // amplitude, m
const LAMBDA: f64 = 100e-6; // wavelength, m
const PER: usize = 1000; // samples per wavelength
const PERIODS: usize = 100;

fn sine() -> Profile {
    sine_padded(0)
}

/// A sine over `PERIODS` whole periods plus `pad` extra samples, so that a
/// derivative scheme that drops `pad` points still covers whole periods.
fn sine_padded(pad: usize) -> Profile {
    let dx = LAMBDA / PER as f64;
    let z = (0..PER * PERIODS + pad)
        .map(|i| A * (2.0 * PI * i as f64 / PER as f64).sin())
        .collect();
    Profile::new("sine", 0.0, dx, z).unwrap()
}

fn mean_params() -> RoughnessParams {
    // A sine over whole periods has zero mean, but its least-squares line
    // is not zero (the sine correlates with x); remove only the mean.
    RoughnessParams {
        detrend: Detrend::Mean,
        ..Default::default()
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn sine_amplitude_parameters_match_closed_forms() {
    let r = analyze_profile(&sine(), &mean_params()).unwrap();
    // Sampled mean of |sin| over N points per period is (2/N)cot(π/N) =
    // (2/π)(1 − π²/(3N²) + …): 3.3e-6 relative for N = 1000. Tolerance 1e-5.
    assert!(rel(r.ra, 2.0 * A / PI) < 1e-5, "Ra {}", r.ra);
    // mean(sin²) = 1/2 and mean(sin⁴) = 3/8 are exact for N > 4 equally
    // spaced phases; only round-off remains (1e-12).
    assert!(rel(r.rq, A / 2f64.sqrt()) < 1e-12, "Rq {}", r.rq);
    assert!(r.rsk.unwrap().abs() < 1e-9, "Rsk {:?}", r.rsk);
    assert!((r.rku.unwrap() - 1.5).abs() < 1e-9, "Rku {:?}", r.rku);
    // A sine is not self-affine: its fractal fit is poor, and says so; no
    // other note.
    assert!(r.notes.only(&[Code::PoorFit]), "{}", r.status());
    assert!(r.notes.has(Code::PoorFit));
}

#[test]
fn sine_rms_slope_matches_closed_form_for_every_scheme() {
    let dx = LAMBDA / PER as f64;
    let k = 2.0 * PI / LAMBDA;
    let kd = k * dx;
    let exact = 2.0 * PI * A / (LAMBDA * 2f64.sqrt());
    // Each scheme's transfer function on a sine gives its exact discrete
    // RMS slope: forward 2 sin(kΔ/2)/kΔ, central sin(kΔ)/kΔ, 7-point
    // (45 sin kΔ − 9 sin 2kΔ + sin 3kΔ)/(30 kΔ). The profile is padded by
    // the points the scheme drops (1, 2, 6), so the slopes cover whole
    // periods and mean(cos²) = 1/2 exactly: only round-off remains (1e-10).
    let cases = [
        (DerivativeScheme::Forward, 1, 2.0 * (kd / 2.0).sin() / kd),
        (DerivativeScheme::Central, 2, kd.sin() / kd),
        (
            DerivativeScheme::Iso7Point,
            6,
            (45.0 * kd.sin() - 9.0 * (2.0 * kd).sin() + (3.0 * kd).sin()) / (30.0 * kd),
        ),
    ];
    let mut by_scheme = Vec::new();
    for (scheme, pad, factor) in cases {
        let p = sine_padded(pad);
        let s = rms_slope(&p.z, p.dx, scheme).unwrap();
        assert!(
            rel(s, exact * factor) < 1e-10,
            "{scheme:?}: {s} vs {}",
            exact * factor
        );
        let r = analyze_profile(
            &p,
            &RoughnessParams {
                derivative: scheme,
                ..mean_params()
            },
        )
        .unwrap();
        let deg = r.rdq_deg.unwrap();
        assert!((deg - s.atan().to_degrees()).abs() < 1e-12);
        by_scheme.push(s);
    }
    // The 7-point scheme is sixth order: (kΔ)⁶ ≈ 6e-11 from the continuous
    // value; second-order central is off by (kΔ)²/6 ≈ 6.6e-6.
    assert!(rel(by_scheme[2], exact) < 1e-9);
    assert!((rel(by_scheme[1], exact) - kd * kd / 6.0).abs() < 1e-8);
}

#[test]
fn triangle_wave_bearing_curve_is_linear_through_the_analysis() {
    let period = 400;
    let z: Vec<f64> = (0..period * 25)
        .map(|i| {
            let p = (i % period) as f64 / period as f64;
            A * (4.0 * (p - 0.5).abs() - 1.0)
        })
        .collect();
    let prof = Profile::new("tri", 0.0, 1e-7, z).unwrap();
    let r = analyze_profile(
        &prof,
        &RoughnessParams {
            detrend: Detrend::Mean,
            bearing_points: 21,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.bearing.len(), 21);
    // Uniform height distribution: c(Rmr) = A(1 − 2 Rmr); the mean removal
    // shifts heights by at most one quantisation step 4A/period = 0.01 A.
    for &(mr, h) in &r.bearing {
        assert!((h - A * (1.0 - 2.0 * mr)).abs() < 0.02 * A, "{mr}: {h}");
    }
    // A triangle wave's Rq = A/√3, Rku = 9/5 (uniform distribution).
    assert!(rel(r.rq, A / 3f64.sqrt()) < 1e-4);
    assert!((r.rku.unwrap() - 1.8).abs() < 1e-3);
}

#[test]
fn flat_profile_reports_zero_roughness_and_null_shape_parameters() {
    // A tilted straight line: after the line detrend only round-off remains.
    let z: Vec<f64> = (0..1000).map(|i| 1e-3 + 2e-6 * i as f64).collect();
    let p = Profile::new("flat", 0.0, 1e-6, z).unwrap();
    let r = analyze_profile(&p, &RoughnessParams::default()).unwrap();
    assert!(r.rq < 1e-15 && r.ra < 1e-15);
    assert!(r.rsk.is_none() && r.rku.is_none() && r.fractal.is_none());
    assert!(r.status().contains("flat"), "{}", r.status());
    // Exactly zero heights.
    let p = Profile::new("zero", 0.0, 1e-6, vec![0.0; 100]).unwrap();
    let r = analyze_profile(&p, &RoughnessParams::default()).unwrap();
    assert!(r.rsk.is_none() && r.rdq_deg.is_some_and(|d| d.abs() < 1e-15));
    // No value claims to be a number while being NaN.
    for v in [Some(r.ra), Some(r.rq), r.rdq_deg, r.rsk, r.rku] {
        assert!(v.is_none_or(f64::is_finite));
    }
}

#[test]
fn bad_inputs_are_clear_errors() {
    assert!(matches!(
        Profile::new("p", 0.0, 1e-6, vec![0.0; 5]),
        Err(Error::Input { .. })
    ));
    // Infinity is an error; NaN is a point not measured
    // (tests/roughness_mask.rs).
    let mut z = vec![0.0; 50];
    z[10] = f64::INFINITY;
    assert!(Profile::new("p", 0.0, 1e-6, z).is_err());
    let x: Vec<f64> = (0..50).map(|i| (i * i) as f64).collect();
    assert!(Profile::from_xz("p", x.clone(), vec![0.0; 50]).is_err());
    // A window that holds too few points.
    let p = sine();
    let e = analyze_profile(
        &p,
        &RoughnessParams {
            window: Some((0.0, 3e-7)),
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("holds 4 points"), "{e}");
    // A cut-off longer than the profile.
    let short = Profile::new("s", 0.0, 1e-6, vec![0.0; 100]).unwrap();
    let e = analyze_profile(
        &short,
        &RoughnessParams {
            filter: Some(GaussianFilterParams::new(0.8e-3).unwrap()),
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(matches!(e, Error::NotApplicable(_)), "{e}");
    // Invalid parameters.
    assert!(ContactParams::new(30e6, 25e6).is_err());
    assert!(RoughnessParams {
        window: Some((1.0, 0.5)),
        ..Default::default()
    }
    .validate()
    .is_err());
}

#[test]
fn gaussian_filter_separates_roughness_from_waviness() {
    // Roughness sine λr = λc/10 plus waviness sine λw = 10 λc, equal
    // amplitudes. The roughness profile transmits 1 − exp(−π(αλc/λ)²):
    // 1 − 2^−100 for λr and 1 − 2^(−1/100) ≈ 0.00691 for λw, so
    // Rq = A/√2 · sqrt(1 + 0.00691²). Discarding λc/2 at each end leaves a
    // non-integer number of periods (error ≲ 1/(2·periods)) and the sampled
    // kernel differs from the continuous one by < 1e-6: tolerance 2e-3.
    let lc = 0.25e-3;
    let dx = 0.25e-6;
    let n = (40.0 * lc / dx) as usize;
    let z: Vec<f64> = (0..n)
        .map(|i| {
            let x = i as f64 * dx;
            A * (2.0 * PI * x / (lc / 10.0)).sin() + A * (2.0 * PI * x / (10.0 * lc)).sin()
        })
        .collect();
    let p = Profile::new("rw", 0.0, dx, z).unwrap();
    let f = GaussianFilterParams::new(lc).unwrap();
    let r = analyze_profile(
        &p,
        &RoughnessParams {
            detrend: Detrend::None,
            filter: Some(f),
            ..Default::default()
        },
    )
    .unwrap();
    let tw = 1.0 - 2f64.powf(-0.01);
    let expect = A / 2f64.sqrt() * (1.0 + tw * tw).sqrt();
    assert!(rel(r.rq, expect) < 2e-3, "Rq {} vs {expect}", r.rq);
    assert_eq!(r.n_points, n - 2 * 500);
    // Renormalised ends keep every point.
    let r2 = analyze_profile(
        &p,
        &RoughnessParams {
            detrend: Detrend::None,
            filter: Some(GaussianFilterParams {
                ends: FilterEnds::Renormalize,
                ..f
            }),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r2.n_points, n);
}

#[test]
fn contact_length_follows_eq_3_15_from_the_reported_values() {
    // One period sampled at 200 000 points so that the sorted heights near
    // the crest are finely spaced in material ratio (2/N per level).
    let n = 200_000;
    let z = (0..n)
        .map(|i| A * (2.0 * PI * i as f64 / n as f64).sin())
        .collect();
    let p = Profile::new("fine-sine", 0.0, LAMBDA / n as f64, z).unwrap();
    let c = ContactParams::new(1.0e6, 20.0e6).unwrap();
    let r = analyze_profile(
        &p,
        &RoughnessParams {
            contact: Some(c),
            ..mean_params()
        },
    )
    .unwrap();
    let est = r.contact.unwrap();
    assert!(rel(est.area_ratio, 0.05) < 1e-12);
    // For a sine the material ratio at depth d below the crest is
    // acos(1 − d/A)/π, so d = A(1 − cos(π ΔA)). The sampled curve reaches
    // ΔA = 0.05 at height level j ≈ ΔA·N/2 = 5000 ± 1, and d ∝ j²: relative
    // error ≤ 2/5000 = 4e-4. Tolerance 1e-3.
    let d = A * (1.0 - (PI * 0.05).cos());
    assert!(rel(est.depth, d) < 1e-3, "d {} vs {d}", est.depth);
    let tan = r.rdq_deg.unwrap().to_radians().tan();
    assert!(rel(est.length, 2.0 * est.depth / tan) < 1e-12);
}

#[test]
fn areal_sine_plane_wave_matches_profile_closed_forms() {
    // z = A sin(2π x/λ) on a (4 periods + 6) × 16 grid: Sa, Sq, Sku as for
    // the profile; Sdq equals the x slope (the y slope is zero).
    let (nx, ny) = (4 * PER + 6, 16);
    let dx = LAMBDA / PER as f64;
    let z: Vec<f64> = (0..ny)
        .flat_map(|_| (0..nx).map(|c| A * (2.0 * PI * c as f64 / PER as f64).sin()))
        .collect();
    let m = AreaMap::new("plane-wave", dx, dx, nx, ny, z).unwrap();
    let r = analyze_map(
        &m,
        &RoughnessParams {
            detrend: Detrend::Mean,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.kind, SurfaceKind::Areal);
    // 6 extra points beyond whole periods: the heights' mean of sin² and
    // |sin| move by at most 6/4006 relative: tolerance 2e-3.
    assert!(rel(r.rq, A / 2f64.sqrt()) < 2e-3);
    assert!(rel(r.ra, 2.0 * A / PI) < 2e-3);
    assert!((r.rku.unwrap() - 1.5).abs() < 1e-2);
    let slope = r.rdq_deg.unwrap().to_radians().tan();
    // The 7-point slopes cover exactly 4 periods: round-off only (1e-9,
    // sixth-order truncation included).
    assert!(rel(slope, 2.0 * PI * A / (LAMBDA * 2f64.sqrt())) < 1e-9);
}

#[test]
fn fractal_dimension_of_synthetic_surface_profiles_through_the_analysis() {
    use tribo::extract::roughness::fractal::synthesize_self_affine;
    for (h, seed) in [(0.4, 21u64), (0.7, 22)] {
        let z = synthesize_self_affine(1 << 14, h, 1e-6, seed);
        let p = Profile::new("fbm", 0.0, 1e-7, z).unwrap();
        let r = analyze_profile(&p, &RoughnessParams::default()).unwrap();
        // Tolerance as in the fractal module's tests (measured ≤ 0.04).
        let d = r.fractal.unwrap().dimension.unwrap();
        assert!((d - (2.0 - h)).abs() < 0.05, "H {h}: D {d}");
    }
}

/// MODELS.md §9 height parameters of a sine over whole periods, through the
/// whole chain: Rp = Rv = A, Rt = Rz = 2A (each fifth holds whole periods
/// with a crest and a trough), next to Ra = 2A/π and Rq = A/√2.
#[test]
fn sine_heights_closed_forms() {
    let r = analyze_profile(&sine(), &mean_params()).unwrap();
    let h = r.heights;
    // Samples fall on the crests (1000 per period, a multiple of 4); the
    // mean removed is ~1e-20 m of round-off: 1e-9 relative is ample.
    assert!(rel(h.peak, A) < 1e-9, "Rp {}", h.peak);
    assert!(rel(h.valley, A) < 1e-9, "Rv {}", h.valley);
    assert!(rel(h.total, 2.0 * A) < 1e-9, "Rt {}", h.total);
    assert!(rel(h.rz_din.unwrap(), 2.0 * A) < 1e-9);
    assert!(rel(h.rz_iso.unwrap(), 2.0 * A) < 1e-9);
    assert_eq!(h.rz_sampling_lengths, 5);
    // Point-based Ra of a sine sampled N = 1000 times per period from a
    // zero: (1/N) Σ|sin(2πk/N)| = (2/N) cot(π/N) exactly, which is 2/π to
    // (π/N)²/3 ≈ 3.3e-6 relative.
    let n = PER as f64;
    assert!(
        rel(r.ra, A * 2.0 / n / (PI / n).tan()) < 1e-9,
        "Ra {}",
        r.ra
    );
    assert!(rel(r.ra, 2.0 * A / PI) < 4e-6, "Ra {}", r.ra);
    assert!(rel(r.rq, A / 2f64.sqrt()) < 1e-9, "Rq {}", r.rq);
    // With the Gaussian filter the ISO sampling length is λc = 3 λ:
    // 100 λ less λc discarded is 97 λ, 32 whole sampling lengths.
    let p = RoughnessParams {
        filter: Some(GaussianFilterParams::new(3.0 * LAMBDA).unwrap()),
        ..mean_params()
    };
    let f = analyze_profile(&sine(), &p).unwrap().heights;
    assert_eq!(f.rz_sampling_lengths, 32);
    // The filter passes a λ = λc/3 sine almost whole (the mean line's
    // transmission there is exp(−π (α/3)²) ≈ 0.03); every sampling length
    // spans crests and troughs, so Rz stays within 1 % of Rt.
    assert!(rel(f.rz_iso.unwrap(), f.total) < 1e-2, "{:?}", f);
}
