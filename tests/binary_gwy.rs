//! Gwyddion GWY: files written by the test writer (`common::writers_afm`)
//! read back — units and their prefixes, several channels, masks,
//! channels in other units — bad files, and the example file of gwyfile
//! (MIT, `fixtures/surface/gwyfile-test.gwy`) against that project's own
//! test.

use std::path::Path;

use crate::common::bad::{self, assert_values};
use crate::common::writers::{sq_finite, Surface};
use crate::common::writers_afm::{gwy, GwyChannel};
use crate::common::{self};
use tribo::ingest::{read_bytes, read_path, IngestOptions};

fn read_with(bytes: &[u8], o: &IngestOptions) -> tribo::Result<tribo::ingest::Dataset> {
    read_bytes(Path::new("t.gwy"), bytes, o)
}

fn read(bytes: &[u8]) -> tribo::Result<tribo::ingest::Dataset> {
    read_with(bytes, &IngestOptions::default())
}

fn channel<'a>(
    title: &'a str,
    s: &'a Surface,
    xy: (&'a str, f64),
    z: (&'a str, f64),
) -> GwyChannel<'a> {
    GwyChannel {
        title,
        surface: s,
        xy,
        z,
        mask: None,
    }
}

#[test]
fn units_and_prefixes_read_back_in_metres() {
    let s = Surface::waves(40, 24, 0.5e-6, 1.25e-6, 2e-7, 5e-8);
    for xy in [("m", 1.0), ("µm", 1e-6), ("nm", 1e-9)] {
        for z in [("m", 1.0), ("nm", 1e-9), ("um", 1e-6)] {
            let ds = read(&gwy(&[channel("Topography", &s, xy, z)])).unwrap();
            assert_eq!(ds.format, "gwy");
            let g = &ds.grids[0];
            assert_eq!((g.nx, g.ny, g.unit.as_str(), g.height), (40, 24, "m", true));
            assert!((g.dx / 0.5e-6 - 1.0).abs() < 1e-12 && (g.dy / 1.25e-6 - 1.0).abs() < 1e-12);
            assert_values(g.values().unwrap(), &s.z, 1e-21, &format!("{xy:?} {z:?}"));
            assert_eq!(bad::meta(&ds, "Date"), Some("2024-05-06 07:08:09"));
            assert_eq!(bad::meta(&ds, "height_unit"), Some(z.0));
        }
    }
}

/// A mask of 1 marks points not measured: NaN, counted, out of Sq.
#[test]
fn masks_are_points_not_measured() {
    let s = Surface::waves(32, 20, 1e-6, 1e-6, 3e-7, 1e-7);
    let mask: Vec<bool> = (0..s.z.len()).map(|i| i % 7 == 3).collect();
    let n_bad = mask.iter().filter(|m| **m).count();
    let mut c = channel("Height", &s, ("m", 1.0), ("m", 1.0));
    c.mask = Some(mask.clone());
    let ds = read(&gwy(&[c])).unwrap();
    let g = &ds.grids[0];
    assert_eq!(g.data.as_ref().unwrap().n_invalid, n_bad);
    let want: Vec<f64> =
        s.z.iter()
            .zip(&mask)
            .map(|(z, m)| if *m { f64::NAN } else { *z })
            .collect();
    assert_values(g.values().unwrap(), &want, 0.0, "masked");
    let ((sq, n), (sq_w, n_w)) = (sq_finite(g.values().unwrap()), sq_finite(&want));
    assert_eq!((n, sq), (n_w, sq_w));
}

/// Every channel is listed with its unit; heights by default, the others
/// by name; a lateral unit that is not a length gives no spacing.
#[test]
fn channels_other_units_and_pixels() {
    let h = Surface::waves(16, 12, 1e-6, 1e-6, 1e-7, 0.0);
    let mut p = Surface::waves(16, 12, 1e-6, 1e-6, 0.0, 0.0);
    p.z = (0..p.z.len()).map(|k| (k % 90) as f64).collect();
    let file = gwy(&[
        channel("Phase", &p, ("m", 1.0), ("deg", 1.0)),
        channel("Height", &h, ("m", 1.0), ("m", 1.0)),
    ]);
    let ds = read(&file).unwrap();
    let names: Vec<_> = ds
        .grids
        .iter()
        .map(|g| (g.name.as_str(), g.unit.as_str(), g.height, g.data.is_some()))
        .collect();
    assert_eq!(
        names,
        [("Phase", "deg", false, false), ("Height", "m", true, true)]
    );
    let o = IngestOptions {
        channel: Some("phase".into()),
        ..Default::default()
    };
    let ds = read_with(&file, &o).unwrap();
    assert_eq!(ds.grids[0].values().unwrap()[..3], [0.0, 1.0, 2.0]);
    let px = read(&gwy(&[channel("Z", &h, ("", 1e-6), ("m", 1.0))])).unwrap();
    assert!(px.grids[0].dx.is_nan() && px.grids[0].dy.is_nan());
}

#[test]
fn bad_files_name_the_structure_and_offset() {
    let s = Surface::waves(12, 10, 1e-6, 1e-6, 1e-7, 1e-8);
    let good = gwy(&[channel("Height", &s, ("m", 1.0), ("m", 1.0))]);
    bad::cuts_name_file_and_offset("t.gwy", "gwy", &good, 37);
    let at = |pat: &[u8]| good.windows(pat.len()).position(|w| w == pat).unwrap();
    for (pos, bytes, want) in [
        (0, &b"GWYO"[..], "Gwyddion 1"),
        (at(b"xres\0i") + 5, b"x", "type 'x'"),
        (
            at(b"xres\0i") + 6,
            &13i32.to_le_bytes(),
            "data points for xres",
        ),
        (
            at(b"xres\0i") + 6,
            &(-1i32).to_le_bytes(),
            "xres is Some(-1)",
        ),
        (at(b"xreal\0d") + 7, &0f64.to_le_bytes(), "spacing along x"),
        (
            at(b"GwyContainer\0") + 13,
            &7u32.to_le_bytes(),
            "not at its stated end",
        ),
    ] {
        bad::altered_names("t.gwy", "gwy", &good, pos, bytes, want);
    }
    let only_meta = {
        let mut f = b"GWYP".to_vec();
        f.extend(crate::common::writers_afm::gwy_object("GwyContainer", &[]));
        f
    };
    let e = read(&only_meta).unwrap_err().to_string();
    assert!(e.contains("no image channel"), "{e}");
}

/// gwyfile's example (MIT): its test asserts a 128 × 128 channel 'Test'
/// with data[0][0] ≈ 0.00082494 and data[44][33] ≈ 0.00085301 (row,
/// column; rel. 1e-5); unitless, so no spacing and not a height.
#[test]
fn gwyfile_example_matches_its_test() {
    let p = common::root().join("fixtures/surface/gwyfile-test.gwy");
    let ds = read_path(&p, &IngestOptions::default()).unwrap();
    let g = &ds.grids[0];
    assert_eq!(
        (ds.grids.len(), g.name.as_str(), g.nx, g.ny),
        (1, "Test", 128, 128)
    );
    assert!(!g.height && g.dx.is_nan());
    let v = g.values().unwrap();
    for (r, c, want) in [(0, 0, 0.00082494), (44, 33, 0.00085301)] {
        let got = v[r * 128 + c];
        assert!(
            (got - want).abs() <= 1e-5 * want,
            "[{r}][{c}] {got} vs {want}"
        );
    }
}
