//! BCR-STM and BCRF (Image Metrology's SPIP exchange format): a text header
//! of `key = value` lines, `fileformat = bcrstm` (16-bit integers) or
//! `bcrf` (32-bit floats) first, in Latin-1 or, for the `_unicode`
//! variants, UTF-16 LE; `headersize` gives its length in characters (2048
//! or 4096), after which come `xpixels` × `ypixels` values, row by row,
//! little-endian when `intelmode = 1`. The lateral sizes are `xlength`,
//! `ylength` in `xunit`/`yunit` (nm when absent); z = raw · `bit2nm` in
//! `zunit` (nm when absent), as SurfaceTopography reads it; raw values
//! equal to `voidpixels` (for floats: within 1e-6 of it, as the header
//! prints it to 7 digits) are points not measured.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Invalid, Sample};
use crate::ingest::binary::keyed::{Keyed, Split};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid, keys, meta, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Bcr;

const STRUCTURE: &str = "BCR header";
const MAGIC: &str = "fileformat = bcr";

impl Reader for Bcr {
    fn name(&self) -> &'static str {
        "bcr"
    }
    fn description(&self) -> &'static str {
        "BCR-STM / BCRF height map (SPIP exchange format; Latin-1 or UTF-16 header)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        let head = &data[..data.len().min(2 * MAGIC.len())];
        head.starts_with(MAGIC.as_bytes()) || utf16(head).starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes))
    }
}

/// UTF-16 LE bytes as text (a lone trailing byte dropped).
fn utf16(b: &[u8]) -> String {
    let units: Vec<u16> = b
        .chunks_exact(2)
        .map(|c| u16::from_le_bytes([c[0], c[1]]))
        .collect();
    String::from_utf16_lossy(&units)
}

/// The header as Latin-1/UTF-8 bytes and its length in the file.
fn header(bytes: &Bytes) -> Result<(Vec<u8>, usize)> {
    let wide = !bytes.data.starts_with(MAGIC.as_bytes());
    let width = if wide { 2 } else { 1 };
    // The size is in the first lines: read the smallest header first.
    let first = &bytes.data[..bytes.len().min(2048 * width)];
    let text = |b: &[u8]| match wide {
        true => utf16(b).into_bytes(),
        false => b.to_vec(),
    };
    let probe = Keyed::parse(*bytes, STRUCTURE, (&text(first), 0), Split::At('='));
    let chars: usize = probe.number("", "headersize")?;
    let len = chars.saturating_mul(width);
    let raw = bytes.slice(0, len, "BCR header")?;
    Ok((text(raw), len))
}

fn read(bytes: &Bytes) -> Result<Decoded> {
    let (text, len) = header(bytes)?;
    let end = text.iter().position(|&b| b == 0).unwrap_or(text.len());
    let h = Keyed::parse(*bytes, STRUCTURE, (&text[..end], 0), Split::At('='));
    let format = h.text("", "fileformat")?;
    let sample = match format.trim_end_matches("_unicode") {
        "bcrstm" => Sample::I16,
        "bcrf" => Sample::F32,
        f => return Err(h.error("", "fileformat", format!("'{f}'; bcrstm or bcrf expected"))),
    };
    let (nx, ny): (usize, usize) = (h.number("", "xpixels")?, h.number("", "ypixels")?);
    let unit = |k: &str| {
        let u = h.get("", k).unwrap_or("nm");
        length_m(u).ok_or_else(|| h.error("", k, format!("'{u}'; a length unit expected")))
    };
    let (fx, fy, fz) = (unit("xunit")?, unit("yunit")?, unit("zunit")?);
    let (sx, sy): (f64, f64) = (h.number("", "xlength")?, h.number("", "ylength")?);
    let mut g = Grid::heights("Height", nx, ny, sx * fx / nx as f64, sy * fy / ny as f64);
    check_grid(bytes, STRUCTURE, 0, &g)?;
    let bit2nm: f64 = match h.get("", "bit2nm") {
        Some(_) => h.number("", "bit2nm")?,
        None => 1.0,
    };
    let mut conv = Conversion::raw(sample).scaled(bit2nm * fz, 0.0);
    if h.get("", "intelmode") == Some("0") {
        conv = conv.big_endian();
    }
    if let Some(v) = h.get("", "voidpixels").and_then(|v| v.parse::<f64>().ok()) {
        conv = conv.invalid(match sample {
            Sample::F32 if v > 0.0 => Invalid::AtLeast(v * (1.0 - 1e-6)),
            _ => Invalid::Equal(v),
        });
    }
    g.data = Some(decode(bytes, len, nx * ny, &conv, "BCR data")?);
    Ok(Decoded {
        preamble: metadata(&h, bit2nm * fz),
        sections: Vec::new(),
        grids: vec![g],
    })
}

fn metadata(h: &Keyed, scale: f64) -> Vec<MetaEntry> {
    let mut m = vec![meta(keys::INSTRUMENT, "BCR / SPIP")];
    for (k, key) in [("xunit", keys::LATERAL_UNIT), ("zunit", keys::HEIGHT_UNIT)] {
        m.push(meta(key, h.get("", k).unwrap_or("nm (not stated)")));
    }
    m.push(meta(keys::HEIGHT_SCALE, format!("{scale:e} m")));
    m.extend(h.meta_of(""));
    m
}
