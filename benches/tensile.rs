//! Speed of the tensile analysis: `cargo bench --bench tensile`.
//! Figures are recorded in docs/tensile.md.

mod common;

use std::hint::black_box;
use std::time::Instant;

use tribo::extract::tensile::synthetic::{sample, KnottedSpec};
use tribo::extract::tensile::{analyze_fibre, analyze_file, FibreMeta, Knot, TensileParams};

fn time<T>(what: &str, reps: usize, mut f: impl FnMut() -> T) {
    let t0 = Instant::now();
    for _ in 0..reps {
        black_box(f());
    }
    let per = t0.elapsed().as_secs_f64() / reps as f64;
    println!("{what}: {:.3} ms per call ({reps} calls)", per * 1e3);
}

fn main() {
    let spec = KnottedSpec {
        plateau: 100e6,
        plateau_rise: 0.02,
        tooth_width: 0.03,
        tooth_drop: 15e6,
        teeth: 10,
        unfastening_peaks: vec![250e6, 300e6, 350e6],
        unfastening_width: 0.03,
        unfastening_trough: 20e6,
        fibre: (10e9, 0.02, 2e9, 0.2),
    };
    let (v, _) = spec.vertices();
    let meta = FibreMeta {
        knot: Knot::Noose,
        fibre_length_m: Some(0.025),
        end_distance_m: Some(0.02),
        ..FibreMeta::new("bench")
    };
    let p = TensileParams::default();
    for step in [1e-3, 1e-4, 1e-5] {
        let c = sample(&v, step, 0.03, 2e6, 10, 1);
        time(
            &format!("analyze_fibre, knotted, {} samples", c.len()),
            20,
            || analyze_fibre(&c, &meta, &p),
        );
    }
    let real = common::root().join("../shared/data/real/nanotensile_t150/B_4_IS_1.txt");
    if real.exists() {
        time(
            "analyze_file, real T150 (1887 rows, read + analyse)",
            50,
            || analyze_file(&real, None, &Default::default(), &p).unwrap(),
        );
    } else {
        println!(
            "analyze_file, real T150: skipped ({} absent)",
            real.display()
        );
    }
}
