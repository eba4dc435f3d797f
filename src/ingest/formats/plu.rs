//! Sensofar PLU (PLu, PLµ 2300, S neox ...): a 500-byte little-endian
//! header (date text, comment, calibration, measurement settings), then
//! each layer as its size, 32-bit floats in µm and the layer's min and max.
//! The value 1000001 marks a point not measured. Lateral steps are in µm
//! per pixel; a profile is a layer of one row. What follows the layers (a
//! colour image in newer versions) is not read.
//!
//! The format has no magic number: a file is taken for PLU when its date
//! and comment fields are text, its measurement type and layer count are
//! in range, and the first layer's size equals the calibration's and fits
//! in the file.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Invalid, Sample};
use crate::ingest::binary::{check_grid, keys, meta, select_channel, unix_date, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Plu;

const HEADER: usize = 500;
const NOT_MEASURED: f64 = 1_000_001.0;
const UM: f64 = 1e-6;

impl Reader for Plu {
    fn name(&self) -> &'static str {
        "plu"
    }
    fn description(&self) -> &'static str {
        "Sensofar PLU (confocal/interferometric profilers): maps and profiles in µm"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        sniff(data).unwrap_or(false)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

fn text_field(b: &[u8]) -> bool {
    let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    end > 0
        && b[..end]
            .iter()
            .all(|&c| c == b'\t' || (0x20..0x7f).contains(&c) || c >= 0xa0)
}

fn sniff(d: &[u8]) -> Option<bool> {
    let u32_at = |o: usize| Some(u32::from_le_bytes(d.get(o..o + 4)?.try_into().ok()?));
    let (cy, cx) = (u32_at(388)? as u64, u32_at(392)? as u64);
    let (ly, lx) = (u32_at(HEADER)? as u64, u32_at(HEADER + 4)? as u64);
    let layers = *d.get(489)?;
    Some(
        text_field(&d[..128])
            && text_field(&d[132..388])
            && u32_at(428)? <= 6
            && (1..=16).contains(&layers)
            && (cy, cx) == (ly, lx)
            && lx > 0
            && ly > 0
            && (HEADER as u64 + 8 + 4 * lx * ly) <= d.len() as u64,
    )
}

/// Each layer's grid (its size read, no data yet) and where its floats
/// start: a layer is its size, the floats, then min and max.
fn layer_grids(
    bytes: &Bytes,
    layers: usize,
    (mx, my): (f64, f64),
) -> Result<(Vec<Grid>, Vec<usize>)> {
    let mut grids = Vec::new();
    let mut starts = Vec::new();
    let mut at = HEADER;
    for k in 0..layers {
        let mut l = bytes.le(at, "PLU layer size");
        let (ny, nx) = (l.u32("rows")? as usize, l.u32("columns")? as usize);
        let name = if layers == 1 {
            "Height".to_string()
        } else {
            format!("Height {}", k + 1)
        };
        let g = Grid::heights(
            &name,
            nx,
            ny,
            mx * UM,
            if ny == 1 { mx * UM } else { my * UM },
        );
        check_grid(bytes, "PLU layer size", at, &g)?;
        starts.push(at + 8);
        at = nx
            .checked_mul(ny)
            .and_then(|n| n.checked_mul(4))
            .and_then(|n| n.checked_add(at + 16))
            .ok_or_else(|| bytes.error("PLU layer size", at, "overflows"))?;
        grids.push(g);
    }
    Ok((grids, starts))
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let mut c = bytes.le(0, "PLU header");
    let date = c.text(128, "date")?;
    let time = c.u32("time")?;
    let comment = c.text(256, "comment")?;
    c.seek(388 + 12);
    let dy_multip = c.f32("dy multiplier")?;
    let (mx, my) = (
        c.f32("µm per pixel x")? as f64,
        c.f32("µm per pixel y")? as f64,
    );
    let (ox, oy) = (c.f32("x offset")?, c.f32("y offset")?);
    c.skip(4);
    let oz = c.f32("z offset")?;
    let kind = c.u32("measurement type")?;
    let algorithm = c.u32("algorithm")?;
    let method = c.u32("method")?;
    let objective = c.u32("objective")?;
    c.seek(489);
    let layers = c.u8("number of layers")? as usize;
    let version = c.u8("version")?;
    if layers == 0 {
        return Err(c.bad("number of layers", 1, "no layer"));
    }
    let (mut grids, starts) = layer_grids(bytes, layers, (mx, my))?;
    let i = select_channel(bytes, &grids, options)?;
    let conv = Conversion::raw(Sample::F32)
        .scaled(UM, 0.0)
        .invalid(Invalid::Equal(NOT_MEASURED));
    let g = &grids[i];
    grids[i].data = Some(decode(
        bytes,
        starts[i],
        g.nx * g.ny,
        &conv,
        &format!("PLU layer {}", i + 1),
    )?);
    let mut m: Vec<MetaEntry> = vec![meta(keys::INSTRUMENT, "Sensofar")];
    if !date.is_empty() {
        m.push(meta(
            keys::DATE,
            unix_date(time as i32).unwrap_or(date.clone()),
        ));
    }
    m.push(meta(
        keys::OBJECTIVE,
        format!("Sensofar objective code {objective}"),
    ));
    m.push(meta(keys::LATERAL_UNIT, "um"));
    m.push(meta(keys::HEIGHT_UNIT, "um"));
    m.push(meta(keys::LATERAL_SCALE, format!("{mx} {my}")));
    m.push(meta(keys::HEIGHT_SCALE, "1"));
    for (k, v) in [
        ("date", date),
        ("comment", comment),
        ("measurement type", kind.to_string()),
        ("algorithm", algorithm.to_string()),
        ("method", method.to_string()),
        ("version", version.to_string()),
        ("dy multiplier", dy_multip.to_string()),
        ("offset x y z (um)", format!("{ox} {oy} {oz}")),
    ] {
        if !v.is_empty() {
            m.push(meta(k, v));
        }
    }
    Ok(Decoded {
        preamble: m,
        sections: Vec::new(),
        grids,
    })
}
