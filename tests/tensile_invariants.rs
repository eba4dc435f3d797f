//! Invariants of the per-fibre analysis (proptest) and determinism of the
//! batch run whatever the thread count.

use std::path::PathBuf;

use proptest::prelude::*;
use tribo::extract::tensile::synthetic::{bilinear, sample, KnottedSpec};
use tribo::extract::tensile::{analyze_fibre, analyze_files, FibreMeta, Knot, TensileParams};
use tribo::ingest::manifest::Manifest;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Any bilinear fibre: the toughness is its closed-form area over ρ
    /// (Eq. 5.1), exactly up to rounding since the data are piecewise linear.
    #[test]
    fn bilinear_toughness_is_the_closed_form(
        e in 1e9f64..2e10, ey in 0.005f64..0.05, h in 0.0f64..5e9, extra in 0.01f64..0.3,
    ) {
        let ef = ey + extra;
        let v = bilinear(0.0, e, ey, h, ef);
        let c = sample(&v, 1e-3, 0.01, 0.0, 5, 1);
        let f = analyze_fibre(&c, &FibreMeta::new("p"), &TensileParams::default());
        let sy = e * ey;
        let sf = sy + h * (ef - ey);
        let area = sy * ey / 2.0 + (sy + sf) / 2.0 * (ef - ey);
        // ~400 trapezoids of exactly linear pieces: 1e-10 relative covers rounding
        let t = f.toughness_j_per_kg.unwrap();
        prop_assert!((t - area / 1400.0).abs() <= 1e-10 * t, "{} vs {}", t, area / 1400.0);
    }

    /// Scaling the stress by a power of two (a unit change that is exact in
    /// binary) scales strength and toughness by it and leaves every ratio,
    /// strain and count bit-identical.
    #[test]
    fn stress_units_do_not_change_ratios(k in -20i32..20, seed in 0u64..1000) {
        let spec = KnottedSpec {
            plateau: 100e6, plateau_rise: 0.02, tooth_width: 0.03, tooth_drop: 15e6,
            teeth: 6, unfastening_peaks: vec![250e6, 320e6], unfastening_width: 0.03,
            unfastening_trough: 20e6, fibre: (10e9, 0.02, 2e9, 0.2),
        };
        let (v, _) = spec.vertices();
        let c = sample(&v, 1e-3, 0.02, 2e6, 5, seed);
        let mut scaled = c.clone();
        let s = 2f64.powi(k);
        for x in &mut scaled.stress_pa { *x *= s; }
        let meta = FibreMeta {
            knot: Knot::Noose, fibre_length_m: Some(0.025), end_distance_m: Some(0.02),
            ..FibreMeta::new("s")
        };
        let p = TensileParams::default();
        let a = analyze_fibre(&c, &meta, &p);
        let b = analyze_fibre(&scaled, &meta, &p);
        prop_assert_eq!(a.strength_pa.map(|x| x * s), b.strength_pa);
        prop_assert_eq!(a.toughness_j_per_kg.map(|x| x * s), b.toughness_j_per_kg);
        prop_assert_eq!(a.friction_ratio, b.friction_ratio);
        prop_assert_eq!(a.toughness_ratio, b.toughness_ratio);
        prop_assert_eq!(a.release_strain, b.release_strain);
        prop_assert_eq!(a.strain_at_break, b.strain_at_break);
        prop_assert_eq!((a.plateau_drops, a.unfastening_drops), (b.plateau_drops, b.unfastening_drops));
    }
}

fn fixture(name: &str) -> PathBuf {
    crate::common::root().join("fixtures/tensile").join(name)
}

/// The batch run gives bit-identical records on 1 and on 4 threads.
#[test]
fn batch_is_deterministic_across_thread_counts() {
    let m = Manifest::read(&fixture("samples.csv")).unwrap();
    let paths: Vec<PathBuf> = [
        "t150_unknotted.txt",
        "t150_knotted.txt",
        "generic_force_extension.csv",
        "bluehill_truncated.csv",
    ]
    .into_iter()
    .map(fixture)
    .collect();
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            analyze_files(
                &paths,
                Some(&m),
                &Default::default(),
                &TensileParams::default(),
            )
            .unwrap()
            .0
        })
    };
    let one = run(1);
    let four = run(4);
    // Debug prints every f64 exactly (shortest round-trip form)
    assert_eq!(format!("{one:?}"), format!("{four:?}"));
    assert_eq!(one.len(), 4);
}
