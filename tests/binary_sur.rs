//! Digital Surf SUR: variants written by the test writer
//! (`common::writers`) — 16 and 32 bits, plain and compressed (one and
//! several zlib streams), units, offsets, points not measured, several
//! objects as channels — bad files, and maps through the roughness stage.

use std::path::Path;

use crate::common::writers::{sq_finite, Sur, Surface};
use crate::common::{self, writers};
use tribo::ingest::{read_bytes, IngestOptions};

fn read_with(bytes: &[u8], o: &IngestOptions) -> tribo::Result<tribo::ingest::Dataset> {
    read_bytes(Path::new("t.sur"), bytes, o)
}

fn read(bytes: &[u8]) -> tribo::Result<tribo::ingest::Dataset> {
    read_with(bytes, &IngestOptions::default())
}

#[test]
fn bits_compression_and_units_read_back() {
    let s = Surface::waves(48, 20, 0.8e-6, 1.6e-6, 2e-7, 5e-8);
    for bits in [16, 32] {
        for (compressed, streams) in [(false, 1), (true, 1), (true, 3)] {
            for units in [["um", "um", "um"], ["mm", "mm", "nm"], ["nm", "um", "m"]] {
                let o = Sur {
                    bits,
                    compressed,
                    streams,
                    units,
                    z_offset_m: 3e-6,
                    ..Default::default()
                };
                let ds = read(&writers::sur(&s, &o)).unwrap();
                assert_eq!(ds.format, "sur");
                let g = &ds.grids[0];
                assert_eq!((g.nx, g.ny, g.unit.as_str()), (48, 20, "m"));
                // Spacings go through f32 in the header.
                assert!((g.dx / 0.8e-6 - 1.0).abs() < 1e-6 && (g.dy / 1.6e-6 - 1.0).abs() < 1e-6);
                let tol = 0.5e-10 + 1e-6 * 3e-6;
                for (a, b) in g.values().unwrap().iter().zip(&s.z) {
                    assert!(
                        (a - b).abs() <= tol,
                        "{bits} {compressed} {units:?}: {a} vs {b}"
                    );
                }
            }
        }
    }
}

#[test]
fn non_measured_points_are_nan_and_counted() {
    let s = Surface::waves(40, 30, 1e-6, 1e-6, 3e-7, 1e-7);
    let invalid: Vec<usize> = (0..s.z.len()).filter(|i| i % 11 == 0).collect();
    for compressed in [false, true] {
        let o = Sur {
            compressed,
            invalid: invalid.clone(),
            ..Default::default()
        };
        let ds = read(&writers::sur(&s, &o)).unwrap();
        let g = &ds.grids[0];
        assert_eq!(g.data.as_ref().unwrap().n_invalid, invalid.len());
        let want: Vec<f64> =
            s.z.iter()
                .enumerate()
                .map(|(i, z)| if invalid.contains(&i) { f64::NAN } else { *z })
                .collect();
        let ((sq, n), (sq_w, n_w)) = (sq_finite(g.values().unwrap()), sq_finite(&want));
        assert_eq!(n, n_w);
        assert!((sq - sq_w).abs() < 1e-3 * sq_w, "{sq} vs {sq_w}");
    }
}

/// Two objects: heights and an intensity image. The heights are decoded
/// by default; `channel` selects the other; both are listed.
#[test]
fn objects_are_channels() {
    let h = Surface::waves(16, 12, 1e-6, 1e-6, 1e-7, 0.0);
    let mut i = Surface::waves(16, 12, 1e-6, 1e-6, 0.0, 0.0);
    i.z = (0..h.z.len()).map(|k| (k % 250) as f64).collect();
    let mut file = writers::sur_object(&h, &Sur::default(), 2, "Height");
    let o = Sur {
        units: ["um", "um", "m"],
        dz_m: 1.0,
        ..Default::default()
    };
    let mut second = writers::sur_object(&i, &o, 2, "Intensity");
    // An intensity image (object type 10) in counts.
    second[18..20].copy_from_slice(&10u16.to_le_bytes());
    second[212..228].copy_from_slice(b"counts          ");
    file.extend(second);
    let ds = read(&file).unwrap();
    let names: Vec<_> = ds
        .grids
        .iter()
        .map(|g| (g.name.as_str(), g.height, g.data.is_some()))
        .collect();
    assert_eq!(names, [("Height", true, true), ("Intensity", false, false)]);
    let o = IngestOptions {
        channel: Some("intensity".into()),
        ..Default::default()
    };
    let ds = read_with(&file, &o).unwrap();
    let g = &ds.grids[1];
    assert_eq!(g.unit, "counts");
    assert_eq!(g.values().unwrap()[..3], [0.0, 1.0, 2.0]);
    let o = IngestOptions {
        channel: Some("Phase".into()),
        ..Default::default()
    };
    let e = read_with(&file, &o).unwrap_err().to_string();
    assert!(
        e.contains("no channel 'Phase'") && e.contains("'Height', 'Intensity'"),
        "{e}"
    );
}

#[test]
fn bad_files_name_the_structure_and_offset() {
    let s = Surface::waves(20, 20, 1e-6, 1e-6, 1e-7, 1e-8);
    let forced = IngestOptions {
        format: Some("sur".into()),
        ..Default::default()
    };
    for compressed in [false, true] {
        let good = writers::sur(
            &s,
            &Sur {
                compressed,
                ..Default::default()
            },
        );
        for cut in (1..good.len()).step_by(61) {
            let e = read_with(&good[..cut], &forced).unwrap_err().to_string();
            assert!(e.starts_with("t.sur: byte "), "cut at {cut}: {e}");
        }
    }
    let good = writers::sur(&s, &Sur::default());
    for (at, bytes, want) in [
        (16, &2u16.to_le_bytes()[..], "version"),
        (12, &1u16.to_le_bytes()[..], "format"),
        (98, &8u16.to_le_bytes()[..], "bits per point"),
        (116, &7i32.to_le_bytes()[..], "do not agree"),
        (120, &0f32.to_le_bytes()[..], "spacing along x"),
        (180, b"furlong ", "step units"),
    ] {
        let mut b = good.clone();
        b[at..at + bytes.len()].copy_from_slice(bytes);
        let e = read(&b).unwrap_err().to_string();
        assert!(e.contains(want) && e.contains("byte"), "{want}: {e}");
    }
    let mut z = writers::sur(
        &s,
        &Sur {
            compressed: true,
            ..Default::default()
        },
    );
    let n = z.len();
    z[n - 10] ^= 0xff;
    let e = read(&z).unwrap_err().to_string();
    assert!(e.contains("zlib stream 1"), "{e}");
}

/// A map without points not measured, through `tribo roughness`: the same
/// heights as a SUR file (a power-of-two step, so exactly) and as a text z
/// matrix give the same Sq, that of the two whole-period waves,
/// sqrt(a²/2 + b²/2), to the SUR's quantisation.
#[test]
fn a_sur_map_through_the_roughness_stage_matches_its_text_matrix() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = Surface::waves(64, 48, 1e-6, 2e-6, 3e-7, 1e-7);
    let step = (-40f64).exp2();
    s.z.iter_mut().for_each(|z| *z = (*z / step).round() * step);
    let sur = dir.path().join("map.sur");
    let o = Sur {
        dz_m: step,
        units: ["m", "m", "m"],
        ..Default::default()
    };
    std::fs::write(&sur, writers::sur(&s, &o)).unwrap();
    let txt = dir.path().join("map.txt");
    let rows: Vec<String> =
        s.z.chunks(64)
            .map(|r| {
                r.iter()
                    .map(|v| format!("{:e}", v * 1e6))
                    .collect::<Vec<_>>()
                    .join("\t")
            })
            .collect();
    std::fs::write(
        &txt,
        format!(
            "# Width: 64 um\n# Height: 96 um\n# Value units: um\n{}\n",
            rows.join("\n")
        ),
    )
    .unwrap();
    let mut sq = Vec::new();
    for f in [&sur, &txt] {
        let out = dir
            .path()
            .join(format!("out-{}", f.file_name().unwrap().to_string_lossy()));
        let o = common::tribo(
            dir.path(),
            &[
                "roughness",
                &f.display().to_string(),
                "--out",
                &out.display().to_string(),
                "--detrend",
                "mean",
            ],
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let (t, _) = tribo::table::Table::read_parquet(&out.join("roughness.parquet")).unwrap();
        sq.push(t.f64("Sq_m").unwrap()[0].unwrap());
    }
    let want = (0.5f64 * 3e-7 * 3e-7 + 0.5 * 1e-7 * 1e-7).sqrt();
    assert!((sq[0] - want).abs() < 1e-5 * want, "{} vs {want}", sq[0]);
    assert!((sq[0] - sq[1]).abs() < 1e-12 * want, "{sq:?}");
}

/// Writes the small fixtures of `fixtures/surface/` (fuzz seeds and
/// always-read examples): `cargo test write_surface_fixtures -- --ignored`.
#[test]
#[ignore]
fn write_surface_fixtures() {
    use crate::common::writers::{X3p, X3pType};
    let dir = common::root().join("fixtures/surface");
    std::fs::create_dir_all(&dir).unwrap();
    let s = Surface::waves(16, 12, 1e-6, 2e-6, 2e-7, 5e-8);
    let mask: Vec<bool> = (0..s.z.len()).map(|i| i % 13 != 5).collect();
    let files: Vec<(&str, Vec<u8>)> = vec![
        ("waves-16x12.x3p", writers::x3p(&s, &X3p::default())),
        (
            "waves-16x12-int16-mask.x3p",
            writers::x3p(
                &s,
                &X3p {
                    kind: X3pType::I,
                    mask: Some(mask),
                    folder: "scan/",
                    ..Default::default()
                },
            ),
        ),
        (
            "waves-16x12.sur",
            writers::sur(
                &s,
                &Sur {
                    bits: 16,
                    invalid: vec![3, 50],
                    ..Default::default()
                },
            ),
        ),
        (
            "waves-16x12-compressed.sur",
            writers::sur(
                &s,
                &Sur {
                    compressed: true,
                    streams: 2,
                    ..Default::default()
                },
            ),
        ),
    ];
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}
