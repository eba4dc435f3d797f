//! Small writers of Keyence ZON and VK4/VK6 and Sensofar PLUX files, after
//! the public descriptions of the formats (Gwyddion, SurfaceTopography,
//! surfalize): the fixtures of the round-trip and variant tests.

use crate::common::writers::Surface;
use tribo::ingest::binary::zip;

/// Options of a ZON file.
pub struct Zon {
    /// `KPK1`: every entry a Zstandard frame; `KPK0`: entries as they are.
    pub compressed: bool,
    /// Bytes between the preview and the zip (a real file has 8).
    pub gap: usize,
    /// Padding bytes at the end of each row of the arrays.
    pub pad: usize,
    /// A UTF-8 BOM before the XML documents.
    pub bom: bool,
    /// The tag of the lateral calibration (`MeterPerPixel`).
    pub xy_tag: &'static str,
}

impl Default for Zon {
    fn default() -> Zon {
        Zon {
            compressed: true,
            gap: 8,
            pad: 0,
            bom: true,
            xy_tag: "MeterPerPixel",
        }
    }
}

/// The heights a ZON reader gives for `s`: counts of `per_unit` m
/// (rounded), NaN where `s` is NaN.
pub fn zon_heights(s: &Surface, per_unit: f64) -> Vec<f64> {
    s.z.iter()
        .map(|z| match z.is_nan() {
            true => f64::NAN,
            false => (z / per_unit).round() * per_unit,
        })
        .collect()
}

/// A 16-byte array header and rows of `item` bytes per point, padded.
fn zon_array(s: &Surface, item: usize, pad: usize, point: impl Fn(usize) -> Vec<u8>) -> Vec<u8> {
    let stride = s.nx * item + pad;
    let mut out = Vec::new();
    for v in [s.nx, s.ny, item, stride] {
        out.extend((v as u32).to_le_bytes());
    }
    for r in 0..s.ny {
        for c in 0..s.nx {
            out.extend(point(r * s.nx + c));
        }
        out.extend(vec![0xAB; pad]);
    }
    out
}

/// A Keyence ZON file of `s`: heights as i32 counts of `per_unit` m, a
/// mask of its NaN points, a colour image (bytes index, index·2, index·3
/// mod 256), the calibration and scan documents; the entries named
/// otherwise than Keyence names them (the reader goes by content).
pub fn zon(s: &Surface, per_unit: f64, o: &Zon) -> Vec<u8> {
    let bom: &[u8] = if o.bom { b"\xEF\xBB\xBF" } else { b"" };
    let xml = |body: String| {
        let mut d = bom.to_vec();
        d.extend(b"<?xml version=\"1.0\" encoding=\"utf-8\"?>\r\n");
        d.extend(body.into_bytes());
        d
    };
    let heights = zon_array(s, 4, o.pad, |i| {
        let z = s.z[i];
        let n = if z.is_nan() {
            0
        } else {
            (z / per_unit).round() as i32
        };
        n.to_le_bytes().to_vec()
    });
    let mask = zon_array(s, 1, o.pad, |i| vec![s.z[i].is_nan() as u8 * 255]);
    let rgb = zon_array(s, 3, o.pad, |i| vec![i as u8, (i * 2) as u8, (i * 3) as u8]);
    let files: Vec<(&str, Vec<u8>)> = vec![
        ("a-version", xml("<Version><FileFormat>7</FileFormat></Version>".into())),
        ("b-heights", heights),
        ("c-mask", mask),
        ("d-image", rgb),
        ("e-broken", b"<Calibration><unclosed".to_vec()),
        (
            "f-calibration",
            xml(format!(
                "<Calibration>\r\n  <XYCalibration>\r\n    <{t}>{:E}</{t}>\r\n  \
                 </XYCalibration>\r\n  <ZCalibration>\r\n    <MeterPerUnit>{per_unit:E}</MeterPerUnit>\r\n  \
                 </ZCalibration>\r\n</Calibration>",
                s.dx,
                t = o.xy_tag
            )),
        ),
        (
            "g-scan",
            xml("<ScanInformations Version=\"1.0.0.0\"><ScanDateTime>12/18/2025 12:47:39 -06:00\
                 </ScanDateTime></ScanInformations>"
                .into()),
        ),
        (
            "h-device",
            xml("<DeviceIndivisuals><DeviceModelName>VR-6100</DeviceModelName>\
                 <DeviceSerialId>#0</DeviceSerialId></DeviceIndivisuals>"
                .into()),
        ),
    ];
    let packed: Vec<(&str, Vec<u8>)> = files
        .into_iter()
        .map(|(n, c)| match o.compressed {
            true => (
                n,
                ruzstd::encoding::compress_to_vec(
                    &c[..],
                    ruzstd::encoding::CompressionLevel::Fastest,
                ),
            ),
            false => (n, c),
        })
        .collect();
    let refs: Vec<(&str, &[u8])> = packed.iter().map(|(n, c)| (*n, c.as_slice())).collect();
    // A BMP preview: its 14-byte file header and a 40-byte info header.
    let mut bmp = b"BM".to_vec();
    bmp.extend(54u32.to_le_bytes());
    bmp.resize(54, 0);
    let mut out = if o.compressed { b"KPK1" } else { b"KPK0" }.to_vec();
    out.extend((bmp.len() as u32).to_le_bytes());
    out.extend(bmp);
    out.extend(vec![0u8; o.gap]);
    out.extend(zip::write(&refs, false));
    out
}

/// The heights a VK reader gives for `s` (z ≥ 0): counts of `pm` pm.
pub fn vk_heights(s: &Surface, pm: u32) -> Vec<f64> {
    let q = pm as f64 * 1e-12;
    s.z.iter().map(|z| (z / q).round() * q).collect()
}

/// A false-colour image: header, palette, `bits`-bit counts.
fn vk_image(nx: usize, ny: usize, bits: u32, count: impl Fn(usize) -> u64) -> Vec<u8> {
    let mut out = Vec::new();
    let bytes = (nx * ny) as u32 * bits / 8;
    for v in [nx as u32, ny as u32, bits, 0, bytes, 0, 1000] {
        out.extend(v.to_le_bytes());
    }
    out.extend(vec![7u8; 768]);
    for i in 0..nx * ny {
        out.extend(&count(i).to_le_bytes()[..bits as usize / 8]);
    }
    out
}

/// A Keyence VK4 file (`VK3_` when `version` is 3) of `s` (z ≥ 0): heights
/// as `bits`-bit counts of `pm` pm, a 16-bit light image (index i), lengths
/// per pixel s.dx, s.dy in whole pm, taken 2022-10-14 09:23:04 +02:00,
/// with a title and a lens name.
pub fn vk4(s: &Surface, pm: u32, bits: u32, version: u8) -> Vec<u8> {
    let q = pm as f64 * 1e-12;
    let heights = vk_image(s.nx, s.ny, bits, |i| (s.z[i] / q).round() as u64);
    let light = vk_image(s.nx, s.ny, 16, |i| i as u64);
    let cond_at = 12 + 72;
    let height_at = cond_at + 304;
    let light_at = height_at + heights.len();
    let strings_at = light_at + light.len();
    let mut out = format!("VK{version}_").into_bytes();
    out.extend(1u32.to_le_bytes());
    out.extend([0u8; 4]);
    let mut table = [0u32; 18];
    table[0] = cond_at as u32;
    table[3] = light_at as u32;
    table[6] = height_at as u32;
    table[16] = strings_at as u32;
    for v in table {
        out.extend(v.to_le_bytes());
    }
    let mut cond = [0u32; 76];
    cond[..7].copy_from_slice(&[304, 2022, 10, 14, 9, 23, 4]);
    cond[7] = 120;
    cond[18] = 10;
    cond[24] = 200;
    cond[42] = (s.dx / 1e-12).round() as u32;
    cond[43] = (s.dy / 1e-12).round() as u32;
    cond[44] = pm;
    for v in cond {
        out.extend(v.to_le_bytes());
    }
    out.extend(heights);
    out.extend(light);
    for text in ["sample 3", "CF IC EPI Plan 20x"] {
        out.extend((text.len() as u32).to_le_bytes());
        out.extend(text.encode_utf16().flat_map(|u| u.to_le_bytes()));
    }
    out
}

/// A VK6 file: a short header, then a zip holding `vk4` as `Vk4File`.
pub fn vk6(vk4: &[u8], deflate: bool) -> Vec<u8> {
    let mut out = b"VK6\x01".to_vec();
    out.extend([0x11u8; 16]);
    out.extend(zip::write(&[("Vk4File", vk4)], deflate));
    out
}

/// A Sensofar PLUX file of `s` (f32 µm, NaN kept) and a second layer of
/// 2·z: `index.xml` (with a BOM when `bom`), `recipe.txt`, the layers,
/// stored or deflated.
pub fn plux(s: &Surface, bom: bool, deflate: bool) -> Vec<u8> {
    let layer = |f: f64| -> Vec<u8> {
        s.z.iter()
            .flat_map(|z| ((f * z / 1e-6) as f32).to_le_bytes())
            .collect()
    };
    let mut index = if bom {
        b"\xEF\xBB\xBF".to_vec()
    } else {
        Vec::new()
    };
    index.extend(
        format!(
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<xml><GENERAL><DATE>2023-02-01 10:11:12</DATE>\
             <IMAGE_SIZE_X>{}</IMAGE_SIZE_X><IMAGE_SIZE_Y>{}</IMAGE_SIZE_Y><FOV_X>{}</FOV_X>\
             <FOV_Y>{}</FOV_Y></GENERAL><INFO><ITEM_0><NAME>Device</NAME><VALUE>S neox</VALUE>\
             </ITEM_0><ITEM_1><NAME>Objective</NAME><VALUE>Nikon 20x</VALUE></ITEM_1></INFO>\
             <LAYER_0><FILENAME_Z>LAYER_0.raw</FILENAME_Z></LAYER_0>\
             <LAYER_1><FILENAME_Z>LAYER_1.raw</FILENAME_Z></LAYER_1></xml>",
            s.nx,
            s.ny,
            s.dx / 1e-6,
            s.dy / 1e-6
        )
        .into_bytes(),
    );
    let (l0, l1) = (layer(1.0), layer(2.0));
    zip::write(
        &[
            ("index.xml", &index),
            ("recipe.txt", b"<xml><RECIPE/></xml>"),
            ("LAYER_0.raw", &l0),
            ("LAYER_1.raw", &l1),
        ],
        deflate,
    )
}
