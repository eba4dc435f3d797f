//! Readers for tensile and surface exports labs use (issue 16): each read
//! from a fixture in its layout, checked against the values the file
//! itself prints or a closed form, and `inspect` showing every channel with
//! its unit and role. Units in headers are converted, and an unknown one is
//! an error naming the file and line.

use std::path::{Path, PathBuf};

use tribo::extract::tensile::{analyze_file, TensileParams};
use tribo::ingest::inspect::inspect;
use tribo::ingest::{read_path, IngestOptions};

fn fixture(rel: &str) -> PathBuf {
    crate::common::root().join("fixtures").join(rel)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// (column, SI unit, role) of every column of every section.
fn columns(f: &Path) -> Vec<(String, String, Option<&'static str>)> {
    let ds = read_path(f, &IngestOptions::default()).unwrap();
    let i = inspect(&ds, &Default::default());
    i.sections
        .iter()
        .flat_map(|s| s.columns.iter())
        .map(|c| (c.name.clone(), c.si_unit.clone(), c.role))
        .collect()
}

fn as_str<'a>(
    v: &'a [(String, String, Option<&'static str>)],
) -> Vec<(&'a str, &'a str, Option<&'a str>)> {
    v.iter()
        .map(|(n, u, r)| (n.as_str(), u.as_str(), *r))
        .collect()
}

/// Writes `text` with one line replaced into a temporary file.
fn with_line(src: &Path, from: &str, to: &str, dir: &Path) -> PathBuf {
    let bytes = std::fs::read(src).unwrap();
    let text = String::from_utf8_lossy(&bytes).replace(from, to);
    let out = dir.join(src.file_name().unwrap());
    std::fs::write(&out, text).unwrap();
    out
}

// ---------------------------------------------------------------- Instron

/// The area in cm² reaches the analysis in m²; the specimen label is the
/// sample id; the maximum stress (Load / Area) equals the printed "Tensile
/// stress at Maximum Load", and the modulus on 50–250 MPa the printed 70 GPa.
#[test]
fn instron_blocks_area_in_cm2_gives_the_printed_results() {
    let f = fixture("tensile/instron_blocks.csv");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "instron-blocks");
    let params = TensileParams {
        modulus_stress_window_mpa: Some([50.0, 250.0]),
        ..Default::default()
    };
    let r = analyze_file(&f, None, &IngestOptions::default(), &params).unwrap();
    assert_eq!(r.meta.sample_id, "AL-03");
    let (kind, area) = r.meta.section().unwrap();
    assert_eq!(kind, "area");
    assert!(rel(area, 0.25e-4) < 1e-12, "area {area} m²");
    let (g, i) = (&r.features.general, &r.instrument);
    // printed: 339.50640 MPa (5 decimals)
    assert!(rel(i.strength_pa.unwrap(), 339.5064e6) < 1e-12);
    assert!(
        rel(g.max_stress_pa.unwrap(), i.strength_pa.unwrap()) < 1e-7,
        "{:?} vs {:?}",
        g.max_stress_pa,
        i.strength_pa
    );
    // printed 10.00000 % at maximum load; the Extension / gauge length there
    assert!(rel(i.strain_at_max.unwrap(), 0.10) < 1e-12);
    assert!(
        rel(g.modulus_pa.unwrap(), i.modulus_pa.unwrap()) < 1e-3,
        "{:?}",
        g.modulus_pa
    );
}

#[test]
fn instron_blocks_inspect_shows_every_channel() {
    let got = columns(&fixture("tensile/instron_blocks.csv"));
    assert_eq!(
        as_str(&got),
        [
            ("Time", "s", Some("time")),
            ("Extension", "m", Some("extension")),
            ("Load", "N", Some("force")),
        ]
    );
}

/// An area in an unknown unit, or a length where an area belongs, is an
/// error naming the file and the line (5).
#[test]
fn instron_blocks_unknown_area_unit_names_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let f = fixture("tensile/instron_blocks.csv");
    for unit in ["acres", "mm"] {
        let bad = with_line(
            &f,
            "Area,0.2500,cm^2",
            &format!("Area,0.2500,{unit}"),
            tmp.path(),
        );
        let e = read_path(&bad, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("instron_blocks.csv") && e.contains("line 5") && e.contains(unit),
            "{e}"
        );
    }
}

// ----------------------------------------------------- stylus heights only

use tribo::extract::roughness::input::{surfaces_from_dataset, AxisUnits, Surface};
use tribo::extract::roughness::params::{Detrend, RoughnessParams};
use tribo::extract::roughness::stage::analyze_dataset;

fn mean_only() -> RoughnessParams {
    RoughnessParams {
        detrend: Detrend::Mean,
        ..Default::default()
    }
}

/// 4001 heights over 4.000 mm: Δx = length / (points − 1) = 1 µm exactly
/// (length / points would be 0.99975 µm); heights in µm become metres;
/// Rq = A·√(2000/4001) for these samples (40 whole periods and the closing
/// zero), Ra within 1e-3 of the closed form 2A/π.
#[test]
fn stylus_heights_spacing_and_sine_roughness() {
    let f = fixture("roughness/stylus/sine_heights.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "stylus-heights");
    let surfaces = surfaces_from_dataset(&ds, &AxisUnits::default()).unwrap();
    let [Surface::Profile(p)] = surfaces.as_slice() else {
        panic!("expected one profile, got {surfaces:?}");
    };
    assert_eq!(p.z.len(), 4001);
    assert!(rel(p.dx, 1e-6) < 1e-12, "dx {}", p.dx);
    let a = 1.5e-6;
    let r = analyze_dataset(&ds, &mean_only(), &AxisUnits::default()).unwrap();
    let r = &r.reports[0];
    assert_eq!(r.n_points, 4001);
    let rq = a * (2000.0_f64 / 4001.0).sqrt();
    assert!(rel(r.rq, rq) < 1e-9, "Rq {} vs {rq}", r.rq);
    assert!(
        rel(r.ra, 2.0 * a / std::f64::consts::PI) < 1e-3,
        "Ra {}",
        r.ra
    );
}

#[test]
fn stylus_heights_inspect_shows_every_channel() {
    let got = columns(&fixture("roughness/stylus/sine_heights.txt"));
    assert_eq!(
        as_str(&got),
        [("x", "m", Some("x")), ("z", "m", Some("height"))]
    );
}

/// A count that disagrees with the heights names the count's line; an
/// unknown length unit names the length's line; a stated spacing that
/// disagrees with length / (points − 1) is refused at its line.
#[test]
fn stylus_heights_bad_headers_name_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let f = fixture("roughness/stylus/sine_heights.txt");
    let cases = [
        ("Number of points: 4001", "Number of points: 4000", "line 3"),
        ("4.000 mm", "4.000 furlong", "line 2"),
        ("Height unit: µm", "Height unit: mV", "line 4"),
        (
            "Height unit: µm",
            "Height unit: µm\nSpacing: 0.99975 um",
            "line 5",
        ),
    ];
    for (from, to, line) in cases {
        let bad = with_line(&f, from, to, tmp.path());
        let e = read_path(&bad, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("sine_heights.txt") && e.contains(line),
            "{to}: {e}"
        );
    }
    // the stated spacing that agrees is accepted
    let ok = with_line(
        &f,
        "Height unit: µm",
        "Height unit: µm\nSpacing: 1 um",
        tmp.path(),
    );
    assert_eq!(
        read_path(&ok, &IngestOptions::default()).unwrap().sections[0].rows(),
        4001
    );
}

// ------------------------------------------- SurfaceTopography text maps

/// UTF-16 with a byte-order mark, German keys, sizes in µm and nm, heights
/// in nm: the same map as the Gwyddion fixture, Sq = A/2 (closed form) and
/// the same spacing Δx = 0.5 µm, Δy = 0.25 µm.
#[test]
fn surface_text_german_utf16_gives_the_closed_form() {
    let f = fixture("roughness/matrix/surface_text_de_utf16.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "surface-text");
    let width = ds.preamble.iter().find(|m| m.key == "Width").unwrap();
    assert_eq!((width.value.as_str(), width.line), ("24.000 µm", 2));
    let surfaces = surfaces_from_dataset(&ds, &AxisUnits::default()).unwrap();
    let [Surface::Map(m)] = surfaces.as_slice() else {
        panic!("expected one map");
    };
    assert_eq!((m.nx, m.ny), (48, 40));
    assert!(
        rel(m.dx, 0.5e-6) < 1e-12 && rel(m.dy, 0.25e-6) < 1e-12,
        "{} {}",
        m.dx,
        m.dy
    );
    let r = analyze_dataset(&ds, &mean_only(), &AxisUnits::default()).unwrap();
    let a = 0.2e-6;
    assert!(
        rel(r.reports[0].rq, a / 2.0) < 1e-8,
        "Sq {}",
        r.reports[0].rq
    );
    assert!(rel(r.reports[0].rku.unwrap(), 2.25) < 1e-6);
    // the English Gwyddion export of the same surface agrees
    let g = read_path(
        &fixture("roughness/matrix/gwyddion_sine.txt"),
        &IngestOptions::default(),
    )
    .unwrap();
    assert_eq!(g.format, "surface-text");
    let rg = analyze_dataset(&g, &mean_only(), &AxisUnits::default()).unwrap();
    assert!(rel(r.reports[0].rq, rg.reports[0].rq) < 1e-8);
    assert!(rel(r.reports[0].ra, rg.reports[0].ra) < 1e-8);
}

#[test]
fn surface_text_inspect_shows_every_channel() {
    let got = columns(&fixture("roughness/matrix/surface_text_de_utf16.txt"));
    assert_eq!(got.len(), 48);
    for (i, (name, unit, role)) in got.iter().enumerate() {
        assert_eq!(name, &format!("column_{}", i + 1));
        assert_eq!((unit.as_str(), *role), ("m", Some("height")));
    }
}

/// An unknown unit in the header names the file and its line.
#[test]
fn surface_text_unknown_units_name_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let src = fixture("roughness/matrix/surface_text_de_utf16.txt");
    let bytes = std::fs::read(&src).unwrap();
    let utf16: Vec<u16> = bytes[2..]
        .chunks(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    let text = String::from_utf16(&utf16).unwrap();
    for (from, to, line) in [
        ("# Höhe: 10000.0 nm", "# Höhe: 10000.0 parsec", "line 3"),
        ("# Value units: nm", "# Value units: V", "line 4"),
    ] {
        let t = text.replace(from, to);
        let mut out = vec![0xFF, 0xFE];
        out.extend(t.encode_utf16().flat_map(u16::to_le_bytes));
        let p = tmp.path().join("bad_map.txt");
        std::fs::write(&p, out).unwrap();
        let e = read_path(&p, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("bad_map.txt") && e.contains(line), "{to}: {e}");
    }
}

// ------------------------------------------------ fixed-width x y z points

/// Heights below −100 µm fill their field and touch the y column; cut at
/// the columns, the map gives Sq = A/2 and Sku = 9/4 (closed forms) with
/// Δx = 0.01 mm, Δy = 0.02 mm from the positions in mm.
#[test]
fn fixed_width_xyz_touching_fields_give_the_closed_form() {
    let f = fixture("roughness/xyz/scanner_fixed_width.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "fixed-width-xyz");
    assert_eq!(ds.sections[0].rows(), 1200);
    // line 11: "    0.0700    0.0000-142.65848"
    let z = &ds.sections[0].channels[2].values;
    assert!((z[7] - -142.65848).abs() < 1e-12, "{}", z[7]);
    let surfaces = surfaces_from_dataset(&ds, &AxisUnits::default()).unwrap();
    let [Surface::Map(m)] = surfaces.as_slice() else {
        panic!("expected one map");
    };
    assert_eq!((m.nx, m.ny), (40, 30));
    assert!(
        rel(m.dx, 1e-5) < 1e-9 && rel(m.dy, 2e-5) < 1e-9,
        "{} {}",
        m.dx,
        m.dy
    );
    let r = analyze_dataset(&ds, &mean_only(), &AxisUnits::default()).unwrap();
    let a = 150e-6;
    assert!(
        rel(r.reports[0].rq, a / 2.0) < 1e-6,
        "Sq {}",
        r.reports[0].rq
    );
    assert!(rel(r.reports[0].rku.unwrap(), 2.25) < 1e-5);
}

#[test]
fn fixed_width_xyz_inspect_shows_every_channel() {
    let got = columns(&fixture("roughness/xyz/scanner_fixed_width.txt"));
    assert_eq!(
        as_str(&got),
        [
            ("X", "m", Some("x")),
            ("Y", "m", Some("y")),
            ("Z", "m", Some("height")),
        ]
    );
}

/// An unknown unit in the header names its line (3); a row that does not
/// fit the columns names its line and field.
#[test]
fn fixed_width_xyz_bad_rows_name_file_and_line() {
    let tmp = tempfile::tempdir().unwrap();
    let f = fixture("roughness/xyz/scanner_fixed_width.txt");
    let cases = [
        ("    Z [um]", "    Z [uV]", "line 3"),
        (
            "    0.0100    0.0000  88.16779",
            "    0.0100    0.00x0  88.16779",
            "line 5",
        ),
    ];
    for (from, to, line) in cases {
        let bad = with_line(&f, from, to, tmp.path());
        let e = read_path(&bad, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("scanner_fixed_width.txt") && e.contains(line),
            "{to}: {e}"
        );
    }
}

/// SurfaceTopography's own example (MIT, copied with its licence): blanks
/// as the delimiter, so the `# Value units: m` line above the numbers looks
/// like a header row of four names; it is read as the header it is, and
/// the 4 × 3 heights as a z matrix.
#[test]
fn surface_text_reads_surfacetopography_example_with_blank_delimiters() {
    let f = fixture("roughness/matrix/surfacetopography_matrix-6.txt");
    let ds = read_path(&f, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "surface-text");
    let s = &ds.sections[0];
    assert_eq!((s.channels.len(), s.rows(), s.header_line), (4, 3, None));
    let row0: Vec<f64> = s.channels.iter().map(|c| c.values[0]).collect();
    assert_eq!(row0, [1.0, 2.0, 3.0, 4.0]);
    let unit = ds.preamble.iter().find(|m| m.key == "Value units").unwrap();
    assert_eq!((unit.value.as_str(), unit.line), ("m", 4));
    assert!(s.channels.iter().all(|c| c.raw_unit == "m"));
}
