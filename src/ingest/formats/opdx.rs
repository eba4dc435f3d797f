//! Bruker Vision64 OPDx (Dektak XT stylus profilers, Contour GT): after
//! the magic `VCA DATA\x01\x00\x00\x55`, a tree of named, typed items
//! (containers, numbers, strings, quantities with units, arrays) ending in
//! a terminator. A profile (`/MetaData/DataKind` = `Surface Profile`) is
//! `/1D_Data/<channel>/Array` (doubles), scaled by `DataScale` (a value
//! with its unit) over `Extent`: the distance from the first point to the
//! last, Δx = Extent / (NumPoints − 1), as the instrument's own text export
//! of the same profile places its points (SurfaceTopography takes Extent /
//! NumPoints, 1/NumPoints larger). A map (`Surface Height`) is
//! `/2D_Data/<PrimaryData2D>/Matrix` (floats, rows along y) with
//! `Dimension2Extent` (x) and `Dimension1Extent` (y) as its scan size,
//! Δx = extent / points (SurfaceTopography's reading; no map with its text
//! export was at hand to settle it). Every 1D channel
//! listed in `/MetaData/1D_Channels/Height` is a channel. Scalars and
//! strings are kept as metadata (the item types as Gwyddion's lextfile.c
//! and SurfaceTopography's OPDx reader read them).

use std::collections::BTreeMap;

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::{check_grid, keys, meta, select_channel, Bytes, Cursor};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};
use crate::units::{parse_unit, Quantity};

/// The registry entry.
pub struct Opdx;

const MAGIC: &[u8] = b"VCA DATA\x01\x00\x00\x55";
const STRUCTURE: &str = "OPDx item";
/// Deepest container nesting accepted (files nest a few levels).
const MAX_DEPTH: usize = 64;

impl Reader for Opdx {
    fn name(&self) -> &'static str {
        "opdx"
    }
    fn description(&self) -> &'static str {
        "Bruker Vision64 OPDx (Dektak XT, Contour GT): profiles and maps"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// An item's value.
#[derive(Debug, Clone)]
enum Item {
    Number(f64),
    Text(String),
    /// A value with a unit symbol (quantities and units).
    Unit(f64, String),
    /// Doubles: where they start and their byte length.
    Doubles(usize, usize),
    /// Floats of a matrix: start, byte length, columns, rows.
    Matrix(usize, usize, usize, usize),
    Texts(Vec<String>),
}

fn name(c: &mut Cursor) -> Result<String> {
    let n = c.u32("name length")? as usize;
    Ok(String::from_utf8_lossy(c.take(n, "name")?).into_owned())
}

fn varlen(c: &mut Cursor) -> Result<usize> {
    Ok(match c.u8("length size")? {
        1 => c.u8("length")? as usize,
        2 => c.u16("length")? as usize,
        4 => c.u32("length")? as usize,
        k => return Err(c.bad("length size", 1, format!("{k}; 1, 2 or 4 expected"))),
    })
}

/// Reads the items from the cursor into `out` (paths `/a/b`); returns
/// at the terminator or the end of a container.
fn items(
    c: &mut Cursor,
    prefix: &str,
    out: &mut BTreeMap<String, Item>,
    depth: usize,
) -> Result<()> {
    loop {
        let start = c.pos();
        let path = format!("{prefix}/{}", name(c)?);
        match c.u8("type")? {
            0x7f => return Ok(()),
            0x7d | 0x46 | 0x47 => {
                if depth >= MAX_DEPTH {
                    return Err(c.error(format!("containers nested deeper than {MAX_DEPTH}")));
                }
                let len = varlen(c)?;
                let end = c.pos() + len;
                items(c, &path, out, depth + 1)?;
                c.skip(2);
                if c.pos() != end {
                    return Err(c.error(format!(
                        "container '{path}' ends at byte {} but its length says {end}",
                        c.pos()
                    )));
                }
            }
            kind => {
                if let Some(item) = item(c, kind, &path, start)? {
                    out.insert(path, item);
                }
            }
        }
    }
}

/// One item of type `kind` (not a container) at the cursor: `None` for
/// the types that hold nothing tribo reads (skipped).
fn item(c: &mut Cursor, kind: u8, path: &str, start: usize) -> Result<Option<Item>> {
    let item = match kind {
        0x01 => Item::Number(c.u8(path)? as f64),
        0x04 => Item::Number(c.i16(path)? as f64),
        0x05 => Item::Number(c.u16(path)? as f64),
        0x06 => Item::Number(c.i32(path)? as f64),
        0x07 => Item::Number(c.u32(path)? as f64),
        0x0a => Item::Number(c.i64(path)? as f64),
        0x0b => Item::Number(c.u64(path)? as f64),
        0x0c => Item::Number(c.f32(path)? as f64),
        0x0d => Item::Number(c.f64(path)?),
        0x0e => {
            name(c)?;
            let n = varlen(c)?;
            c.take(n, path)?;
            return Ok(None);
        }
        0x12 => {
            let n = varlen(c)?;
            Item::Text(String::from_utf8_lossy(c.take(n, path)?).into_owned())
        }
        0x13 => {
            let n = varlen(c)?;
            let end = c.pos() + n;
            let v = c.f64(path)?;
            name(c)?;
            let symbol = name(c)?;
            c.seek(end);
            Item::Unit(v, symbol)
        }
        0x15 => {
            c.take(9, path)?;
            return Ok(None);
        }
        0x18 => {
            let n = varlen(c)?;
            let end = c.pos() + n;
            name(c)?;
            let symbol = name(c)?;
            let v = c.f64(path)?;
            c.seek(end);
            Item::Unit(v, symbol)
        }
        0x40 => {
            name(c)?;
            let n = varlen(c)?;
            let at = c.pos();
            c.take(n, path)?;
            Item::Doubles(at, n)
        }
        0x42 => {
            name(c)?;
            let n = varlen(c)?;
            let end = c.pos() + n;
            let mut v = Vec::new();
            while c.pos() < end {
                v.push(name(c)?);
            }
            Item::Texts(v)
        }
        0x7c => {
            name(c)?;
            let n = varlen(c)?;
            c.take(n, path)?;
            return Ok(None);
        }
        0x00 => {
            name(c)?;
            c.skip(4);
            name(c)?;
            let n = varlen(c)?;
            let rows = c.u32("rows")? as usize;
            let cols = c.u32("columns")? as usize;
            let len = n
                .checked_sub(8)
                .ok_or_else(|| c.error(format!("matrix '{path}' of {n} bytes")))?;
            let at = c.pos();
            c.take(len, path)?;
            Item::Matrix(at, len, cols, rows)
        }
        t => {
            let mut e = c.error(format!("item '{path}' of unknown type 0x{t:02x}"));
            if let crate::error::Error::Structure { offset, .. } = &mut e {
                *offset = start as u64;
            }
            return Err(e);
        }
    };
    Ok(Some(item))
}

fn metres(bytes: &Bytes, symbol: &str, what: &str) -> Result<f64> {
    let s = symbol.replace('Å', "angstrom");
    parse_unit(&s)
        .filter(|u| u.quantity == Quantity::Length)
        .map(|u| u.scale)
        .ok_or_else(|| bytes.error(STRUCTURE, 0, format!("{what} in '{symbol}', not a length")))
}

/// The items of a file, read with errors naming the missing path.
struct File<'a> {
    bytes: &'a Bytes<'a>,
    m: &'a BTreeMap<String, Item>,
}

/// Each channel's grid and where and how its values are stored.
type Channels = (Vec<Grid>, Vec<(usize, Sample, f64)>);

impl File<'_> {
    fn text(&self, k: &str) -> Option<String> {
        match self.m.get(k) {
            Some(Item::Text(t)) => Some(t.clone()),
            _ => None,
        }
    }

    /// A value with its unit.
    fn unit(&self, k: &str) -> Result<(f64, String)> {
        match self.m.get(k) {
            Some(Item::Unit(v, s)) => Ok((*v, s.clone())),
            _ => Err(self
                .bytes
                .error(STRUCTURE, 0, format!("no {k} (a value with a unit)"))),
        }
    }

    /// A count (a whole number ≥ 1).
    fn number(&self, k: &str) -> Result<usize> {
        match self.m.get(k) {
            Some(Item::Number(v)) if *v >= 1.0 && v.fract() == 0.0 => Ok(*v as usize),
            _ => Err(self.bytes.error(STRUCTURE, 0, format!("no {k} (a count)"))),
        }
    }
}

/// A profile file's channels (`Surface Profile`): arrays of doubles.
fn profiles(f: &File) -> Result<Channels> {
    let (mut grids, mut data) = (Vec::new(), Vec::new());
    let names = match f.m.get("/MetaData/1D_Channels/Height") {
        Some(Item::Texts(v)) if !v.is_empty() => v.clone(),
        _ => vec!["Raw".to_string()],
    };
    for n in names {
        let p = format!("/1D_Data/{n}");
        let points = f.number(&format!("{p}/NumPoints"))?;
        let (extent, eu) = f.unit(&format!("{p}/Extent"))?;
        let (scale, su) = f.unit(&format!("{p}/DataScale"))?;
        let Some(Item::Doubles(at, len)) = f.m.get(&format!("{p}/Array")) else {
            return Err(f.bytes.error(STRUCTURE, 0, format!("no {p}/Array")));
        };
        if len.checked_sub(5) != Some(8 * points) {
            return Err(f.bytes.error(
                STRUCTURE,
                *at,
                format!("{p}/Array holds {len} bytes; {points} doubles expected"),
            ));
        }
        let dx = extent * metres(f.bytes, &eu, "extent")? / (points.max(2) - 1) as f64;
        let mut g = Grid::heights(&n, points, 1, dx, dx);
        g.height = !n.eq_ignore_ascii_case("intensity");
        check_grid(f.bytes, STRUCTURE, *at, &g)?;
        grids.push(g);
        data.push((
            *at + 5,
            Sample::F64,
            scale * metres(f.bytes, &su, "data scale")?,
        ));
    }
    Ok((grids, data))
}

/// A map file's channel (`Surface Height`): a matrix of floats.
fn height_map(f: &File) -> Result<Channels> {
    let (mut grids, mut data) = (Vec::new(), Vec::new());
    let n = f
        .text("/MetaData/PrimaryData2D")
        .unwrap_or_else(|| "Raw".into());
    let p = format!("/2D_Data/{n}");
    let (ey, uy) = f.unit(&format!("{p}/Dimension1Extent"))?;
    let (ex, ux) = f.unit(&format!("{p}/Dimension2Extent"))?;
    let (scale, su) = f.unit(&format!("{p}/DataScale"))?;
    let Some(Item::Matrix(at, len, cols, rows)) = f.m.get(&format!("{p}/Matrix")) else {
        return Err(f.bytes.error(STRUCTURE, 0, format!("no {p}/Matrix")));
    };
    let (ny, nx) = (
        f.number(&format!("{p}/Dimension1Points"))?,
        f.number(&format!("{p}/Dimension2Points"))?,
    );
    if (*cols, *rows) != (nx, ny) || *len != 4 * nx * ny {
        return Err(f.bytes.error(
            STRUCTURE,
            *at,
            format!("matrix of {cols} × {rows} in {len} bytes; {nx} × {ny} floats expected"),
        ));
    }
    let dx = ex * metres(f.bytes, &ux, "x extent")? / nx as f64;
    let dy = ey * metres(f.bytes, &uy, "y extent")? / ny as f64;
    let g = Grid::heights(&n, nx, ny, dx, dy);
    check_grid(f.bytes, STRUCTURE, *at, &g)?;
    grids.push(g);
    data.push((
        *at,
        Sample::F32,
        scale * metres(f.bytes, &su, "data scale")?,
    ));
    Ok((grids, data))
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let mut c = bytes.le(MAGIC.len(), STRUCTURE);
    bytes.slice(0, MAGIC.len(), "OPDx magic")?;
    let mut m = BTreeMap::new();
    items(&mut c, "", &mut m, 0)?;
    let f = File { bytes, m: &m };
    let kind = f.text("/MetaData/DataKind").unwrap_or_default();
    let (mut grids, data) = match kind.as_str() {
        "Surface Profile" => profiles(&f)?,
        "Surface Height" => height_map(&f)?,
        k => {
            return Err(bytes.error(
                STRUCTURE,
                0,
                format!("data kind '{k}'; Surface Profile and Surface Height are read"),
            ))
        }
    };
    let i = select_channel(bytes, &grids, options)?;
    let (at, sample, scale) = data[i];
    let g = &grids[i];
    let conv = Conversion::raw(sample).scaled(scale, 0.0);
    grids[i].data = Some(decode(
        bytes,
        at,
        g.nx * g.ny,
        &conv,
        &format!("OPDx '{}' data", g.name),
    )?);
    Ok(Decoded {
        preamble: metadata(&m),
        sections: Vec::new(),
        grids,
    })
}

fn metadata(m: &BTreeMap<String, Item>) -> Vec<MetaEntry> {
    let text = |k: &str| match m.get(k) {
        Some(Item::Text(t)) if !t.is_empty() => Some(t.clone()),
        _ => None,
    };
    let mut out = Vec::new();
    let instrument = ["InstrumentName", "InstrumentSerial", "SerialNumber"]
        .iter()
        .filter_map(|k| text(&format!("/MetaData/MeasurementSettings/{k}")))
        .collect::<Vec<_>>();
    out.push(meta(
        keys::INSTRUMENT,
        format!("Bruker {}", instrument.join(" "))
            .trim()
            .to_string(),
    ));
    if let (Some(d), Some(t)) = (text("/MetaData/Date"), text("/MetaData/Time")) {
        out.push(meta(keys::DATE, format!("{d} {t}")));
    }
    if let Some(t) = text("/MetaData/MeasurementSettings/StylusRadius")
        .or(text("/MetaData/MeasurementSettings/Stylus"))
    {
        out.push(meta(keys::TIP, t));
    }
    for (k, v) in m {
        let v = match v {
            Item::Number(x) => x.to_string(),
            Item::Text(t) => t.clone(),
            Item::Unit(x, s) => format!("{x} {s}"),
            Item::Texts(t) => t.join(", "),
            _ => continue,
        };
        out.push(meta(k, v));
    }
    out
}
