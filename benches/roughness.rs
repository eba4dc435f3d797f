//! Roughness of a 10-million-point profile and of a 2000 × 2000 map: wall
//! time per stage and peak resident memory (VmHWM from /proc/self/status).
//!
//! `cargo bench --bench roughness` (release). Figures go to
//! docs/roughness.md. Inputs are seeded self-affine surfaces (H = 0.7), so
//! runs are comparable.

use std::time::Instant;

use tribo::extract::roughness::fractal::synthesize_self_affine;
use tribo::extract::roughness::*;
use tribo::signal::gaussian_filter::GaussianFilterParams;

fn vm_hwm_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

/// Resets VmHWM to the current RSS (Linux: write 5 to clear_refs), so each
/// stage reports its own peak.
fn reset_peak() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn time<T>(what: &str, f: impl FnOnce() -> T) -> T {
    reset_peak();
    let t = Instant::now();
    let r = f();
    println!(
        "{what:<58} {:>8.3} s   peak RSS {:>7.0} MB",
        t.elapsed().as_secs_f64(),
        vm_hwm_mb()
    );
    r
}

fn main() {
    println!("start: peak RSS {:.0} MB", vm_hwm_mb());
    let n = 10_000_000;
    let dx = 0.1e-6;
    let z = time("synthesize 10M-point profile (2^24 FFT)", || {
        let mut z = synthesize_self_affine(1 << 24, 0.7, 1e-6, 1);
        z.truncate(n);
        z
    });
    let p = Profile::new("bench", 0.0, dx, z).unwrap();
    let base = RoughnessParams::default();
    time("profile 10M: line detrend, 7-point, structure fn", || {
        analyze_profile(&p, &base).unwrap()
    });
    let filt = RoughnessParams {
        filter: Some(GaussianFilterParams::new(0.8e-3).unwrap()),
        ..base.clone()
    };
    time(
        "profile 10M: + Gaussian filter λc = 0.8 mm (16001 taps)",
        || analyze_profile(&p, &filt).unwrap(),
    );
    let psd = RoughnessParams {
        fractal: FractalParams {
            method: FractalMethod::PowerSpectrum,
            ..FractalParams::default()
        },
        ..base.clone()
    };
    time("profile 10M: power-spectrum fractal (2^24 FFT)", || {
        analyze_profile(&p, &psd).unwrap()
    });
    drop(p);

    let side = 2000;
    let d = 1e-6;
    let zmap = time("synthesize 2000 x 2000 map (rows of 2^11 FFTs)", || {
        let mut z = Vec::with_capacity(side * side);
        for r in 0..side {
            let row = synthesize_self_affine(2048, 0.7, 1e-6, 100 + r as u64);
            z.extend_from_slice(&row[..side]);
        }
        z
    });
    let m = AreaMap::new("bench-map", d, d, side, side, zmap).unwrap();
    time("map 4M: plane detrend, 7-point Sdq, structure fn", || {
        analyze_map(&m, &base).unwrap()
    });
    let filt_map = RoughnessParams {
        filter: Some(GaussianFilterParams::new(0.25e-3).unwrap()),
        ..base.clone()
    };
    time("map 4M: + areal Gaussian filter λc = 0.25 mm", || {
        analyze_map(&m, &filt_map).unwrap()
    });
    println!("end: peak RSS {:.0} MB", vm_hwm_mb());
}
