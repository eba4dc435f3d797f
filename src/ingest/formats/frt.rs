//! FRT MicroProf (`.frt`): `FRTM_GLIDERV` and a 4-character version
//! (`1.00`, `1.01`), a u16 block count, then blocks of a u16 id and a size
//! (u32 in 1.00, u64 in 1.01) and their content, little-endian
//! (SurfaceTopography's and Gwyddion's reading of the format). Read here:
//! 0x66 (points along x and y, bits per point: 16 unsigned or 32 signed),
//! 0x67 (scan sizes in m, f64), 0x6c (measuring range, then the height
//! scale factor in m per count, f64) and 0x0b (the heights, row by row).
//! A raw value of 1 is a point not measured (the format's marker). Other
//! blocks are skipped; 0x65 and 0x77 (text) are kept as metadata.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Invalid, Sample};
use crate::ingest::binary::{check_grid, keys, latin1_or_utf8, meta, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, Reader};

/// The registry entry.
pub struct Frt;

const MAGIC: &[u8] = b"FRTM_GLIDERV";
const STRUCTURE: &str = "FRT block";

impl Reader for Frt {
    fn name(&self) -> &'static str {
        "frt"
    }
    fn description(&self) -> &'static str {
        "FRT MicroProf height map (versions 1.00 and 1.01)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes))
    }
}

/// Where each block's content lies: id → (offset, size).
fn blocks(bytes: &Bytes) -> Result<BTreeMap<u16, (usize, usize)>> {
    let version = latin1_or_utf8(bytes.slice(MAGIC.len(), 4, "FRT version")?);
    let wide = match version.as_str() {
        "1.00" => false,
        "1.01" => true,
        v => {
            return Err(bytes.error(
                "FRT version",
                MAGIC.len(),
                format!("'{v}'; versions 1.00 and 1.01 are read"),
            ))
        }
    };
    let mut c = bytes.le(MAGIC.len() + 4, STRUCTURE);
    let count = c.u16("block count")?;
    let mut out = BTreeMap::new();
    for _ in 0..count {
        if c.pos() == bytes.len() {
            break; // Files seen end before their count (SurfaceTopography stops there too).
        }
        let id = c.u16("id")?;
        let size = match wide {
            true => c.u64("size")?,
            false => c.u32("size")? as u64,
        };
        let at = c.pos();
        let size = usize::try_from(size).unwrap_or(usize::MAX);
        bytes.slice(at, size, &format!("FRT block {id:#06x}"))?;
        out.entry(id).or_insert((at, size));
        c.skip(size);
    }
    Ok(out)
}

fn read(bytes: &Bytes) -> Result<Decoded> {
    let b = blocks(bytes)?;
    let need = |id: u16, what: &str| {
        b.get(&id).copied().ok_or_else(|| {
            bytes.error(
                STRUCTURE,
                MAGIC.len() + 4,
                format!("no block {id:#06x} ({what}) in the file"),
            )
        })
    };
    let (at, _) = need(0x66, "grid size")?;
    let mut c = bytes.le(at, "FRT block 0x0066");
    let (nx, ny) = (
        c.u32("points along x")? as usize,
        c.u32("points along y")? as usize,
    );
    let bits = c.u32("bits per point")?;
    let sample = match bits {
        16 => Sample::U16,
        32 => Sample::I32,
        b => return Err(c.bad("bits per point", 4, format!("{b}; 16 or 32 expected"))),
    };
    let (at, _) = need(0x67, "scan size")?;
    let mut c = bytes.le(at, "FRT block 0x0067");
    let (sx, sy) = (c.f64("size along x")?, c.f64("size along y")?);
    let (at, _) = need(0x6c, "height scale")?;
    let mut c = bytes.le(at, "FRT block 0x006c");
    c.u32("measuring range")?;
    let scale = c.f64("height scale factor")?;
    if !(scale.is_finite() && scale != 0.0) {
        return Err(c.bad(
            "height scale factor",
            8,
            format!("{scale}; a finite, non-zero factor expected"),
        ));
    }
    let mut g = Grid::heights("Height", nx, ny, sx / nx as f64, sy / ny as f64);
    check_grid(bytes, "FRT block 0x0067", at, &g)?;
    let (data, size) = need(0x0b, "heights")?;
    if nx * ny * sample.size() != size {
        return Err(bytes.error(
            "FRT block 0x000b",
            data,
            format!("{size} bytes for {nx} × {ny} points of {bits} bits"),
        ));
    }
    let conv = Conversion::raw(sample)
        .scaled(scale, 0.0)
        .invalid(Invalid::Equal(1.0));
    g.data = Some(decode(bytes, data, nx * ny, &conv, "FRT heights")?);
    let mut m = vec![
        meta(keys::INSTRUMENT, "FRT MicroProf"),
        meta(
            "version",
            latin1_or_utf8(&bytes.data[MAGIC.len()..MAGIC.len() + 4]),
        ),
        meta(keys::LATERAL_UNIT, "m"),
        meta(keys::HEIGHT_UNIT, "m"),
        meta(keys::HEIGHT_SCALE, format!("{scale:e} m")),
    ];
    for id in [0x65u16, 0x77] {
        if let Some(&(at, n)) = b.get(&id) {
            m.push(meta(
                &format!("text {id:#06x}"),
                latin1_or_utf8(&bytes.data[at..at + n]),
            ));
        }
    }
    Ok(Decoded {
        preamble: m,
        sections: Vec::new(),
        grids: vec![g],
    })
}
