//! Keyence ZON (and VK4/VK6, Sensofar PLUX): variants written by the test
//! writers (`common::writers_keyence`) read back, and bad files.

use std::path::Path;

use crate::common::bad::{altered_names, assert_values, cuts_name_file_and_offset, meta};
use crate::common::writers::Surface;
use crate::common::writers_keyence as w;
use tribo::ingest::{read_bytes, IngestOptions};

fn zon_surface() -> Surface {
    let mut s = Surface::waves(21, 9, 2.36e-5, 2.36e-5, 3e-6, 1e-6);
    for i in [0, 40, 188] {
        s.z[i] = f64::NAN;
    }
    s
}

#[test]
fn zon_variants_read_back_heights_mask_and_image() {
    let s = zon_surface();
    for (compressed, gap, pad, bom) in [
        (true, 8, 0, true),
        (false, 0, 0, false),
        (true, 0, 12, false),
        (false, 8, 3, true),
    ] {
        let o = w::Zon {
            compressed,
            gap,
            pad,
            bom,
            ..Default::default()
        };
        let what = format!("compressed {compressed}, gap {gap}, pad {pad}, bom {bom}");
        let b = w::zon(&s, 1e-8, &o);
        let ds = read_bytes(Path::new("t.zon"), &b, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "zon");
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "Height",
                "Image 1 byte 0",
                "Image 1 byte 1",
                "Image 1 byte 2"
            ]
        );
        let g = &ds.grids[0];
        assert_eq!(
            (g.nx, g.ny, g.dx, g.dy),
            (21, 9, 2.36e-5, 2.36e-5),
            "{what}"
        );
        assert_values(g.values().unwrap(), &w::zon_heights(&s, 1e-8), 1e-18, &what);
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 3, "{what}");
        assert_eq!(meta(&ds, "instrument"), Some("Keyence VR-6100"));
        assert_eq!(
            meta(&ds, "acquisition_date"),
            Some("2025-12-18T12:47:39-06:00")
        );
        assert_eq!(meta(&ds, "height_scale"), Some("1e-8"));
        // The one document that does not parse is counted, not hidden.
        assert_eq!(meta(&ds, "xml_documents_not_parsed"), Some("1"));
        let o = IngestOptions {
            channel: Some("Image 1 byte 2".into()),
            ..Default::default()
        };
        let ds = read_bytes(Path::new("t.zon"), &b, &o).unwrap();
        let want: Vec<f64> = (0..189).map(|i| ((i * 3) % 256) as f64).collect();
        assert_values(ds.grids[3].values().unwrap(), &want, 0.0, &what);
    }
}

#[test]
fn zon_bad_files_name_the_entry_and_offset() {
    let s = Surface::waves(6, 4, 1e-5, 1e-5, 1e-6, 0.0);
    let plain = w::Zon {
        compressed: false,
        ..Default::default()
    };
    let good = w::zon(&s, 1e-8, &plain);
    cuts_name_file_and_offset("t.zon", "zon", &good, 7);
    // The heights entry's content follows its name in its local header.
    let heights = find(&good, b"b-heights") + 9;
    assert_eq!(&good[heights..heights + 4], &6u32.to_le_bytes());
    // A row of a million points: it cannot fit its stride.
    altered_names(
        "t.zon",
        "zon",
        &good,
        heights,
        &[0, 0, 0x10, 0],
        "array header",
    );
    // A changed height: the entry's CRC-32 says so.
    altered_names("t.zon", "zon", &good, heights + 20, &[0x55], "CRC-32");
    // No lateral calibration.
    let o = w::Zon {
        xy_tag: "MetrePerPixel",
        ..w::Zon::default()
    };
    let e = crate::common::bad::read_forced("t.zon", "zon", &w::zon(&s, 1e-8, &o));
    let e = e.unwrap_err().to_string();
    assert!(
        e.contains("byte ") && e.contains("Calibration/XYCalibration/MeterPerPixel is ''"),
        "{e}"
    );
    // Compressed: a corrupted frame is an error of its entry, not a panic.
    let packed = w::zon(&s, 1e-8, &w::Zon::default());
    let at = find(&packed, b"b-heights") + 9 + 6;
    altered_names(
        "t.zon",
        "zon",
        &packed,
        at,
        &[0xFF, 0xFF],
        "ZON entry 'b-heights'",
    );
}

fn find(hay: &[u8], needle: &[u8]) -> usize {
    hay.windows(needle.len())
        .position(|w| w == needle)
        .expect("present")
}

/// Writes the small fixtures of `fixtures/surface/` for these formats
/// (fuzz seeds): `cargo test write_keyence_fixtures -- --ignored`.
#[test]
#[ignore]
fn write_keyence_fixtures() {
    let dir = crate::common::root().join("fixtures/surface");
    let mut s = Surface::waves(16, 12, 1e-6, 1e-6, 2e-7, 5e-8);
    s.z[5] = f64::NAN;
    let files: Vec<(&str, Vec<u8>)> =
        vec![("waves-16x12.zon", w::zon(&s, 1e-9, &w::Zon::default()))];
    let mut vk = Surface::waves(16, 12, 1e-6, 1e-6, 2e-7, 5e-8);
    vk.z.iter_mut().for_each(|z| *z += 1e-6);
    let files = files.into_iter().chain([
        ("waves-16x12.vk4", w::vk4(&vk, 10, 32, 4)),
        ("waves-16x12.vk6", w::vk6(&w::vk4(&vk, 10, 16, 4), true)),
        ("waves-16x12.plux", w::plux(&s, true, true)),
    ]);
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
}

fn vk_surface() -> Surface {
    let mut s = Surface::waves(19, 7, 1.3634e-6, 1.3634e-6, 2e-6, 5e-7);
    for z in s.z.iter_mut() {
        *z += 3e-6;
    }
    s
}

#[test]
fn vk_variants_read_back_heights_and_light() {
    let s = vk_surface();
    for (bits, version, zipped) in [
        (32, 4, None),
        (16, 3, None),
        (32, 4, Some(true)),
        (32, 4, Some(false)),
    ] {
        let pm = if bits == 16 { 200 } else { 1 };
        let raw = w::vk4(&s, pm, bits, version);
        let b = match zipped {
            Some(deflate) => w::vk6(&raw, deflate),
            None => raw,
        };
        let what = format!("{bits} bits, VK{version}, zip {zipped:?}");
        let ds = read_bytes(Path::new("t.vk4"), &b, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "vk", "{what}");
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["Height", "Light"], "{what}");
        let g = &ds.grids[0];
        assert_eq!(
            (g.nx, g.ny, g.dx, g.dy),
            (19, 7, 1.3634e-6, 1.3634e-6),
            "{what}"
        );
        assert_values(g.values().unwrap(), &w::vk_heights(&s, pm), 1e-20, &what);
        assert_eq!(
            meta(&ds, "acquisition_date"),
            Some("2022-10-14T09:23:04+02:00")
        );
        assert_eq!(meta(&ds, "objective"), Some("CF IC EPI Plan 20x"));
        assert_eq!(meta(&ds, "lens_magnification"), Some("20"));
        let o = IngestOptions {
            channel: Some("light".into()),
            ..Default::default()
        };
        let ds = read_bytes(Path::new("t.vk4"), &b, &o).unwrap();
        let want: Vec<f64> = (0..133).map(|i| i as f64).collect();
        assert_values(ds.grids[1].values().unwrap(), &want, 0.0, &what);
    }
}

#[test]
fn vk_bad_files_name_the_structure() {
    let s = vk_surface();
    let good = w::vk4(&s, 1, 32, 4);
    cuts_name_file_and_offset("t.vk4", "vk", &good, 11);
    // The height image's bits per point (offset table → 388, + 8).
    altered_names("t.vk4", "vk", &good, 388 + 8, &[24], "bits per point");
    // Its byte size.
    altered_names("t.vk4", "vk", &good, 388 + 16, &[1], "byte size");
    // No height image.
    altered_names("t.vk4", "vk", &good, 12 + 24, &[0; 4], "no height image");
    // A zero length per pixel.
    altered_names("t.vk4", "vk", &good, 84 + 168, &[0; 4], "spacing along x");
    // In a VK6: the offset is the entry's, named so.
    let six = w::vk6(&good, true);
    let e = crate::common::bad::read_forced("t.vk6", "vk", &w::vk6(&good[..300], false));
    let e = e.unwrap_err().to_string();
    assert!(
        e.contains("byte 388: zip entry 'Vk4File', VK4 image 'Height'"),
        "{e}"
    );
    cuts_name_file_and_offset("t.vk6", "vk", &six, 13);
    // A text file that happens to start with `VK6` is not taken for one.
    use tribo::ingest::Reader;
    let vk = tribo::ingest::formats::vk::Vk;
    assert!(vk.sniff_bytes(&six) && !vk.sniff_bytes(b"VK6,1.0\n2,3\n"));
}

#[test]
fn plux_layers_not_measured_points_and_metadata_read_back() {
    let mut s = Surface::waves(23, 11, 0.645e-6, 0.645e-6, 2e-6, 3e-7);
    s.z[30] = f64::NAN;
    for (bom, deflate) in [(true, false), (false, true)] {
        let b = w::plux(&s, bom, deflate);
        let ds = read_bytes(Path::new("t.plux"), &b, &IngestOptions::default()).unwrap();
        assert_eq!(ds.format, "plux");
        let names: Vec<&str> = ds.grids.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(names, ["Layer 0", "Layer 1"]);
        let g = &ds.grids[0];
        assert_eq!((g.nx, g.ny), (23, 11));
        assert!((g.dx / 0.645e-6 - 1.0).abs() < 1e-12 && (g.dy / 0.645e-6 - 1.0).abs() < 1e-12);
        // f32 µm: 2^-24 relative of values up to 2.3 µm.
        assert_values(g.values().unwrap(), &s.z, 3e-13, "layer 0");
        assert_eq!(g.data.as_ref().unwrap().n_invalid, 1);
        assert_eq!(meta(&ds, "instrument"), Some("Sensofar S neox"));
        assert_eq!(meta(&ds, "objective"), Some("Nikon 20x"));
        let o = IngestOptions {
            channel: Some("Layer 1".into()),
            ..Default::default()
        };
        let ds = read_bytes(Path::new("t.plux"), &b, &o).unwrap();
        let twice: Vec<f64> = s.z.iter().map(|z| 2.0 * z).collect();
        assert_values(ds.grids[1].values().unwrap(), &twice, 6e-13, "layer 1");
    }
}

#[test]
fn plux_bad_files_name_the_element_or_layer() {
    let s = Surface::waves(6, 4, 1e-6, 1e-6, 1e-6, 0.0);
    let good = w::plux(&s, false, false);
    cuts_name_file_and_offset("t.plux", "plux", &good, 7);
    // A layer shorter than the grid; a size that is not a number; a
    // layer that is not in the archive.
    let index = |x: &str, file: &str| {
        format!(
            "<xml><GENERAL><IMAGE_SIZE_X>{x}</IMAGE_SIZE_X><IMAGE_SIZE_Y>4</IMAGE_SIZE_Y>\
             <FOV_X>1</FOV_X><FOV_Y>1</FOV_Y></GENERAL>\
             <LAYER_0><FILENAME_Z>{file}</FILENAME_Z></LAYER_0></xml>"
        )
    };
    for (x, file, want) in [
        (
            "6",
            "LAYER_0.raw",
            "PLUX layer 'LAYER_0.raw': holds 92 bytes; 6 × 4 f32 need 96",
        ),
        ("six", "LAYER_0.raw", "GENERAL/IMAGE_SIZE_X is 'six'"),
        (
            "6",
            "LAYER_9.raw",
            "'LAYER_9.raw' is not in the zip archive",
        ),
    ] {
        let doc = index(x, file);
        let b = tribo::ingest::binary::zip::write(
            &[("index.xml", doc.as_bytes()), ("LAYER_0.raw", &[0u8; 92])],
            false,
        );
        let e = crate::common::bad::read_forced("t.plux", "plux", &b);
        let e = e.unwrap_err().to_string();
        assert!(e.contains(want) && e.contains("byte "), "{want}: {e}");
    }
}
