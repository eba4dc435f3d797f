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
