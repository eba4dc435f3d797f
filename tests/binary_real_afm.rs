//! Real AFM and profiler files of other labs for the IBW, NID, MI, BCR,
//! WSxM and FRT readers: SurfaceTopography's example files (MIT; copied by
//! `scripts/format-examples.sh` into `TRIBO_FORMAT_EXAMPLES`, skipped,
//! saying so, without them). Each is checked against the values
//! SurfaceTopography's own tests assert (`test/IO/test_*.py`) to their
//! tolerance; where they assert none (Sq of the IBW, MI and FRT files),
//! against SurfaceTopography 1.27.1's `read_topography(f).rms_height_from_area()`
//! run on the same file, and point by point against its `heights()`
//! (first point, one step along x, one along y: the same orientation).

use std::path::Path;

use crate::binary_real::{check_all, examples, Expected};
use tribo::ingest::{read_path, IngestOptions};

/// The grid of channel `name` of `file` in the examples folder.
fn channel(dir: &Path, file: &str, name: &str) -> tribo::ingest::grid::Grid {
    let o = IngestOptions {
        channel: Some(name.into()),
        ..Default::default()
    };
    let ds = read_path(&dir.join(file), &o).unwrap_or_else(|e| panic!("{file} {name}: {e}"));
    ds.grids.into_iter().find(|g| g.name == name).unwrap()
}

/// Heights at (0, 0), (1, 0) and (0, 1) against SurfaceTopography's
/// `heights()[i, j]` (x index i, y index j), and Sq against `sq`.
fn points(g: &tribo::ingest::grid::Grid, want: [f64; 3], sq: f64, tol: f64, what: &str) {
    let v = g.values().unwrap();
    for (got, want) in [v[0], v[1], v[g.nx]].into_iter().zip(want) {
        assert!(
            (got - want).abs() <= tol * want.abs(),
            "{what}: {got:e} vs {want:e}"
        );
    }
    let (s, _) = crate::common::writers::sq_finite(v);
    assert!((s - sq).abs() <= tol * sq, "{what}: Sq {s:e} vs {sq:e}");
}

fn present(file: &str) -> Option<std::path::PathBuf> {
    let dir = examples()?;
    match dir.join(file).is_file() {
        true => Some(dir),
        false => {
            eprintln!("skipped: {file} not present");
            None
        }
    }
}

/// spot_1-1000nm.ibw, an Asylum Cypher KPFM scan of 8 layers: their test
/// asserts 20 µm sides (abs 0.01) for every channel; the sides are
/// 256 · 7.843137e-8 m. Height by default; every layer by name.
#[test]
fn ibw_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "spot_1-1000nm.ibw",
        format: "ibw",
        nx: 256,
        ny: 256,
        size_m: Some((2.007843137254902e-05, 2.007843137254902e-05, 1e-12)),
        sq_m: Some((8.945481491256412e-08, 1e-9)),
        n_invalid: Some(0),
    }]);
    let Some(dir) = present("spot_1-1000nm.ibw") else {
        return;
    };
    let g = channel(&dir, "spot_1-1000nm.ibw", "HeightRetrace");
    let want = [
        -3.0985046350906487e-07,
        -3.111690318746696e-07,
        -3.107382724465424e-07,
    ];
    points(&g, want, 1.1028457213263469e-07, 1e-9, "HeightRetrace");
    let g = channel(&dir, "spot_1-1000nm.ibw", "PhaseTrace");
    assert!(
        !g.height && g.unit == "m",
        "one unit for the wave, as written"
    );
    points(
        &g,
        [103.14872741699219, 101.37335968017578, 104.15983581542969],
        1.639972647724918,
        1e-9,
        "PhaseTrace",
    );
}

#[test]
fn ibw_without_labels_names_its_layer_as_surfacetopography() {
    let p = crate::common::root().join("fixtures/surface/10x10-one_channel_without_name.ibw");
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    assert_eq!(ds.format, "ibw");
    let g = &ds.grids[0];
    assert_eq!(
        (ds.grids.len(), g.name.as_str(), g.nx, g.ny),
        (1, "no name (1)", 10, 10)
    );
    // No unit in the file: values as written, spacing to be given.
    assert!(g.unit.is_empty() && g.dx.is_nan());
    let (sq, n) = crate::common::writers::sq_finite(g.values().unwrap());
    assert_eq!(n, 100);
    assert!((sq - 0.480049350063276).abs() < 1e-12, "{sq}");
}

/// nid-1.nid: their test asserts 256 × 256, 20 µm sides and the Sq of the
/// four length channels (rtol 1e-6).
#[test]
fn nid_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "nid-1.nid",
        format: "nid",
        nx: 256,
        ny: 256,
        size_m: Some((2e-5, 2e-5, 1e-6)),
        sq_m: Some((2.395896706764167e-07, 1e-6)),
        n_invalid: Some(0),
    }]);
    let Some(dir) = present("nid-1.nid") else {
        return;
    };
    let ds = read_path(&dir.join("nid-1.nid"), &IngestOptions::default()).unwrap();
    assert_eq!(ds.grids.len(), 8, "every channel listed, lengths or not");
    let g = channel(&dir, "nid-1.nid", "Scan forward (Z-Axis)");
    let want = [
        -9.253918035998941e-07,
        -9.266565515175462e-07,
        -9.262948113754393e-07,
    ];
    points(&g, want, 2.395896706764167e-07, 1e-6, "forward Z");
    for (name, sq) in [
        ("Scan forward (Z-AxisSensor)", 3.026701737129839e-07),
        ("Scan backward (Z-Axis)", 2.3941867686171115e-07),
        ("Scan backward (Z-AxisSensor)", 3.029781629305204e-07),
    ] {
        let g = channel(&dir, "nid-1.nid", name);
        let (s, _) = crate::common::writers::sq_finite(g.values().unwrap());
        assert!((s - sq).abs() <= 1e-6 * sq, "{name}: {s:e} vs {sq:e}");
    }
    let date = ds.preamble.iter().find(|m| m.key == "acquisition_date");
    assert_eq!(date.map(|m| m.value.as_str()), Some("2022-11-03T11:46:25"));
}

/// mi-1.mi: their test asserts 4 channels, 256 × 256, 20 µm sides, the
/// unit µm and heights[0, 0] = −0.4986900329589844 µm (rtol 1e-6).
#[test]
fn mi_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "mi-1.mi",
        format: "mi",
        nx: 256,
        ny: 256,
        size_m: Some((2e-5, 2e-5, 1e-6)),
        sq_m: Some((3.3215426493512654e-08, 1e-9)),
        n_invalid: Some(0),
    }]);
    let Some(dir) = present("mi-1.mi") else {
        return;
    };
    let ds = read_path(&dir.join("mi-1.mi"), &IngestOptions::default()).unwrap();
    let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "Topography Trace",
            "Deflection Trace",
            "Friction Trace",
            "Friction Retrace"
        ]
    );
    let want = [
        -0.4986900329589844e-6,
        -0.4986900329589844e-6,
        -0.4978042602539063e-6,
    ];
    points(
        &ds.grids[0],
        want,
        3.3215426493512654e-08,
        1e-6,
        "Topography",
    );
}

/// bcrf-1.bcrf (UTF-16 header): their test asserts 960 × 600, the sides
/// 1777404 × 1110878 nm and Sq 24.560207201442292 nm (rtol 1e-6).
#[test]
fn bcr_example_matches_surfacetopography() {
    check_all(&[Expected {
        file: "bcrf-1.bcrf",
        format: "bcr",
        nx: 960,
        ny: 600,
        size_m: Some((1777404e-9, 1110878e-9, 1e-6)),
        sq_m: Some((2.456020720144229e-8, 1e-6)),
        n_invalid: Some(0),
    }]);
}

/// stp-1 (double) and top-1 (16-bit): their tests assert 256 × 256,
/// 600 nm sides and Sq 1.654156 and 3.153099 nm (rtol 1e-6).
#[test]
fn wsxm_examples_match_surfacetopography() {
    check_all(&[
        Expected {
            file: "stp-1.stp",
            format: "wsxm",
            nx: 256,
            ny: 256,
            size_m: Some((600e-9, 600e-9, 1e-6)),
            sq_m: Some((1.654156e-9, 1e-6)),
            n_invalid: Some(0),
        },
        Expected {
            file: "top-1.top",
            format: "wsxm",
            nx: 256,
            ny: 256,
            size_m: Some((600e-9, 600e-9, 1e-6)),
            sq_m: Some((3.153099e-9, 1e-6)),
            n_invalid: Some(0),
        },
    ]);
    let Some(dir) = present("top-1.top") else {
        return;
    };
    // Oriented as the snapshot's reader does (`reshape(ny, nx).T`: row 0
    // first), values from numpy on the raw counts × 18.8851 nm / (6900 −
    // 5927); SurfaceTopography 1.27.1 turns the map by 180°.
    let g = channel(&dir, "top-1.top", "Topography");
    let want = [
        130.9729237410072e-9,
        130.83705971223023e-9,
        131.22524265159302e-9,
    ];
    points(&g, want, 3.1530985989941165e-9, 1e-9, "top-1");
}

/// frt-1, frt-2: their tests assert the sizes (rtol 1e-6) and undefined
/// data. Their Sq (2.047476e-05, 1.853335e-05 m) is not what the file's
/// counts give: SurfaceTopography 1.27.1 reading the same files, and
/// numpy on the raw u16 counts (≠ 1) × 0x6c's factor, both give the Sq
/// below, with 76 456 and 12 314 points not measured.
#[test]
fn frt_examples_match_surfacetopography() {
    check_all(&[
        Expected {
            file: "frt-1.frt",
            format: "frt",
            nx: 500,
            ny: 500,
            size_m: Some((0.012, 0.012, 1e-6)),
            sq_m: Some((4.915785774480653e-06, 1e-9)),
            n_invalid: Some(76_456),
        },
        Expected {
            file: "frt-2.frt",
            format: "frt",
            nx: 150,
            ny: 300,
            size_m: Some((0.03, 0.06, 1e-6)),
            sq_m: Some((8.826763181113768e-06, 1e-9)),
            n_invalid: Some(12_314),
        },
    ]);
}
