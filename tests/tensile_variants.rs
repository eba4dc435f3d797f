//! Generated variants of each mechanical-test family tribo reads (other
//! software versions, locales, column orders, line endings, encodings):
//! every variant of a family must read as that family and give the same
//! numbers, which are known in closed form.
//!
//! The specimen: elastic E = 2 GPa to ε = 0.01 (20 MPa), then hardening
//! 0.2 GPa to ε = 0.20 (58 MPa), then a fracture within four samples.

use std::path::Path;

use tribo::extract::tensile::{analyze_file, FibreRecord, TensileParams};
use tribo::ingest::manifest::Manifest;
use tribo::ingest::{read_path, IngestOptions};
use tribo::status::Code;

const E: f64 = 2e9;
const STRENGTH: f64 = 58e6;
const BREAK: f64 = 0.20;

/// (strain, stress Pa) of the specimen, 0.0005 strain apart, then the
/// fracture.
fn curve() -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let e = i as f64 * 0.0005;
            let s = if e <= 0.01 {
                E * e
            } else {
                20e6 + 0.2e9 * (e - 0.01)
            };
            (e, s)
        })
        .collect();
    for (k, f) in [0.6, 0.3, 0.05, 0.01].into_iter().enumerate() {
        v.push((BREAK + (k + 1) as f64 * 0.0001, STRENGTH * f));
    }
    v
}

/// A number with `decimal` as its mark.
fn num(x: f64, decimal: char) -> String {
    let s = format!("{x}");
    match decimal {
        ',' => s.replace('.', ","),
        _ => s,
    }
}

/// Text to bytes in the variant's encoding and line ending.
fn encode(lines: &[String], latin1: bool, crlf: bool) -> Vec<u8> {
    let ending = if crlf { "\r\n" } else { "\n" };
    let text = lines.join(ending) + ending;
    match latin1 {
        true => text
            .chars()
            .map(|c| u8::try_from(u32::from(c)).unwrap())
            .collect(),
        false => text.into_bytes(),
    }
}

/// One variant of a family's layout.
#[derive(Clone, Copy, Debug)]
struct Variant {
    decimal: char,
    latin1: bool,
    crlf: bool,
    /// Columns in reverse order.
    reversed: bool,
    /// The other language or software version of the family.
    other: bool,
}

fn variants() -> Vec<Variant> {
    let mut out = Vec::new();
    for (i, decimal) in ['.', ','].into_iter().enumerate() {
        for j in 0..2 {
            for other in [false, true] {
                out.push(Variant {
                    decimal,
                    latin1: (i + j) % 2 == 0,
                    crlf: j == 1,
                    reversed: (i + j + usize::from(other)) % 2 == 1,
                    other,
                });
            }
        }
    }
    out
}

/// Columns as (header, unit, values), in the variant's order.
fn ordered(
    v: Variant,
    mut columns: Vec<(&'static str, &'static str, Vec<f64>)>,
) -> Vec<(&'static str, &'static str, Vec<f64>)> {
    if v.reversed {
        columns.reverse();
    }
    columns
}

fn write_and_analyze(dir: &Path, name: &str, bytes: Vec<u8>, manifest: &str) -> FibreRecord {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    let m = dir.join(format!("{name}.samples.csv"));
    std::fs::write(&m, format!("file,{manifest}")).unwrap();
    let m = Manifest::read(&m).unwrap();
    analyze_file(
        &p,
        Some(&m),
        &IngestOptions::default(),
        &TensileParams::default(),
    )
    .unwrap()
}

fn format_of(dir: &Path, name: &str) -> &'static str {
    read_path(&dir.join(name), &IngestOptions::default())
        .unwrap()
        .format
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The numbers every variant must give (coupon of `area` m²).
fn assert_specimen(r: &FibreRecord, area: f64, what: &str) {
    let g = &r.features.general;
    assert!(
        rel(g.max_stress_pa.unwrap(), STRENGTH) < 1e-9,
        "{what}: {:?}",
        g.max_stress_pa
    );
    assert!(
        rel(g.max_force_n.unwrap(), STRENGTH * area) < 1e-9,
        "{what}: {:?} {:?}",
        g.max_force_n,
        r.meta.section()
    );
    let e = g.strain_at_max_stress.unwrap();
    assert!(
        (e - BREAK).abs() < 1e-9,
        "{what}: {e} {}",
        r.features.status
    );
    assert!(
        rel(g.modulus_pa.unwrap(), E) < 1e-6,
        "{what}: {:?}",
        g.modulus_pa
    );
}

/// testXpert parameter lines: German (`E-Modul`, `Kraftmaximum` in N,
/// `Probenbreite b0`) or English (`Young's modulus`, `Fmax`, `Specimen
/// width`) templates, printed results matching the rows.
#[test]
fn testxpert_variants() {
    let dir = tempfile::tempdir().unwrap();
    let (b0, a0, l0) = (10.0, 2.0, 50.0); // mm
    let area = b0 * a0 * 1e-6;
    for (k, v) in variants().into_iter().enumerate() {
        let d = v.decimal;
        let c = curve();
        let keys = match v.other {
            false => [
                "Probenbreite b0",
                "Probendicke a0",
                "E-Modul",
                "Kraftmaximum",
                "Dehnung bei Fmax",
                "Dehnung bei Bruch",
            ],
            true => [
                "Specimen width",
                "Specimen thickness",
                "Young's modulus",
                "Fmax",
                "Strain at Fmax",
                "Strain at break",
            ],
        };
        let mut lines = vec![
            format!("\"{}\"\t{}\t\"mm\"", keys[0], num(b0, d)),
            format!("\"{}\"\t{}\t\"mm\"", keys[1], num(a0, d)),
            "\"Messlänge\"\t\"nicht bekannt\"".to_string(),
            format!("\"{}\"\t{}\t\"N/mm²\"", keys[2], num(E * 1e-6, d)),
            format!("\"{}\"\t{}\t\"N\"", keys[3], num(STRENGTH * area, d)),
            format!("\"{}\"\t{}\t\"%\"", keys[4], num(BREAK * 100.0, d)),
            format!(
                "\"{}\"\t{}\t\"%\"",
                keys[5],
                num((BREAK + 0.0002) * 100.0, d)
            ),
        ];
        let names = match v.other {
            false => ["Prüfzeit", "Standardweg", "Standardkraft", "Dehnung"],
            true => [
                "Test time",
                "Standard travel",
                "Standard force",
                "Nominal strain",
            ],
        };
        let cols = ordered(
            v,
            vec![
                (
                    names[0],
                    "s",
                    (0..c.len()).map(|i| i as f64 * 0.1).collect(),
                ),
                (names[1], "mm", c.iter().map(|p| p.0 * l0).collect()),
                (names[2], "N", c.iter().map(|p| p.1 * area).collect()),
                (names[3], "%", c.iter().map(|p| p.0 * 100.0).collect()),
            ],
        );
        lines.push(
            cols.iter()
                .map(|c| format!("\"{}\"", c.0))
                .collect::<Vec<_>>()
                .join("\t"),
        );
        lines.push(
            cols.iter()
                .map(|c| format!("\"{}\"", c.1))
                .collect::<Vec<_>>()
                .join("\t"),
        );
        for i in 0..c.len() {
            lines.push(
                cols.iter()
                    .map(|c| num(c.2[i], d))
                    .collect::<Vec<_>>()
                    .join("\t"),
            );
        }
        let name = format!("zwick{k}.txt");
        let r = write_and_analyze(
            dir.path(),
            &name,
            encode(&lines, v.latin1, v.crlf),
            &format!("material_class\n{name},plastic\n"),
        );
        let what = format!("{v:?}");
        assert_eq!(format_of(dir.path(), &name), "zwick-testxpert", "{what}");
        assert_specimen(&r, area, &what);
        assert!(
            rel(r.instrument.max_force_n.unwrap(), STRENGTH * area) < 1e-12,
            "{what}"
        );
        assert!(r.features.status.only(&[]), "{what}: {}", r.features.status);
    }
}

/// MTS 793 in German (decimal comma) and English (decimal point) locales:
/// a compression test, the displacement zeroed at the preload.
#[test]
fn mts793_variants() {
    let dir = tempfile::tempdir().unwrap();
    let (d0, l0) = (50.0, 100.0); // mm
    let area = std::f64::consts::PI / 4.0 * (d0 * 1e-3) * (d0 * 1e-3);
    for (k, v) in variants().into_iter().enumerate() {
        let d = v.decimal;
        let thousands = if d == ',' { '.' } else { ',' };
        let lang = if v.other { "ENU" } else { "DEU" };
        let c = curve();
        let (title, diameter, length, names) = match v.other {
            false => (
                "Datenerfassung",
                "Durchmesser :",
                "Länge :",
                ["Laufzeit", "Ch 1 Kraft", "Ch 1 Weg"],
            ),
            true => (
                "Data Acquisition",
                "Diameter :",
                "Length :",
                ["Running Time", "Ch 1 Force", "Ch 1 Displacement"],
            ),
        };
        let mut lines = vec![
            format!("MTS793|MPT|{lang}|x|x|{d}|{thousands}|:|49|1|1|A"),
            String::new(),
            format!("{diameter}\t{}", num(d0, d)),
            format!("{length}\t{}", num(l0, d)),
            String::new(),
            format!("{title}\t\t\tZeit:\t{}\ts", num(544.5, d)),
        ];
        // the displacement moves down as the specimen shortens; zeroed at
        // sample 3 (a step of 5 mm at a steady load)
        let disp: Vec<f64> = c
            .iter()
            .enumerate()
            .map(|(i, p)| -p.0 * l0 - if i < 3 { 5.0 } else { 0.0 })
            .collect();
        let cols = ordered(
            v,
            vec![
                (
                    names[0],
                    "s",
                    (0..c.len()).map(|i| i as f64 * 0.5).collect(),
                ),
                (
                    names[1],
                    "kN",
                    c.iter().map(|p| -p.1 * area * 1e-3).collect(),
                ),
                (names[2], "mm", disp),
            ],
        );
        lines.push(cols.iter().map(|c| c.0).collect::<Vec<_>>().join("\t"));
        lines.push(cols.iter().map(|c| c.1).collect::<Vec<_>>().join("\t"));
        for i in 0..c.len() {
            lines.push(
                cols.iter()
                    .map(|c| num(c.2[i], d))
                    .collect::<Vec<_>>()
                    .join("\t"),
            );
        }
        let name = format!("mts{k}.txt");
        let r = write_and_analyze(
            dir.path(),
            &name,
            encode(&lines, v.latin1, v.crlf),
            &format!("material_class\n{name},plastic\n"),
        );
        let what = format!("{v:?}");
        assert_eq!(format_of(dir.path(), &name), "mts-793", "{what}");
        assert_eq!(r.meta.section().unwrap().0, "circular", "{what}");
        assert_specimen(&r, area, &what);
        let s = r.features.status.to_string();
        assert!(
            r.features.status.only(&[Code::AssumedUnit, Code::Rezeroed]),
            "{what}: {s}"
        );
        assert!(s.contains("rezeroed"), "{what}: {s}");
    }
}

/// HBM catman exports: German or English time channel, an extensometer or
/// a `Weg` channel, decimal comma or point, a trailing tab, unused
/// channels written as −1000000 or 1e308; the section from the manifest.
#[test]
fn catman_tensile_variants() {
    let dir = tempfile::tempdir().unwrap();
    let area = 9.9e-6 * 2.0;
    for (k, v) in variants().into_iter().enumerate() {
        let d = v.decimal;
        let c = curve();
        let (time, ext, force, temp) = match v.other {
            false => ("Zeit  1 - Standardmessrate", "Maytec", "Kraft", "Pyrometer"),
            true => (
                "Time  1 - default sample rate",
                "Extensometer",
                "Force",
                "Temperature",
            ),
        };
        let sentinel = if k % 2 == 0 { -1_000_000.0 } else { 1e308 };
        let mut cols = ordered(
            v,
            vec![
                (
                    ext,
                    "mm",
                    c.iter().map(|p| p.0 * 20.0).collect::<Vec<f64>>(),
                ),
                (force, "N", c.iter().map(|p| p.1 * area).collect()),
                (temp, "°C", vec![300.0; c.len()]),
                ("MX840_0_CH 6", "V", vec![sentinel; c.len()]),
            ],
        );
        // the time channel comes first in every catman export
        cols.insert(
            0,
            (time, "s", (0..c.len()).map(|i| i as f64 * 0.02).collect()),
        );
        let mut lines = vec![cols
            .iter()
            .map(|c| format!("{} [{}]", c.0, c.1))
            .collect::<Vec<_>>()
            .join("\t")];
        for i in 0..c.len() {
            let row: Vec<String> = cols
                .iter()
                .map(|c| match c.2[i].abs() >= 1e300 {
                    true => "1,00000E+308".replace(',', &d.to_string()),
                    false => num(c.2[i], d),
                })
                .collect();
            lines.push(row.join("\t") + "\t");
        }
        let name = format!("catman{k}.ASC");
        let job = format!("CATMAN TEST FILE\r\nJobname=Job1\r\nMesswertdatei={name}\r\n");
        std::fs::write(dir.path().join(format!("catman{k}.TSX")), job).unwrap();
        let r = write_and_analyze(
            dir.path(),
            &name,
            encode(&lines, v.latin1, v.crlf),
            &format!(
                "material_class,width_mm,thickness_mm,gauge_length_mm\n{name},plastic,9.9,2,20\n"
            ),
        );
        let what = format!("{v:?}");
        assert_eq!(format_of(dir.path(), &name), "hbm-catman", "{what}");
        // its job file beside it is read with it
        let ds = read_path(&dir.path().join(&name), &IngestOptions::default()).unwrap();
        let job = ds.preamble.iter().find(|m| m.key == "Jobname");
        assert_eq!(job.map(|m| m.value.as_str()), Some("Job1"), "{what}");
        assert_specimen(&r, area, &what);
        assert!(r.features.status.is_ok(), "{what}: {}", r.features.status);
    }
}

/// Instron `PARAMETER;INFO` exports: semicolons or commas, with or without
/// the URL column, strain as a fraction or in percent (found from true =
/// ln(1 + engineering)), the section in cm²; and a file whose true stress
/// contradicts its engineering channels is named.
#[test]
fn instron_parameter_variants() {
    let dir = tempfile::tempdir().unwrap();
    let area = 3e-3 * 6e-3;
    for (k, v) in variants().into_iter().enumerate() {
        // a comma-separated file keeps its decimal point
        let (sep, d) = if v.decimal == ',' {
            (',', '.')
        } else {
            (';', '.')
        };
        let percent = v.other;
        let scale = if percent { 100.0 } else { 1.0 };
        let c = curve();
        let head = if v.crlf {
            "PARAMETER;INFO;URL;;"
        } else {
            "PARAMETER;INFO;;;"
        };
        let mut lines: Vec<String> = [
            head.to_string(),
            "Specimen Thickness (mm);3;;;".into(),
            "Specimen Width (mm);6;;;".into(),
            "Specimen Cross-section (cm^2);0.18;;;".into(),
            "Machine;Instron  5569;;;".into(),
            ";;;;".into(),
        ]
        .into_iter()
        .map(|l| l.replace(';', &sep.to_string()))
        .collect();
        let eng: Vec<f64> = c.iter().map(|p| p.0).collect();
        let cols = ordered(
            v,
            vec![
                (
                    "Time (s)",
                    (0..c.len()).map(|i| i as f64 * 0.1).collect::<Vec<f64>>(),
                ),
                (
                    "True Strain",
                    eng.iter().map(|e| (1.0 + e).ln() * scale).collect(),
                ),
                (
                    "True Stress (MPa)",
                    c.iter().map(|p| p.1 * (1.0 + p.0) * 1e-6).collect(),
                ),
                (
                    "Engineering Strain",
                    eng.iter().map(|e| e * scale).collect(),
                ),
                (
                    "Engineering Stress (MPa)",
                    c.iter().map(|p| p.1 * 1e-6).collect(),
                ),
            ]
            .into_iter()
            .map(|(n, v)| (n, "", v))
            .collect(),
        );
        lines.push(
            cols.iter()
                .map(|c| c.0)
                .collect::<Vec<_>>()
                .join(&sep.to_string()),
        );
        for i in 0..c.len() {
            lines.push(
                cols.iter()
                    .map(|c| num(c.2[i], d))
                    .collect::<Vec<_>>()
                    .join(&sep.to_string()),
            );
        }
        let name = format!("instron{k}.csv");
        let r = write_and_analyze(
            dir.path(),
            &name,
            encode(&lines, v.latin1, v.crlf),
            &format!("material_class\n{name},plastic\n"),
        );
        let what = format!("{v:?}");
        assert_eq!(format_of(dir.path(), &name), "instron-parameters", "{what}");
        assert_specimen(&r, area, &what);
        assert!(r.features.status.is_ok(), "{what}: {}", r.features.status);
        // one true stress 10 % off: the rows disagree, named
        if k == 0 {
            let col = cols
                .iter()
                .position(|c| c.0.starts_with("True Stress"))
                .unwrap();
            let row = 7 + 200;
            let mut cells: Vec<String> = lines[row].split(sep).map(str::to_string).collect();
            cells[col] = num(cols[col].2[200] * 1.1, d);
            lines[row] = cells.join(&sep.to_string());
            let r = write_and_analyze(
                dir.path(),
                "bad.csv",
                encode(&lines, v.latin1, v.crlf),
                "material_class\nbad.csv,plastic\n",
            );
            let s = r.features.status.to_string();
            assert!(
                s.starts_with("channel_mismatch: 'True Stress' = 'Engineering Stress' (1 + 'Engineering Strain'): 1 of 405 rows"),
                "{s}"
            );
        }
    }
}
