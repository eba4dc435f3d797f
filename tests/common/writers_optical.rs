//! Small writers of optical profiler formats (AL3D, FRT, BCR, TMD, VK4,
//! PLUX, ZON), after their public descriptions: the fixtures of the
//! round-trip and variant tests.

use crate::common::writers::Surface;

/// A TrueMap TMD v2.0 file: heights and lengths in µm (f32), the comment
/// line `comment` + CR LF NUL (24 bytes as TrueMap writes it when
/// `fixed`, else as long as it is), offsets (µm).
pub fn tmd(s: &Surface, comment: &str, fixed: bool, offset_um: (f32, f32)) -> Vec<u8> {
    let mut out = b"Binary TrueMap Data File v2.0\r\n\0".to_vec();
    let mut c = comment.as_bytes().to_vec();
    if fixed {
        c.resize(21, b' ');
    }
    c.extend(b"\r\n\0");
    out.extend(c);
    out.extend((s.nx as u32).to_le_bytes());
    out.extend((s.ny as u32).to_le_bytes());
    for v in [s.nx as f64 * s.dx / 1e-6, s.ny as f64 * s.dy / 1e-6] {
        out.extend((v as f32).to_le_bytes());
    }
    out.extend(offset_um.0.to_le_bytes());
    out.extend(offset_um.1.to_le_bytes());
    for z in &s.z {
        out.extend(((z / 1e-6) as f32).to_le_bytes());
    }
    out
}

/// An Alicona AL3D file: depth in m (f32, rows padded to 8 bytes),
/// `invalid` points as `InvalidPixelValue`, `planes` texture planes
/// (plane p holds (p + 1) · index mod 256), the tags in the order given
/// reversed when `reverse`.
pub fn al3d(s: &Surface, invalid: &[usize], planes: usize, reverse: bool) -> Vec<u8> {
    const INVALID: f32 = 3e15;
    let stride = (s.nx * 4).div_ceil(8) * 8;
    let tstride = s.nx.div_ceil(8) * 8;
    let n_tags = 9;
    let depth_at = 17 + 52 * (2 + n_tags);
    let texture_at = depth_at + stride * s.ny;
    let tag = |k: &str, v: String| {
        let mut t = vec![0u8; 52];
        t[..k.len()].copy_from_slice(k.as_bytes());
        t[20..20 + v.len()].copy_from_slice(v.as_bytes());
        t[50..].copy_from_slice(b"\r\n");
        t
    };
    let mut tags = vec![
        tag("Cols", s.nx.to_string()),
        tag("Rows", s.ny.to_string()),
        tag("PixelSizeXMeter", format!("{:e}", s.dx)),
        tag("PixelSizeYMeter", format!("{:e}", s.dy)),
        tag("DepthImageOffset", depth_at.to_string()),
        tag("InvalidPixelValue", "3.000000028082e+15".into()),
        tag(
            "TextureImageOffset",
            if planes > 0 {
                texture_at.to_string()
            } else {
                "0".into()
            },
        ),
        tag("NumberOfPlanes", planes.to_string()),
        tag("CreatingApplication", "MeasureSuite 5.3.6".into()),
    ];
    if reverse {
        tags.reverse();
    }
    let mut out = b"AliconaImaging\x00\r\n".to_vec();
    out.extend(tag("Version", "1".into()));
    out.extend(tag("TagCount", n_tags.to_string()));
    out.extend(tags.concat());
    for r in 0..s.ny {
        let start = out.len();
        for c in 0..s.nx {
            let i = r * s.nx + c;
            let v = if invalid.contains(&i) {
                INVALID
            } else {
                s.z[i] as f32
            };
            out.extend(v.to_le_bytes());
        }
        out.resize(start + stride, 0xee);
    }
    for p in 0..planes {
        for r in 0..s.ny {
            let start = out.len();
            out.extend((0..s.nx).map(|c| ((p + 1) * (r * s.nx + c) % 256) as u8));
            out.resize(start + tstride, 0xee);
        }
    }
    out
}
