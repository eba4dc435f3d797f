//! `alsfm_contact_map` and `alsfm_time_series` against the spring law they
//! come from (MODELS.md §5, "Load and separation", "Adhesion"): two
//! identical 2-D sinusoids z = A sin(2πx/λ) sin(2πy/λ), adhesion on, slid at
//! β = 0° and 45°. At an instant where the upper surface has moved by
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
