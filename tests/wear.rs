//! The wear stage (MODELS.md §9): a synthetic track of known cross-section,
//! volume and wear rate by hand through a pipeline, and the real
//! pin-on-disc track profiles of `../shared` (skipped without it).
#![deny(clippy::float_cmp)]

use std::f64::consts::PI;
use std::path::Path;

use crate::common;
use tribo::extract::wear::track::{track_section, TrackParams};
use tribo::table::Table;

/// A tilted surface with a parabolic groove of depth `d` and width `w`
/// centred at `xc` (cross-section (2/3) d w), 0.5 µm steps over 2.4 mm,
/// plus a deterministic ripple of amplitude `noise` (incommensurate
/// sines, standing in for the surface's roughness).
fn groove(d: f64, w: f64, xc: f64, noise: f64) -> (Vec<f64>, Vec<f64>) {
    let x: Vec<f64> = (0..4800).map(|i| 0.5e-6 * (i + 1) as f64).collect();
    let z = x
        .iter()
        .map(|&x| {
            let u = (x - xc) / (w / 2.0);
            let g = if u.abs() < 1.0 {
                -d * (1.0 - u * u)
            } else {
                0.0
            };
            let ripple = noise * (0.6 * (x / 3.1e-6).sin() + 0.4 * (x / 1.7e-6 + 1.0).sin());
            2e-5 * x + 1e-7 + g + ripple
        })
        .collect();
    (x, z)
}

#[test]
fn synthetic_groove_area_within_half_a_percent() {
    let (d, w) = (0.4e-6, 80e-6);
    let exact = 2.0 / 3.0 * d * w;
    // Noise-free: the only error is the trapezoids on the parabola,
    // (w/Δx)^-2 relative ≈ 4e-5, and the edge points on the grid.
    let (x, z) = groove(d, w, 0.8e-3, 0.0);
    let s = track_section("g", &x, &z, &TrackParams::default().with_band(1e-9)).unwrap();
    assert!((s.area / exact - 1.0).abs() < 1e-3, "{} vs {exact}", s.area);
    assert!((s.depth / d - 1.0).abs() < 1e-3, "depth {}", s.depth);
    // The edges are found on the moving average (25 points, 12 µm): they
    // lie up to half a window (6 µm) plus a step outside the true edges,
    // where the profile is on the line and adds no area.
    let (l, r) = (0.8e-3 - w / 2.0, 0.8e-3 + w / 2.0);
    assert!(s.edges.0 <= l && s.edges.0 > l - 6.5e-6, "{:?}", s.edges);
    assert!(s.edges.1 >= r && s.edges.1 < r + 6.5e-6, "{:?}", s.edges);
    // Ripple of 2 % of the depth: edges found from the 3 RMS band.
    let (x, z) = groove(d, w, 0.8e-3, 0.008e-6);
    let s = track_section("g", &x, &z, &TrackParams::default()).unwrap();
    assert!((s.area / exact - 1.0).abs() < 5e-3, "{} vs {exact}", s.area);
    // Edges given at the groove's true edges: same area to 0.5 %.
    let given = TrackParams {
        edges: Some((0.76e-3, 0.84e-3)),
        ..TrackParams::default()
    };
    let s = track_section("g", &x, &z, &given).unwrap();
    assert!((s.area / exact - 1.0).abs() < 5e-3, "{} vs {exact}", s.area);
    assert!(!s.edges_found);
}

fn write_groove_csv(dir: &Path, name: &str) {
    let (x, z) = groove(0.4e-6, 80e-6, 0.8e-3, 0.008e-6);
    let mut s = String::from("x (mm),z (um)\n");
    for (x, z) in x.iter().zip(&z) {
        s.push_str(&format!("{:.7},{:.9}\n", x * 1e3, z * 1e6));
    }
    std::fs::write(dir.join(name), s).unwrap();
}

fn read(dir: &Path, name: &str) -> Table {
    Table::read_parquet(&dir.join(format!("{name}.parquet")))
        .unwrap()
        .0
}

#[test]
fn pipeline_gives_volume_and_rate_from_the_manifest() {
    let tmp = tempfile::tempdir().unwrap();
    write_groove_csv(tmp.path(), "disc.csv");
    write_groove_csv(tmp.path(), "recip.csv");
    write_groove_csv(tmp.path(), "bare.csv");
    std::fs::write(
        tmp.path().join("samples.csv"),
        "file,sample_id,track_radius_mm,stroke_length_mm,normal_force_N,sliding_distance_m,laps,hardness_HV\n\
         disc.csv,D1,5,,10,,1000,200\n\
         recip.csv,R1,,8,2,50,,\n\
         bare.csv,B1,,,,,,\n",
    )
    .unwrap();
    std::fs::write(
        tmp.path().join("p.toml"),
        "stages = [\"wear\"]\n[input]\nfiles = [\"*.csv\"]\nsamples = \"samples.csv\"\n\
         [output]\ndir = \"out\"\n",
    )
    .unwrap();
    let out = common::tribo(tmp.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let t = read(&tmp.path().join("out"), "wear");
    tribo::pipeline::registry::schema("wear")
        .unwrap()
        .check(&t)
        .unwrap();
    let ids = t.str("sample_id").unwrap();
    let row = |id: &str| ids.iter().position(|v| v.as_deref() == Some(id)).unwrap();
    let f = |c: &str, id: &str| t.f64(c).unwrap()[row(id)];
    let status = t.str("status").unwrap();
    let area = f("area_m2", "D1").unwrap();
    // Pin-on-disc: L = 2π · 5 mm, s = 1000 laps · L, k = A L / (F_N s)
    // = A / (F_N · 1000), in mm³/(N·m).
    let l = 2.0 * PI * 5e-3;
    assert!((f("track_length_m", "D1").unwrap() / l - 1.0).abs() < 1e-12);
    assert!((f("volume_m3", "D1").unwrap() / (area * l) - 1.0).abs() < 1e-12);
    assert!((f("sliding_distance_m", "D1").unwrap() / (1000.0 * l) - 1.0).abs() < 1e-12);
    let k = f("specific_wear_rate_mm3_per_N_m", "D1").unwrap();
    assert!(
        (k / (area / (10.0 * 1000.0) * 1e9) - 1.0).abs() < 1e-12,
        "{k}"
    );
    assert_eq!(status[row("D1")].as_deref(), Some("ok"));
    // Archard: H = 200 HV = 200 · 9.80665 MPa; K = V H / (F_N s) = k H.
    let h = 200.0 * 9.80665e6;
    assert!((f("hardness_Pa", "D1").unwrap() / h - 1.0).abs() < 1e-12);
    let archard = area * l * h / (10.0 * 1000.0 * l);
    assert!((f("archard_K", "D1").unwrap() / archard - 1.0).abs() < 1e-12);
    assert_eq!(f("hardness_Pa", "R1"), None);
    assert_eq!(f("archard_K", "R1"), None);
    // The groove as built: a reference line of slope 2e-5 (the tilt, plus
    // the ripple's own least-squares slope over the unworn surface: about
    // −2.2e-8 by numpy, for the track ± 0–60 µm left out),
    // 0.4 µm deep (2 % ripple: within 3 %), and its edges found up to half
    // the 12 µm smoothing window plus a step outside the true 80 µm.
    let slope = f("reference_slope", "D1").unwrap();
    assert!((slope - (2e-5 - 2.2e-8)).abs() < 1e-8, "{slope}");
    assert!((f("depth_m", "D1").unwrap() / 0.4e-6 - 1.0).abs() < 0.03);
    let width = f("width_m", "D1").unwrap();
    assert!((80e-6..93.5e-6).contains(&width), "{width}");
    let (left, right) = (
        f("edge_left_m", "D1").unwrap(),
        f("edge_right_m", "D1").unwrap(),
    );
    assert!((width - (right - left)).abs() < 1e-15);
    // Reciprocating: L = stroke = 8 mm, k = A · 8 mm / (2 N · 50 m).
    let k = f("specific_wear_rate_mm3_per_N_m", "R1").unwrap();
    assert!((k / (area * 8e-3 / 100.0 * 1e9) - 1.0).abs() < 1e-12, "{k}");
    // No length: area only, and the status says why.
    assert_eq!(f("volume_m3", "B1"), None);
    assert!(status[row("B1")]
        .as_deref()
        .unwrap()
        .starts_with("missing_lengths"));
    // The area is the groove's (2/3) d w to 0.5 %.
    assert!(
        (area / (2.0 / 3.0 * 0.4e-6 * 80e-6) - 1.0).abs() < 5e-3,
        "{area}"
    );
}

/// The GPL-3 pin-on-disc track profiles (read from `../shared`, never
/// copied): each gives a cross-section and, with the track radius and test
/// of the matching tribometer runs (c1/c2.csv: 30.23 m over 1592.6 laps,
/// so r = 30.23 / (2π · 1592.6) = 3.02 mm; F_N = FrictionForce / mu =
/// 3.0 N), a volume and a wear rate.
#[test]
fn real_track_profiles_give_an_area_and_a_volume() {
    let Some(dir) = common::shared_real("profile_pin_on_disc_track") else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let files: Vec<String> = ["C1.csv", "C2.csv"]
        .iter()
        .map(|f| format!("\"{}\"", dir.join(f).display()))
        .collect();
    std::fs::write(
        tmp.path().join("samples.csv"),
        "file,sample_id,track_radius_mm,normal_force_N,sliding_distance_m\n\
         C1.csv,c1,3.021,3.0,30.23\nC2.csv,c2,3.021,3.0,30.24\n",
    )
    .unwrap();
    std::fs::write(
        tmp.path().join("p.toml"),
        format!(
            "stages = [\"wear\"]\n[input]\nfiles = [{}]\nsamples = \"samples.csv\"\n\
             [output]\ndir = \"out\"\n[wear]\nx_unit = \"mm\"\nz_unit = \"um\"\n",
            files.join(", ")
        ),
    )
    .unwrap();
    let out = common::tribo(tmp.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let t = read(&tmp.path().join("out"), "wear");
    same_without_the_units(tmp.path(), &t);
    assert_eq!(t.height(), 2);
    for (i, r) in t.str("status").unwrap().iter().enumerate() {
        assert_eq!(r.as_deref(), Some("ok"), "row {i}");
    }
    let area = t.f64("area_m2").unwrap();
    let vol = t.f64("volume_m3").unwrap();
    let width = t.f64("width_m").unwrap();
    let depth = t.f64("depth_m").unwrap();
    for i in 0..2 {
        let (a, v) = (area[i].unwrap(), vol[i].unwrap());
        eprintln!(
            "track {i}: A = {a:.4e} m², width {:.1} µm, depth {:.3} µm, V = {v:.4e} m³",
            width[i].unwrap() * 1e6,
            depth[i].unwrap() * 1e6
        );
        // Tracks tens of µm wide and a few tenths of a µm deep (C1: 48 µm
        // by 0.44 µm, A = 1.34e-11 m²; C2: 17.5 µm by 0.20 µm, A =
        // 2.08e-12 m²): A is of order 1e-12 to 1e-10 m².
        assert!(a > 1e-12 && a < 1e-10, "A {a}");
        assert!((v / (a * 2.0 * PI * 3.021e-3) - 1.0).abs() < 1e-12);
    }
}

/// The track profiles' run again without `x_unit`/`z_unit`: read in their
/// layout's units (mm, µm), the same areas, each row `assumed_unit`.
fn same_without_the_units(dir: &Path, with: &Table) {
    let p = std::fs::read_to_string(dir.join("p.toml")).unwrap();
    let bare = p.replace("x_unit = \"mm\"\nz_unit = \"um\"\n", "");
    let bare = bare.replace("dir = \"out\"", "dir = \"bare\"");
    assert_ne!(bare, p);
    std::fs::write(dir.join("bare.toml"), bare).unwrap();
    let out = common::tribo(dir, &["run", "bare.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let t = read(&dir.join("bare"), "wear");
    assert_eq!(t.f64("area_m2").unwrap(), with.f64("area_m2").unwrap());
    for codes in t.status_codes().unwrap() {
        assert_eq!(codes, [tribo::status::Code::AssumedUnit]);
    }
}
