//! `alsfm_contact_map` and `alsfm_time_series` against the spring law they
//! come from (MODELS.md §5, "Load and separation", "Adhesion", the local
//! law on a tangent plane): two identical 2-D sinusoids
//! z = A sin(2πx/λ) sin(2πy/λ), adhesion on, slid at β = 0° and 45°.
//! At an instant where the upper surface has moved by
//! s (s cos β, s sin β), the spring at (x, y) is compressed by
//! c − d with c = l0 − z2(x − s cos β, y − s sin β) + z1(x, y) and one
//! separation d for all; its force is k_c (c − d) in compression and
//! k_t (c − d) in tension, and their mean is the load. Every expected value
//! here is computed from the surfaces as written in the scene.
#![deny(clippy::float_cmp)]

use std::collections::BTreeMap;
use std::f64::consts::PI;

use tribo::table::Table;

use crate::common;

const A: f64 = 0.05;
const K_C: f64 = 2.0;
const K_T: f64 = 1.0;
const V: f64 = 0.5;

const SCENE: &str = r#"
mu0 = 0.3
beta_deg = [0.0, 45.0]
load = [0.1, 0.02, -0.01]
[lower]
kind = "sinusoid"
amplitude = 0.05
lambda_x = 1.0
lambda_y = 1.0
[upper]
kind = "sinusoid"
amplitude = 0.05
lambda_x = 1.0
lambda_y = 1.0
[springs]
k_c = 2.0
l0 = 1.0
[adhesion]
k_t_over_k_c = 0.5
[motion]
velocity = 0.5
[resolution]
springs = 16
springs_y = 16
[outputs]
time_series = true
adhesion = true
contact_maps = [0, 3]
"#;

fn z(x: f64, y: f64) -> f64 {
    A * (2.0 * PI * x).sin() * (2.0 * PI * y).sin()
}

fn tables() -> (Table, Table) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.toml"), SCENE).unwrap();
    let o = common::tribo(dir.path(), &["simulate", "alsfm", "s.toml", "--out", "o"]);
    assert!(
        o.status.code().is_some_and(|c| c <= 1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let read = |n: &str| {
        Table::read_parquet(&dir.path().join("o").join(n))
            .unwrap()
            .0
    };
    (
        read("alsfm_contact_map.parquet"),
        read("alsfm_time_series.parquet"),
    )
}

/// A map instant: (β, load, step) by their bits.
type Instant = (u64, u64, i64);

/// Each instant's springs: (x, y, force_N, state).
fn springs(map: &Table) -> BTreeMap<Instant, Vec<(f64, f64, f64, String)>> {
    let (beta, load, step) = (
        common::f64s(map, "beta_deg"),
        common::f64s(map, "load"),
        map.i64("step").unwrap(),
    );
    let (x, y, f) = (
        common::f64s(map, "x_m"),
        common::f64s(map, "y_m"),
        common::f64s(map, "force_N"),
    );
    let state = map.str("state").unwrap();
    let mut out: BTreeMap<Instant, Vec<_>> = BTreeMap::new();
    for i in 0..map.height() {
        let key = (beta[i].to_bits(), load[i].to_bits(), step[i].unwrap());
        out.entry(key)
            .or_default()
            .push((x[i], y[i], f[i], state[i].clone().unwrap()));
    }
    out
}

/// Every mapped instant: the forces' mean is the load; each force is the
/// spring law at one separation (the same d from every spring, to 1e-12);
/// the state names the force's sign. At step 0 the surfaces are in phase:
/// the gap is uniform and every spring carries the load.
#[test]
fn mapped_forces_follow_the_spring_law_at_one_separation() {
    let (map, series) = tables();
    let shift: BTreeMap<Instant, f64> = {
        let (b, l, s, d) = (
            common::f64s(&series, "beta_deg"),
            common::f64s(&series, "load"),
            series.i64("step").unwrap(),
            common::f64s(&series, "distance_m"),
        );
        (0..series.height())
            .map(|i| ((b[i].to_bits(), l[i].to_bits(), s[i].unwrap()), d[i]))
            .collect()
    };
    let instants = springs(&map);
    assert_eq!(
        instants.len(),
        2 * 3 * 2,
        "two betas, three loads, two steps"
    );
    for (key, springs) in &instants {
        let (beta, load, step) = (f64::from_bits(key.0), f64::from_bits(key.1), key.2);
        assert_eq!(springs.len(), 256);
        let mean = springs.iter().map(|s| s.2).sum::<f64>() / 256.0;
        assert!((mean - load).abs() < 1e-12, "{key:?}: mean force {mean}");
        let s = shift[key];
        let (sx, sy) = (s * beta.to_radians().cos(), s * beta.to_radians().sin());
        let mut gaps = Vec::new();
        for (x, y, f, state) in springs {
            let want = match *f {
                f if f > 0.0 => "compressed",
                f if f < 0.0 => "tension",
                _ => "slack",
            };
            assert_eq!(state, want);
            let k = if *f > 0.0 { K_C } else { K_T };
            // c − f/k = d, with c = l0 − z2(x − s) + z1(x).
            gaps.push(1.0 - z(x - sx, y - sy) + z(*x, *y) - f / k);
        }
        let (lo, hi) = gaps
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), g| {
                (a.min(*g), b.max(*g))
            });
        assert!(hi - lo < 1e-12, "{key:?}: separations {lo}..{hi}");
        if step == 0 {
            assert!(
                springs.iter().all(|sp| (sp.2 - load).abs() < 1e-15),
                "{key:?}"
            );
        }
    }
}

/// The time series at the mapped instants: R_z^(c) is the mean of the
/// compressive forces, n_compressed and n_tension count the map's springs,
/// μ is |(R_x, R_y)| / L (null where L ≤ 0) with its components along and
/// across β (the lateral one is zero here, by the surfaces' symmetry about
/// both directions); time is distance over the scene's velocity.
#[test]
fn time_series_columns_agree_with_the_map_and_their_definitions() {
    let (map, series) = tables();
    let instants = springs(&map);
    let (beta, load, dist, time) = (
        common::f64s(&series, "beta_deg"),
        common::f64s(&series, "load"),
        common::f64s(&series, "distance_m"),
        common::f64s(&series, "time_s"),
    );
    let (rx, ry, rzc) = (
        common::f64s(&series, "r_x_N"),
        common::f64s(&series, "r_y_N"),
        common::f64s(&series, "r_zc_N"),
    );
    let step = series.i64("step").unwrap();
    let (nc, nt) = (
        series.i64("n_compressed").unwrap(),
        series.i64("n_tension").unwrap(),
    );
    let (mu, par, perp) = (
        series.f64("mu").unwrap(),
        series.f64("mu_parallel").unwrap(),
        series.f64("mu_perp").unwrap(),
    );
    let mut mapped = 0;
    for i in 0..series.height() {
        assert!((time[i] * V - dist[i]).abs() < 1e-15, "row {i}");
        let b = beta[i].to_radians();
        if load[i] > 0.0 {
            let l = load[i];
            let m = mu[i].unwrap();
            // R_z is the solved mean force: the load to 1e-12.
            assert!((m - rx[i].hypot(ry[i]) / l).abs() < 1e-11 * m, "row {i}");
            let p = par[i].unwrap();
            assert!((p - (rx[i] * b.cos() + ry[i] * b.sin()) / l).abs() < 1e-11 * m);
            let q = perp[i].unwrap();
            let across = (ry[i] * b.cos() - rx[i] * b.sin()) / l;
            assert!((q.abs() - across.abs()).abs() < 1e-11 * m, "row {i}");
        } else {
            assert_eq!((mu[i], par[i], perp[i]), (None, None, None), "row {i}");
        }
        let key = (beta[i].to_bits(), load[i].to_bits(), step[i].unwrap());
        let Some(springs) = instants.get(&key) else {
            continue;
        };
        mapped += 1;
        let compressed: Vec<f64> = springs.iter().map(|s| s.2).filter(|f| *f > 0.0).collect();
        let tension = springs.iter().filter(|s| s.2 < 0.0).count();
        assert_eq!(nc[i], Some(compressed.len() as i64), "{key:?}");
        assert_eq!(nt[i], Some(tension as i64), "{key:?}");
        let want = compressed.iter().sum::<f64>() / springs.len() as f64;
        assert!(
            (rzc[i] - want).abs() < 1e-14,
            "{key:?}: {} vs {want}",
            rzc[i]
        );
    }
    assert_eq!(mapped, 12);
}

/// ∇z of [`z`].
fn gradient(x: f64, y: f64) -> (f64, f64) {
    let (w, k) = (2.0 * PI * A, 2.0 * PI);
    (
        w * (k * x).cos() * (k * y).sin(),
        w * (k * x).sin() * (k * y).cos(),
    )
}

/// The thesis' local law on a tangent plane, by its angles (Eq. 1.27, 1.28
/// and Sec. 1.4): φ = atan |∇z|, α_P = atan2(∂z/∂y, ∂z/∂x), the law at
/// β' = β − α_P, its ratios rotated back by α_P.
fn ratios(mu0: f64, g: (f64, f64), beta: f64) -> (f64, f64) {
    let (phi, alpha) = (g.0.hypot(g.1).atan(), g.1.atan2(g.0));
    let b = beta - alpha;
    let s = (1.0 + (phi.tan() * b.cos()).powi(2)).sqrt();
    let d = phi.cos() * s - mu0 * phi.tan() * b.cos();
    let (hx, hy) = ((phi.sin() * s + mu0 * b.cos()) / d, mu0 * b.sin() / d);
    (
        hx * alpha.cos() - hy * alpha.sin(),
        hx * alpha.sin() + hy * alpha.cos(),
    )
}

/// R_x and R_y at the mapped instants, from the map's forces and the
/// surfaces as written (MODELS.md §5, "Numeric set-up", "Adhesion"): each
/// lattice point holds one spring of each body, the upper body's sliding on
/// z1 at (x, y) and the lower body's on z2 at the shifted point; a
/// compressed point adds F (H₁ + H₂)/2, a spring in tension nothing, and the
/// sums are divided by the number of points.
#[test]
fn reactions_are_the_local_law_over_the_mapped_forces() {
    let (map, series) = tables();
    let rows: BTreeMap<Instant, (f64, f64, f64)> = {
        let (b, l, s) = (
            common::f64s(&series, "beta_deg"),
            common::f64s(&series, "load"),
            series.i64("step").unwrap(),
        );
        let (d, rx, ry) = (
            common::f64s(&series, "distance_m"),
            common::f64s(&series, "r_x_N"),
            common::f64s(&series, "r_y_N"),
        );
        (0..series.height())
            .map(|i| {
                (
                    (b[i].to_bits(), l[i].to_bits(), s[i].unwrap()),
                    (d[i], rx[i], ry[i]),
                )
            })
            .collect()
    };
    let (mut lateral, mut loaded) = (0, 0);
    for (key, springs) in &springs(&map) {
        let beta = f64::from_bits(key.0).to_radians();
        let (s, rx, ry) = rows[key];
        let (sx, sy) = (s * beta.cos(), s * beta.sin());
        let (mut want_x, mut want_y) = (0.0, 0.0);
        for (x, y, f, _) in springs.iter().filter(|sp| sp.2 > 0.0) {
            let h1 = ratios(0.3, gradient(*x, *y), beta);
            let h2 = ratios(0.3, gradient(x - sx, y - sy), beta);
            want_x += f * (h1.0 + h2.0) / 2.0;
            want_y += f * (h1.1 + h2.1) / 2.0;
        }
        let n = springs.len() as f64;
        let (want_x, want_y) = (want_x / n, want_y / n);
        let scale = want_x.hypot(want_y);
        if scale == 0.0 {
            // No spring compressed (all in tension at the negative load).
            assert_eq!((rx, ry), (0.0, 0.0), "{key:?}");
            continue;
        }
        assert!(
            (rx - want_x).abs() < 1e-12 * scale,
            "{key:?}: R_x {rx} vs {want_x}"
        );
        assert!(
            (ry - want_y).abs() < 1e-12 * scale,
            "{key:?}: R_y {ry} vs {want_y}"
        );
        loaded += 1;
        lateral += usize::from(want_y.abs() > 1e-3 * scale);
    }
    // Twelve instants, two of them (step 0 at the negative load) with
    // every spring in tension; at 45° R_y is checked, not only zero.
    assert_eq!((loaded, lateral), (10, 5));
}
