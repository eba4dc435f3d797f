//! Wyko / Bruker Vision OPD: after two bytes, a directory of 24-byte
//! entries (name, type, length, attributes), the first being the
//! directory itself; the blocks' contents follow in the directory's order.
//!
//! Array blocks hold u16 width, u16 height, u16 element size (1, 2 or 4:
//! bytes, 16-bit integers, floats), then the values column by column, each
//! column from the last row to the first. Height arrays (`OPD`, `RAW DATA`,
//! `RAW_DATA`, `SAMPLE_DATA`, `Raw`) are in wavelengths / `Mult`: z =
//! v · λ(nm) / Mult; floats ≥ 1e38 and integers ≥ 32766 are points not
//! measured. `Pixel_size` is in mm, Δy = Δx · `Aspect`. Intensity arrays
//! (`Image`, `Intensity`, `SecArr_0`) are channels in counts. Text and
//! number blocks are kept as metadata (Gwyddion's reading of the format).

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Invalid, Order, Sample};
use crate::ingest::binary::{check_grid, keys, latin1_or_utf8, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Opd;

const MAGIC: &[u8] = b"\x01\x00Directory";
const ENTRY: usize = 24;
const HEIGHTS: [&str; 5] = ["OPD", "RAW DATA", "RAW_DATA", "SAMPLE_DATA", "Raw"];
const INTENSITY: [&str; 3] = ["Image", "Intensity", "SecArr_0"];

impl Reader for Opd {
    fn name(&self) -> &'static str {
        "opd"
    }
    fn description(&self) -> &'static str {
        "Wyko / Bruker Vision OPD (white-light interferometers): height and intensity arrays"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// A directory entry with where its content lies.
struct Block {
    name: String,
    kind: i16,
    at: usize,
    len: usize,
}

fn directory(bytes: &Bytes) -> Result<Vec<Block>> {
    let mut c = bytes.le(2, "OPD directory");
    let name = c.text(16, "name")?;
    let kind = c.i16("type")?;
    let len = c.i32("length")?;
    if name != "Directory" || kind != 1 || len < ENTRY as i32 || len % ENTRY as i32 != 0 {
        return Err(bytes.error(
            "OPD directory",
            2,
            format!("entry '{name}', type {kind}, length {len}; a Directory of type 1 and a multiple of 24 bytes expected"),
        ));
    }
    let count = len as usize / ENTRY;
    bytes.slice(2, len as usize, "OPD directory")?;
    let mut at = 2 + len as usize;
    let mut blocks = Vec::new();
    c.seek(2 + ENTRY);
    for _ in 1..count {
        let entry = c.pos();
        let name = c.text(16, "name")?;
        let kind = c.i16("type")?;
        let len = c.i32("length")?;
        c.skip(2);
        if len < 0 {
            return Err(bytes.error(
                "OPD directory entry",
                entry,
                format!("'{name}' has length {len}"),
            ));
        }
        let len = len as usize;
        bytes.slice(at, len, &format!("OPD block '{name}'"))?;
        if len > 0 {
            blocks.push(Block {
                name,
                kind,
                at,
                len,
            });
        }
        at += len;
    }
    Ok(blocks)
}

/// A text or number block's value: as text, and as a number (the stored
/// binary value, not its text) for number blocks.
fn value(bytes: &Bytes, b: &Block) -> Result<Option<(String, Option<f64>)>> {
    let mut c = bytes.le(b.at, "OPD block");
    let num = |v: f64, t: String| Some((t, Some(v)));
    Ok(match (b.kind, b.len) {
        (5, _) => Some((
            latin1_or_utf8(bytes.slice(b.at, b.len, "OPD text block")?),
            None,
        )),
        (6, 2..) => c.i16(&b.name).map(|v| num(v as f64, v.to_string()))?,
        (7, 4..) => c.f32(&b.name).map(|v| num(v as f64, v.to_string()))?,
        (8, 8..) => c.f64(&b.name).map(|v| num(v, v.to_string()))?,
        (12, 4..) => c.i32(&b.name).map(|v| num(v as f64, v.to_string()))?,
        _ => None,
    })
}

/// A height or intensity array's grid (pixel size in m, NaN when the
/// file gives none) and where and how its values are stored.
fn array(
    bytes: &Bytes,
    b: &Block,
    height: bool,
    pixel: f64,
    aspect: f64,
) -> Result<(Grid, (usize, Sample, Invalid))> {
    let mut c = bytes.le(b.at, "OPD array");
    let (nx, ny, el) = (
        c.u16("width")? as usize,
        c.u16("height")? as usize,
        c.u16("element size")?,
    );
    let (sample, invalid) = match el {
        1 => (Sample::U8, Invalid::None),
        2 => (Sample::I16, Invalid::AtLeast(32766.0)),
        4 => (Sample::F32, Invalid::AtLeast(1e38)),
        e => return Err(c.bad("element size", 2, format!("{e}; 1, 2 or 4 expected"))),
    };
    if 6 + nx * ny * el as usize > b.len {
        return Err(bytes.error(
            &format!("OPD array '{}'", b.name),
            b.at,
            format!(
                "{nx} × {ny} values of {el} bytes do not fit in its {} bytes",
                b.len
            ),
        ));
    }
    let mut g = Grid::heights(&b.name, nx, ny, pixel, pixel * aspect);
    if !height {
        g.height = false;
        g.unit = String::new();
    }
    if g.dx.is_finite() {
        check_grid(bytes, "OPD array", b.at, &g)?;
    }
    Ok((g, (b.at + 6, sample, invalid)))
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let blocks = directory(bytes)?;
    let mut m: Vec<MetaEntry> = vec![meta(keys::INSTRUMENT, "Wyko / Bruker Vision")];
    let mut scalars = std::collections::BTreeMap::new();
    for b in &blocks {
        if let Some((text, number)) = value(bytes, b)? {
            if let Some(v) = number {
                scalars.insert(b.name.clone(), v);
            }
            m.push(meta(&b.name, text));
        }
    }
    let number = |k: &str| scalars.get(k).copied();
    let pixel = number("Pixel_size").map(|p| p.abs() * 1e-3);
    let wavelength = number("Wavelength").map(|w| w * 1e-9);
    let mult = number("Mult").filter(|m| *m != 0.0).unwrap_or(1.0);
    let aspect = number("Aspect").filter(|a| *a > 0.0).unwrap_or(1.0);
    let mut grids = Vec::new();
    let mut arrays = Vec::new();
    for b in blocks.iter().filter(|b| b.kind == 3) {
        let height = HEIGHTS.contains(&b.name.as_str());
        if !height && !INTENSITY.contains(&b.name.as_str()) {
            continue;
        }
        let (g, array) = array(bytes, b, height, pixel.unwrap_or(f64::NAN), aspect)?;
        grids.push(g);
        arrays.push(array);
    }
    if grids.is_empty() {
        return Err(bytes.error("OPD directory", 2, "no height or intensity array"));
    }
    let i = select_channel(bytes, &grids, options)?;
    let scale = match grids[i].height {
        true => {
            wavelength.ok_or_else(|| {
                bytes.error(
                    "OPD directory",
                    2,
                    "no Wavelength block: heights cannot be scaled",
                )
            })? / mult
        }
        false => 1.0,
    };
    let (at, sample, invalid) = arrays[i];
    let conv = Conversion::raw(sample).scaled(scale, 0.0).invalid(invalid);
    let order = Order {
        column_major: true,
        flip_y: true,
    };
    let g = &grids[i];
    let data = decode_grid(
        bytes,
        at,
        (g.nx, g.ny),
        &conv,
        &format!("OPD array '{}'", g.name),
        order,
    )?;
    grids[i].data = Some(data);
    m.push(meta(keys::LATERAL_UNIT, "mm"));
    m.push(meta(keys::HEIGHT_UNIT, "wavelength / Mult"));
    if let Some(p) = number("Pixel_size") {
        m.push(meta(keys::LATERAL_SCALE, format!("{p} {}", p * aspect)));
    }
    m.push(meta(keys::HEIGHT_SCALE, format!("{scale:e} m")));
    Ok(Decoded {
        preamble: m,
        sections: Vec::new(),
        grids,
    })
}
