//! X3P (ISO 25178-72): variants written by the test writer
//! (`common::writers`) and read back — data types, folders, stored and
//! deflated entries, non-square pixels, masks, inline point lists,
//! profiles — bad files, and a map through the roughness stage.

use std::path::Path;

use crate::common::writers::{self, sq_finite, Surface, X3p, X3pType};
use tribo::extract::roughness::input::{surfaces_from_dataset, AxisUnits, Surface as S};
use tribo::ingest::{read_bytes, IngestOptions};

fn read(bytes: &[u8]) -> tribo::Result<tribo::ingest::Dataset> {
    read_bytes(Path::new("t.x3p"), bytes, &IngestOptions::default())
}

#[test]
fn every_data_type_folder_and_compression_reads_back() {
    let s = Surface::waves(40, 24, 0.5e-6, 1.25e-6, 2e-7, 5e-8);
    for kind in [X3pType::D, X3pType::F, X3pType::I, X3pType::L] {
        for folder in ["", "scan 01/"] {
            for deflate in [false, true] {
                let o = X3p {
                    kind,
                    folder,
                    deflate,
                    origin: (1e-3, -2e-3),
                    ..Default::default()
                };
                let ds = read(&writers::x3p(&s, &o)).unwrap();
                assert_eq!(ds.format, "x3p");
                assert!(ds.dialect.is_none());
                let g = &ds.grids[0];
                assert_eq!((g.nx, g.ny, g.unit.as_str(), g.height), (40, 24, "m", true));
                assert_eq!((g.dx, g.dy, g.x0, g.y0), (0.5e-6, 1.25e-6, 1e-3, -2e-3));
                // Quantisation: half a count of 1e-9 m for integers, float
                // rounding for F; exact for D.
                let tol = match kind {
                    X3pType::D => 0.0,
                    X3pType::F => 1e-7 * 3e-7,
                    _ => 0.5e-9,
                };
                for (a, b) in g.values().unwrap().iter().zip(&s.z) {
                    assert!((a - b).abs() <= tol, "{kind:?}: {a} vs {b}");
                }
                assert_eq!(g.data.as_ref().unwrap().n_invalid, 0);
            }
        }
    }
}

#[test]
fn metadata_is_kept_with_the_common_keys() {
    let s = Surface::waves(16, 16, 1e-6, 1e-6, 1e-7, 0.0);
    let ds = read(&writers::x3p(&s, &X3p::default())).unwrap();
    let get = |k: &str| {
        ds.preamble
            .iter()
            .find(|m| m.key == k)
            .map(|m| m.value.as_str())
    };
    assert_eq!(get("instrument"), Some("Acme & Co Profilometer 3000 1.0"));
    assert_eq!(get("acquisition_date"), Some("2024-03-01T10:20:30+01:00"));
    assert_eq!(get("objective"), Some("50x objective"));
    assert_eq!(get("Record2/Instrument/Serial"), Some("42"));
    assert_eq!(get("height_unit"), Some("m"));
    // inspect --json carries them, with the grid's size and spacing.
    let i = tribo::ingest::inspect::inspect(&ds, &Default::default());
    let j = serde_json::to_value(&i).unwrap();
    assert!(j["dialect"].is_null());
    assert_eq!(j["grids"][0]["nx"], 16);
    assert_eq!(j["grids"][0]["n_invalid"], 0);
    assert_eq!(j["grids"][0]["dx_m"], 1e-6);
}

/// The valid-points mask and NaN floats are points not measured: NaN,
/// counted; Sq over the measured points is that of the surface without
/// them.
#[test]
fn masks_and_nan_floats_are_points_not_measured() {
    let s = Surface::waves(32, 20, 1e-6, 1e-6, 3e-7, 1e-7);
    let mask: Vec<bool> = (0..s.z.len()).map(|i| i % 7 != 3 && i > 10).collect();
    let bad = mask.iter().filter(|v| !**v).count();
    for kind in [X3pType::I, X3pType::D] {
        let o = X3p {
            kind,
            mask: Some(mask.clone()),
            ..Default::default()
        };
        let ds = read(&writers::x3p(&s, &o)).unwrap();
        let g = &ds.grids[0];
        assert_eq!(g.data.as_ref().unwrap().n_invalid, bad);
        // The written heights: quantised to the 1e-9 m increment for I.
        let q = |z: f64| match kind {
            X3pType::I => (z / 1e-9).round() * 1e-9,
            _ => z,
        };
        let want: Vec<f64> =
            s.z.iter()
                .zip(&mask)
                .map(|(z, m)| if *m { q(*z) } else { f64::NAN })
                .collect();
        let (sq, n) = sq_finite(g.values().unwrap());
        let (sq_want, n_want) = sq_finite(&want);
        assert_eq!(n, n_want);
        assert!((sq - sq_want).abs() <= 1e-12 * sq_want, "{sq} vs {sq_want}");
    }
    let mut nan = Surface::waves(16, 16, 1e-6, 1e-6, 1e-7, 0.0);
    nan.z[5] = f64::NAN;
    nan.z[200] = f64::INFINITY;
    for kind in [X3pType::F, X3pType::D] {
        let ds = read(&writers::x3p(
            &nan,
            &X3p {
                kind,
                ..Default::default()
            },
        ))
        .unwrap();
        assert_eq!(ds.grids[0].data.as_ref().unwrap().n_invalid, 2);
    }
}

#[test]
fn inline_points_and_profiles() {
    let s = Surface::waves(12, 9, 2e-6, 3e-6, 1e-7, 1e-8);
    let ds = read(&writers::x3p(
        &s,
        &X3p {
            inline: true,
            ..Default::default()
        },
    ))
    .unwrap();
    let g = &ds.grids[0];
    for (a, b) in g.values().unwrap().iter().zip(&s.z) {
        assert!((a - b).abs() <= 1e-15 * b.abs().max(1e-7), "{a} {b}");
    }
    let p = Surface::waves(64, 1, 0.1e-6, 0.0, 1e-7, 0.0);
    let ds = read(&writers::x3p(&p, &X3p::default())).unwrap();
    assert_eq!(ds.grids[0].ny, 1);
    let kind = tribo::ingest::kind::classify(&ds, &Default::default());
    assert_eq!(kind, Some(tribo::ingest::kind::DataKind::Profile));
    let surfaces = surfaces_from_dataset(&ds, &AxisUnits::default()).unwrap();
    let S::Profile(prof) = &surfaces[0] else {
        panic!("a profile")
    };
    assert_eq!((prof.z.len(), prof.dx), (64, 0.1e-6));
}

/// A cut, a changed byte, a missing entry or an unknown layout is an error
/// naming the file, the structure and a byte offset; never a panic.
#[test]
fn bad_files_name_the_structure_and_offset() {
    let s = Surface::waves(24, 24, 1e-6, 1e-6, 1e-7, 1e-8);
    let good = writers::x3p(
        &s,
        &X3p {
            deflate: false,
            ..Default::default()
        },
    );
    let forced = IngestOptions {
        format: Some("x3p".into()),
        ..Default::default()
    };
    for cut in (1..good.len()).step_by(97) {
        let e = match read_bytes(Path::new("t.x3p"), &good[..cut], &forced) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("a file cut at {cut} read"),
        };
        assert!(e.starts_with("t.x3p: byte "), "cut at {cut}: {e}");
    }
    // One byte of the heights changed: the entry's CRC-32 says so.
    let mut bad = good.clone();
    let at = bad.len() / 2;
    bad[at] ^= 1;
    let msg = read(&bad).unwrap_err().to_string();
    assert!(msg.contains("CRC-32"), "{msg}");
    for (from, to, want) in [
        ("<FeatureType>SUR", "<FeatureType>PCL", "feature type 'PCL'"),
        (
            "<DataType>D</DataType><Increment>1<",
            "<DataType>Q</DataType><Increment>1<",
            "data type 'Q'",
        ),
        ("<SizeZ>1</SizeZ>", "<SizeZ>3</SizeZ>", "3 layers"),
        ("<SizeX>24</SizeX>", "<SizeX>25</SizeX>", "samples"),
        ("<SizeX>24</SizeX>", "<SizeX>-24</SizeX>", "is not a count"),
        (
            "<Increment>1e-6</Increment>",
            "<Increment>0</Increment>",
            "spacing along x",
        ),
        (
            "bindata/data.bin</Point",
            "bindata/other.bin</Point",
            "not in the zip",
        ),
        ("</Record1>", "</Record2>", "closes <Record1>"),
        ("<Revision>", "<Revision", "X3P main.xml"),
    ] {
        let o = X3p {
            deflate: false,
            ..Default::default()
        };
        let z = writers::x3p_edited(&s, &o, &|x: String| {
            assert!(x.contains(from), "{from}");
            x.replacen(from, to, 1)
        });
        let msg = read(&z).unwrap_err().to_string();
        assert!(
            msg.contains(want) && msg.contains("byte"),
            "{from} -> {to}: {msg}"
        );
    }
    // A zip without main.xml is not an X3P: not recognised, and an error
    // naming it when the reader is forced.
    let other = tribo::ingest::binary::zip::write(&[("readme.txt", b"hello")], true);
    let msg = read_bytes(Path::new("t.zip"), &other, &forced)
        .unwrap_err()
        .to_string();
    assert!(msg.contains("no main.xml"), "{msg}");
}
