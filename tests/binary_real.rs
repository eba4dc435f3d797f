//! Real instrument files of other labs: SurfaceTopography's example files
//! (MIT; `scripts/format-examples.sh` copies them into a folder named by
//! `TRIBO_FORMAT_EXAMPLES`). Each is checked against what
//! SurfaceTopography's own tests assert for it (`test/IO/test_*.py`: grid
//! size, physical size nx·Δx, rms height about the mean over the measured
//! points) to their tolerance. The tests skip, saying so, when the folder
//! or a file is absent (CI has no network); the small files are also
//! fixtures (`fixtures/surface/`), read always.

use std::path::{Path, PathBuf};

use crate::common::writers::sq_finite;
use tribo::ingest::{read_path, IngestOptions};

/// The examples folder, if given and present.
pub fn examples() -> Option<PathBuf> {
    let dir = std::env::var_os("TRIBO_FORMAT_EXAMPLES").map(PathBuf::from);
    match dir.filter(|d| d.is_dir()) {
        Some(d) => Some(d),
        None => {
            eprintln!(
                "skipped: TRIBO_FORMAT_EXAMPLES is not a folder of example files \
                 (scripts/format-examples.sh makes one)"
            );
            None
        }
    }
}

/// What SurfaceTopography's tests assert about one file.
pub struct Expected {
    pub file: &'static str,
    pub format: &'static str,
    pub nx: usize,
    pub ny: usize,
    /// nx·Δx and ny·Δy (m), with the relative tolerance of their test.
    pub size_m: Option<(f64, f64, f64)>,
    /// Sq about the mean over measured points (m), relative tolerance.
    pub sq_m: Option<(f64, f64)>,
    /// Points not measured, when known.
    pub n_invalid: Option<usize>,
}

/// Reads `path` and checks it against `e`; returns the dataset.
pub fn check(path: &Path, e: &Expected) -> tribo::ingest::Dataset {
    let ds = read_path(path, &IngestOptions::default()).unwrap_or_else(|err| panic!("{err}"));
    assert_eq!(ds.format, e.format, "{}", e.file);
    let g = ds
        .grids
        .iter()
        .find(|g| g.data.is_some())
        .expect("a decoded grid");
    assert_eq!((g.nx, g.ny), (e.nx, e.ny), "{}", e.file);
    let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.abs();
    if let Some((sx, sy, tol)) = e.size_m {
        assert!(
            close(g.width(), sx, tol),
            "{}: width {} vs {sx}",
            e.file,
            g.width()
        );
        if g.ny > 1 {
            assert!(
                close(g.height_extent(), sy, tol),
                "{}: height {} vs {sy}",
                e.file,
                g.height_extent()
            );
        }
    }
    if let Some(n) = e.n_invalid {
        assert_eq!(g.data.as_ref().unwrap().n_invalid, n, "{}", e.file);
    }
    if let Some((sq, tol)) = e.sq_m {
        let (got, _) = sq_finite(g.values().unwrap());
        assert!(close(got, sq, tol), "{}: Sq {got:e} vs {sq:e}", e.file);
    }
    ds
}

/// Runs `check` on each file present in the examples folder.
pub fn check_all(list: &[Expected]) -> Vec<tribo::ingest::Dataset> {
    let Some(dir) = examples() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for e in list {
        let p = dir.join(e.file);
        match p.is_file() {
            true => out.push(check(&p, e)),
            false => eprintln!("skipped: {} not present", p.display()),
        }
    }
    out
}

#[test]
fn x3p_examples_match_surfacetopography() {
    check_all(&[Expected {
        file: "x3p-2.x3p",
        format: "x3p",
        nx: 650,
        ny: 650,
        size_m: Some((8.29767313942749e-05, 0.0002044783737930349, 1e-6)),
        sq_m: Some((7.728033273597876e-08, 1e-6)),
        n_invalid: Some(0),
    }]);
}

/// SurfaceTopography does not mask SUR's points not measured: its rms of
/// sur-3 counts them as heights (zmin − 2)·Δz. Filled so, ours gives its
/// value; over the measured points only, the value read independently
/// from the raw integers (Python `struct`, zmin − 2 excluded).
#[test]
fn sur_examples_match_surfacetopography() {
    let ds = check_all(&[
        Expected {
            file: "sur-3.sur",
            format: "sur",
            nx: 512,
            ny: 512,
            size_m: Some((0.151319552, 0.151319552, 1e-6)),
            sq_m: Some((0.0011131994265859665, 1e-9)),
            n_invalid: Some(233_009),
        },
        Expected {
            file: "sur-2.sur",
            format: "sur",
            nx: 563,
            ny: 484,
            size_m: None,
            sq_m: Some((1.751788124358975e-08, 1e-9)),
            n_invalid: Some(117),
        },
    ]);
    let Some(sur3) = ds.first() else { return };
    let get = |k: &str| {
        sur3.preamble
            .iter()
            .find(|m| m.key == k)
            .map(|m| m.value.clone())
            .unwrap()
    };
    let zmin: f64 = get("zmin").parse().unwrap();
    let dz_m: f64 = get("height_scale")
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let offset_m: f64 = get("z offset (m)").parse().unwrap();
    let fill = (zmin - 2.0) * dz_m + offset_m;
    let filled: Vec<f64> = sur3.grids[0]
        .values()
        .unwrap()
        .iter()
        .map(|v| if v.is_nan() { fill } else { *v })
        .collect();
    let (sq, _) = sq_finite(&filled);
    let want = 0.0019200491394179297;
    assert!((sq - want).abs() <= 1e-6 * want, "{sq:e} vs {want:e}");
}

#[test]
fn metropro_and_plu_examples_match_surfacetopography() {
    check_all(&[
        Expected {
            file: "metropro-1.dat",
            format: "metropro",
            nx: 640,
            ny: 480,
            size_m: Some((0.0007028812979115173, 0.000527160973433638, 1e-6)),
            sq_m: Some((7.528822204734589e-08, 1e-6)),
            n_invalid: None,
        },
        Expected {
            file: "plu-1.plu",
            format: "plu",
            nx: 768,
            ny: 576,
            size_m: Some((1274.880066e-6, 956.160049e-6, 1e-6)),
            sq_m: Some((2.834391e-6, 1e-6)),
            n_invalid: Some(0),
        },
    ]);
}

/// opd-1: SurfaceTopography asserts the size (pytest.approx, 1e-6); its Sq
/// is computed here independently from the raw floats (Python `struct`,
/// values ≥ 1e38 excluded, λ = 577.295 nm, Mult absent = 1).
#[test]
fn opd_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "opd-1.opd",
        format: "opd",
        nx: 640,
        ny: 480,
        size_m: Some((0.125909140e-3, 0.094431855e-3, 1e-6)),
        sq_m: Some((8.356451162721002e-09, 1e-9)),
        n_invalid: Some(116),
    }]);
}

/// opdx-3, a Dektak profile: the heights equal the instrument's own text
/// export of it (SurfaceTopography's test, rtol 1e-7), and so do the
/// positions (Δx = Extent / (n − 1)).
#[test]
fn opdx_profile_matches_its_text_export() {
    let Some(dir) = examples() else { return };
    let (bin, txt) = (dir.join("opdx-3.opdx"), dir.join("opdx-3.txt"));
    if !bin.is_file() || !txt.is_file() {
        eprintln!("skipped: opdx-3 not present");
        return;
    }
    let ds = read_path(&bin, &IngestOptions::default()).unwrap();
    let g = &ds.grids[0];
    let rows: Vec<(f64, f64)> = std::fs::read_to_string(&txt)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let mut f = l.split_whitespace().map(|v| v.parse::<f64>().unwrap());
            Some((f.next()?, f.next()?))
        })
        .collect();
    assert_eq!((g.nx, g.ny, rows.len()), (3001, 1, 3001));
    for (k, (z, (x, zt))) in g.values().unwrap().iter().zip(&rows).enumerate() {
        assert!(
            (z - zt).abs() <= 1e-7 * zt.abs(),
            "point {k}: {z:e} vs {zt:e}"
        );
        assert!(
            (k as f64 * g.dx - x).abs() <= 1e-7 * x.abs() + 1e-15,
            "x {k}"
        );
    }
}

/// gwy-1/gwy-2 are not in every snapshot of SurfaceTopography (skipped,
/// saying so, when absent).
#[test]
fn gwy_examples_match_surfacetopography() {
    let ds = check_all(&[
        Expected {
            file: "gwy-1.gwy",
            format: "gwy",
            nx: 640,
            ny: 480,
            size_m: Some((0.0001259091403335333, 9.443185525014996e-05, 1e-6)),
            sq_m: Some((8.355506e-09, 1e-6)),
            n_invalid: None,
        },
        Expected {
            file: "gwy-2.gwy",
            format: "gwy",
            nx: 1000,
            ny: 1000,
            size_m: None,
            sq_m: None,
            n_invalid: None,
        },
    ]);
    if let Some(g2) = ds.iter().find(|d| d.grids[0].nx == 1000) {
        let g = g2.grids.iter().find(|g| g.data.is_some()).unwrap();
        assert!(
            g.data.as_ref().unwrap().n_invalid > 0,
            "gwy-2 has undefined data"
        );
    }
}

/// SurfaceTopography's tests assert di-5's Sq (5.831926 nm, default rtol
/// 1e-7 of numpy's assert_allclose), di-1's date and instrument, and that
/// di_corrupted.di is refused; the other files are read whole (every
/// channel decodes).
#[test]
fn nanoscope_examples_match_surfacetopography() {
    let ds = check_all(&[
        Expected {
            file: "di-5.di",
            format: "nanoscope",
            nx: 512,
            ny: 512,
            size_m: Some((1e-6, 1e-6, 1e-12)),
            sq_m: Some((5.831926e-9, 1e-7)),
            n_invalid: Some(0),
        },
        Expected {
            file: "di-1.di",
            format: "nanoscope",
            nx: 512,
            ny: 512,
            size_m: Some((500e-9, 500e-9, 1e-12)),
            sq_m: None,
            n_invalid: Some(0),
        },
    ]);
    if let Some(di1) = ds.get(1) {
        let get = |k: &str| {
            di1.preamble
                .iter()
                .find(|m| m.key == k)
                .map(|m| m.value.as_str())
        };
        assert_eq!(get("acquisition_date"), Some("2016-01-12T09:57:48"));
        assert_eq!(get("instrument"), Some("Bruker Nanoscope Dimension V"));
    }
    let Some(dir) = examples() else { return };
    for f in [
        "di-1.di", "di-2.di", "di-3.di", "di-4.di", "di-5.di", "di-6.di",
    ] {
        let p = dir.join(f);
        if !p.is_file() {
            continue;
        }
        let n = read_path(&p, &IngestOptions::default())
            .unwrap()
            .grids
            .len();
        for g in 0..n {
            let o = IngestOptions {
                channel: Some(
                    read_path(&p, &IngestOptions::default()).unwrap().grids[g]
                        .name
                        .clone(),
                ),
                ..Default::default()
            };
            let ds = read_path(&p, &o).unwrap_or_else(|e| panic!("{f} channel {g}: {e}"));
            assert!(ds.grids[g].data.is_some());
        }
    }
    let bad = dir.join("di_corrupted.di");
    if bad.is_file() {
        let e = read_path(&bad, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("di_corrupted.di: byte "), "{e}");
    }
}

/// tmd-1: SurfaceTopography asserts 300 × 300 and 18.9566 µm sides (rtol
/// 1e-3); Sq computed independently from the raw f32 with numpy.
#[test]
fn tmd_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "tmd-1.tmd",
        format: "tmd",
        nx: 300,
        ny: 300,
        size_m: Some((18.9566e-6, 18.9566e-6, 1e-3)),
        sq_m: Some((0.07434134067352181e-6, 1e-9)),
        n_invalid: Some(0),
    }]);
}

/// al3d-1: SurfaceTopography's test asserts 200 × 296, the sides and the
/// rms height over the area (rtol 1e-6 each).
#[test]
fn al3d_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "al3d-1.al3d",
        format: "al3d",
        nx: 200,
        ny: 296,
        size_m: Some((8.76054e-05, 0.000129655992, 1e-6)),
        sq_m: Some((7.688266102603082e-06, 1e-6)),
        n_invalid: None,
    }]);
}

/// SurfaceTopography's `test_datx.py` (its sizes and rms in nm, rtol
/// 1e-6); both maps are square, so its (x, y) order of the dataset's axes
/// and ours (rows are y) give the same numbers.
#[test]
fn datx_examples_match_surfacetopography() {
    check_all(&[
        Expected {
            file: "datx-1.datx",
            format: "datx",
            nx: 1000,
            ny: 1000,
            size_m: Some((6306280.26666992e-9, 6306280.26666992e-9, 1e-6)),
            sq_m: Some((6304.986277e-9, 1e-6)),
            n_invalid: None,
        },
        Expected {
            file: "datx-2.datx",
            format: "datx",
            nx: 1000,
            ny: 1000,
            size_m: Some((173108.716695e-9, 173108.716695e-9, 1e-6)),
            sq_m: Some((1.905869e-9, 1e-6)),
            n_invalid: None,
        },
    ]);
}
