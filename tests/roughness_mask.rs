//! Points not measured (NaN heights, `extract::roughness::mask`): every
//! parameter is computed over the measured points, their number is
//! reported, and too many of them give a status. The checks compare a
//! surface with gaps against the same surface's measured points analysed
//! without them, or against closed forms that hold for any subset of
//! points.
#![deny(clippy::float_cmp)]

use std::f64::consts::PI;

use tribo::extract::roughness::*;
use tribo::signal::gaussian_filter::GaussianFilterParams;
use tribo::status::Code;

const A: f64 = 1e-6;
const PER: usize = 400;
const DX: f64 = 0.25e-6;

fn sine(periods: usize) -> Vec<f64> {
    (0..PER * periods)
        .map(|i| A * (2.0 * PI * i as f64 / PER as f64).sin())
        .collect()
}

fn mean_only() -> RoughnessParams {
    RoughnessParams {
        detrend: Detrend::Mean,
        ..Default::default()
    }
}

/// Whole periods blanked out leave whole periods measured: the amplitude
/// parameters of a sine are those of the closed form, the same as without
/// the gaps, and the gaps are counted.
#[test]
fn whole_periods_missing_leave_the_sine_closed_forms() {
    let mut z = sine(40);
    // Periods 5..8 and 20 not measured: 4 + 1 periods of 40.
    z[5 * PER..9 * PER].fill(f64::NAN);
    z[20 * PER..21 * PER].fill(f64::NAN);
    let p = Profile::new("gappy", 0.0, DX, z).unwrap();
    assert_eq!(p.n_invalid(), 5 * PER);
    let r = analyze_profile(&p, &mean_only()).unwrap();
    assert_eq!((r.n_points, r.n_invalid), (40 * PER, 5 * PER));
    // Over whole periods mean(sin²) = 1/2 exactly (round-off 1e-12); the
    // mean removed is that of the measured points (zero over whole periods).
    assert!((r.rq - A / 2f64.sqrt()).abs() < 1e-12 * A, "Rq {}", r.rq);
    // (2/N)cot(π/N) for N = 400: 2.1e-5 relative below 2/π. Tolerance 3e-5.
    assert!((r.ra - 2.0 * A / PI).abs() < 3e-5 * A, "Ra {}", r.ra);
    assert!(r.rsk.unwrap().abs() < 1e-9 && (r.rku.unwrap() - 1.5).abs() < 1e-9);
    // Peaks and valleys: the crests are measured.
    assert!((r.heights.peak - A).abs() < 1e-12 * A);
    assert!((r.heights.valley - A).abs() < 1e-12 * A);
    // 12.5 % not measured: above the default 10 %, a status.
    assert!(r.notes.has(Code::TooManyInvalid), "{}", r.status());
    let lenient = RoughnessParams {
        max_invalid_fraction: 0.2,
        ..mean_only()
    };
    // Within the allowance: no too_many_invalid; the PSD fills the gaps
    // (gaps_filled) and a sine is not self-affine (poor_fit).
    let lenient = analyze_profile(&p, &lenient).unwrap();
    let st = lenient.status();
    assert!(
        lenient.notes.only(&[Code::GapsFilled, Code::PoorFit]),
        "{st}"
    );
    assert!(st.contains("gaps_filled"), "{st}");
}

/// The slope of a sine where every stencil is measured: a gap removes the
/// stencils that touch it, not more, and the RMS slope over the rest of
/// whole periods is the closed form times the scheme's factor.
#[test]
fn slopes_skip_the_stencils_that_touch_a_gap() {
    let mut z = sine(20);
    let full = analyze_profile(
        &Profile::new("s", 0.0, DX, z.clone()).unwrap(),
        &mean_only(),
    )
    .unwrap()
    .rms_slope
    .unwrap();
    // Blank one whole period plus the 6 points a 7-point stencil needs
    // around it, so that the stencils left cover whole periods... less
    // simple: compare with the slope of the profile cut at the gap, which
    // the same stencils see.
    z[10 * PER..11 * PER].fill(f64::NAN);
    let gappy = analyze_profile(
        &Profile::new("s", 0.0, DX, z.clone()).unwrap(),
        &mean_only(),
    )
    .unwrap()
    .rms_slope
    .unwrap();
    let (left, right) = (&z[..10 * PER], &z[11 * PER..]);
    let s = |v: &[f64]| {
        tribo::extract::roughness::amplitude::slopes(v, DX, DerivativeScheme::Iso7Point)
    };
    let both: Vec<f64> = s(left).into_iter().chain(s(right)).collect();
    let expect = (both.iter().map(|d| d * d).sum::<f64>() / both.len() as f64).sqrt();
    assert!(
        (gappy - expect).abs() < 1e-12 * expect,
        "{gappy} vs {expect}"
    );
    // And both are the sine's RMS slope to the scheme's accuracy (the
    // stencils left do not cover whole periods: 1e-3).
    assert!((gappy - full).abs() < 1e-3 * full);
}

/// The bearing curve and heights use the measured points only: a profile
/// with gaps has the bearing curve of its measured points.
#[test]
fn bearing_curve_is_that_of_the_measured_points() {
    let mut z: Vec<f64> = (0..1000)
        .map(|i| ((i * 7919) % 1000) as f64 * 1e-9)
        .collect();
    for i in (0..1000).step_by(9) {
        z[i] = f64::NAN;
    }
    let measured: Vec<f64> = z.iter().copied().filter(|v| !v.is_nan()).collect();
    let params = RoughnessParams {
        detrend: Detrend::None,
        ..Default::default()
    };
    let a = analyze_profile(&Profile::new("g", 0.0, DX, z).unwrap(), &params).unwrap();
    let b = analyze_profile(&Profile::new("m", 0.0, DX, measured).unwrap(), &params).unwrap();
    assert_eq!(a.bearing, b.bearing);
    assert_eq!(a.ra.to_bits(), b.ra.to_bits());
    assert_eq!(a.rq.to_bits(), b.rq.to_bits());
    assert_eq!(a.heights.peak.to_bits(), b.heights.peak.to_bits());
}

/// The mean line by its definition, summed directly: the ISO 16610-21
/// weights s(x) = exp(−π(x/αλc)²) over |x| ≤ λc, normalised over the
/// measured samples; NaN where they carry less than half of the in-range
/// weight (the rule of `extract::roughness::mask`).
fn direct_mean_line(z: &[f64], dx: f64, lc: f64) -> Vec<f64> {
    let al = (std::f64::consts::LN_2 / PI).sqrt() * lc;
    let half = (lc / dx).ceil() as isize;
    let w: Vec<f64> = (-half..=half)
        .map(|j| (-PI * (j as f64 * dx / al).powi(2)).exp())
        .collect();
    let n = z.len() as isize;
    (0..n)
        .map(|i| {
            let (mut num, mut den, mut full) = (0.0, 0.0, 0.0);
            for j in -half..=half {
                let k = i + j;
                if k < 0 || k >= n {
                    continue;
                }
                let wk = w[(j + half) as usize];
                full += wk;
                if !z[k as usize].is_nan() {
                    num += wk * z[k as usize];
                    den += wk;
                }
            }
            if den >= 0.5 * full {
                num / den
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// A Gaussian filter bridges a short gap by the normalised convolution and
/// keeps a gap wider than its kernel: the roughness equals the profile
/// minus the mean line summed directly by its definition, point by point,
/// NaN for NaN.
#[test]
fn filter_bridges_short_gaps_and_keeps_wide_ones() {
    let lc = 4.0 * PER as f64 * DX;
    let f = GaussianFilterParams::new(lc).unwrap();
    let params = RoughnessParams {
        detrend: Detrend::None,
        filter: Some(f),
        ..Default::default()
    };
    let mut z = sine(60);
    z[30 * PER..31 * PER].fill(f64::NAN);
    // A short gap; then a wide one (2.5 λc) beside it; then a second wide
    // one that leaves an island of half a period between them, whose points
    // have less than half of the kernel's weight measured: they become
    // points not measured too.
    let island = 20 * PER + PER / 2;
    let cases = [
        (None, PER),
        (Some(10 * PER..20 * PER), 11 * PER),
        (
            Some(island..30 * PER),
            11 * PER + (30 * PER - island) + PER / 2,
        ),
    ];
    for (gap, expect_nan) in cases {
        if let Some(g) = gap {
            z[g].fill(f64::NAN);
        }
        let r = analyze_profile(&Profile::new("f", 0.0, DX, z.clone()).unwrap(), &params).unwrap();
        let m = direct_mean_line(&z, DX, lc);
        let drop = 2 * PER; // λc/2 discarded at each end
        let want: Vec<f64> = (drop..z.len() - drop).map(|i| z[i] - m[i]).collect();
        let rq = {
            let v: Vec<f64> = want.iter().copied().filter(|v| !v.is_nan()).collect();
            (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
        };
        // FFT against direct sums: round-off, 1e-12 relative.
        assert!((r.rq - rq).abs() < 1e-12 * rq, "Rq {} vs {rq}", r.rq);
        let nan = want.iter().filter(|v| v.is_nan()).count();
        assert_eq!((r.n_invalid, nan), (expect_nan, expect_nan));
        // Near a gap the kernel misses periods over which the sine does not
        // quite cancel under the sloping weights: Rq stays within 2 % of the
        // transmitted sine (1 − 2^-16) A/√2.
        assert!((r.rq - A / 2f64.sqrt()).abs() < 2e-2 * A, "Rq {}", r.rq);
    }
}

/// Maps: Sa, Sq over the measured points, Sdq where both derivatives'
/// stencils are measured.
#[test]
fn map_parameters_over_measured_points() {
    let (nx, ny) = (200, 160);
    let d = 1e-6;
    // A plane wave along x with whole periods in every row; one period of
    // columns (40..80) not measured on rows 40..80, so every row still
    // holds whole periods.
    let per = 40;
    let mut z: Vec<f64> = (0..ny)
        .flat_map(|_| (0..nx).map(move |c| A * (2.0 * PI * c as f64 / per as f64).sin()))
        .collect();
    for r in 40..80 {
        z[r * nx + 40..r * nx + 80].fill(f64::NAN);
    }
    let m = AreaMap::new("m", d, d, nx, ny, z).unwrap();
    let r = analyze_map(&m, &mean_only()).unwrap();
    assert_eq!(r.n_invalid, 40 * 40);
    // Whole periods: mean(sin²) = 1/2 to round-off; Sa (2/N)cot(π/N) for
    // N = 40: 2.1e-3 below 2A/π.
    assert!((r.rq - A / 2f64.sqrt()).abs() < 1e-12 * A, "Sq {}", r.rq);
    let sa = 2.0 * A / per as f64 / (PI / per as f64).tan();
    assert!((r.ra - sa).abs() < 1e-12 * A, "Sa {}", r.ra);
    // Sdq: the 7-point gradient at the points whose two stencils (13
    // points) are all measured, written out here.
    let at = |r: usize, c: usize| m.z[r * nx + c];
    let g7 = |f: &dyn Fn(isize) -> f64| {
        (f(3) - 9.0 * f(2) + 45.0 * f(1) - 45.0 * f(-1) + 9.0 * f(-2) - f(-3)) / (60.0 * d)
    };
    let (mut s, mut k) = (0.0, 0);
    for r in 3..ny - 3 {
        for c in 3..nx - 3 {
            let gx = g7(&|j| at(r, (c as isize + j) as usize));
            let gy = g7(&|j| at((r as isize + j) as usize, c));
            if !(gx.is_nan() || gy.is_nan()) {
                s += gx * gx + gy * gy;
                k += 1;
            }
        }
    }
    let sdq = (s / k as f64).sqrt();
    let got = r.rms_slope.unwrap();
    assert!((got - sdq).abs() < 1e-12 * sdq, "Sdq {got} vs {sdq}");
    // 5 % not measured: no status for it (a plane wave has no structure
    // along y, so the fractal dimension says so).
    assert!(!r.notes.has(Code::TooManyInvalid), "{}", r.status());
}
