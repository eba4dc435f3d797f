//! The `film` stage: λ of each velocity step of the stepped pin-on-disc
//! fixture over the roughness the same run measured of its counterface and
//! its pin, two generated sine profiles of known Rq = A/√2 (whole periods,
//! mean line): λ = h_min / √(A₁²/2 + A₂²/2) with h_min the step's own
//! `friction_steps.film_min_m`.

use crate::common;

use std::fmt::Write;

use tribo::table::Table;

/// `x [um],z [um]`, 4 whole periods of 200 points of amplitude `a_um`.
fn sine(a_um: f64) -> String {
    let mut s = String::from("x [um],z [um]\n");
    for i in 0..800 {
        let z = a_um * (2.0 * std::f64::consts::PI * i as f64 / 200.0).sin();
        writeln!(s, "{:.4},{z:.15e}", i as f64 * 0.5).unwrap();
    }
    s
}

fn run(pin_profile: bool) -> (Table, Table) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::copy(
        common::root().join("fixtures/friction/pin_on_disc_stepped.tsv"),
        d.join("pod.tsv"),
    )
    .unwrap();
    std::fs::write(d.join("disc.csv"), sine(0.3)).unwrap();
    let mut files = vec!["pod.tsv", "disc.csv"];
    if pin_profile {
        std::fs::write(d.join("pin.csv"), sine(0.4)).unwrap();
        files.push("pin.csv");
    }
    let lub = "viscosity_Pa_s,pressure_viscosity_per_GPa,reduced_modulus_GPa,reduced_radius_mm";
    std::fs::write(
        d.join("samples.csv"),
        format!(
            "file,sample_id,pin,normal_force_N,{lub}\n\
             pod.tsv,D1,P1,3.0,0.05,20,231,3\n\
             disc.csv,D1,,,,,,\n\
             pin.csv,,P1,,,,,\n"
        ),
    )
    .unwrap();
    let list: Vec<String> = files.iter().map(|f| format!("\"{f}\"")).collect();
    std::fs::write(
        d.join("p.toml"),
        format!(
            "stages = [\"friction\", \"roughness\", \"film\"]\n[input]\nfiles = [{}]\n\
             samples = \"samples.csv\"\n[output]\ndir = \"out\"\n[roughness]\ndetrend = \"mean\"\n",
            list.join(", ")
        ),
    )
    .unwrap();
    let o = common::tribo(d, &["run", "p.toml"]);
    assert!(
        o.status.code().is_some_and(|c| c <= 1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let read = |n: &str| Table::read_parquet(&d.join("out").join(n)).unwrap().0;
    (read("film.parquet"), read("friction_steps.parquet"))
}

#[test]
fn film_parameter_over_the_runs_measured_roughness() {
    let (film, steps) = run(true);
    let h_steps: Vec<f64> = steps
        .f64("film_min_m")
        .unwrap()
        .into_iter()
        .flatten()
        .collect();
    assert!(!h_steps.is_empty(), "no step has a film");
    assert_eq!(film.height(), h_steps.len());
    let sigma = ((0.3e-6f64).powi(2) / 2.0 + (0.4e-6f64).powi(2) / 2.0).sqrt();
    let (h, l, s) = (
        film.f64("film_min_m").unwrap(),
        film.f64("film_parameter").unwrap(),
        film.f64("composite_rq_m").unwrap(),
    );
    let rq_face = film.f64("rq_counterface_m").unwrap();
    for i in 0..film.height() {
        assert_eq!(h[i], Some(h_steps[i]));
        assert!((rq_face[i].unwrap() / (0.3e-6 / 2f64.sqrt()) - 1.0).abs() < 1e-9);
        assert!((s[i].unwrap() / sigma - 1.0).abs() < 1e-9, "{:?}", s[i]);
        assert!((l[i].unwrap() / (h_steps[i] / sigma) - 1.0).abs() < 1e-9);
    }
    assert!(common::status_texts(&film)
        .iter()
        .all(|t| t.as_deref() == Some("ok")));
}

/// Only the counterface measured: σ is its Rq alone and the rows say λ is
/// an upper bound.
#[test]
fn one_body_measured_gives_an_upper_bound() {
    let (film, _) = run(false);
    let l = film.f64("film_parameter").unwrap();
    let h = film.f64("film_min_m").unwrap();
    for i in 0..film.height() {
        let want = h[i].unwrap() / (0.3e-6 / 2f64.sqrt());
        assert!((l[i].unwrap() / want - 1.0).abs() < 1e-9);
    }
    assert!(common::status_texts(&film).iter().all(|t| t
        .as_deref()
        .is_some_and(|t| t.starts_with("partial_roughness"))));
}
