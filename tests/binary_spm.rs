//! AFM and profiler formats (IBW, NID, MI, BCR, WSxM, FRT): files written
//! by the test writers (`common::writers_spm`) read back, their variants
//! (byte orders, sample types, header encodings, versions, scan
//! directions, channels), and bad files: every cut and corrupted field is
//! an error naming the file, the structure and the byte offset.

use std::path::Path;

use crate::common::bad::{altered_names, assert_values, cuts_name_file_and_offset, meta};
use crate::common::writers::Surface;
use crate::common::writers_spm as w;
use tribo::ingest::{read_bytes, Dataset, IngestOptions};

fn read(name: &str, b: &[u8]) -> Dataset {
    read_bytes(Path::new(name), b, &IngestOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn read_channel(name: &str, b: &[u8], channel: &str) -> Dataset {
    let o = IngestOptions {
        channel: Some(channel.into()),
        ..Default::default()
    };
    read_bytes(Path::new(name), b, &o).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs()
}

#[test]
fn ibw_layers_byte_orders_and_units_read_back() {
    let s = Surface::waves(12, 7, 2e-8, 3e-8, 4e-9, 1e-9);
    let amp = Surface::waves(12, 7, 2e-8, 3e-8, 1e-10, 0.0);
    for big in [false, true] {
        let b = w::ibw(
            &s,
            &[("AmplitudeRetrace", &amp), ("HeightRetrace", &s)],
            "m",
            big,
        );
        let ds = read("t.ibw", &b);
        assert_eq!(ds.format, "ibw");
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["AmplitudeRetrace", "HeightRetrace"]);
        let g = &ds.grids[1];
        assert!(
            g.height && g.data.is_some(),
            "height by default, not the first layer"
        );
        assert!(close(g.dx, 2e-8) && close(g.dy, 3e-8) && (g.nx, g.ny) == (12, 7));
        assert_values(g.values().unwrap(), &s.z, 5e-16, "height");
        let a = read_channel("t.ibw", &b, "amplituderetrace");
        assert_values(a.grids[0].values().unwrap(), &amp.z, 2e-17, "amplitude");
        assert_eq!(meta(&ds, "instrument"), Some("Asylum Research MFP3D"));
        assert_eq!(meta(&ds, "acquisition_date"), Some("2021-03-04T13:02:03"));
    }
    // Heights in nm: converted to metres.
    let nm = Surface {
        z: s.z.iter().map(|v| v * 1e9).collect(),
        ..Surface::waves(12, 7, 2e-8, 3e-8, 0.0, 0.0)
    };
    let ds = read("t.ibw", &w::ibw(&s, &[("Height", &nm)], "nm", false));
    assert_values(ds.grids[0].values().unwrap(), &s.z, 1e-15, "nm");
}

#[test]
fn ibw_bad_files_name_the_field() {
    let s = Surface::waves(6, 4, 1e-8, 1e-8, 1e-9, 0.0);
    let good = w::ibw(&s, &[("Height", &s)], "m", false);
    cuts_name_file_and_offset("t.ibw", "ibw", &good, 7);
    altered_names("t.ibw", "ibw", &good, 0, &[3, 0], "IBW header (version)");
    altered_names("t.ibw", "ibw", &good, 2, &[0, 0], "checksum");
    // One more point along x than the wave holds, checksum made good.
    let mut b = good.clone();
    b[64 + 68] += 1;
    b[2..4].copy_from_slice(&[0, 0]);
    let sum = b[..384].chunks(2).fold(0u16, |a, w| {
        a.wrapping_add(u16::from_le_bytes([w[0], w[1]]))
    });
    b[2..4].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
    let e = crate::common::bad::read_forced("t.ibw", "ibw", &b)
        .unwrap_err()
        .to_string();
    assert!(e.contains("t.ibw: byte 132: IBW wave header (nDim)"), "{e}");
}

#[test]
fn nid_channels_bits_and_orientation_read_back() {
    let s = Surface::waves(10, 6, 5e-8, 8e-8, 2e-7, 5e-8);
    let defl = Surface::waves(10, 6, 5e-8, 8e-8, 1e-9, 0.0);
    for bits in [16, 32] {
        let (b, steps) = w::nid(
            &s,
            &[("Deflection", "N", 1.0, &defl), ("Z-Axis", "nm", 1e-9, &s)],
            bits,
        );
        let ds = read("t.nid", &b);
        assert_eq!(ds.format, "nid");
        assert_eq!(ds.grids[1].name, "Scan forward (Z-Axis)");
        assert!(ds.grids[1].height && !ds.grids[0].height && ds.grids[0].unit == "N");
        assert!(close(ds.grids[1].dx, 5e-8) && close(ds.grids[1].dy, 8e-8));
        assert_values(ds.grids[1].values().unwrap(), &s.z, steps[1] * 0.501, "Z");
        let d = read_channel("t.nid", &b, "Scan forward (Deflection)");
        assert_values(
            d.grids[0].values().unwrap(),
            &defl.z,
            steps[0] * 0.501,
            "deflection",
        );
        assert_eq!(meta(&ds, "acquisition_date"), Some("2023-06-05T07:08:09"));
    }
}

#[test]
fn nid_bad_files_name_the_section() {
    let s = Surface::waves(6, 4, 1e-8, 1e-8, 1e-9, 0.0);
    let (good, _) = w::nid(&s, &[("Z-Axis", "m", 1.0, &s)], 16);
    let text = String::from_utf8_lossy(&good).into_owned();
    let at = |k: &str| text.find(k).unwrap();
    altered_names(
        "t.nid",
        "nid",
        &good,
        at("SaveBits=16") + 9,
        b"24",
        "NID header [DataSet-0:0] (SaveBits)",
    );
    altered_names(
        "t.nid",
        "nid",
        &good,
        at("SaveMode=Binary") + 9,
        b"Ascii_",
        "(SaveMode)",
    );
    altered_names(
        "t.nid",
        "nid",
        &good,
        at("Points=6"),
        b"Pxints",
        "(Points): missing",
    );
    let cut = &good[..good.len() - 3];
    let e = crate::common::bad::read_forced("t.nid", "nid", cut)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("t.nid: byte ") && e.contains("NID data") && e.contains("truncated"),
        "{e}"
    );
}

#[test]
fn mi_encodings_and_scan_directions_read_back() {
    let s = Surface::waves(9, 5, 4e-8, 4e-8, 3e-7, 1e-7);
    for (bits32, up) in [(true, true), (false, true), (true, false)] {
        let (b, step) = w::mi(&s, bits32, up);
        let ds = read("t.mi", &b);
        assert_eq!(ds.format, "mi");
        assert_eq!(ds.grids[0].name, "Topography Trace");
        assert_values(
            ds.grids[0].values().unwrap(),
            &s.z,
            step * 0.501,
            "topography",
        );
        let d = read_channel("t.mi", &b, "Deflection Trace");
        assert_eq!(d.grids[1].unit, "V");
        let v = 7.0 * 10.0 / if bits32 { 2147483648.0 } else { 32768.0 };
        assert!(d.grids[1].values().unwrap().iter().all(|x| close(*x, v)));
        assert_eq!(meta(&ds, "acquisition_date"), Some("2020-03-04T05:06:07"));
    }
}

#[test]
fn mi_bad_files_name_the_key() {
    let s = Surface::waves(6, 4, 1e-8, 1e-8, 1e-9, 0.0);
    let (good, _) = w::mi(&s, false, true);
    let text = String::from_utf8_lossy(&good).into_owned();
    let at = |k: &str| text.find(k).unwrap();
    altered_names(
        "t.mi",
        "mi",
        &good,
        at("BINARY"),
        b"ASCII!",
        "MI header (data)",
    );
    altered_names(
        "t.mi",
        "mi",
        &good,
        at("Image"),
        b"Spect",
        "MI header (fileType)",
    );
    altered_names(
        "t.mi",
        "mi",
        &good,
        at("xPixels       6") + 14,
        b"x",
        "MI header (xPixels)",
    );
    let e = crate::common::bad::read_forced("t.mi", "mi", &good[..good.len() - 1])
        .unwrap_err()
        .to_string();
    assert!(e.contains("t.mi: byte ") && e.contains("truncated"), "{e}");
}

#[test]
fn bcr_integer_float_and_unicode_headers_read_back() {
    let s = Surface::waves(11, 6, 2e-7, 3e-7, 4e-7, 1e-7);
    for (float, unicode) in [(false, false), (true, false), (false, true), (true, true)] {
        let b = w::bcr(&s, float, unicode, &[3, 40]);
        let ds = read("t.bcr", &b);
        assert_eq!(ds.format, "bcr", "{float} {unicode}");
        let g = &ds.grids[0];
        assert!(close(g.dx, 2e-7) && close(g.dy, 3e-7));
        let mut want = s.z.clone();
        want[3] = f64::NAN;
        want[40] = f64::NAN;
        let tol = if float { 1e-13 } else { 0.501e-9 };
        assert_values(g.values().unwrap(), &want, tol, "bcr");
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 2);
    }
}

#[test]
fn bcr_bad_files_name_the_key() {
    let s = Surface::waves(6, 4, 1e-8, 1e-8, 1e-9, 0.0);
    let good = w::bcr(&s, true, false, &[]);
    let text = String::from_utf8_lossy(&good).into_owned();
    let at = |k: &str| text.find(k).unwrap();
    altered_names(
        "t.bcr",
        "bcr",
        &good,
        at("bcrf"),
        b"bcrx",
        "BCR header (fileformat)",
    );
    altered_names(
        "t.bcr",
        "bcr",
        &good,
        at("zunit = um") + 8,
        b"V ",
        "BCR header (zunit)",
    );
    altered_names(
        "t.bcr",
        "bcr",
        &good,
        at("xpixels = 6") + 10,
        b"0",
        "BCR header",
    );
    let e = crate::common::bad::read_forced("t.bcr", "bcr", &good[..good.len() - 2])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("t.bcr: byte 2048: BCR data") && e.contains("truncated"),
        "{e}"
    );
}

#[test]
fn wsxm_short_and_double_read_back() {
    let s = Surface::waves(8, 5, 2.5e-9, 2.5e-9, 3e-9, 1e-9);
    for double in [false, true] {
        let b = w::wsxm(&s, double);
        let ds = read("t.top", &b);
        assert_eq!(ds.format, "wsxm");
        let g = &ds.grids[0];
        assert_eq!((g.name.as_str(), g.nx, g.ny), ("Topography", 8, 5));
        assert!(close(g.dx, 2.5e-9));
        // The format has no offset: heights about their mean.
        let centred = |v: &[f64]| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            v.iter().map(|x| x - m).collect::<Vec<_>>()
        };
        let tol = if double { 1e-20 } else { 5e-9 / 60000.0 };
        assert_values(&centred(g.values().unwrap()), &centred(&s.z), tol, "wsxm");
        assert_eq!(meta(&ds, "acquisition_date"), Some("2011-11-03T20:23:46"));
    }
}

#[test]
fn wsxm_bad_files_name_the_key() {
    let s = Surface::waves(6, 4, 1e-8, 1e-8, 1e-9, 0.0);
    let good = w::wsxm(&s, false);
    let text = String::from_utf8_lossy(&good).into_owned();
    let at = |k: &str| text.find(k).unwrap();
    altered_names(
        "t.top",
        "wsxm",
        &good,
        at("short"),
        b"shirt",
        "WSxM header [General Info] (Image Data Type)",
    );
    altered_names(
        "t.top",
        "wsxm",
        &good,
        at("X Amplitude: ") + 13,
        b"x",
        "[Control] (X Amplitude)",
    );
    let e = crate::common::bad::read_forced("t.top", "wsxm", &good[..good.len() - 1])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("t.top: byte ") && e.contains("WSxM data") && e.contains("truncated"),
        "{e}"
    );
}

#[test]
fn frt_versions_and_invalid_points_read_back() {
    let s = Surface::waves(13, 6, 2e-5, 4e-5, 2e-5, 5e-6);
    let step = 1e-8;
    let lo = s.z.iter().fold(f64::MAX, |a, v| a.min(*v));
    for v101 in [false, true] {
        let ds = read("t.frt", &w::frt(&s, v101, step, &[0, 30]));
        assert_eq!(ds.format, "frt");
        let g = &ds.grids[0];
        assert!(close(g.dx, 2e-5) && close(g.dy, 4e-5));
        let mut want: Vec<f64> = s.z.iter().map(|z| z - lo + 2.0 * step).collect();
        want[0] = f64::NAN;
        want[30] = f64::NAN;
        assert_values(g.values().unwrap(), &want, 0.501 * step, "frt");
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 2);
    }
}

#[test]
fn frt_bad_files_name_the_block() {
    let s = Surface::waves(6, 4, 1e-5, 1e-5, 1e-6, 0.0);
    let good = w::frt(&s, false, 1e-8, &[]);
    cuts_name_file_and_offset("t.frt", "frt", &good, 5);
    altered_names("t.frt", "frt", &good, 12, b"2.00", "FRT version");
    // Block 0x66 holds nx, ny, bits after the comment block (6 + 10 bytes).
    let bits = 18 + 16 + 6 + 8;
    altered_names(
        "t.frt",
        "frt",
        &good,
        bits,
        &[24],
        "FRT block 0x0066 (bits per point)",
    );
}

/// Writes the small fixtures of `fixtures/surface/` for these formats
/// (fuzz seeds): `cargo test write_spm_fixtures -- --ignored`.
#[test]
#[ignore]
fn write_spm_fixtures() {
    let dir = crate::common::root().join("fixtures/surface");
    let s = Surface::waves(16, 12, 1e-7, 1e-7, 2e-8, 5e-9);
    let files: Vec<(&str, Vec<u8>)> = vec![
        (
            "waves-16x12.ibw",
            w::ibw(
                &s,
                &[("HeightRetrace", &s), ("PhaseRetrace", &s)],
                "m",
                false,
            ),
        ),
        (
            "waves-16x12.nid",
            w::nid(&s, &[("Z-Axis", "m", 1.0, &s)], 16).0,
        ),
        ("waves-16x12.mi", w::mi(&s, false, true).0),
        ("waves-16x12-unicode.bcrf", w::bcr(&s, true, true, &[5])),
        ("waves-16x12.top", w::wsxm(&s, false)),
        ("waves-16x12.frt", w::frt(&s, true, 1e-10, &[7])),
    ];
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}
