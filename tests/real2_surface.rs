//! The real surface-profile text exports of `../shared/data/real2` (tests
//! skip, saying so, when it is absent) and the MIT ones among them kept as
//! fixtures: channels, SI units, points, and the numbers the files print.

use crate::common;

use tribo::extract::roughness::heights::rz_iso;
use tribo::extract::roughness::input::{surfaces_from_dataset, AxisUnits, Surface};
use tribo::extract::roughness::{analyze_profile, Detrend, Profile, RoughnessParams};
use tribo::ingest::companion::{companion_of, data_file_of, Family, Inputs};
use tribo::ingest::source::Source;
use tribo::ingest::{read_data, read_path, Dataset, IngestOptions, Reading};

fn the_profile(ds: &Dataset) -> Profile {
    match surfaces_from_dataset(ds, &AxisUnits::default())
        .unwrap()
        .remove(0)
    {
        Surface::Profile(p) => p,
        Surface::Map(_) => panic!("a map"),
    }
}

/// The value a `Key,3.066 µm` line of the results table prints, µm.
fn printed(results: &str, key: &str) -> f64 {
    let line = results.lines().find(|l| l.starts_with(key)).unwrap();
    let value = line.rsplit(',').next().unwrap();
    value.split_whitespace().next().unwrap().parse().unwrap()
}

/// Surfcom-style `.tx1`/`.tx2`: 28 087 heights over 10 mm in µm, read with
/// the conditions of the `.tx3` beside them (ISO 8859-1, Spanish keys: λc
/// 2.5 mm Gaussian, λs 25 µm, ISO '97; the instrument's results masked).
/// Ra, Rq, Rp, Rv, Rt and Rz of the `.tx2` (the instrument's roughness
/// profile, analysed as it is: no form removal, no second filter) agree
/// with the results table beside it to its printed 0.001 µm; that table's
/// Rz is over five sampling lengths of 2 mm, ours over the `.tx3`'s λc
/// (four of 2.5 mm) is reported beside. The `.tx3` is a companion, the
/// results table not data.
#[test]
fn surfcom_profiles_agree_with_the_results_beside_them() {
    let Some(dir) = common::shared_real2("surfcom_tx_profile/GrupoI_EspeI") else {
        return;
    };
    for name in ["3.tx1", "3.tx2"] {
        let ds = read_path(&dir.join(name), &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "surfcom-tx");
        let s = &ds.sections[0];
        assert_eq!((s.rows(), s.channels.len()), (28087, 2));
        assert_eq!(
            (
                s.channels[0].raw_unit.as_str(),
                s.channels[1].raw_unit.as_str()
            ),
            ("mm", "um")
        );
        let p = the_profile(&ds);
        assert!(((p.z.len() - 1) as f64 * p.dx - 10e-3).abs() < 1e-12);
        let get = |k: &str| {
            ds.preamble
                .iter()
                .find(|m| m.key == k)
                .map(|m| m.value.as_str())
        };
        assert_eq!(get("tribo.cutoff_lambda_c"), Some("2.5mm"));
        assert_eq!(get("tribo.cutoff_lambda_s"), Some("25.0um"));
        assert_eq!(get("tribo.filter"), Some("Gausiano"));
        assert_eq!(get("tribo.standard"), Some("ISO '97"));
        assert_eq!(get("tribo.evaluation_length"), Some("10.0mm"));
        assert_eq!(
            get("Ra"),
            Some("*.*******um\t*.*******um"),
            "masked, kept as text"
        );
    }
    let results = std::fs::read_to_string(dir.join("resultados_rugosidad.csv")).unwrap();
    let ds = read_path(&dir.join("3.tx2"), &IngestOptions::default()).unwrap();
    let p = the_profile(&ds);
    let params = RoughnessParams {
        detrend: Detrend::None,
        ..Default::default()
    };
    let r = analyze_profile(&p, &params).unwrap();
    let um = |v: f64| v * 1e6;
    for (ours, key) in [
        (um(r.ra), "Ra (Promedio"),
        (um(r.rq), "Rq (RMS)"),
        (um(r.heights.peak), "Rp (Pico"),
        (-um(r.heights.valley), "Rv (Valle"),
        (um(r.heights.total), "Rz/Rt (Altura Total)"),
        (um(r.heights.rz_iso.unwrap()), "Rz (ISO 4287:1997)"),
    ] {
        let want = printed(&results, key);
        assert!(
            (ours - want).abs() <= 0.0005 + 1e-9,
            "{key}: {ours} µm vs printed {want}"
        );
    }
    assert_eq!(r.heights.rz_sampling_lengths, 5);
    let (rz_lc, n) = rz_iso(&p.z, p.dx, 2.5e-3).unwrap();
    assert_eq!(n, 4, "10 mm / λc 2.5 mm");
    assert!(um(rz_lc) > 0.0 && um(rz_lc) <= um(r.heights.total));
    // The conditions file is a companion of both profiles; alone it is no
    // data, and neither is the results table.
    let tx3 = dir.join("3.tx3");
    let c = companion_of(&tx3).unwrap();
    assert_eq!(c.family, Family::SurfcomConditions);
    let (tx1, tx2) = (dir.join("3.tx1"), dir.join("3.tx2"));
    assert_eq!(
        data_file_of(&tx3, &Inputs::new(&[&tx2, &tx3, &tx1])),
        Some(tx1.as_path())
    );
    assert_eq!(
        data_file_of(&tx3, &Inputs::new(&[&tx2, &tx3])),
        Some(tx2.as_path())
    );
    let e = read_path(&tx3, &IngestOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("companion") && e.contains("3.tx2"), "{e}");
    let csv = dir.join("resultados_rugosidad.csv");
    let e = read_path(&csv, &IngestOptions::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("a table of roughness results") && e.contains("Ra = 3.066"),
        "{e}"
    );
    for f in [&tx3, &csv] {
        let source = Source::open(f).unwrap();
        let (_, reading) = read_data(f, &source, None, &IngestOptions::default());
        assert!(
            matches!(reading, Ok(Reading::NotData(_))),
            "{}",
            f.display()
        );
    }
}

/// The heights of a headerless `x  z` line, parsed here from the text.
fn raw_pairs(text: &str) -> Vec<(f64, f64)> {
    text.lines()
        .map(|l| {
            let mut f = l.split_whitespace().map(|v| v.parse::<f64>().unwrap());
            (f.next().unwrap(), f.next().unwrap())
        })
        .collect()
}

/// The Dektak OPDx text export (MIT fixture, the same bytes as the real
/// batch's copy): 3001 points over 50 µm, x and z in m as
/// SurfaceTopography's own test reads them (`y * 1e6` against the binary's
/// µm heights), every value as the file prints it.
#[test]
fn opdx_text_export_reads_in_metres() {
    let f = common::root().join("fixtures/roughness/surfacetopography_text/opdx-3.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "xz-line-scan");
    let s = &ds.sections[0];
    let units: Vec<&str> = s.channels.iter().map(|c| c.raw_unit.as_str()).collect();
    assert_eq!(units, ["m", "m"]);
    let raw = raw_pairs(&std::fs::read_to_string(&f).unwrap());
    assert_eq!((s.rows(), raw.len()), (3001, 3001));
    for (k, (x, z)) in raw.iter().enumerate() {
        assert_eq!((s.channels[0].values[k], s.channels[1].values[k]), (*x, *z));
    }
    let p = the_profile(&ds);
    assert!(((p.z.len() - 1) as f64 * p.dx - 4.9966689e-5).abs() < 1e-12);
    assert!(ds
        .preamble
        .iter()
        .any(|m| m.key == "tribo.units" && m.value.starts_with("x and z in m")));
    if let Some(real) = common::shared_real2("surfacetopography_text/opdx-3.txt") {
        assert_eq!(std::fs::read(real).unwrap(), std::fs::read(&f).unwrap());
    }
}
