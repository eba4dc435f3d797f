//! Spring-block speed and accuracy (run: `cargo bench --bench spring_block`).
//!
//! Prints
//! 1. block-steps per second of the RK4 hot loop (85 × 85, every block
//!    sliding);
//! 2. the static-peak error against a fine-step RK4 reference (dt = 2.5e-9
//!    s) for fixed-step RK4 and for the event-driven scheme (with and without
//!    parked hole clusters) at several dt, with their wall times (flat and
//!    pattern-B lattices of 16 × 16);
//! 3. the time of 85 × 85 runs (loading to the peak, then sliding) and the
//!    extrapolated time of the thesis sweep (8 pressures × 10 repetitions,
//!    1 ms of sliding) on 2 threads, with the static peak of each setting
//!    against the finest one (event, parked, dt = 1e-8).
//!
//! `SPRING_BLOCK_BENCH_QUICK=1` shortens everything (smoke test);
//! `SPRING_BLOCK_BENCH_ONLY=hot,accuracy,sweep` selects sections.

use std::time::Instant;

use tribo::models::spring_block::{Interface, Lattice, Pattern, SpringBlockParams};
use tribo::simulate::spring_block::{
    simulate_run, IntegratorParams, RunControl, RunSpec, Scheme, SpringBlockState, Stepper,
};

fn hot_loop(quick: bool) {
    let p = SpringBlockParams::default();
    let lat = Lattice::new(&p);
    let n = lat.len();
    // Every block sliding against kinetic friction (threshold tiny but not
    // zero, so none is free, and all start moving).
    let fnn = 10e3 * p.spacing * p.spacing;
    let iface = Interface {
        mu_static: vec![1e-9; n],
        mu_dynamic: vec![0.0; n],
        threshold: vec![1e-30; n],
        kinetic: vec![3.0 * fnn; n],
        normal_force: fnn,
    };
    let mut s = SpringBlockState::at_rest(&iface);
    for i in 0..n {
        s.sliding[i] = true;
        s.vx[i] = 1e-4 + 1e-6 * (i % 7) as f64;
        s.vy[i] = 1e-5;
    }
    let mut st = Stepper::new(&lat, &iface, (2e-4, 0.0), p.damping, &s);
    let steps = if quick { 200 } else { 3000 };
    let t0 = Instant::now();
    for _ in 0..steps {
        st.step(&mut s, 1e-8).unwrap();
    }
    let el = t0.elapsed().as_secs_f64();
    println!(
        "hot loop: 85x85, all sliding: {} block-steps in {:.3} s = {:.3e} block-steps/s (1 thread)",
        st.block_steps,
        el,
        st.block_steps as f64 / el
    );
}

/// Integrator variants compared: fixed-step RK4, the event scheme without
/// and with parked hole clusters.
#[derive(Clone, Copy, Debug)]
enum Variant {
    Rk4,
    Event,
    Parked,
}

fn peak(
    p: &SpringBlockParams,
    mask: &[bool],
    variant: Variant,
    dt: f64,
    sliding: f64,
) -> (f64, f64, u64, Option<f64>) {
    let lat = Lattice::new(p);
    let integ = IntegratorParams {
        scheme: match variant {
            Variant::Rk4 => Scheme::Rk4,
            _ => Scheme::Event,
        },
        dt,
        park_holes: matches!(variant, Variant::Parked),
        ..Default::default()
    };
    let control = RunControl {
        sliding_time: sliding,
        curve_interval: 0.0,
        ..Default::default()
    };
    let spec = RunSpec {
        pressure: 10e3,
        angle: 0.3,
        seed: 42,
    };
    let t0 = Instant::now();
    let r = simulate_run(p, &lat, mask, &integ, &control, &spec).unwrap();
    let el = t0.elapsed().as_secs_f64();
    assert_eq!(r.stop.status(), "ok", "{}", r.stop.message());
    (r.mu_static.unwrap(), el, r.block_steps, r.mu_dynamic)
}

fn accuracy(quick: bool) {
    let n = if quick { 8 } else { 16 };
    let p = SpringBlockParams {
        nx: n,
        ny: n,
        ..Default::default()
    };
    let dts: &[f64] = if quick {
        &[2e-8, 1e-7]
    } else {
        &[1e-8, 2e-8, 5e-8, 1e-7, 2e-7]
    };
    let dt_ref = if quick { 1e-8 } else { 2.5e-9 };
    for (name, pattern) in [
        ("flat", Pattern::Flat),
        (
            "B",
            Pattern::Holes {
                diameter: 10e-6,
                pitch: 15e-6,
            },
        ),
    ] {
        let mask = pattern.mask(n, n, p.spacing).unwrap();
        let (mref, tref, _, _) = peak(&p, &mask, Variant::Rk4, dt_ref, 0.0);
        println!(
            "accuracy {name} {n}x{n} @10 kPa: reference RK4 dt={dt_ref:e}: mu_s={mref:.6} ({tref:.2} s)"
        );
        for &dt in dts {
            for v in [Variant::Rk4, Variant::Event, Variant::Parked] {
                let (m, t, bs, _) = peak(&p, &mask, v, dt, 0.0);
                println!(
                    "  {v:?} dt={dt:e}: mu_s={m:.6} rel.err={:+.2e} time={t:.3} s speed-up={:.1} block-steps={bs}",
                    (m - mref) / mref,
                    tref / t
                );
            }
        }
    }
}

fn thesis_sweep(quick: bool) {
    let n = if quick { 20 } else { 85 };
    let p = SpringBlockParams {
        nx: n,
        ny: n,
        ..Default::default()
    };
    let sliding = if quick { 2e-5 } else { 1e-4 };
    let settings: &[(Variant, f64)] = &[
        (Variant::Parked, 1e-8),
        (Variant::Parked, 5e-8),
        (Variant::Parked, 1e-7),
        (Variant::Event, 5e-8),
    ];
    for (name, pattern) in [
        ("flat", Pattern::Flat),
        (
            "B",
            Pattern::Holes {
                diameter: 10e-6,
                pitch: 15e-6,
            },
        ),
    ] {
        let mask = pattern.mask(n, n, p.spacing).unwrap();
        let mut m_fine = f64::NAN;
        for &(v, dt) in settings {
            if name == "flat" && matches!(v, Variant::Event) {
                continue; // no holes: the same as parked
            }
            let (m0, t_peak, _, _) = peak(&p, &mask, v, dt, 0.0);
            if m_fine.is_nan() {
                m_fine = m0;
            }
            let (_, t_all, bs, md) = peak(&p, &mask, v, dt, sliding);
            let per_ms = (t_all - t_peak) / sliding * 1e-3;
            let run = t_peak + per_ms;
            println!(
                "{name} {n}x{n} {v:?} dt={dt:e}: to peak {t_peak:.2} s (mu_s {m0:.5}, {:+.1e} vs parked dt=1e-8); \
                 sliding {per_ms:.2} s per ms ({:.2e} block-steps/s, mu_d {:.3}); one run with 1 ms sliding \
                 ~{run:.1} s; thesis sweep 80 runs on 2 threads ~{:.1} min",
                (m0 - m_fine) / m_fine,
                bs as f64 / t_all,
                md.unwrap_or(f64::NAN),
                80.0 * run / 2.0 / 60.0
            );
        }
        if name == "B" && !quick {
            // The unparked event scheme at the thesis step: static peak only.
            let (m, t, _, _) = peak(&p, &mask, Variant::Event, 1e-8, 0.0);
            println!(
                "{name} {n}x{n} Event dt=1e-8: to peak {t:.2} s (mu_s {m:.5}, {:+.1e} vs parked dt=1e-8)",
                (m - m_fine) / m_fine
            );
        }
    }
}

fn main() {
    let quick = std::env::var("SPRING_BLOCK_BENCH_QUICK").is_ok();
    let only = std::env::var("SPRING_BLOCK_BENCH_ONLY").unwrap_or_default();
    let on = |name: &str| only.is_empty() || only.split(',').any(|s| s == name);
    if on("hot") {
        hot_loop(quick);
    }
    if on("accuracy") {
        accuracy(quick);
    }
    if on("sweep") {
        thesis_sweep(quick);
    }
}
