//! Optical profiler formats (TrueMap TMD): variants written by the test
//! writers (`common::writers_optical`) and bad files.

use std::path::Path;

use crate::common::bad::{altered_names, assert_values, cuts_name_file_and_offset, meta};
use crate::common::writers::Surface;
use crate::common::writers_optical::tmd;
use tribo::ingest::{read_bytes, IngestOptions};

#[test]
fn tmd_comments_offsets_and_not_measured_points_read_back() {
    let mut s = Surface::waves(30, 14, 0.25e-6, 0.5e-6, 2e-7, 5e-8);
    s.z[17] = f64::NAN;
    for (comment, fixed) in [
        ("Created by TrueMap v6", true),
        ("x", true),
        ("a longer comment of the lab, 40 chars", false),
        ("", false),
    ] {
        let b = tmd(&s, comment, fixed, (1.5, -2.0));
        let ds = read_bytes(Path::new("t.tmd"), &b, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "tmd");
        let g = &ds.grids[0];
        assert_eq!((g.nx, g.ny), (30, 14), "{comment}");
        assert!((g.dx / 0.25e-6 - 1.0).abs() < 1e-6 && (g.dy / 0.5e-6 - 1.0).abs() < 1e-6);
        assert!((g.x0 - 1.5e-6).abs() < 1e-15 && (g.y0 + 2e-6).abs() < 1e-15);
        // f32 µm: 2^-24 relative of values up to 0.25 µm.
        assert_values(g.values().unwrap(), &s.z, 2.5e-7 * 1e-7, comment);
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 1);
        assert_eq!(meta(&ds, "comment"), Some(comment));
    }
}

#[test]
fn tmd_bad_files_name_the_field() {
    let s = Surface::waves(6, 4, 1e-6, 1e-6, 1e-7, 0.0);
    let good = tmd(&s, "Created by TrueMap v6", true, (0.0, 0.0));
    cuts_name_file_and_offset("t.tmd", "tmd", &good, 3);
    // Zero points along x; a negative length along y.
    altered_names("t.tmd", "tmd", &good, 56, &[0, 0, 0, 0], "TMD header");
    altered_names(
        "t.tmd",
        "tmd",
        &good,
        68,
        &(-1f32).to_le_bytes(),
        "spacing along y",
    );
}

#[test]
fn al3d_depth_padding_invalid_points_and_texture_read_back() {
    use crate::common::writers_optical::al3d;
    // 13 columns: rows of 52 bytes padded to 56, texture rows to 16.
    let s = Surface::waves(13, 7, 4.38e-7, 5e-7, 3e-6, 1e-6);
    let invalid = [0, 20, 90];
    for reverse in [false, true] {
        let b = al3d(&s, &invalid, 3, reverse);
        let ds = read_bytes(Path::new("t.al3d"), &b, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "al3d");
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["Height", "Texture 0", "Texture 1", "Texture 2"]);
        let g = &ds.grids[0];
        assert_eq!(
            (g.nx, g.ny, g.dx, g.dy, g.height),
            (13, 7, 4.38e-7, 5e-7, true)
        );
        let mut want = s.z.clone();
        for &i in &invalid {
            want[i] = f64::NAN;
        }
        assert_values(g.values().unwrap(), &want, 1e-6 * 4e-6, "depth");
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 3);
        assert_eq!(
            meta(&ds, "instrument"),
            Some("Alicona Imaging MeasureSuite 5.3.6")
        );
        let o = IngestOptions {
            channel: Some("Texture 2".into()),
            ..Default::default()
        };
        let ds = read_bytes(Path::new("t.al3d"), &b, &o).unwrap();
        let want: Vec<f64> = (0..91).map(|i| (3 * i % 256) as f64).collect();
        assert_values(ds.grids[3].values().unwrap(), &want, 0.0, "texture");
    }
}

#[test]
fn al3d_bad_files_name_the_field() {
    use crate::common::writers_optical::al3d;
    let s = Surface::waves(6, 4, 1e-6, 1e-6, 1e-7, 0.0);
    let good = al3d(&s, &[], 0, false);
    cuts_name_file_and_offset("t.al3d", "al3d", &good, 5);
    // Version's key, TagCount's value, Cols' value, a tag's CR LF.
    altered_names("t.al3d", "al3d", &good, 17, b"Verzion", "Version expected");
    altered_names("t.al3d", "al3d", &good, 17 + 52 + 20, b"x", "TagCount 'x");
    altered_names("t.al3d", "al3d", &good, 17 + 104 + 20, b"y", "Cols 'y");
    altered_names("t.al3d", "al3d", &good, 17 + 156 + 50, b"\n\n", "CR LF");
}
