//! Generated variants of each surface-profile text family (Surfcom-style
//! `.tx1/.tx2/.tx3`, headerless x z line scans, SurfaceTopography's UTF-16
//! CSV): the same profile with another line ending, encoding, locale,
//! separator or conditions language reads as the same x and z in metres.

use std::path::Path;

use crate::common;
use crate::common::variants::{
    assert_same, read_written, render, signature, Enc, Ending, ENCODINGS, ENDINGS,
};

use tribo::extract::roughness::input::{surfaces_from_dataset, AxisUnits, Surface};
use tribo::ingest::companion::{data_file_of, Inputs};
use tribo::ingest::Dataset;

fn fixture(rel: &str) -> std::path::PathBuf {
    common::root().join("fixtures").join(rel)
}

/// The one profile of a dataset, in m.
fn profile(ds: &Dataset) -> (f64, f64, Vec<f64>) {
    match &surfaces_from_dataset(ds, &AxisUnits::default()).unwrap()[..] {
        [Surface::Profile(p)] => (p.x0, p.dx, p.z.clone()),
        other => panic!(
            "{}: expected one profile, found {}",
            ds.source.display(),
            other.len()
        ),
    }
}

/// A `.tx2` of 400 heights over 4 mm: `comma` writes decimal commas.
fn tx(comma: bool) -> String {
    let mut l = vec!["4.00000".to_string(), "400".to_string()];
    l.extend((0..400).map(|i| format!("{:.4}", 1.5 * (i as f64 * 0.3).sin() - 0.2)));
    let s = l.join("\n");
    match comma {
        true => s.replace('.', ","),
        false => s,
    }
}

/// Measuring conditions in Spanish (the real export), English, German or
/// Portuguese.
fn tx3(language: &str) -> String {
    let rows: [[&str; 4]; 5] = [
        [
            "Unidad salida",
            "Output unit",
            "Ausgabeeinheit",
            "Unidade de saída",
        ],
        [
            "Longitud evaluación",
            "Evaluation length",
            "Auswertelänge",
            "Comprimento de avaliação",
        ],
        [
            "Onda de corte",
            "Cutoff",
            "Grenzwellenlänge",
            "Comprimento de onda de corte",
        ],
        [
            "Longitud onda corte Ls",
            "Ls cutoff",
            "Ls-Grenzwellenlänge",
            "Comprimento de onda de corte Ls",
        ],
        ["Tipo corte", "Filter type", "Filtertyp", "Tipo de filtro"],
    ];
    let k = ["es", "en", "de", "pt"]
        .iter()
        .position(|l| *l == language)
        .unwrap();
    let values = ["mm,um", "4.0mm", "0.8mm", "2.5um", "Gaussian"];
    let mut out = vec![
        "Fecha\t08.04.2025".to_string(),
        "Ra\t*.*******um\t*.*******um".into(),
    ];
    out.extend(
        rows.iter()
            .zip(values)
            .map(|(r, v)| format!("{}\t{v}", r[k])),
    );
    out.join("\n")
}

/// Decimal point or comma, every line ending, UTF-8 or ISO-8859-1
/// conditions in Spanish, English, German or Portuguese beside it, or none: the same
/// x and z in m (400 heights in µm over 4 mm), the same conditions under
/// language-free keys, and the `.tx3` a companion of the profile.
#[test]
fn surfcom_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let base = read_written(dir.path(), "1.tx2", tx(false).as_bytes());
    assert_eq!(base.format, "surfcom-tx");
    let (x0, dx, z) = profile(&base);
    assert!(x0.abs() < 1e-15, "{x0}");
    assert!((dx / (4e-3 / 399.0) - 1.0).abs() < 1e-12, "{dx}");
    assert!((z[0] + 0.2e-6).abs() < 1e-15 && z.len() == 400, "{}", z[0]);
    let want = signature(&base);
    for language in ["es", "en", "de", "pt"] {
        for conditions_enc in [Enc::Utf8, Enc::Latin1] {
            let cond = render(&tx3(language), Ending::Crlf, conditions_enc);
            std::fs::write(dir.path().join("1.tx3"), cond).unwrap();
            for comma in [false, true] {
                for ending in ENDINGS {
                    let what = format!("{language} {conditions_enc:?} comma={comma} {ending:?}");
                    let ds =
                        read_written(dir.path(), "1.tx2", &render(&tx(comma), ending, Enc::Utf8));
                    assert_eq!(ds.format, "surfcom-tx", "{what}");
                    assert_same(&want, &signature(&ds), &what);
                    let get = |k: &str| {
                        ds.preamble
                            .iter()
                            .find(|m| m.key == k)
                            .map(|m| m.value.clone())
                    };
                    assert_eq!(
                        get("tribo.cutoff_lambda_c").as_deref(),
                        Some("0.8mm"),
                        "{what}"
                    );
                    assert_eq!(
                        get("tribo.cutoff_lambda_s").as_deref(),
                        Some("2.5um"),
                        "{what}"
                    );
                    assert_eq!(
                        get("tribo.evaluation_length").as_deref(),
                        Some("4.0mm"),
                        "{what}"
                    );
                    assert!(
                        get("tribo.units")
                            .unwrap()
                            .contains("as the measuring conditions"),
                        "{what}"
                    );
                }
            }
            let tx3_path = dir.path().join("1.tx3");
            let tx2_path = dir.path().join("1.tx2");
            assert_eq!(
                data_file_of(&tx3_path, &Inputs::new(&[&tx3_path, &tx2_path])),
                Some(tx2_path.as_path())
            );
        }
    }
    // Conditions that state other units are followed: heights in nm.
    std::fs::write(
        dir.path().join("1.tx3"),
        tx3("en").replace("mm,um", "mm,nm"),
    )
    .unwrap();
    let ds = read_written(dir.path(), "1.tx2", tx(false).as_bytes());
    assert!((profile(&ds).2[0] + 0.2e-9).abs() < 1e-18);
}

/// The Dektak OPDx text export with every line ending, UTF-8 with or
/// without BOM, UTF-16 LE or BE, and tabs, commas, single blanks or no
/// trailing blanks between the columns: 3001 points in m, the same values.
#[test]
fn xz_line_scan_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let text =
        std::fs::read_to_string(fixture("roughness/surfacetopography_text/opdx-3.txt")).unwrap();
    let base = read_written(dir.path(), "s.txt", text.as_bytes());
    assert_eq!(base.format, "xz-line-scan");
    let want = signature(&base);
    let cells = |l: &str| l.split_whitespace().map(str::to_string).collect::<Vec<_>>();
    let with = |sep: &str| {
        text.lines()
            .map(|l| cells(l).join(sep))
            .collect::<Vec<_>>()
            .join("\n")
    };
    for (what, v) in [
        ("as is", text.clone()),
        ("tab", with("\t")),
        ("comma", with(",")),
        ("blank", with(" ")),
    ] {
        for ending in ENDINGS {
            for enc in [Enc::Utf8, Enc::Utf8Bom, Enc::Utf16Le, Enc::Utf16Be] {
                let what = format!("{what} {ending:?} {enc:?}");
                let ds = read_written(dir.path(), "s.txt", &render(&v, ending, enc));
                assert_eq!(ds.format, "xz-line-scan", "{what}");
                assert_same(&want, &signature(&ds), &what);
            }
        }
    }
}

/// SurfaceTopography's UTF-16 CSV with an index column (CRLF) and without
/// (LF) give one profile, x and y in µm; so do both re-encoded as UTF-8
/// and UTF-16 BE.
#[test]
fn utf16_index_csv_reads_as_its_profile() {
    let dir = tempfile::tempdir().unwrap();
    let decode = |p: &Path| {
        let b = std::fs::read(p).unwrap();
        let units: Vec<u16> = b[2..]
            .chunks(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect();
        String::from_utf16(&units).unwrap()
    };
    let two = fixture("roughness/surfacetopography_text/csv-2.csv");
    let three = fixture("roughness/surfacetopography_text/csv-3.csv");
    let a = tribo::ingest::read_path(&two, &Default::default()).unwrap();
    let b = tribo::ingest::read_path(&three, &Default::default()).unwrap();
    let (pa, pb) = (profile(&a), profile(&b));
    assert_eq!(pa.2.len(), 8);
    assert!((pa.0 + 99.958_333_333_333_33e-6).abs() < 1e-15, "{}", pa.0);
    assert!((pa.1 - 0.083_333_333e-6).abs() < 1e-12, "{}", pa.1);
    for (x, y) in pa.2.iter().zip(&pb.2) {
        assert!((x - y).abs() < 1e-18 + 1e-13 * x.abs());
    }
    for (src, name) in [(&two, "c2.csv"), (&three, "c3.csv")] {
        let text = decode(src);
        let want = signature(&tribo::ingest::read_path(src, &Default::default()).unwrap());
        for enc in [Enc::Utf8, Enc::Utf16Be, Enc::Utf8Bom] {
            for ending in [Ending::Lf, Ending::Crlf, Ending::Cr] {
                let ds = read_written(dir.path(), name, &render(&text, ending, enc));
                assert_same(
                    &want,
                    &signature(&ds),
                    &format!("{name} {enc:?} {ending:?}"),
                );
            }
        }
    }
}

/// The Dektak CSV (its micro sign in ISO-8859-1, as the instrument writes
/// it), the Nanovea x,y,z points and a quoted decimal-comma
/// `"Distance","Profile"` export (comma or semicolon between its cells),
/// each with every line ending and in UTF-8, UTF-8 with BOM, UTF-16 LE/BE
/// or ISO-8859-1: the same reader, sections, channels, units and values.
#[test]
fn dektak_nanovea_and_profile_csv_variants_read_alike() {
    let dir = tempfile::tempdir().unwrap();
    let latin1 = |b: Vec<u8>| b.into_iter().map(char::from).collect::<String>();
    let profile_csv = |sep: &str| {
        let mut l = vec![format!("\"Distance\"{sep}\"Profile\"")];
        l.extend((1..=300).map(|i| {
            let z = format!("{:.2}", 0.4 * (i as f64 * 0.2).sin());
            format!("\"{:.5}\"{sep}\"{z}\"", i as f64 * 0.0005).replace('.', ",")
        }));
        l.join("\n")
    };
    let families = [
        (
            "dektak",
            "d.csv",
            latin1(std::fs::read(fixture("roughness/dektak/dektak-1.csv")).unwrap()),
        ),
        (
            "nanovea",
            "n.txt",
            std::fs::read_to_string(fixture("roughness/nanovea/test1.txt")).unwrap(),
        ),
        ("profile-csv", "p.csv", profile_csv(",")),
        ("profile-csv", "p.csv", profile_csv(";")),
    ];
    for (format, name, text) in families {
        let base = read_written(dir.path(), name, &render(&text, Ending::Crlf, Enc::Latin1));
        assert_eq!(base.format, format);
        let want = signature(&base);
        for ending in ENDINGS {
            for enc in ENCODINGS {
                let what = format!("{format} {ending:?} {enc:?}");
                let ds = read_written(dir.path(), name, &render(&text, ending, enc));
                assert_eq!(ds.format, format, "{what}");
                assert_same(&want, &signature(&ds), &what);
            }
        }
    }
}
