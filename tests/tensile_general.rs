//! The general tensile analysis beside the knot analysis (MODELS.md §9):
//! maximum stress also without a fracture, offset and upper/lower yield,
//! the modulus on a stated window, sections and specimen ids from the file,
//! and refusals (reversed strain). Checked against Bluehill's printed
//! results and hand computations.

use crate::common;

use tribo::extract::tensile::{
    analyze_fibre, analyze_file, FibreMeta, StressStrainCurve, TensileParams,
};
use tribo::ingest::read_path;
use tribo::status::Code;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// Bluehill `Tens_Yield`: the modulus by regression over 20–50 MPa of the
/// first loading (the straight part of these curves, which bend above
/// ~57 MPa) is within 1 % of Bluehill's "Automatic Young's" (observed
/// −0.33 % and −0.62 %; Bluehill does not print its window). The 0.2 %
/// offset yield equals a hand computation with the same convention (numpy:
/// `polyfit` over the same samples, then the first sign change of
/// σ − E(ε − 0.002) interpolated linearly): 90.9527 and 90.4485 MPa; with
/// Bluehill's own modulus the hand computation gives 90.9215 and 90.4215
/// MPa, within 0.05 %. Bluehill prints no yield for these files.
#[test]
fn bluehill_tens_yield_modulus_and_offset_yield() {
    let Some(dir) = common::shared_real("tensile_bluehill/Tens_Yield") else {
        return;
    };
    let params = TensileParams {
        modulus_stress_window_mpa: Some([20.0, 50.0]),
        ..Default::default()
    };
    // (file, specimen id, hand Rp0.2 with our E, with Bluehill's E, MPa)
    let cases = [
        ("Specimen_RawData_1.csv", "009", 90.952_714, 90.921_451),
        ("Specimen_RawData_3.csv", "007", 90.448_494, 90.421_467),
    ];
    for (name, id, hand, hand_bluehill_e) in cases {
        let r = analyze_file(&dir.join(name), None, &Default::default(), &params).unwrap();
        let (g, i) = (&r.features.general, &r.instrument);
        let (e, ei) = (g.modulus_pa.unwrap(), i.modulus_pa.unwrap());
        assert!(rel(e, ei) < 0.01, "{name}: E = {e}, Bluehill {ei}");
        let y = g.yield_stress_pa.unwrap() * 1e-6;
        assert!(rel(y, hand) < 1e-6, "{name}: Rp0.2 = {y}, hand {hand}");
        assert!(
            rel(y, hand_bluehill_e) < 5e-4,
            "{name}: {y} vs {hand_bluehill_e}"
        );
        assert!(g.modulus_method.as_deref().unwrap().contains("20–50 MPa"));
        // no yield drop on these curves
        assert_eq!((g.upper_yield_pa, g.lower_yield_pa), (None, None));
        // the file's own block: specimen id, rectangular section
        assert_eq!(r.meta.sample_id, id);
        let (kind, area) = r.meta.section().unwrap();
        assert_eq!(kind, "rectangular");
        // maximum stress = Bluehill's tensile strength (same column)
        // (the file writes stress with 4 decimals of MPa, the results block
        // with more: 1e-6 relative)
        assert!(
            rel(g.max_stress_pa.unwrap(), i.strength_pa.unwrap()) < 1e-6,
            "{name}: {:?} vs {:?}",
            g.max_stress_pa,
            i.strength_pa
        );
        // σ_m × w × t against the file's own Load column: Bluehill's stress
        // is its load over the same width × thickness (stress written with
        // 4 decimals of MPa: 1e-6 relative)
        let fm = g.max_stress_pa.unwrap() * area;
        let ds = read_path(&dir.join(name), &Default::default()).unwrap();
        let load = ds.sections[0].channel("Load").unwrap();
        let lmax = load.values.iter().copied().fold(f64::MIN, f64::max);
        assert!(
            rel(fm, lmax) < 1e-5,
            "{name}: {fm} N vs the file's {lmax} N"
        );
        // knot quantities are null for a coupon
        assert_eq!((r.features.friction_stress_pa, r.features.k1), (None, None));
    }
}

fn curve(strain: Vec<f64>, stress: Vec<f64>) -> StressStrainCurve {
    StressStrainCurve::new(strain, stress).unwrap()
}

/// A test stopped at its maximum: no fracture, status `no_fracture`, but
/// the maximum stress, the modulus and the yield are reported. Elastic
/// 100 GPa to 200 MPa, then 1 GPa hardening to ε = 0.05 where it stops:
/// σ_m = 200 + 1000 · 0.048 = 248 MPa; Rp0.2 where 100e9 (ε − 0.002) =
/// 200e6 + 1e9 (ε − 0.002): ε = 0.004 + 0.002·… solved below.
#[test]
fn a_record_that_ends_at_its_peak_still_gives_max_stress_modulus_and_yield() {
    let e: Vec<f64> = (0..=5000).map(|i| i as f64 * 1e-5).collect();
    let s: Vec<f64> = e
        .iter()
        .map(|&e| {
            if e <= 0.002 {
                100e9 * e
            } else {
                200e6 + 1e9 * (e - 0.002)
            }
        })
        .collect();
    let f = analyze_fibre(
        &curve(e, s),
        &FibreMeta::new("stop"),
        &TensileParams::default(),
    );
    assert!(f.status.has(Code::NoFracture), "{}", f.status);
    assert!(!f.status.is_ok());
    assert_eq!(f.strength_pa, None, "no strength at break without a break");
    let g = &f.general;
    assert!(rel(g.max_stress_pa.unwrap(), 248e6) < 1e-12);
    assert!(rel(g.modulus_pa.unwrap(), 100e9) < 1e-9);
    // 100e9 ε − 200e6 = 198e6 + 1e9 ε  →  ε = 398e6 / 99e9
    let ey = 398e6 / 99e9;
    assert!((g.yield_strain.unwrap() - ey).abs() < 1e-9);
    assert!(rel(g.yield_stress_pa.unwrap(), 198e6 + 1e9 * ey) < 1e-6);
}

/// A yield drop: elastic to 250 MPa, a drop to 230 MPa, a plateau, then
/// hardening to 320 MPa and fracture.
#[test]
fn a_yield_drop_gives_upper_and_lower_yield() {
    let mut e = Vec::new();
    let mut s = Vec::new();
    let mut push = |a: f64, b: f64| {
        e.push(a);
        s.push(b);
    };
    for i in 0..=50 {
        push(i as f64 * 2.5e-5, i as f64 * 5e6); // 200 GPa to 250 MPa
    }
    for (k, v) in [240.0, 231.0, 230.0, 232.0, 231.0, 233.0]
        .iter()
        .enumerate()
    {
        push(1.25e-3 + (k + 1) as f64 * 1e-3, v * 1e6);
    }
    for i in 1..=40 {
        push(7.25e-3 + i as f64 * 1e-3, 233e6 + i as f64 * (87e6 / 40.0));
    }
    for i in 1..=5 {
        push(47.25e-3 + i as f64 * 1e-5, 320e6 * (1.0 - i as f64 / 5.0));
    }
    let f = analyze_fibre(
        &curve(e, s),
        &FibreMeta::new("drop"),
        &TensileParams::default(),
    );
    let g = &f.general;
    assert_eq!(
        (g.upper_yield_pa, g.lower_yield_pa),
        (Some(250e6), Some(230e6)),
        "{}",
        f.status
    );
    assert!(rel(g.max_stress_pa.unwrap(), 320e6) < 1e-12);
}

/// A record whose strain runs backwards used to give a negative modulus
/// with `ok`; it is refused with `reversed_strain`.
#[test]
fn reversed_strain_is_a_status_not_a_negative_modulus() {
    let e: Vec<f64> = (0..=1000).rev().map(|i| i as f64 * 1e-4).collect();
    let s: Vec<f64> = (0..=1000).map(|i| i as f64 * 1e6).collect();
    let f = analyze_fibre(
        &curve(e, s),
        &FibreMeta::new("rev"),
        &TensileParams::default(),
    );
    assert!(f.status.has(Code::ReversedStrain), "{}", f.status);
    assert_eq!(f.modulus_pa, None);
    assert_eq!(f.general.modulus_pa, None);
    assert_eq!(f.toughness_j_per_kg, None);
}

/// The testXpert II export (our own file in its layout,
/// fixtures/tensile/make_zwick.py): German channel names, quoted
/// tab-separated decimal-comma values in Windows-1252, and a results block
/// whose printed values are checked: Fm 8978.8 N, Rm 448.9 MPa, Rp0,2
/// 309.9 MPa (printed with one decimal), E 200.0 GPa, specimen Z-017 of
/// a0 × b0 = 2.00 × 10.00 mm.
#[test]
fn zwick_testxpert_export_gives_its_printed_results() {
    let p = common::root().join("fixtures/tensile/zwick_testxpert.txt");
    let ds = read_path(&p, &Default::default()).unwrap();
    assert_eq!(ds.format, "zwick-testxpert");
    let i = tribo::ingest::inspect::inspect(&ds, &Default::default());
    let cols: Vec<(&str, &str, &str, Option<&str>)> = i.sections[0]
        .columns
        .iter()
        .map(|c| (c.name.as_str(), c.unit.as_str(), c.si_unit.as_str(), c.role))
        .collect();
    assert_eq!(
        cols,
        [
            ("Standardweg", "mm", "m", Some("extension")),
            ("Standardkraft", "N", "N", Some("force")),
            ("Dehnung", "%", "1", Some("strain")),
            ("Prüfzeit", "s", "s", Some("time"))
        ]
    );
    let params = TensileParams {
        modulus_stress_window_mpa: Some([50.0, 250.0]),
        ..Default::default()
    };
    let r = analyze_file(&p, None, &Default::default(), &params).unwrap();
    let (f, ins) = (&r.features, &r.instrument);
    let g = &f.general;
    assert_eq!(r.meta.sample_id, "Z-017");
    assert_eq!(r.meta.section(), Some(("rectangular", 20e-6)));
    // printed with one decimal: within half a unit of the last digit
    assert!((g.max_stress_pa.unwrap() - ins.strength_pa.unwrap()).abs() <= 0.05e6);
    assert!((g.max_stress_pa.unwrap() * 20e-6 - 8978.8).abs() <= 0.05);
    assert!(rel(g.modulus_pa.unwrap(), ins.modulus_pa.unwrap()) < 1e-4);
    let (y, yi) = (g.yield_stress_pa.unwrap(), ins.yield_pa.unwrap());
    assert!((y - yi).abs() <= 0.05e6, "Rp0,2 {y} vs printed {yi}");
    // the record has its fracture
    assert!(!f.status.has(Code::NoFracture), "{}", f.status);
    // a steel coupon gets no silk density: the toughness per volume only
    assert!(!f.status.has(Code::DefaultedDensity), "{}", f.status);
    assert_eq!(f.toughness_j_per_kg, None);
    assert!(f.energy_density_j_per_m3.is_some());
    // its printed results agree with ours: no instrument_mismatch
    assert!(!f.status.has(Code::InstrumentMismatch), "{}", f.status);
}
