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
