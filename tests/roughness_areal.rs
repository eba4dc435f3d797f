//! Areal maps from z matrices and x,y,z points, and evaluation windows along
//! both axes (MODELS.md §4). The reference values are closed forms of sine
//! surfaces over whole periods; the two readers of one surface must agree.
#![deny(clippy::float_cmp)]

use std::path::{Path, PathBuf};

use tribo::extract::roughness::analyze::RoughnessReport;
use tribo::extract::roughness::input::AxisUnits;
use tribo::extract::roughness::params::{Detrend, RoughnessParams};
use tribo::extract::roughness::stage::analyze_dataset;
use tribo::extract::roughness::stage::RoughnessFile;
use tribo::ingest::{read_path, IngestOptions};

/// Reads and analyses one file.
fn process_file(
    path: &Path,
    options: &IngestOptions,
    params: &RoughnessParams,
    units: &AxisUnits,
) -> tribo::Result<RoughnessFile> {
    analyze_dataset(&read_path(path, options)?, params, units)
}

/// The Gwyddion-style fixture: z = A sin(2πx/λx) cos(2πy/λy), A = 0.2 µm,
/// 48 × 40 points at Δx = 0.5 µm, Δy = 0.25 µm, four periods each way.
fn gwyddion() -> PathBuf {
    crate::common::root().join("fixtures/roughness/matrix/gwyddion_sine.txt")
}

const A: f64 = 0.2e-6;

fn mean_only() -> RoughnessParams {
    RoughnessParams {
        detrend: Detrend::Mean,
        ..Default::default()
    }
}

fn one(path: &Path, params: &RoughnessParams, units: &AxisUnits) -> RoughnessReport {
    let mut f = process_file(path, &IngestOptions::default(), params, units).unwrap();
    assert_eq!(f.reports.len(), 1);
    f.reports.remove(0)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The same heights as x,y,z points in µm, µm, nm, with a header.
fn write_xyz(dir: &Path, nx: usize, ny: usize, z: impl Fn(usize, usize) -> f64) -> PathBuf {
    let mut s = String::from("x (um),y (um),z (nm)\n");
    for r in 0..ny {
        for c in 0..nx {
            s += &format!(
                "{},{},{:.9}\n",
                c as f64 * 0.5,
                r as f64 * 0.25,
                z(c, r) * 1e9
            );
        }
    }
    let p = dir.join("points.csv");
    std::fs::write(&p, s).unwrap();
    p
}

fn sine_product(c: usize, r: usize) -> f64 {
    use std::f64::consts::PI;
    A * (2.0 * PI * c as f64 * 0.5 / 6.0).sin() * (2.0 * PI * r as f64 * 0.25 / 2.5).cos()
}

#[test]
fn gwyddion_matrix_gives_the_closed_forms_and_agrees_with_xyz_points() {
    let m = one(&gwyddion(), &mean_only(), &AxisUnits::default());
    assert_eq!(m.n_points, 48 * 40);
    // Whole periods: mean(sin² cos²) = 1/4, mean(sin⁴ cos⁴) = 9/64.
    assert!(rel(m.rq, A / 2.0) < 1e-9, "Sq {}", m.rq);
    assert!(rel(m.rku.unwrap(), 2.25) < 1e-9, "Sku {:?}", m.rku);
    assert!(m.rsk.unwrap().abs() < 1e-9, "Ssk {:?}", m.rsk);
    // Length from the Width line: 47 steps of 24 µm / 48.
    assert!(rel(m.length, 47.0 * 0.5e-6) < 1e-12, "{}", m.length);

    let tmp = tempfile::tempdir().unwrap();
    let xyz = write_xyz(tmp.path(), 48, 40, sine_product);
    let p = one(&xyz, &mean_only(), &AxisUnits::default());
    assert_eq!(p.n_points, m.n_points);
    for (a, b, what) in [
        (m.ra, p.ra, "Sa"),
        (m.rq, p.rq, "Sq"),
        (m.rms_slope.unwrap(), p.rms_slope.unwrap(), "Sdq"),
        (m.rku.unwrap(), p.rku.unwrap(), "Sku"),
    ] {
        // The points file prints z to 1e-9 nm of a 200 nm amplitude.
        assert!(rel(a, b) < 1e-9, "{what}: matrix {a} vs points {b}");
    }
}

/// A plain matrix: rows r < 20 flat, rows r ≥ 20 a sine along x with whole
/// periods, A sin(2π c / 12).
fn write_half_rough(dir: &Path) -> PathBuf {
    use std::f64::consts::PI;
    let mut s = String::new();
    for r in 0..40 {
        let row: Vec<String> = (0..48)
            .map(|c| {
                let z = if r >= 20 {
                    0.2 * (2.0 * PI * c as f64 / 12.0).sin()
                } else {
                    0.0
                };
                format!("{z:.12}")
            })
            .collect();
        s += &row.join(",");
        s.push('\n');
    }
    let p = dir.join("half.csv");
    std::fs::write(&p, s).unwrap();
    p
}

#[test]
fn window_along_y_selects_rows_of_a_plain_matrix_with_given_spacing() {
    let tmp = tempfile::tempdir().unwrap();
    let path = write_half_rough(tmp.path());
    let units = AxisUnits {
        x: None,
        z: Some("um".into()),
        spacing: Some((0.5e-6, 0.25e-6)),
    };
    // Rows 20..40 are at y = 5 µm .. 9.75 µm; columns 0..=47 cover 4 periods
    // only over 0..48, so take the whole x range.
    let upper = RoughnessParams {
        window_y: Some((5e-6, 9.75e-6)),
        ..mean_only()
    };
    let u = one(&path, &upper, &units);
    assert_eq!(u.n_points, 48 * 20);
    // A sine along x, constant along y: Sq = A/√2, Sku = 3/2.
    assert!(rel(u.rq, 0.2e-6 / 2f64.sqrt()) < 1e-9, "Sq {}", u.rq);
    assert!(rel(u.rku.unwrap(), 1.5) < 1e-9, "Sku {:?}", u.rku);
    // The flat rows alone: Sq = 0, skewness undefined and said so.
    let lower = RoughnessParams {
        window_y: Some((0.0, 4.75e-6)),
        ..mean_only()
    };
    let l = one(&path, &lower, &units);
    assert_eq!(l.n_points, 48 * 20);
    assert!(l.rq.abs() < 1e-18 && l.rsk.is_none(), "{l:?}");
    assert!(l.status().contains("flat"), "{}", l.status());
    // Both windows: the x window keeps 2 whole periods (c = 12..=35).
    let both = RoughnessParams {
        window: Some((6e-6, 17.5e-6)),
        window_y: Some((5e-6, 9.75e-6)),
        ..mean_only()
    };
    let b = one(&path, &both, &units);
    assert_eq!(b.n_points, 24 * 20);
    assert!(rel(b.rq, 0.2e-6 / 2f64.sqrt()) < 1e-9, "Sq {}", b.rq);
    // A window outside the map is an error naming the axis.
    let outside = RoughnessParams {
        window_y: Some((20e-6, 30e-6)),
        ..mean_only()
    };
    let e = process_file(&path, &IngestOptions::default(), &outside, &units)
        .unwrap_err()
        .to_string();
    assert!(e.contains("along y") && e.contains("holds 0 points"), "{e}");
}

#[test]
fn a_matrix_without_spacing_or_height_unit_says_how_to_give_them() {
    let tmp = tempfile::tempdir().unwrap();
    let path = write_half_rough(tmp.path());
    let p = mean_only();
    let no_spacing = AxisUnits {
        z: Some("um".into()),
        ..Default::default()
    };
    let e = process_file(&path, &IngestOptions::default(), &p, &no_spacing)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("half.csv") && e.contains("48 columns × 40 rows") && e.contains("--spacing"),
        "{e}"
    );
    let no_unit = AxisUnits {
        spacing: Some((1e-6, 1e-6)),
        ..Default::default()
    };
    let e = process_file(&path, &IngestOptions::default(), &p, &no_unit)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--z-unit"), "{e}");
    // A Width that is not a length is named with its line.
    let text = std::fs::read_to_string(gwyddion())
        .unwrap()
        .replace("# Width: 24.000 µm", "# Width: 24.000 s");
    let bad = tmp.path().join("bad_width.txt");
    std::fs::write(&bad, text).unwrap();
    let e = process_file(&bad, &IngestOptions::default(), &p, &AxisUnits::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 2") && e.contains("Width"), "{e}");
}

#[test]
fn xyz_map_windows_use_the_file_positions() {
    // The points start at x = 0, y = 0 here; shift them to start at 100 µm
    // in x: a window in file coordinates must follow.
    let tmp = tempfile::tempdir().unwrap();
    let mut s = String::from("x (um),y (um),z (nm)\n");
    for r in 0..40 {
        for c in 0..48 {
            let z = sine_product(c, r) * 1e9;
            s += &format!("{},{},{z:.9}\n", 100.0 + c as f64 * 0.5, r as f64 * 0.25);
        }
    }
    let path = tmp.path().join("shifted.csv");
    std::fs::write(&path, s).unwrap();
    // Two whole periods along x (c = 12..=35 → x = 106 .. 117.5 µm).
    let p = RoughnessParams {
        window: Some((106e-6, 117.5e-6)),
        ..mean_only()
    };
    let r = one(&path, &p, &AxisUnits::default());
    assert_eq!(r.n_points, 24 * 40);
    assert!(rel(r.rq, A / 2.0) < 1e-9, "Sq {}", r.rq);
}
