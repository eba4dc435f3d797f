//! A height map as a small PNG (RGB, uncompressed deflate blocks), for
//! embedding in an SVG as a data URI: a 200 × 200 image is 120 kB, where
//! the same map as SVG rectangles would be megabytes. Written here rather
//! than through an image crate: the format needs 60 lines, and the report
//! builds no native libraries.

use base64::Engine as _;

/// Viridis, sampled at five stops (the map is interpolated between them).
const STOPS: [(u8, u8, u8); 5] = [
    (68, 1, 84),
    (59, 82, 139),
    (33, 145, 140),
    (94, 201, 98),
    (253, 231, 37),
];

/// The colour of `t` in [0, 1] (clamped; non-finite is grey).
pub fn colour(t: f64) -> (u8, u8, u8) {
    if !t.is_finite() {
        return (128, 128, 128);
    }
    let s = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let i = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    (mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Averages a `rows × cols` row-major grid down to at most `max` cells
/// a side (non-finite cells are left out of the averages).
pub fn shrink(values: &[f64], rows: usize, cols: usize, max: usize) -> (Vec<f64>, usize, usize) {
    let k = rows.max(cols).div_ceil(max.max(1)).max(1);
    let (r2, c2) = (rows.div_ceil(k), cols.div_ceil(k));
    let mut sum = vec![0.0; r2 * c2];
    let mut count = vec![0u32; r2 * c2];
    for r in 0..rows {
        for c in 0..cols {
            let v = values[r * cols + c];
            if v.is_finite() {
                sum[(r / k) * c2 + c / k] += v;
                count[(r / k) * c2 + c / k] += 1;
            }
        }
    }
    let out = sum
        .iter()
        .zip(&count)
        .map(|(s, n)| if *n > 0 { s / *n as f64 } else { f64::NAN })
        .collect();
    (out, r2, c2)
}

/// The PNG file of a `rows × cols` grid, coloured from its finite range.
pub fn encode(values: &[f64], rows: usize, cols: usize) -> Vec<u8> {
    let (lo, hi) = super::downsample::range(values).unwrap_or((0.0, 1.0));
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut raw = Vec::with_capacity(rows * (3 * cols + 1));
    for r in 0..rows {
        raw.push(0); // filter: none
        for v in &values[r * cols..(r + 1) * cols] {
            let (cr, cg, cb) = colour((v - lo) / span);
            raw.extend([cr, cg, cb]);
        }
    }
    let mut ihdr = Vec::with_capacity(13);
    ihdr.extend((cols as u32).to_be_bytes());
    ihdr.extend((rows as u32).to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]); // 8-bit RGB, deflate, no filter, no interlace
    let mut png = vec![0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];
    chunk(&mut png, b"IHDR", &ihdr);
    chunk(&mut png, b"IDAT", &zlib_stored(&raw));
    chunk(&mut png, b"IEND", &[]);
    png
}

/// `data:image/png;base64,…` of [`encode`].
pub fn data_uri(values: &[f64], rows: usize, cols: usize) -> String {
    let b64 = base64::engine::general_purpose::STANDARD.encode(encode(values, rows, cols));
    format!("data:image/png;base64,{b64}")
}

fn chunk(out: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    out.extend((data.len() as u32).to_be_bytes());
    let start = out.len();
    out.extend(kind);
    out.extend(data);
    let crc = crc32(&out[start..]);
    out.extend(crc.to_be_bytes());
}

/// A zlib stream of stored (uncompressed) deflate blocks.
fn zlib_stored(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0x78, 0x01];
    let mut blocks = data.chunks(65_535).peekable();
    if blocks.peek().is_none() {
        out.extend([1, 0, 0, 0xff, 0xff]);
    }
    while let Some(b) = blocks.next() {
        out.push(u8::from(blocks.peek().is_none()));
        let len = b.len() as u16;
        out.extend(len.to_le_bytes());
        out.extend((!len).to_le_bytes());
        out.extend(b);
    }
    out.extend(adler32(data).to_be_bytes());
    out
}

fn adler32(data: &[u8]) -> u32 {
    let (mut a, mut b) = (1u32, 0u32);
    for chunk in data.chunks(5552) {
        for &x in chunk {
            a += x as u32;
            b += a;
        }
        a %= 65_521;
        b %= 65_521;
    }
    (b << 16) | a
}

fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &x in data {
        crc ^= x as u32;
        for _ in 0..8 {
            crc = (crc >> 1) ^ (0xEDB8_8320 & (crc & 1).wrapping_neg());
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checksums_match_published_values() {
        // RFC 1950 / ISO 3309 check values.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(adler32(b"Wikipedia"), 0x11E6_0398);
    }

    #[test]
    fn png_has_the_declared_layout() {
        let png = encode(&[0.0, 1.0, 2.0, 3.0, 4.0, f64::NAN], 2, 3);
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        assert_eq!(&png[12..16], b"IHDR");
        assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 3);
        assert_eq!(u32::from_be_bytes(png[20..24].try_into().unwrap()), 2);
        // IDAT holds 2 rows of (1 + 3*3) bytes, stored, plus zlib framing.
        let idat_len = u32::from_be_bytes(png[33..37].try_into().unwrap()) as usize;
        assert_eq!(idat_len, 2 + 5 + 20 + 4);
        assert_eq!(&png[png.len() - 8..png.len() - 4], b"IEND");
    }

    #[test]
    fn shrink_averages_blocks() {
        let v: Vec<f64> = (0..16).map(|i| i as f64).collect();
        let (s, r, c) = shrink(&v, 4, 4, 2);
        assert_eq!((r, c), (2, 2));
        assert_eq!(s, vec![2.5, 4.5, 10.5, 12.5]);
    }

    #[test]
    fn colours_span_the_map() {
        assert_eq!(colour(0.0), STOPS[0]);
        assert_eq!(colour(1.0), STOPS[4]);
        assert_eq!(colour(f64::NAN), (128, 128, 128));
    }
}
