//! The functional, spatial and hybrid parameters through the whole analysis
//! against closed forms on synthetic surfaces (MODELS.md §10).

use std::f64::consts::PI;

use tribo::extract::roughness::*;
use tribo::status::Code;

const A: f64 = 1e-6;
const LAMBDA: f64 = 64e-6;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Complete elliptic integral of the second kind E(m) (parameter m) by
/// composite Simpson over 20 000 intervals: the integrand is smooth and
/// periodic, so the error is far below 1e-12.
fn ellipe(m: f64) -> f64 {
    let n = 20_000;
    let h = PI / 2.0 / n as f64;
    let f = |t: f64| (1.0 - m * t.sin().powi(2)).sqrt();
    let mut s = f(0.0) + f(PI / 2.0);
    for i in 1..n {
        s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

fn periodic() -> RoughnessParams {
    RoughnessParams {
        detrend: Detrend::Mean,
        periodic: true,
        ..Default::default()
    }
}

/// z = A sin(2πx/λ) on a map of `nx` × 512 points, 256 points per period.
fn sine_map(nx: usize) -> AreaMap {
    let per = 256;
    let ny = 2 * per;
    let dx = LAMBDA / per as f64;
    let z = (0..ny)
        .flat_map(|_| (0..nx).map(move |i| A * (2.0 * PI * i as f64 / per as f64).sin()))
        .collect();
    AreaMap::new("sine", dx, dx, nx, ny, z).unwrap()
}

#[test]
fn sine_map_sdr_sal_std_and_undefined_str() {
    // Sdr = (2/π)√(1 + a²) E(a²/(1 + a²)) − 1, a = 2πA/λ (MODELS.md §10),
    // on cells spanning whole periods (4 periods + 1 point: the n − 1 cells
    // of a map of 4 whole periods miss one cell of the steepest slope, 1e-3
    // of Sdr). The grid's triangles replace the slope by the chord's:
    // relative error of its square (kΔ)²/12 = 5e-5 for 256 points per
    // period. Tolerance 2e-4.
    let a = 2.0 * PI * A / LAMBDA;
    let exact = 2.0 / PI * (1.0 + a * a).sqrt() * ellipe(a * a / (1.0 + a * a)) - 1.0;
    let whole = analyze_map(&sine_map(4 * 256 + 1), &periodic()).unwrap();
    let sdr = whole.spatial.sdr.unwrap();
    assert!(rel(sdr, exact) < 2e-4, "Sdr {sdr} vs {exact}");
    let r = analyze_map(&sine_map(4 * 256), &periodic()).unwrap();
    let s = r.spatial;
    // The circular ACF of a sine is cos(2πt/λ) along x and 1 along y: Sal
    // is where cos falls to 0.2 along x, λ·acos(0.2)/2π. Linear
    // interpolation between lags errs by (Δ²/8)|f″| / |f′|: 1e-5 of Sal.
    let sal = LAMBDA * 0.2f64.acos() / (2.0 * PI);
    assert!(rel(s.sal.unwrap(), sal) < 1e-3, "Sal {:?} vs {sal}", s.sal);
    // No decay along the lay (y): Str undefined, null with a status.
    assert_eq!(s.str_ratio, None);
    assert!(r.notes.has(Code::ParameterUndefined), "{}", r.status());
    // The wavevector lies along x: Std = 0° (or 180°, the same direction).
    let std = s.std_deg.unwrap();
    assert!(std.min(180.0 - std) < 0.05, "Std {std}");
}

#[test]
fn cross_sine_sal_and_str_follow_the_product_acf() {
    // z = A sin(kx) sin(ky): circular ACF cos(k tx) cos(k ty), which falls
    // to 0.2 first along the axes (at acos(0.2)/k) and last along the
    // diagonals (at √2·acos(√0.2)/k): Str = acos(0.2)/(√2·acos(√0.2)).
    let per = 128;
    let n = 2 * per;
    let dx = LAMBDA / per as f64;
    let k = 2.0 * PI / LAMBDA;
    let z = (0..n)
        .flat_map(|j| {
            (0..n).map(move |i| A * (k * i as f64 * dx).sin() * (k * j as f64 * dx).sin())
        })
        .collect();
    let m = AreaMap::new("cross", dx, dx, n, n, z).unwrap();
    let r = analyze_map(&m, &periodic()).unwrap();
    let sal = 0.2f64.acos() / k;
    let longest = 2f64.sqrt() * 0.2f64.sqrt().acos() / k;
    // Bilinear interpolation of a product of cosines: 1e-4 relative at 128
    // points per period; the parabola through the rays near the diagonal
    // adds about as much. Tolerance 1e-3.
    assert!(
        rel(r.spatial.sal.unwrap(), sal) < 1e-3,
        "Sal {:?}",
        r.spatial.sal
    );
    let str_ratio = r.spatial.str_ratio.unwrap();
    assert!(
        rel(str_ratio, sal / longest) < 1e-3,
        "Str {str_ratio} vs {}",
        sal / longest
    );
    assert!(str_ratio <= 1.0);
}

#[test]
fn sine_profile_volumes_and_material_ratio_match_the_arcsine_curve() {
    // Over whole periods the material ratio curve of A sin is
    // c(mr) = A cos(π mr), so Vm(p) = A(sin πp/π − p cos πp) and
    // Vv(p) = A((1 − p) cos πp + sin πp/π). 20 periods of 5000 points: the
    // polyline's quantiles are O(1/n) = 1e-5 off. Tolerance 1e-3.
    let per = 5000;
    let n = 20 * per;
    let dx = LAMBDA / per as f64;
    let z = (0..n)
        .map(|i| A * (2.0 * PI * i as f64 / per as f64).sin())
        .collect();
    let p = Profile::new("sine", 0.0, dx, z).unwrap();
    let params = RoughnessParams {
        detrend: Detrend::Mean,
        ..Default::default()
    };
    let r = analyze_profile(&p, &params).unwrap();
    let f = r.functional.unwrap();
    let vm = |p: f64| A * ((PI * p).sin() / PI - p * (PI * p).cos());
    let vv = |p: f64| A * ((1.0 - p) * (PI * p).cos() + (PI * p).sin() / PI);
    let (pp, qq) = (0.1, 0.8);
    assert!(rel(f.volume.vmp, vm(pp)) < 1e-3, "Vmp {}", f.volume.vmp);
    assert!(
        rel(f.volume.vmc, vm(qq) - vm(pp)) < 1e-3,
        "Vmc {}",
        f.volume.vmc
    );
    assert!(
        rel(f.volume.vvc, vv(pp) - vv(qq)) < 1e-3,
        "Vvc {}",
        f.volume.vvc
    );
    assert!(rel(f.volume.vvv, vv(qq)) < 1e-3, "Vvv {}", f.volume.vvv);
    // Smc(0.1) = A cos(0.1π); Smr(0) = 1/2; Sxp = A(cos 0.025π − 0).
    assert!(rel(f.smc, A * (0.1 * PI).cos()) < 1e-3, "Smc {}", f.smc);
    assert!((f.smr - 0.5).abs() < 1e-3, "Smr {}", f.smr);
    assert!(rel(f.sxp, A * (0.025 * PI).cos()) < 1e-3, "Sxp {}", f.sxp);
    // RSm: one element per period.
    assert!(
        rel(r.spatial.rsm.unwrap(), LAMBDA) < 1e-3,
        "RSm {:?}",
        r.spatial.rsm
    );
}
