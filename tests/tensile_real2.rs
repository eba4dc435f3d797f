//! Real mechanical-test exports from other labs: each file's channels,
//! units and rows, and the numbers it prints against ours. The Apache-2.0
//! Mat-O-Lab files are fixtures (`fixtures/tensile/matolab/`); the others
//! are read from `../shared/data/real2` and skipped when it is absent.

use std::path::{Path, PathBuf};

use crate::common;
use crate::common::shared_real2 as real2;
use tribo::extract::tensile::{analyze_file, tensile_table, Direction, FibreRecord, TensileParams};
use tribo::ingest::inspect::inspect;
use tribo::ingest::manifest::Manifest;
use tribo::ingest::{read_path, Dataset, IngestOptions};
use tribo::status::Code;

fn matolab(name: &str) -> PathBuf {
    common::root().join("fixtures/tensile/matolab").join(name)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// (name, unit as written, SI unit, role) of a section's columns.
fn columns(ds: &Dataset, section: usize) -> Vec<(String, String, String, Option<&'static str>)> {
    inspect(ds, &Default::default()).sections[section]
        .columns
        .iter()
        .map(|c| (c.name.clone(), c.unit.clone(), c.si_unit.clone(), c.role))
        .collect()
}

fn cols(
    v: &[(&str, &str, &str, Option<&'static str>)],
) -> Vec<(String, String, String, Option<&'static str>)> {
    v.iter()
        .map(|(a, b, c, d)| (a.to_string(), b.to_string(), c.to_string(), *d))
        .collect()
}

/// A manifest in `dir` with one row for `file`.
fn manifest(dir: &Path, header: &str, row: &str) -> Manifest {
    let p = dir.join("samples.csv");
    std::fs::write(&p, format!("file,{header}\n{row}\n")).unwrap();
    Manifest::read(&p).unwrap()
}

fn analyze(p: &Path, m: Option<&Manifest>) -> FibreRecord {
    analyze_file(p, m, &IngestOptions::default(), &TensileParams::default()).unwrap()
}

fn note(r: &FibreRecord, code: Code) -> Vec<&str> {
    r.features
        .status
        .notes()
        .iter()
        .filter(|n| n.code == code)
        .map(|n| n.detail.as_str())
        .collect()
}

/// Zwick testXpert, parameter lines: E-Modul 1127.12 N/mm² is the ISO 527-1
/// regression over 0.05–0.25 % strain (ours 1127.116), Kraftmaximum
/// 37.9483 N/mm² is Rm = Fmax / (a0 · b0) = 86.5222 N / 2.28 mm², and the
/// strains at Fmax and at break are the rows' own (306.402 %, the last row
/// 309.236 %).
#[test]
fn zwick_testxpert_real_export_gives_its_printed_results() {
    let p = matolab("example.csv");
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "zwick-testxpert");
    assert_eq!(ds.sections.len(), 1);
    assert_eq!(ds.sections[0].rows(), 18876);
    assert_eq!(
        columns(&ds, 0),
        cols(&[
            ("Prüfzeit", "s", "s", Some("time")),
            ("Standardweg", "mm", "m", Some("extension")),
            ("Standardkraft", "N", "N", Some("force")),
            ("Dehnung", "%", "1", Some("strain")),
            ("Traverse abs.", "mm", "m", None),
        ])
    );
    let e = ds.preamble.iter().find(|m| m.key == "E-Modul").unwrap();
    assert_eq!(e.value, "1127.12 N/mm²");
    let unknown = ds.preamble.iter().find(|m| m.key == "Messlänge").unwrap();
    assert_eq!(unknown.value, "nicht bekannt");

    let dir = tempfile::tempdir().unwrap();
    let m = manifest(dir.path(), "material_class", "example.csv,plastic");
    let r = analyze(&p, Some(&m));
    let (f, g, i) = (&r.features, &r.features.general, &r.instrument);
    assert_eq!(r.meta.section(), Some(("rectangular", 11.4e-3 * 0.2e-3)));
    // E within 0.01 % of the printed 1127.12 (ours 1127.116)
    assert!(
        rel(g.modulus_pa.unwrap(), 1127.12e6) < 1e-4,
        "{:?}",
        g.modulus_pa
    );
    assert_eq!(i.modulus_pa, Some(1127.12e6));
    // Rm: the same rows, printed with six digits
    assert!((g.max_stress_pa.unwrap() - 37.9483e6).abs() < 0.00005e6);
    assert!((g.max_force_n.unwrap() - 86.5222).abs() < 1e-9);
    assert!((g.strain_at_max_stress.unwrap() - 3.06402).abs() < 1e-12);
    // ISO 527: the last recorded point (the record ends at 59 % of Fmax)
    assert!((f.strain_at_break.unwrap() - 3.09236).abs() < 1e-12);
    assert!((i.strain_at_break.unwrap() - 3.09236).abs() < 1e-12);
    assert!(f.truncated);
    assert!(f.status.only(&[Code::FractureTruncated]), "{}", f.status);
    // no density for a film: the toughness per volume only
    assert_eq!(f.toughness_j_per_kg, None);
    assert!(f.energy_density_j_per_m3.unwrap() > 0.0);
}

/// Without a material class the modulus is tribo's default window (the
/// steepest 3 %-wide window of this 300 % film): 34 % below the printed E,
/// which the status says with both values.
#[test]
fn zwick_without_a_class_says_its_modulus_window_differs() {
    let r = analyze(&matolab("example.csv"), None);
    let s = &r.features.status;
    assert!(s.has(Code::DefaultModulusWindow), "{s}");
    let m = note(&r, Code::InstrumentMismatch);
    assert_eq!(m.len(), 1, "{s}");
    assert!(
        m[0].starts_with("modulus: ours 0.7473") && m[0].contains("prints 1.1271 GPa (−33.69"),
        "{}",
        m[0]
    );
}

/// A test alters the file's printed modulus: the status appears, naming
/// both values; the untouched file has none.
#[test]
fn an_altered_printed_modulus_is_a_status() {
    // bytes, not text: the file is ISO-8859-1 (N/mm² must stay N/mm²)
    let bytes = std::fs::read(matolab("example.csv")).unwrap();
    let (from, to) = (b"\t1127.12\t".as_slice(), b"\t1300\t".as_slice());
    let at = bytes.windows(from.len()).position(|w| w == from).unwrap();
    let altered = [&bytes[..at], to, &bytes[at + from.len()..]].concat();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("altered.csv");
    std::fs::write(&p, altered).unwrap();
    let m = manifest(dir.path(), "material_class", "altered.csv,plastic");
    let r = analyze(&p, Some(&m));
    let m = note(&r, Code::InstrumentMismatch);
    assert_eq!(m.len(), 1, "{}", r.features.status);
    assert!(
        m[0].starts_with("modulus: ours 1.1271 GPa, the file prints 1.3 GPa (−13.29")
            && m[0].ends_with(
                "ours by regression over strain 0.05–0.25 % of the first loading (ISO 527-1)"
            ),
        "{}",
        m[0]
    );
}

/// MTS 793, German locale: a concrete cylinder crushed after three load
/// cycles. The peak of the force channel over π/4 · 100.1² mm² is the
/// compressive strength; stress and strain are magnitudes; the operator's
/// unitless entries are read in mm and g, and give concrete's density.
#[test]
fn mts793_compression_of_a_concrete_cylinder() {
    let p = matolab("example4.csv");
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "mts-793");
    let d = ds.dialect.as_ref().unwrap();
    assert_eq!((d.delimiter, d.decimal), ('\t', ','));
    assert_eq!(ds.sections.len(), 2);
    assert_eq!(ds.sections[0].rows(), 931);
    assert_eq!(ds.sections[1].rows(), 2);
    assert_eq!(
        columns(&ds, 0),
        cols(&[
            ("Datum", "d", "unknown", None),
            ("Laufzeit", "s", "s", Some("time")),
            ("Ch 1 Kraft Sollwert", "kN", "N", None),
            ("Ch 1 Kraft", "kN", "N", Some("force")),
            ("Ch 1 Weg", "mm", "m", Some("extension")),
            ("1944 B", "mm", "m", None),
            ("1281068", "mm", "m", None),
            ("2157", "mm", "m", None),
        ])
    );
    let force = &ds.sections[0].channel("Ch 1 Kraft").unwrap().values;
    let peak = force.iter().copied().fold(0.0_f64, f64::min);
    assert_eq!(peak, -472.88068);

    let dir = tempfile::tempdir().unwrap();
    let m = manifest(dir.path(), "material_class", "example4.csv,brittle");
    let r = analyze(&p, Some(&m));
    let g = &r.features.general;
    let area = std::f64::consts::PI / 4.0 * 0.1001_f64.powi(2);
    assert_eq!(r.meta.section().unwrap().0, "circular");
    assert!(rel(g.max_force_n.unwrap(), 472_880.68) < 1e-12);
    assert!(rel(g.max_stress_pa.unwrap(), 472_880.68 / area) < 1e-12);
    assert!(rel(g.max_stress_pa.unwrap(), 60.0888e6) < 1e-5);
    // 5646.2 g / (π/4 · 10.01² · 29.98 cm³) = 2.393 g/cm³
    let rho = r.meta.density_kg_per_m3.unwrap();
    assert!((rho - 2393.13).abs() < 0.01, "{rho}");
    let s = &r.features.status;
    assert!(s.only(&[Code::AssumedUnit, Code::Rezeroed]), "{s}");
    let z = note(&r, Code::Rezeroed);
    assert!(
        z[0].contains("'Ch 1 Weg'") && z[0].contains("1.711 mm"),
        "{}",
        z[0]
    );
    // a compressive strain as a magnitude, below concrete's bound
    let e = g.strain_at_max_stress.unwrap();
    assert!(e > 0.0 && e < 0.01, "{e}");
    // no yield is reported for a brittle class (the cycles are no drops)
    assert_eq!((g.upper_yield_pa, g.yield_stress_pa), (None, None));
    assert!(g.modulus_pa.unwrap() > 0.0);
}

/// The same cylinder's row of the `tensile` table: the columns a materials
/// lab reports, with their units in their names, against the file (force
/// channel peak in kN, Durchmesser and Länge in mm, Masse in g) and the
/// manifest's class.
#[test]
fn mts793_row_of_the_tensile_table() {
    let p = matolab("example4.csv");
    let dir = tempfile::tempdir().unwrap();
    let m = manifest(dir.path(), "material_class", "example4.csv,brittle");
    let r = analyze(&p, Some(&m));
    assert_eq!(r.features.general.direction, Direction::Compression);
    let t = tensile_table(std::slice::from_ref(&r)).unwrap();
    let f = |c: &str| t.f64(c).unwrap()[0].unwrap_or(f64::NAN);
    let s = |c: &str| t.str(c).unwrap()[0].clone();
    assert_eq!(s("test_direction").as_deref(), Some("compression"));
    assert_eq!(s("material_class").as_deref(), Some("brittle"));
    assert!(rel(f("max_force_N"), 472_880.68) < 1e-12);
    let area_mm2 = std::f64::consts::PI / 4.0 * 100.1_f64.powi(2);
    assert!(rel(f("max_stress_MPa"), 472_880.68 / area_mm2) < 1e-12);
    assert!(rel(f("gauge_length_mm"), 299.8) < 1e-12);
    // per mass = per volume / ρ: MJ/m³ over g/cm³ is J/g
    let rho = 5646.2 / (area_mm2 * 299.8 * 1e-3); // g over cm³
    assert!(rel(f("density_g_per_cm3"), rho) < 1e-9);
    let per_volume = f("energy_density_MJ_per_m3");
    assert!(per_volume > 0.0);
    assert!(rel(f("toughness_J_per_g"), per_volume / rho) < 1e-9);
    // the brittle class's window is stated with the modulus
    assert!(f("modulus_GPa") > 0.0);
    assert!(s("modulus_method").unwrap().contains("C469"));
}

/// HBM catmanEasy, hot tensile test of DD11 sheet: the four unused
/// channels (−1000000 on every row) are dropped, the geometry comes from
/// the manifest (gauge 20 mm, 9.9 × 2 mm), and Rm = Fmax / 19.8 mm² with
/// Fmax read from the file here. The yield stress that came out as
/// −8.2 MPa (the offset line met the pre-load, where the hot specimen was
/// briefly in compression) is on the final loading now.
#[test]
fn hbm_catman_hot_tensile_test() {
    let Some(p) = real2("hbm_catman_hot_tensile/DD11_7_1.ASC") else {
        return;
    };
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "hbm-catman");
    assert_eq!(ds.sections[0].rows(), 1290);
    assert_eq!(
        columns(&ds, 0),
        cols(&[
            ("Zeit  1 - Standardmessrate", "s", "s", Some("time")),
            ("Maytec", "mm", "m", Some("extension")),
            ("Kraft", "N", "N", Some("force")),
            ("Standardwegaufnehmer", "mm", "m", None),
            ("Pyrometer", "°C", "K", None),
        ])
    );
    let dropped = ds
        .preamble
        .iter()
        .filter(|m| m.key == "tribo.dropped_channel")
        .count();
    assert_eq!(dropped, 4);
    // Fmax from the file's own text
    let text = String::from_utf8_lossy(&std::fs::read(&p).unwrap()).to_string();
    let fmax = text
        .lines()
        .skip(1)
        .filter_map(|l| l.split('\t').nth(2)?.trim().parse::<f64>().ok())
        .fold(f64::MIN, f64::max);
    assert_eq!(fmax, 7145.0);

    let dir = tempfile::tempdir().unwrap();
    let m = manifest(
        dir.path(),
        "material_class,width_mm,thickness_mm,gauge_length_mm",
        "DD11_7_1.ASC,metal,9.9,2,20",
    );
    let r = analyze(&p, Some(&m));
    let g = &r.features.general;
    assert!(rel(g.max_stress_pa.unwrap(), fmax / 19.8e-6) < 1e-12);
    assert_eq!(g.max_force_n, Some(fmax));
    let y = g.yield_stress_pa.unwrap();
    assert!(
        y > 0.5 * g.max_stress_pa.unwrap() && y < g.max_stress_pa.unwrap(),
        "{y}"
    );
    assert!(rel(y, 229.05e6) < 1e-3, "{y}");
    // the strain counts from the foot of the pull (Maytec 0.1428 mm), not
    // from the heating: (3.3346 − 0.1428) / 20 at Fmax
    assert!(
        (g.strain_at_max_stress.unwrap() - 0.159595).abs() < 1e-6,
        "{:?}",
        g.strain_at_max_stress
    );
    assert!(r.features.status.is_ok(), "{}", r.features.status);
    // the folder's .TSX names DD11_7_3.ASC: a job file, not this file's
    let tsx = p.with_file_name("DD11_7_3.TSX");
    use tribo::ingest::companion::{companion_of, Family};
    let c = companion_of(&tsx).expect("a catman job file");
    assert_eq!(c.family, Family::CatmanJob);
    assert_eq!(c.data_files, vec![p.with_file_name("DD11_7_3.ASC")]);
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert!(ds.preamble.iter().all(|m| m.key != "tribo.companion"));
}

/// Instron 5569, ASTM D412 die C of a silicone: the section is printed in
/// cm² (0.18 cm² = 3 × 6 mm, stated twice and consistent), the strain
/// columns have no unit and are fractions (true = ln(1 + engineering) on
/// every row), the record ends at its maximum.
#[test]
fn instron5569_elastomer_strength_from_its_section_in_cm2() {
    let Some(p) = real2("instron5569_elastomer_srmd/Dragon Skin 20.csv") else {
        return;
    };
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "instron-parameters");
    assert_eq!(ds.sections[0].rows(), 404);
    assert_eq!(
        columns(&ds, 0),
        cols(&[
            ("Time", "s", "s", Some("time")),
            ("True Strain", "mm/mm", "1", None),
            ("True Stress", "MPa", "Pa", None),
            ("Engineering Strain", "mm/mm", "1", Some("strain")),
            ("Engineering Stress", "MPa", "Pa", Some("stress")),
        ])
    );
    let dir = tempfile::tempdir().unwrap();
    let m = manifest(dir.path(), "material_class", "Dragon Skin 20.csv,elastomer");
    let r = analyze(&p, Some(&m));
    let g = &r.features.general;
    assert_eq!(r.meta.section(), Some(("rectangular", 6e-3 * 3e-3)));
    assert!(rel(r.meta.area_m2.unwrap_or(0.18e-4), 0.18e-4) < 1e-12);
    assert!((g.max_stress_pa.unwrap() - 4.434225e6).abs() < 1e-6);
    // Fmax = 4.434225 MPa × 0.18 cm²
    assert!(rel(g.max_force_n.unwrap(), 4.434225e6 * 0.18e-4) < 1e-12);
    assert!((g.strain_at_max_stress.unwrap() - 9.20455).abs() < 1e-12);
    // the stress at 100 % elongation (M100)
    assert!(
        rel(g.modulus_pa.unwrap(), 0.31836e6) < 1e-4,
        "{:?}",
        g.modulus_pa
    );
    let s = &r.features.status;
    assert!(s.only(&[Code::NoFracture]), "{s}");
}

/// Rail steel: read as written. Stress = Load / A0 holds (A0 = 120.9 mm²),
/// so the strength is the file's; the strain column contradicts the
/// extension (it implies a 0.043 mm gauge), the time column counts ms, and
/// the strain goes beyond any metal's: each is a status.
#[test]
fn rail_steel_strength_with_its_strain_column_flagged() {
    let Some(p) = real2("rail_steel_tension_csv/exemplo1.csv") else {
        return;
    };
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "delimited");
    assert_eq!(ds.sections[0].rows(), 540);
    assert_eq!(
        columns(&ds, 0),
        cols(&[
            ("Time", "s", "s", Some("time")),
            ("Extension", "mm", "m", Some("extension")),
            ("Strain", "%", "1", Some("strain")),
            ("Load", "kN", "N", Some("force")),
            ("Stress", "MPa", "Pa", Some("stress")),
        ])
    );
    let text = std::fs::read_to_string(&p).unwrap();
    let column = |k: usize| -> Vec<f64> {
        text.lines()
            .skip(1)
            .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
            .collect()
    };
    let smax = column(4).into_iter().fold(f64::MIN, f64::max);
    let fmax = column(3).into_iter().fold(f64::MIN, f64::max);
    let dir = tempfile::tempdir().unwrap();
    let m = manifest(dir.path(), "material_class", "exemplo1.csv,metal");
    let r = analyze(&p, Some(&m));
    let g = &r.features.general;
    assert!(rel(g.max_stress_pa.unwrap(), smax * 1e6) < 1e-12);
    assert!(rel(g.max_force_n.unwrap(), fmax * 1e3) < 1e-12);
    let s = &r.features.status;
    let strain = note(&r, Code::ChannelMismatch);
    assert_eq!(strain.len(), 1, "{s}");
    assert!(
        strain[0].contains("'Strain' = ('Extension' − x0) / L0: it implies L0 = 0.0426"),
        "{}",
        strain[0]
    );
    let time = note(&r, Code::SuspectUnit);
    assert!(
        time[0].contains("spans 436500 s") && time[0].contains("436.5 s"),
        "{}",
        time[0]
    );
    assert!(s.has(Code::ImpossibleValue), "{s}");
    // a section in the manifest that disagrees with Stress / Load is named
    let m = manifest(
        dir.path(),
        "material_class,diameter_mm",
        "exemplo1.csv,metal,10",
    );
    let r = analyze(&p, Some(&m));
    let area = note(&r, Code::ChannelMismatch);
    assert!(
        area.iter().any(
            |d| d.starts_with("'Stress' = 'Load' / A: it implies A = 120.")
                && d.contains("the specimen's section gives 78.54 mm^2")
        ),
        "{area:?}"
    );
}

/// The T150 and Bluehill real files keep their results (their own tests
/// in tensile_real_files.rs); here, the Bluehill section agrees with its
/// stress and load channels, and the one modulus beyond 5 % is named.
#[test]
fn bluehill_channels_agree_and_its_modulus_is_checked() {
    let Some(dir) = common::shared_real("tensile_bluehill") else {
        return;
    };
    for (name, mismatch) in [
        ("Tens_Yield/Specimen_RawData_1.csv", false),
        ("Tens_No_Yield/Specimen_RawData_1.csv", true),
    ] {
        let r = analyze(&dir.join(name), None);
        let s = &r.features.status;
        assert!(!s.has(Code::ChannelMismatch), "{name}: {s}");
        let m = note(&r, Code::InstrumentMismatch);
        assert_eq!(!m.is_empty(), mismatch, "{name}: {s}");
        assert!(m.iter().all(|d| d.starts_with("modulus: ")), "{m:?}");
    }
}
