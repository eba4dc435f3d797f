//! Zygo DATX (HDF5): the real file of monolithic (MIT,
//! `fixtures/surface/zygo_test.datx`) against values computed from it with
//! h5py and numpy, the variants `scripts/write-datx-variants.py` writes
//! with h5py (`fixtures/surface/datx/`) against the heights it stored,
//! and bad files.

use std::path::Path;

use crate::common::bad::{altered_names, assert_values, cuts_name_file_and_offset, meta};
use crate::common::root;
use crate::common::writers::sq_finite;
use tribo::ingest::{read_bytes, read_path, Dataset, IngestOptions};

fn fixture(name: &str) -> Dataset {
    let p = root().join("fixtures/surface").join(name);
    read_path(&p, &IngestOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn bytes(name: &str) -> Vec<u8> {
    std::fs::read(root().join("fixtures/surface").join(name)).unwrap()
}

fn close(a: f64, b: f64, rtol: f64) -> bool {
    (a - b).abs() <= rtol * b.abs()
}

/// The real file. Every expected number comes from h5py 3.16 and numpy:
///
/// ```python
/// d = h5py.File('zygo_test.datx')['Data/Surface/{1CE20D93-8A91-4847-9CEF-B83B2F42271E}']
/// a = d.attrs; z = d[()]                       # shape (259, 33): rows are y
/// s = a['Wavelength'][0] * a['Interferometric Scale Factor'][0] * a['Obliquity Factor'][0]
/// h = np.where(z == a['No Data'][0], np.nan, z * s); m = h[np.isfinite(h)]
/// np.isnan(h).sum()                            # 776
/// np.sqrt(np.mean((m - m.mean()) ** 2))        # 8.08176526396592e-08
/// a['X Converter'][0][2][1]                    # 0.0010000000474974513 (and Y)
/// h[0, 0], h[100, 10], h[258, 32], h[50, 5]    # below; h[0, 30] is NaN
/// ```
#[test]
fn real_file_matches_h5py() {
    let ds = fixture("zygo_test.datx");
    assert_eq!(ds.format, "datx");
    let g = &ds.grids[0];
    assert_eq!(
        (g.name.as_str(), g.unit.as_str(), g.height),
        ("Surface", "m", true)
    );
    assert_eq!((g.nx, g.ny), (33, 259));
    assert_eq!((g.dx, g.dy), (0.0010000000474974513, 0.0010000000474974513));
    let data = g.data.as_ref().unwrap();
    assert_eq!(data.n_invalid, 776);
    let v = &data.values;
    let (sq, n) = sq_finite(v);
    assert_eq!(n, 33 * 259 - 776);
    assert!(close(sq, 8.08176526396592e-08, 1e-12), "Sq {sq:e}");
    for ((r, c), want) in [
        ((0, 0), 1.2533055123082136e-07),
        ((100, 10), 1.4161572464506053e-07),
        ((258, 32), 3.065554266607459e-07),
        ((50, 5), -2.398703625788183e-09),
    ] {
        let got = v[r * 33 + c];
        assert!(close(got, want, 1e-14), "({r}, {c}): {got:e} vs {want:e}");
    }
    assert!(v[30].is_nan());
    assert_eq!(meta(&ds, "instrument"), Some("Zygo GPI (serial 651365)"));
    assert_eq!(meta(&ds, "software"), Some("MetroPro 8.3.3"));
    assert_eq!(meta(&ds, "objective"), Some("Sm Aperture"));
    assert_eq!(meta(&ds, "height_unit"), Some("Fringes"));
    // Its Time Stamp holds 719529 (not a time of acquisition): no date.
    assert_eq!(meta(&ds, "acquisition_date"), None);
}

/// The value the variants script stores at (r, c), in the file's unit.
fn stored(r: usize, c: usize) -> f64 {
    ((7 * r + 3 * c) % 23) as f64 - 11.0 + 0.25
}

/// Heights in metres of a 12 × 9 variant: `stored` × `scale`, NaN at `bad`.
fn expected(scale: f64, bad: &[(usize, usize)]) -> Vec<f64> {
    let mut z: Vec<f64> = (0..12)
        .flat_map(|r| (0..9).map(move |c| stored(r, c) * scale))
        .collect();
    for &(r, c) in bad {
        z[r * 9 + c] = f64::NAN;
    }
    z
}

/// A variant: file, metres per stored unit, (Δx, Δy), points not
/// measured, height unit.
type Variant = (
    &'static str,
    f64,
    (f64, f64),
    Vec<(usize, usize)>,
    &'static str,
);

#[test]
fn h5py_variants_read_back() {
    let row3: Vec<(usize, usize)> = (0..9).map(|c| (3, c)).chain([(5, 2), (7, 8)]).collect();
    let fringe = 632.8e-9 * 0.5 * 1.25;
    let cases: [Variant; 5] = [
        (
            "chunked-gzip-nm.datx",
            1e-9,
            (2e-6, 2e-6),
            vec![],
            "NanoMeters",
        ),
        ("latest-um.datx", 1e-6, (5e-7, 5e-7), vec![], "MicroMeters"),
        (
            "latest-chunked-um.datx",
            1e-6,
            (5e-7, 5e-7),
            vec![],
            "MicroMeters",
        ),
        (
            "nodata-nonsquare-um.datx",
            1e-6,
            (1e-6, 3e-6),
            row3,
            "MicroMeters",
        ),
        (
            "fringes-userblock.datx",
            fringe,
            (1e-3, 1e-3),
            vec![(0, 0)],
            "Fringes",
        ),
    ];
    for (name, scale, (dx, dy), bad, unit) in cases {
        let ds = fixture(&format!("datx/{name}"));
        let g = &ds.grids[0];
        assert_eq!(
            (ds.format, g.nx, g.ny, g.height),
            ("datx", 9, 12, true),
            "{name}"
        );
        assert!(close(g.dx, dx, 1e-15) && close(g.dy, dy, 1e-15), "{name}");
        let want = expected(scale, &bad);
        assert_values(g.values().unwrap(), &want, 1e-15 * scale * 12.0, name);
        assert_eq!(g.data.as_ref().unwrap().n_invalid, bad.len(), "{name}");
        assert_eq!(meta(&ds, "height_unit"), Some(unit), "{name}");
        assert_eq!(
            meta(&ds, "instrument"),
            Some("Zygo NewView 9000 (serial 12345)")
        );
        assert_eq!(meta(&ds, "acquisition_date"), Some("2023-11-14T22:13:20Z"));
        assert_eq!(meta(&ds, "objective"), Some("50x Mirau"));
        assert_eq!(meta(&ds, "software"), Some("Mx 7.3.0"));
    }
}

/// The intensity image is a second channel, selectable, not heights.
#[test]
fn intensity_channel_and_unknown_channel() {
    let b = bytes("datx/chunked-gzip-nm.datx");
    let o = IngestOptions {
        channel: Some("intensity".into()),
        ..Default::default()
    };
    let ds = read_bytes(Path::new("t.datx"), &b, &o).unwrap();
    let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["Surface", "Intensity"]);
    let g = &ds.grids[1];
    assert!(!g.height);
    let want: Vec<f64> = (0..108).map(|i| (i * 10) as f64).collect();
    assert_values(g.values().unwrap(), &want, 0.0, "intensity");
    assert!(ds.grids[0].values().is_none());
    let o = IngestOptions {
        channel: Some("Phase".into()),
        ..Default::default()
    };
    let e = read_bytes(Path::new("t.datx"), &b, &o)
        .unwrap_err()
        .to_string();
    assert!(e.contains("'Surface', 'Intensity'"), "{e}");
}

#[test]
fn bad_files_name_the_structure_and_offset() {
    for name in ["zygo_test.datx", "datx/latest-chunked-um.datx"] {
        let good = bytes(name);
        cuts_name_file_and_offset("t.datx", "datx", &good, good.len() / 40);
        // The superblock's version (byte 8) as 7.
        altered_names(
            "t.datx",
            "datx",
            &good,
            8,
            &[7],
            "HDF5 superblock (version)",
        );
        // The signature broken: no superblock anywhere.
        altered_names("t.datx", "datx", &good, 1, b"X", "no HDF5 signature");
    }
    // Cuts whose end-of-file address is rewritten to match reach the
    // structures past the superblock: each is an error, or (a cut in what
    // the map does not need) the same map.
    let real = bytes("zygo_test.datx");
    let bits = |d: &Dataset| -> Vec<u64> {
        let v = d.grids[0].values().unwrap_or(&[]);
        v.iter().map(|x| x.to_bits()).collect()
    };
    let whole = bits(&fixture("zygo_test.datx"));
    for cut in (48..real.len()).step_by(997) {
        let mut b = real[..cut].to_vec();
        b[40..48].copy_from_slice(&(cut as u64).to_le_bytes());
        match crate::common::bad::read_forced("t.datx", "datx", &b) {
            Err(e) => assert!(e.to_string().starts_with("t.datx: byte "), "{e}"),
            Ok(d) => assert!(bits(&d) == whole, "cut at {cut}: another map"),
        }
    }
    // Not forced, a damaged DATX file (its bytes name a Surface) is still
    // taken as DATX, and its error says where it breaks.
    let e = read_bytes(
        Path::new("t.datx"),
        &real[..100_000],
        &IngestOptions::default(),
    )
    .map(|_| ())
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("t.datx: byte 40: HDF5 superblock (end of file address)"),
        "{e}"
    );
    // Version-1 object header of the real file's root group (byte 96).
    altered_names("t.datx", "datx", &real, 96, &[9], "HDF5 object header");
    // A byte of a version-2 object header: its checksum no longer holds.
    let latest = bytes("datx/latest-um.datx");
    let at = latest.windows(4).position(|w| w == b"OHDR").unwrap();
    let mut b = latest.clone();
    b[at + 12] ^= 0x40;
    altered_names("t.datx", "datx", &b, at + 12, &[b[at + 12]], "checksum");
    // An HDF5 file without a Surface dataset: not taken as DATX, and an
    // error naming it when DATX is forced.
    let other = bytes("datx/no-surface.h5");
    let read = read_bytes(Path::new("t.h5"), &other, &IngestOptions::default());
    assert!(read.map_or(true, |d| d.format != "datx"));
    let e = crate::common::bad::read_forced("t.h5", "datx", &other)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("t.h5: byte ") && e.contains("no Surface dataset"),
        "{e}"
    );
}
