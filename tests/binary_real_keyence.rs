//! Real Keyence (and Sensofar PLUX) files, when `TRIBO_FORMAT_EXAMPLES`
//! holds them (`scripts/format-examples.sh`); skipped, saying so, when not.
//!
//! - `surfalize-test_1.zon`: surfalize's `tests/test_files/test_1.zon`
//!   (GPL-3; read while testing, never committed), checked against what
//!   surfalize's own reader (`surfalize/file/zon.py` at commit f558db5,
//!   with `zstandard` and numpy) gives for it: its grid, step, mask and
//!   heights, and numpy's RMS about the mean over the measured points.
//! - SurfaceTopography's `zon-1.zon` (absent from the snapshot used here),
//!   against what its `test_zon.py` asserts.

use std::path::PathBuf;

use crate::binary_real::{check, examples, Expected};
use crate::common::bad::meta;

/// An example file in the examples folder, or `None` (saying so) when
/// the folder or the file is absent.
fn example(file: &str) -> Option<PathBuf> {
    let path = examples()?.join(file);
    if !path.exists() {
        eprintln!("skipped: {} is absent", path.display());
        return None;
    }
    Some(path)
}

/// surfalize's reading of its `test_1.zon`: 1024 × 769 points of
/// 23.6311288524538 µm; the mask marks 2048 points (rows 767 and 768);
/// Sq over the others 569.69346608 µm; heights (µm) at (row, column).
const SURFALIZE_HEIGHTS_UM: [(usize, usize, f64); 4] = [
    (0, 0, 296.2),
    (0, 1, 296.6),
    (100, 200, 407.8),
    (384, 512, -1795.4),
];

#[test]
fn zon_matches_surfalize_reader() {
    let Some(path) = example("surfalize-test_1.zon") else {
        return;
    };
    let step = 2.36311288524538e-5;
    let ds = check(
        &path,
        &Expected {
            file: "surfalize-test_1.zon",
            format: "zon",
            nx: 1024,
            ny: 769,
            size_m: Some((1024.0 * step, 769.0 * step, 1e-12)),
            sq_m: Some((5.6969346608e-4, 1e-9)),
            n_invalid: Some(2048),
        },
    );
    let g = &ds.grids[0];
    assert_eq!((g.dx, g.dy), (step, step));
    let v = g.values().unwrap();
    for (r, c, um) in SURFALIZE_HEIGHTS_UM {
        let got = v[r * 1024 + c];
        assert!((got - um * 1e-6).abs() < 1e-12, "({r}, {c}): {got:e}");
    }
    assert!(v[767 * 1024].is_nan() && v[768 * 1024 + 1023].is_nan());
    assert!(v[766 * 1024 + 1023].is_finite());
    assert_eq!(meta(&ds, "instrument"), Some("Keyence VR-6100"));
    assert_eq!(
        meta(&ds, "acquisition_date"),
        Some("2025-12-18T12:47:39-06:00")
    );
}

#[test]
fn zon_matches_surfacetopography() {
    let Some(path) = example("zon-1.zon") else {
        return;
    };
    let ds = check(
        &path,
        &Expected {
            file: "zon-1.zon",
            format: "zon",
            nx: 1779,
            ny: 2588,
            size_m: Some((0.004378, 0.006369, 1e-4)),
            sq_m: None,
            n_invalid: None,
        },
    );
    // Their heights[x, y]: (0, 0) and (10, 5).
    let v = ds.grids[0].values().unwrap();
    for (i, want) in [(0, 1.301e-5), (5 * 1779 + 10, 8.47e-5)] {
        assert!((v[i] / want - 1.0).abs() < 1e-6, "{i}: {:e}", v[i]);
    }
    assert_eq!(meta(&ds, "instrument"), Some("Keyence VR-3200"));
    assert_eq!(meta(&ds, "serial"), Some("#3C810114"));
}

/// SurfaceTopography's VK examples (absent from the snapshot used here):
/// grid, physical size (n − 1)·Δ in pm, Sq in pm and date as its
/// `test_vk.py` asserts (rtol 1e-6).
#[test]
fn vk_examples_match_surfacetopography() {
    for (file, (nx, ny), (sx, sy), sq, date) in [
        (
            "vk3-1.vk3",
            (1024, 768),
            (704847000.0, 528463000.0),
            1223148.5774419378,
            "2022-10-28T09:51:59+02:00",
        ),
        (
            "vk4-1.vk4",
            (1024, 768),
            (1396330551.0, 1046906679.0),
            54193042.85097,
            "2022-10-14T09:23:04+02:00",
        ),
        (
            "vk6-1.vk6",
            (2048, 1536),
            (97169043.0, 72864915.0),
            1061663.7395845044,
            "2022-10-23T12:13:10-04:00",
        ),
    ] {
        let Some(path) = example(file) else {
            continue;
        };
        let ds = check(
            &path,
            &Expected {
                file,
                format: "vk",
                nx,
                ny,
                size_m: None,
                sq_m: Some((sq * 1e-12, 1e-6)),
                n_invalid: Some(0),
            },
        );
        let g = &ds.grids[0];
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-6;
        assert!(
            close(g.dx * (nx - 1) as f64, sx * 1e-12),
            "{file}: dx {:e}",
            g.dx
        );
        assert!(
            close(g.dy * (ny - 1) as f64, sy * 1e-12),
            "{file}: dy {:e}",
            g.dy
        );
        assert_eq!(meta(&ds, "acquisition_date"), Some(date), "{file}");
    }
}

/// SurfaceTopography's `plux-1.plux` (absent from the snapshot used here):
/// grid, size, Sq over the measured points and device as its
/// `test_plux.py` asserts (rtol 1e-6); it has points not measured.
#[test]
fn plux_example_matches_surfacetopography() {
    let Some(path) = example("plux-1.plux") else {
        return;
    };
    let ds = check(
        &path,
        &Expected {
            file: "plux-1.plux",
            format: "plux",
            nx: 2583,
            ny: 1023,
            size_m: Some((1666.034951e-6, 659.83498e-6, 1e-6)),
            sq_m: Some((2.15209e-6, 1e-6)),
            n_invalid: None,
        },
    );
    assert!(ds.grids[0].data.as_ref().unwrap().n_invalid > 0);
    assert_eq!(meta(&ds, "instrument"), Some("Sensofar S neox"));
}
