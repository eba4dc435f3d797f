//! ALSFM speed/accuracy trade: error against lattice resolution against
//! time per scene point, for each path. Run with
//! `cargo bench --bench alsfm`; prints Markdown tables (recorded in
//! docs/alsfm.md).

use std::time::Instant;

use tribo::models::alsfm::closed_form::{mu_across, WedgeCase};
use tribo::models::alsfm::instant::SpringParams;
use tribo::models::alsfm::numeric_1d::{Contact, Lattice};
use tribo::models::alsfm::numeric_2d::simulate_2d_with;
use tribo::models::alsfm::separation::{solve_separation, solve_separation_sorted};
use tribo::models::alsfm::solver::{evaluate, Keep, Path, PointResult, Resolution};
use tribo::models::alsfm::surface::Surface;

fn point(c: &Contact, res: &Resolution, force: Option<Path>) -> (PointResult, f64) {
    // Repeat until 0.2 s have passed (at least once) and report the mean.
    let start = Instant::now();
    let mut n = 0u32;
    let mut last = None;
    while n == 0 || start.elapsed().as_secs_f64() < 0.2 {
        last = Some(
            evaluate(
                c,
                res,
                &Keep {
                    force,
                    ..Default::default()
                },
            )
            .unwrap(),
        );
        n += 1;
    }
    (last.unwrap(), start.elapsed().as_secs_f64() / n as f64)
}

fn contact<'a>(z1: &'a Surface, z2: &'a Surface, beta: f64, load: f64) -> Contact<'a> {
    Contact {
        z1,
        z2,
        mu0: 0.3,
        beta_deg: beta,
        springs: SpringParams::default(),
        load,
    }
}

fn row(label: &str, n: usize, r: &PointResult, reference: f64, t: f64) {
    let mu = r.mu.unwrap();
    println!(
        "| {label} | {} | {n} | {} | {:.3e} | {:.3e} |",
        r.path.name(),
        r.steps,
        (mu - reference).abs() / reference,
        t
    );
}

/// μ on an `n`-point lattice (n × n in 2-D).
fn at(n: usize) -> Resolution {
    Resolution {
        nx: Some(n),
        ..Default::default()
    }
}

/// μ of a fine-lattice reference, then a row per lattice size in `ns`
/// (`points` gives the row's lattice count from n). Returns the reference.
fn sweep(
    label: &str,
    c: &Contact,
    reference_n: usize,
    ns: &[usize],
    points: fn(usize) -> usize,
) -> f64 {
    let reference = evaluate(c, &at(reference_n), &Keep::default())
        .unwrap()
        .mu
        .unwrap();
    for &n in ns {
        let (r, t) = point(c, &at(n), None);
        row(label, points(n), &r, reference, t);
    }
    reference
}

/// CPU time (user + system) of this process so far, s, from
/// `/proc/self/stat` (Linux; 10 ms ticks); NaN elsewhere. On a machine
/// shared with other work the CPU time, unlike the wall time, does not grow
/// with the load.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // Fields after the command name (which ends with ')'): utime and stime
    // are the 12th and 13th.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    if f.len() == 2 {
        (f[0] + f[1]) / 100.0
    } else {
        f64::NAN
    }
}

/// The 2-D lattice goal: 256 × 256 springs over `steps` instants of 2-D
/// sinusoids, the upper surface sampled once / per row and column (`fast`)
/// against evaluated at every point, with the largest relative difference
/// of the mean μ between the two.
fn lattice_256(beta: f64, steps: Option<usize>) {
    let s2 = Surface::Sinusoid {
        amplitude: 0.03,
        lambda_x: 1.0,
        lambda_y: Some(1.0),
    };
    let c = contact(&s2, &s2, beta, 0.05);
    let lat = Lattice {
        nx: 256,
        ny: 256,
        steps,
        record: vec![],
    };
    let mu = |fast: bool| {
        let (t, cpu) = (Instant::now(), cpu_seconds());
        let s = simulate_2d_with(&c, &lat, fast).unwrap();
        let (rz, rx, ry) = s.instants.iter().fold((0.0, 0.0, 0.0), |a, i| {
            (a.0 + i.r_z, a.1 + i.r_x, a.2 + i.r_y)
        });
        (
            rx.hypot(ry) / rz,
            s.instants.len(),
            (t.elapsed().as_secs_f64(), cpu_seconds() - cpu),
        )
    };
    let (mf, n, (tf, cf)) = mu(true);
    let (ma, _, (ta, ca)) = mu(false);
    println!(
        "| 2-D sinusoids 256 x 256, beta {beta}, {n} instants | {tf:.3} s | {cf:.2} s | {ta:.3} s | {ca:.2} s | {:.2} | {:.1e} |",
        ca / cf,
        (mf - ma).abs() / ma
    );
}

/// The separation solve alone on the compressions of a 256 × 256 lattice
/// of 2-D sinusoids (A = 0.03, λ = 1, sampled at 256 points per period,
/// the upper surface shifted by 0.37 cell), selection against the full
/// sort, 200 solves each; and the largest difference of d.
fn separation_256() {
    let n = 256;
    let c: Vec<f64> = (0..n * n)
        .map(|k| {
            let (x, y) = ((k % n) as f64 / n as f64, (k / n) as f64 / n as f64);
            let tau = std::f64::consts::TAU;
            let z1 = 0.03 * (tau * x).sin() * (tau * y).sin();
            let z2 = 0.03 * (tau * (x - 0.37 / n as f64)).sin() * (tau * y).sin();
            1.0 - (z2 - z1) - 0.06
        })
        .collect();
    let (mut s1, mut s2) = (Vec::new(), Vec::new());
    let time = |f: &mut dyn FnMut() -> f64| {
        let t = Instant::now();
        let mut d = 0.0;
        for _ in 0..200 {
            d = f();
        }
        (d, t.elapsed().as_secs_f64() / 200.0)
    };
    let (a, ta) = time(&mut || solve_separation(&c, 1.0, 0.0, 0.05, &mut s1).unwrap().d);
    let (b, tb) = time(&mut || {
        solve_separation_sorted(&c, 1.0, 0.0, 0.05, &mut s2)
            .unwrap()
            .d
    });
    println!(
        "| separation of 256 x 256 springs | {ta:.3e} s | {tb:.3e} s | {:.2} | {:.1e} |",
        tb / ta,
        (a - b).abs()
    );
}

fn main() {
    if std::env::args().any(|a| a == "separation256") {
        println!("| case | selection [s] | full sort [s] | ratio | abs. diff. of d |");
        println!("|---|---|---|---|---|");
        separation_256();
        return;
    }
    if std::env::args().any(|a| a == "lattice256") {
        println!(
            "| case | sampled, wall | sampled, CPU | evaluated, wall | evaluated, CPU | CPU ratio | rel. diff. of mu |"
        );
        println!("|---|---|---|---|---|---|---|");
        lattice_256(0.0, None);
        lattice_256(0.0, Some(1000));
        lattice_256(30.0, Some(1000));
        return;
    }
    println!("| scene | path | lattice | steps | relative error | time per point [s] |");
    println!("|---|---|---|---|---|---|");
    // 1. Identical wedges across, L = 0.1 (closed form exact).
    let w = Surface::wedges(0.4_f64.atan(), 1.0);
    let cf = mu_across(WedgeCase::BothRough, 0.3, 0.4_f64.atan()).unwrap();
    let c = contact(&w, &w, 0.0, 0.1);
    let (r, t) = point(&c, &Resolution::default(), None);
    row("wedges case 2, L = 0.1", 0, &r, cf, t);
    for n in [16, 64, 256, 1024, 4096] {
        let (r, t) = point(&c, &at(n), Some(Path::Numeric1d));
        row("wedges case 2, L = 0.1", n, &r, cf, t);
    }
    // 2. Identical wedges across, L = 0.01 (numeric required).
    let c = contact(&w, &w, 0.0, 0.01);
    sweep(
        "wedges case 2, L = 0.01 (ref n = 16384)",
        &c,
        16384,
        &[16, 64, 256, 1024, 4096],
        |n| n,
    );
    // 3. 1-D sinusoids, beta = 30 deg, light load.
    let s = Surface::Sinusoid {
        amplitude: 0.05,
        lambda_x: 1.0,
        lambda_y: None,
    };
    let c = contact(&s, &s, 30.0, 0.02);
    let reference = sweep(
        "1-D sinusoids, beta 30, L = 0.02 (ref n = 16384)",
        &c,
        16384,
        &[16, 64, 256, 1024, 4096],
        |n| n,
    );
    for tol in [1e-3, 1e-5, 1e-7] {
        let (r, t) = point(
            &c,
            &Resolution {
                tolerance: Some(tol),
                ..Default::default()
            },
            None,
        );
        row(
            &format!("  same, tolerance {tol:e}"),
            r.springs,
            &r,
            reference,
            t,
        );
    }
    // 4. The same 1-D profile forced onto the 2-D lattice (cost of 2-D).
    let c = contact(&s, &s, 30.0, 0.02);
    let (r, t) = point(
        &c,
        &Resolution {
            nx: Some(256),
            ny: Some(1),
            ..Default::default()
        },
        Some(Path::Numeric2d),
    );
    row(
        "1-D sinusoids on the 2-D lattice (ny = 1)",
        256,
        &r,
        reference,
        t,
    );
    // 5. 2-D sinusoids, beta = 0.
    let s2 = Surface::Sinusoid {
        amplitude: 0.03,
        lambda_x: 1.0,
        lambda_y: Some(1.0),
    };
    let c = contact(&s2, &s2, 0.0, 0.05);
    sweep(
        "2-D sinusoids, beta 0, L = 0.05 (ref 128 x 128)",
        &c,
        128,
        &[8, 16, 32, 64],
        |n| n * n,
    );
    // 6. Adhesion bookkeeping: same 1-D scene with k_t > 0 at a load where
    // nothing is in tension, and below it.
    for (load, label) in [
        (0.2, "adhesion on, no tension (L = 0.2)"),
        (0.02, "adhesion on, tension (L = 0.02)"),
    ] {
        for k_t in [0.0, 0.5] {
            let c = Contact {
                springs: SpringParams {
                    k_t,
                    ..Default::default()
                },
                ..contact(&s, &s, 30.0, load)
            };
            let (r, t) = point(&c, &at(1024), None);
            let mu = r.mu.unwrap();
            println!(
                "| {label}, k_t = {k_t} | {} | 1024 | {} | mu = {mu:.6} | {t:.3e} |",
                r.path.name(),
                r.steps
            );
        }
    }
}
