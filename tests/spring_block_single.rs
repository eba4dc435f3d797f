//! A single block and a two-block chain against hand-derived results
//! (MODELS.md §7): the time the static threshold is crossed and the slip
//! distance of an undamped spring-mass with Coulomb friction.
#![deny(clippy::float_cmp)]

use tribo::models::spring_block::{Interface, Lattice, SpringBlockParams};
use tribo::simulate::spring_block::{
    simulate_run, IntegratorParams, Jump, Jumper, RunControl, RunSpec, Scheme, SpringBlockState,
    Stepper,
};

fn params(nx: usize, ny: usize) -> SpringBlockParams {
    let mut p = SpringBlockParams {
        nx,
        ny,
        damping: 0.0,
        slider_speed: 0.02,
        ..Default::default()
    };
    p.friction.mu_static_sd = 0.0;
    p.friction.mu_dynamic_sd = 0.0;
    p
}

/// Interface with given thresholds and kinetic forces per block.
fn interface(threshold: Vec<f64>, kinetic: Vec<f64>, fn_: f64) -> Interface {
    Interface {
        mu_static: vec![0.0; threshold.len()],
        mu_dynamic: vec![0.0; threshold.len()],
        threshold,
        kinetic,
        normal_force: fn_,
    }
}

/// Slip distance of an undamped mass on a spring of stiffness k whose
/// kinetic equilibrium moves at speed v_eq. Released from rest at an offset
/// a = (threshold − kinetic)/k behind that equilibrium, x = x_eq + u with
/// u = −a cos ωτ − (v_eq/ω) sin ωτ. It stops when ẋ = v_eq + u̇ = 0 again,
/// v_eq(1 − cos ωτ) + aω sin ωτ = 0, i.e. ωτ = 2π − 2 atan(aω/v_eq), after
/// a distance v_eq τ + a − a cos ωτ − (v_eq/ω) sin ωτ (→ 2a as v_eq → 0).
fn slip_distance(a: f64, omega: f64, v_eq: f64) -> (f64, f64) {
    let wt = 2.0 * std::f64::consts::PI - 2.0 * (a * omega / v_eq).atan();
    let tau = wt / omega;
    (v_eq * tau + a - a * wt.cos() - v_eq / omega * wt.sin(), tau)
}

#[test]
fn single_block_threshold_time_matches_closed_form() {
    // t* = (μ_s F_n + F_ad)/(K_s v).
    let p = params(1, 1);
    let lat = Lattice::new(&p);
    let pressure = 10e3;
    let f_n = pressure * p.spacing * p.spacing;
    let th = p.friction.mu_static_mean * f_n + p.adhesion_force();
    let t_star = th / (p.k_shear() * p.slider_speed);
    let control = RunControl {
        sliding_time: 0.0,
        curve_interval: 0.0,
        ..Default::default()
    };
    let spec = RunSpec {
        pressure,
        angle: 0.3,
        seed: 1,
    };
    let mask = [false];
    // Event scheme: the jump lands on t* to rounding.
    let integ = IntegratorParams {
        dt: 1e-9,
        ..Default::default()
    };
    // Once sliding, u ≈ ½ A (t − t*)² with A = (th − μ_d F_n)/m, so T = K_s
    // (v t − u) still rises until t* + v/A, by ½ K_s v²/A (2e-5 of th here).
    let acc = (th - p.friction.mu_dynamic_mean * f_n) / p.block_mass();
    let t_peak = t_star + p.slider_speed / acc;
    let r = simulate_run(&p, &lat, &mask, &integ, &control, &spec).unwrap();
    let tp = r.peak_time.unwrap();
    // The peak is located to one step.
    assert!((tp - t_peak).abs() <= 1.0001e-9, "{tp} vs {t_peak}");
    // Static force = threshold: μ_s_macro N = μ_s F_n + F_ad (1 block).
    let fs = r.static_force.unwrap();
    let excess = 0.5 * p.k_shear() * p.slider_speed.powi(2) / acc;
    // The peak is sampled on the step grid: T is within ½ K_s A dt² of it.
    let grid = 0.5 * p.k_shear() * acc * 1e-18;
    assert!((fs - th - excess).abs() <= grid, "{fs} vs {th}");
    assert!(r.jumps >= 1);
    // Fixed-step RK4: the crossing is found within one step.
    let integ = IntegratorParams {
        scheme: Scheme::Rk4,
        dt: 1e-8,
        ..Default::default()
    };
    let r = simulate_run(&p, &lat, &mask, &integ, &control, &spec).unwrap();
    let tp = r.peak_time.unwrap();
    // The crossing is detected at the end of its step, the peak is one step
    // in error at most on either side.
    assert!((tp - t_peak).abs() <= 2.0001e-8, "{tp} vs {t_peak}");
    assert_eq!(r.jumps, 0);
}

#[test]
fn single_block_slip_distance_matches_spring_mass() {
    let p = params(1, 1);
    let lat = Lattice::new(&p);
    let f_n = 10e3 * p.spacing * p.spacing;
    let (mu_s, mu_d) = (4.5, 3.0);
    let fad = p.adhesion_force();
    let iface = interface(vec![mu_s * f_n + fad], vec![mu_d * f_n], f_n);
    let vel = (p.slider_speed, 0.0);
    let mut state = SpringBlockState::at_rest(&iface);
    let mut st = Stepper::new(&lat, &iface, vel, 0.0, &state);
    let mut jumper = Jumper::new(&st);
    let dt = 2e-10;
    let j = jumper.try_jump(&mut st, &mut state, 1e-3, 1.0, dt, 1.0);
    assert!(matches!(j, Jump::Jumped(_)));
    assert!(state.sliding[0]);
    let (u0, t0) = (state.ux[0], state.t);
    while state.sliding[0] {
        st.step(&mut state, dt).unwrap();
        assert!(state.t - t0 < 1e-5, "block never stuck again");
    }
    let k = p.k_shear();
    let omega = (k / p.block_mass()).sqrt();
    // Released at μ_s F_n + F_ad, kinetic equilibrium at μ_d F_n.
    let a = ((mu_s - mu_d) * f_n + fad) / k;
    let (expected, tau) = slip_distance(a, omega, p.slider_speed);
    let got = state.ux[0] - u0;
    // The stop is found at the end of the step in which the velocity
    // reverses: the position error is at most ½ ω² a dt² ≈ 2e-7 of 2a.
    assert!(
        (got - expected).abs() <= 1e-6 * expected,
        "{got} vs {expected}"
    );
    assert!((state.t - t0 - tau).abs() <= dt * 1.0001);
    // Small-v limit of MODELS §7: 2(μ_s − μ_d)F_n/K_s (+ adhesion), plus the
    // slider travel during the half period, v π/ω, to first order.
    let v_pi_omega = p.slider_speed * std::f64::consts::PI / omega;
    assert!((got - 2.0 * a - v_pi_omega).abs() < 0.05 * v_pi_omega);
    assert!(!state.sliding[0]);
}

#[test]
fn two_block_chain_slip_loads_the_neighbour() {
    // Block 0 (weaker) slips first against K_s + K_int (its neighbour stuck),
    // moves s0 towards block 1 and compresses the axial spring by s0, which
    // pushes block 1 forward with K_int s0: block 1 then slips at
    // t1 = (th1 − K_int s0)/(K_s v).
    let p = params(2, 1);
    let lat = Lattice::new(&p);
    let f_n = 10e3 * p.spacing * p.spacing;
    let th0 = 4.0 * f_n;
    let fd0 = 2.5 * f_n;
    let th1 = 6.0 * f_n;
    let iface = interface(vec![th0, th1], vec![fd0, 3.0 * f_n], f_n);
    let (ks, kint, v) = (p.k_shear(), p.k_internal(), p.slider_speed);
    let m = p.block_mass();
    let omega = ((ks + kint) / m).sqrt();
    let a = (th0 - fd0) / (ks + kint);
    let v_eq = v * ks / (ks + kint);
    let (s0, _) = slip_distance(a, omega, v_eq);
    let t0 = th0 / (ks * v);
    let t1 = (th1 - kint * s0) / (ks * v);
    // Block 0 must not reach its threshold again before t1.
    assert!((th0 + (ks + kint) * s0) / (ks * v) > t1);

    let mut state = SpringBlockState::at_rest(&iface);
    let mut st = Stepper::new(&lat, &iface, (v, 0.0), 0.0, &state);
    let mut jumper = Jumper::new(&st);
    let dt = 2e-10;
    let mut first_slip = None;
    let mut stuck_at = None;
    while !state.sliding[1] {
        let before = state.sliding[0];
        if let Jump::NotQuiet = jumper.try_jump(&mut st, &mut state, 1e-3, 1.0, dt, 1.0) {
            st.step(&mut state, dt).unwrap();
        }
        if !before && state.sliding[0] && first_slip.is_none() {
            first_slip = Some(state.t);
        }
        if before && !state.sliding[0] {
            stuck_at = Some(state.ux[0]);
        }
        assert!(state.t < 2.0 * t1);
    }
    assert!((first_slip.unwrap() - t0).abs() <= 1e-12 * t0);
    let s = stuck_at.unwrap();
    assert!((s - s0).abs() <= 1e-6 * s0, "{s} vs {s0}");
    // The jump to block 1's slip is exact given the state; the state carries
    // the 1e-6 relative error of s0, i.e. K_int · 1e-6 s0 / (K_s v) in time.
    let tol = kint * 1e-6 * s0 / (ks * v) + 1e-12 * t1;
    assert!((state.t - t1).abs() <= tol, "{} vs {t1}", state.t);
}
