//! TrueMap TMD (`Binary TrueMap Data File v2.0`): the 32-byte magic line,
//! a comment line ended by CR LF NUL (24 bytes in the files seen, written
//! so by SurfaceTopography and surfalize; any length ending in NUL is
//! read), points along x and y (u32), lengths along x and y and offsets
//! (f32), then ny rows of nx f32 heights. The file states no unit: lengths
//! and heights are micrometres, as SurfaceTopography and surfalize read
//! them (the metadata says so); Δ = length / points. NaN heights are
//! points not measured.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::{check_grid, keys, latin1_or_utf8, meta, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, Reader};

/// The registry entry.
pub struct Tmd;

const MAGIC: &[u8] = b"Binary TrueMap Data File v2.0";
const STRUCTURE: &str = "TMD header";
const UM: f64 = 1e-6;
/// The comment's end in the files seen (magic 32 + comment 24 bytes).
const FIXED_END: usize = 56;

impl Reader for Tmd {
    fn name(&self) -> &'static str {
        "tmd"
    }
    fn description(&self) -> &'static str {
        "TrueMap TMD v2.0 height map (f32, µm)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes))
    }
}

/// Where the comment ends: at 56 when the sizes there account for the
/// file's length, else after the first NUL past the magic line.
fn comment_end(bytes: &Bytes) -> usize {
    let fits = |at: usize| {
        let mut c = bytes.le(at, STRUCTURE);
        match (c.u32("nx"), c.u32("ny")) {
            (Ok(nx), Ok(ny)) => {
                (nx as u64 * ny as u64)
                    .checked_mul(4)
                    .and_then(|n| n.checked_add(at as u64 + 24))
                    == Some(bytes.len() as u64)
            }
            _ => false,
        }
    };
    if fits(FIXED_END) {
        return FIXED_END;
    }
    let tail = bytes.data.get(32..).unwrap_or(&[]);
    tail.iter()
        .take(4096)
        .position(|&b| b == 0)
        .map_or(FIXED_END, |i| 32 + i + 1)
}

fn read(bytes: &Bytes) -> Result<Decoded> {
    let magic = bytes.slice(0, 32, "TMD magic")?;
    let end = comment_end(bytes);
    let comment = latin1_or_utf8(bytes.slice(32, end.saturating_sub(32), "TMD comment")?);
    let mut c = bytes.le(end, STRUCTURE);
    let nx = c.u32("points along x")? as usize;
    let ny = c.u32("points along y")? as usize;
    let lx = c.f32("length along x")? as f64;
    let ly = c.f32("length along y")? as f64;
    let (x0, y0) = (c.f32("offset x")? as f64, c.f32("offset y")? as f64);
    if nx == 0 || ny == 0 {
        return Err(c.bad("points along y", 4, format!("{nx} × {ny} points")));
    }
    let mut g = Grid::heights("Height", nx, ny, lx * UM / nx as f64, ly * UM / ny as f64);
    (g.x0, g.y0) = (x0 * UM, y0 * UM);
    check_grid(bytes, STRUCTURE, end + 8, &g)?;
    let conv = Conversion::raw(Sample::F32).scaled(UM, 0.0);
    g.data = Some(decode(bytes, c.pos(), nx * ny, &conv, "TMD heights")?);
    let trim = |s: &str| {
        s.trim_matches(|ch: char| ch == '\0' || ch.is_whitespace())
            .to_string()
    };
    Ok(Decoded {
        preamble: vec![
            meta(keys::INSTRUMENT, "TrueMap"),
            meta("version", trim(&latin1_or_utf8(magic))),
            meta("comment", trim(&comment)),
            meta(keys::LATERAL_UNIT, "µm (not stated in the file)"),
            meta(keys::HEIGHT_UNIT, "µm (not stated in the file)"),
        ],
        sections: Vec::new(),
        grids: vec![g],
    })
}
