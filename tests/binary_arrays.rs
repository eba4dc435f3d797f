//! netCDF 3, NumPy .npy and ISO 25178-71 SDF: variants written by the
//! test writers (`common::writers_arrays`), bad files, and the small
//! example files of SurfaceTopography (MIT, `fixtures/surface/`), checked
//! against closed forms of their values.

use std::path::Path;

use crate::common::bad::{
    altered_names, assert_values, cuts_name_file_and_offset, meta, read_forced,
};
use crate::common::writers::{sq_finite, Surface};
use crate::common::writers_arrays::{metres, netcdf, npy, sdf_ascii, sdf_binary, Nc, NcType};
use tribo::ingest::{read_bytes, read_path, Dataset, IngestOptions};

fn read(name: &str, bytes: &[u8]) -> Dataset {
    read_bytes(Path::new(name), bytes, &IngestOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn fixture(name: &str) -> Dataset {
    let p = crate::common::root().join("fixtures/surface").join(name);
    read_path(&p, &IngestOptions::default()).unwrap_or_else(|e| panic!("{e}"))
}

fn with_nan(s: &Surface, bad: &[usize]) -> Vec<f64> {
    let mut z = s.z.clone();
    for &i in bad {
        z[i] = f64::NAN;
    }
    z
}

#[test]
fn netcdf_versions_types_layouts_and_units_read_back() {
    let s = Surface::waves(24, 10, 0.5e-6, 0.25e-6, 3e-8, 1e-8);
    for version in [1, 2, 5] {
        for xy in [true, false] {
            for (kind, unit) in [
                (NcType::Double, "Å"),
                (NcType::Float, "µm"),
                (NcType::Short, "nm"),
            ] {
                for length_attr in [true, false] {
                    let o = Nc {
                        version,
                        xy,
                        kind,
                        unit,
                        length_attr,
                        ..Default::default()
                    };
                    let what = format!("v{version} xy {xy} {unit} length {length_attr}");
                    let ds = read("t.nc", &netcdf(&s, &o));
                    assert_eq!(ds.format, "netcdf", "{what}");
                    let g = &ds.grids[0];
                    assert_eq!(
                        (g.nx, g.ny, g.unit.as_str(), g.height),
                        (24, 10, "m", true),
                        "{what}"
                    );
                    assert!(
                        (g.dx / 0.5e-6 - 1.0).abs() < 1e-9 && (g.dy / 0.25e-6 - 1.0).abs() < 1e-9,
                        "{what}"
                    );
                    // Shorts hold 0.01 Å steps; floats 2^-24 relative.
                    let tol = match kind {
                        NcType::Double => 1e-20,
                        NcType::Float => 1e-7 * 4e-8,
                        NcType::Short => 0.005 * metres(unit) * 1.0001,
                    };
                    assert_values(g.values().unwrap(), &s.z, tol, &what);
                }
            }
        }
    }
}

#[test]
fn netcdf_fill_values_mask_and_channels() {
    let s = Surface::waves(16, 12, 1e-6, 1e-6, 1e-7, 2e-8);
    let fill: Vec<usize> = (0..s.z.len()).filter(|i| i % 7 == 0).collect();
    let mask: Vec<usize> = (0..s.z.len()).filter(|i| i % 5 == 1).collect();
    for kind in [NcType::Double, NcType::Float, NcType::Short] {
        let o = Nc {
            kind,
            fill: fill.clone(),
            mask: mask.clone(),
            phase: true,
            ..Default::default()
        };
        let bytes = netcdf(&s, &o);
        let ds = read("t.nc", &bytes);
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["phase", "heights"]);
        let g = &ds.grids[1];
        let both: Vec<usize> = fill.iter().chain(&mask).copied().collect();
        let want = with_nan(&s, &both);
        let tol = match kind {
            NcType::Short => 0.0051e-9,
            NcType::Float => 1e-7 * 2e-7,
            NcType::Double => 1e-15,
        };
        assert_values(g.values().unwrap(), &want, tol, "fill and mask");
        let n_invalid = want.iter().filter(|v| v.is_nan()).count();
        assert_eq!(g.data.as_ref().unwrap().n_invalid, n_invalid);
        // The other channel keeps its unit and is not a height.
        let o = IngestOptions {
            channel: Some("phase".into()),
            ..Default::default()
        };
        let ds = read_bytes(Path::new("t.nc"), &bytes, &o).unwrap();
        let p = &ds.grids[0];
        assert_eq!((p.unit.as_str(), p.height), ("deg", false));
        let want: Vec<f64> = (0..s.z.len()).map(|i| i as f64).collect();
        assert_values(p.values().unwrap(), &want, 0.0, "phase");
    }
}

/// nc-1.nc (SurfaceTopography): heights(x = 5, y = 10) in nm, each column
/// 9, 7, ..., −9 along y, `length` 5 and 10 nm: Sq = √33 nm exactly.
#[test]
fn netcdf_example_file() {
    let ds = fixture("nc-1.nc");
    let g = &ds.grids[0];
    assert_eq!((g.nx, g.ny, g.dx, g.dy), (5, 10, 1e-9, 1e-9));
    let v = g.values().unwrap();
    for c in 0..5 {
        let column: Vec<f64> = (0..10).map(|r| v[r * 5 + c] * 1e9).collect();
        let want: Vec<f64> = (0..10).map(|r| 9.0 - 2.0 * r as f64).collect();
        assert_values(&column, &want, 1e-9, "nc-1 column");
    }
    let (sq, n) = sq_finite(v);
    assert_eq!(n, 50);
    assert!((sq - 33f64.sqrt() * 1e-9).abs() < 1e-21, "{sq}");
}

#[test]
fn netcdf_bad_files_name_the_field() {
    let s = Surface::waves(8, 6, 1e-6, 1e-6, 1e-7, 0.0);
    let good = netcdf(&s, &Nc::default());
    cuts_name_file_and_offset("t.nc", "netcdf", &good, 7);
    // The dimension list's tag (byte 8) is 10.
    altered_names("t.nc", "netcdf", &good, 8, &[0, 0, 0, 9], "dimension list");
    // The heights' type (NC_DOUBLE = 6) as 99.
    let at = good.windows(7).position(|w| w == b"heights").unwrap();
    let kind_at = good[at..]
        .windows(4)
        .position(|w| w == [0, 0, 0, 6])
        .unwrap()
        + at;
    let mut b = good.clone();
    b[kind_at + 3] = 99;
    let e = read_forced("t.nc", "netcdf", &b)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no numeric variable") || e.contains("type"),
        "{e}"
    );
}

#[test]
fn npy_versions_types_and_orders_read_back() {
    let (r, c) = (5, 7);
    let a: Vec<f64> = (0..r * c)
        .map(|i| (i as f64 * 0.37).sin() * 100.0)
        .collect();
    let ints: Vec<f64> = a.iter().map(|v| v.round()).collect();
    for version in [1, 2, 3] {
        for fortran in [false, true] {
            for (descr, want, tol) in [
                ("<f8", &a, 0.0),
                (">f8", &a, 0.0),
                ("<f4", &a, 1e-5),
                ("<i4", &ints, 0.0),
                (">i2", &ints, 0.0),
            ] {
                let what = format!("v{version} {descr} fortran {fortran}");
                let ds = read("t.npy", &npy(want, &[r, c], descr, fortran, version));
                assert_eq!(ds.format, "npy");
                let g = &ds.grids[0];
                assert_eq!((g.nx, g.ny), (c, r), "{what}");
                assert!(g.dx.is_nan() && g.dy.is_nan(), "the file states no spacing");
                assert_values(g.values().unwrap(), want, tol, &what);
            }
        }
    }
    let ds = read("t.npy", &npy(&a[..9], &[9], "<f8", false, 1));
    assert_eq!((ds.grids[0].nx, ds.grids[0].ny), (9, 1));
    let nan = [1.0, f64::NAN, f64::INFINITY, 2.0];
    let ds = read("t.npy", &npy(&nan, &[2, 2], "<f8", false, 1));
    assert_eq!(ds.grids[0].data.as_ref().unwrap().n_invalid, 2);
}

/// example-2d.npy (SurfaceTopography): [[0.1, 1], [4, 7]]; wrongnpyfile.npy
/// (a damaged magic) is refused.
#[test]
fn npy_example_files() {
    let ds = fixture("example-2d.npy");
    assert_values(
        ds.grids[0].values().unwrap(),
        &[0.1, 1.0, 4.0, 7.0],
        0.0,
        "example-2d",
    );
    assert_eq!(meta(&ds, "descr"), Some("<f8"));
    let bad =
        b"\xef\xbf\xbdNUMPY\x01\x00v\x00{'descr': '<f8', 'fortran_order': True, 'shape': (2, 3), }";
    assert!(read_forced("w.npy", "npy", bad)
        .unwrap_err()
        .to_string()
        .starts_with("w.npy: byte 0"));
}

#[test]
fn npy_bad_headers_name_the_field() {
    let good = npy(&[1.0; 12], &[3, 4], "<f8", false, 1);
    cuts_name_file_and_offset("t.npy", "npy", &good[..good.len() - 1], 5);
    for (from, to, want) in [
        ("'<f8'", "'<c8'", "type 'c8'"),
        ("False", "Maybe", "fortran_order"),
        (
            "'shape': (3, 4)",
            "'shape':(3,4,1)",
            "one or two dimensions",
        ),
        ("(3, 4)", "(3, x)", "shape entry"),
    ] {
        let at = good
            .windows(from.len())
            .position(|w| w == from.as_bytes())
            .unwrap();
        let mut h = good.clone();
        h[at..at + from.len()].copy_from_slice(format!("{to:<w$}", w = from.len()).as_bytes());
        let e = read_forced("t.npy", "npy", &h)
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(want) && e.starts_with("t.npy: byte "),
            "{want}: {e}"
        );
    }
    altered_names("t.npy", "npy", &good, 6, &[4], "major version");
}

#[test]
fn sdf_ascii_and_binary_read_back() {
    let s = Surface::waves(20, 9, 0.5e-6, 2e-6, 4e-8, 1e-8);
    let bad: Vec<usize> = (0..s.z.len()).filter(|i| i % 9 == 4).collect();
    let want = with_nan(&s, &bad);
    for eol in ["\n", "\r\n"] {
        let ds = read("t.sdf", &sdf_ascii(&s, 1e-9, &bad, eol));
        assert_eq!(ds.format, "sdf");
        let g = &ds.grids[0];
        assert_eq!((g.nx, g.ny, g.dx, g.dy), (20, 9, 0.5e-6, 2e-6));
        assert_values(g.values().unwrap(), &want, 1e-17, "ascii");
        assert_eq!(g.data.as_ref().unwrap().n_invalid, bad.len());
        assert_eq!(meta(&ds, "ManufacID"), Some("TEST"));
    }
    for (data_type, tol) in [(3, 1e-7 * 5e-8), (5, 0.5e-10), (6, 0.5e-10), (7, 1e-20)] {
        let ds = read("t.sdf", &sdf_binary(&s, 1e-10, data_type, &bad));
        let g = &ds.grids[0];
        assert_eq!((g.nx, g.ny, g.dx, g.dy), (20, 9, 0.5e-6, 2e-6));
        assert_values(
            g.values().unwrap(),
            &want,
            tol,
            &format!("binary type {data_type}"),
        );
    }
}

/// sdf-1.sdf (SurfaceTopography, after ISO 25178-71's example): 7 × 4
/// points, 1 µm steps; Sq of its printed values (µm) computed here by
/// hand with numpy: 13.602897289 nm.
#[test]
fn sdf_example_file() {
    let ds = fixture("sdf-1.sdf");
    let g = &ds.grids[0];
    assert_eq!((g.nx, g.ny), (7, 4));
    assert!((g.width() - 7e-6).abs() < 1e-15 && (g.dy - 1e-6).abs() < 1e-18);
    let (sq, n) = sq_finite(g.values().unwrap());
    assert_eq!(n, 28);
    assert!((sq / 1.3602897289488261e-08 - 1.0).abs() < 1e-9, "{sq}");
    assert_eq!(g.values().unwrap()[1], 0.99874e-6);
}

#[test]
fn sdf_bad_files_name_the_field() {
    let s = Surface::waves(6, 5, 1e-6, 1e-6, 1e-7, 0.0);
    let good = sdf_binary(&s, 1e-9, 7, &[]);
    cuts_name_file_and_offset("t.sdf", "sdf", &good, 3);
    altered_names("t.sdf", "sdf", &good, 79, &[9], "DataType");
    altered_names("t.sdf", "sdf", &good, 78, &[1], "Compression");
    let text = String::from_utf8(sdf_ascii(&s, 1e-9, &[], "\n")).unwrap();
    for (from, to, want) in [
        ("NumPoints = 6", "NumPoints = x", "NumPoints = 'x' (line 5)"),
        ("Xscale", "Xskale", "no Xscale"),
    ] {
        let t = text.replacen(from, to, 1);
        let e = read_forced("t.sdf", "sdf", t.as_bytes())
            .map(|_| ())
            .unwrap_err()
            .to_string();
        assert!(e.contains(want), "{want}: {e}");
    }
    let extra = text.replacen("\n*\n\n<", " 1.0\n*\n\n<", 1);
    let e = read_forced("t.sdf", "sdf", extra.as_bytes())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("more than NumPoints") && e.starts_with("t.sdf: byte "),
        "{e}"
    );
    let short = text.replacen("\n*\n\n<", "\nBAD BAD\n*\n\n<", 1).replacen(
        "NumProfiles = 5",
        "NumProfiles = 6",
        1,
    );
    let e = read_forced("t.sdf", "sdf", short.as_bytes())
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("2 values") || e.contains("values; NumPoints"),
        "{e}"
    );
}
