//! netCDF 3 (classic `CDF\x01`, 64-bit offset `CDF\x02`, CDF-5 `CDF\x05`),
//! read by hand from the format's specification: dimensions, global and
//! variable attributes, variables with their type, shape and offset; data
//! big-endian. (netCDF 4 files are HDF5 and are not read here.)
//!
//! Every numeric variable of one or two dimensions that is not a
//! coordinate variable (one named as its only dimension) is a channel.
//! Heights: the variable `heights` (SurfaceTopography's layout, also
//! `height`, `z`, `topography`), or one whose unit is a length. A
//! two-dimensional variable is (x, y) when its dimensions are named so
//! (SurfaceTopography writes `heights(x, y)`), else (y, x) (the CF and
//! image convention). Spacing: the coordinate variable's `length`
//! attribute over the points (SurfaceTopography), else the step of its
//! values. Units: the variable's `unit` or `units`, else the x axis'.
//! `scale_factor`, `add_offset` are applied; `_FillValue` /
//! `missing_value` and, for heights, a `mask` variable (non-zero) mark
//! points not measured. Record variables are not read.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Invalid, Order, Sample};
use crate::ingest::binary::units::length_m as length;
use crate::ingest::binary::{check_grid, keys, meta, select_channel, Bytes, Cursor};
use crate::ingest::grid::{count_nan, Grid, GridData};
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct NetCdf;

const STRUCTURE: &str = "netCDF header";

impl Reader for NetCdf {
    fn name(&self) -> &'static str {
        "netcdf"
    }
    fn description(&self) -> &'static str {
        "netCDF 3 (classic, 64-bit offset, CDF-5): maps and profiles"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.len() >= 4 && &data[..3] == b"CDF" && matches!(data[3], 1 | 2 | 5)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// An attribute: numbers or text.
#[derive(Debug, Clone)]
enum Value {
    Numbers(Vec<f64>),
    Text(String),
}

impl Value {
    fn number(&self) -> Option<f64> {
        match self {
            Value::Numbers(v) => v.first().copied(),
            Value::Text(t) => t.trim().parse().ok(),
        }
    }
    fn text(&self) -> String {
        match self {
            Value::Text(t) => t.clone(),
            Value::Numbers(v) => v
                .iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join(" "),
        }
    }
}

struct Variable {
    name: String,
    dims: Vec<usize>,
    attrs: BTreeMap<String, Value>,
    kind: u32,
    begin: usize,
}

struct Header {
    dims: Vec<(String, usize)>,
    attrs: BTreeMap<String, Value>,
    vars: Vec<Variable>,
}

fn sample(kind: u32) -> Option<Sample> {
    Some(match kind {
        1 => Sample::I8,
        3 => Sample::I16,
        4 => Sample::I32,
        5 => Sample::F32,
        6 => Sample::F64,
        7 => Sample::U8,
        8 => Sample::U16,
        9 => Sample::U32,
        10 => Sample::I64,
        11 => Sample::U64,
        _ => return None,
    })
}

struct Parser<'a> {
    c: Cursor<'a>,
    cdf5: bool,
    wide: bool,
}

impl Parser<'_> {
    fn count(&mut self, what: &str) -> Result<usize> {
        let n = match self.cdf5 {
            true => self.c.u64(what)?,
            false => self.c.u32(what)? as u64,
        };
        usize::try_from(n).map_err(|_| self.c.bad(what, 8, format!("{n} is too large")))
    }
    fn name(&mut self) -> Result<String> {
        let n = self.count("name length")?;
        let s = String::from_utf8_lossy(self.c.take(n, "name")?).into_owned();
        self.c.skip((4 - n % 4) % 4);
        Ok(s)
    }
    /// A list's tag and count; ABSENT (two zeros) is an empty list.
    fn list(&mut self, tag: u32, what: &str) -> Result<usize> {
        let t = self.c.u32(what)?;
        let n = self.count(what)?;
        match t {
            0 if n == 0 => Ok(0),
            t if t == tag => Ok(n),
            t => Err(self
                .c
                .bad(what, 4, format!("tag {t}; {tag} or absent expected"))),
        }
    }
    fn attributes(&mut self) -> Result<BTreeMap<String, Value>> {
        let n = self.list(12, "attribute list")?;
        let mut out = BTreeMap::new();
        for _ in 0..n {
            let name = self.name()?;
            let kind = self.c.u32("attribute type")?;
            let count = self.count("attribute length")?;
            let v = match (kind, sample(kind)) {
                (2, _) => {
                    let b = self.c.take(count, &name)?;
                    self.c.skip((4 - count % 4) % 4);
                    Value::Text(crate::ingest::binary::latin1_or_utf8(b))
                }
                (_, Some(s)) => {
                    let len = count
                        .checked_mul(s.size())
                        .ok_or_else(|| self.c.error("attribute too long"))?;
                    let raw = self.c.take(len, &name)?;
                    self.c.skip((4 - len % 4) % 4);
                    // Attributes are short; the first 64 values are kept.
                    let head = &raw[..len.min(64 * s.size())];
                    let mut values = vec![0.0; head.len() / s.size()];
                    Conversion::raw(s).big_endian().convert(head, &mut values);
                    Value::Numbers(values)
                }
                (k, None) => {
                    return Err(self.c.bad(
                        "attribute type",
                        4,
                        format!("type {k} of attribute '{name}'"),
                    ))
                }
            };
            out.insert(name, v);
        }
        Ok(out)
    }
}

fn header(bytes: &Bytes) -> Result<Header> {
    let version = *bytes.slice(0, 4, "netCDF magic")?.last().unwrap_or(&0);
    let mut p = Parser {
        c: bytes.be(4, STRUCTURE),
        cdf5: version == 5,
        wide: version != 1,
    };
    p.count("number of records")?;
    let nd = p.list(10, "dimension list")?;
    let mut dims = Vec::new();
    for _ in 0..nd {
        let name = p.name()?;
        dims.push((name, p.count("dimension length")?));
    }
    let attrs = p.attributes()?;
    let nv = p.list(11, "variable list")?;
    let mut vars = Vec::new();
    for _ in 0..nv {
        let name = p.name()?;
        let rank = p.count("rank")?;
        if rank > 64 {
            return Err(p
                .c
                .bad("rank", 4, format!("{rank} dimensions of variable '{name}'")));
        }
        let mut ids = Vec::new();
        for _ in 0..rank {
            let id = p.count("dimension id")?;
            ids.push(id);
        }
        if let Some(i) = ids.iter().find(|&&i| i >= dims.len()) {
            return Err(bytes.error(
                STRUCTURE,
                p.c.pos(),
                format!("variable '{name}' names dimension {i} of {}", dims.len()),
            ));
        }
        let attrs = p.attributes()?;
        let kind = p.c.u32("variable type")?;
        p.count("variable size")?;
        let begin = match p.wide {
            true => p.c.u64("variable offset")? as usize,
            false => p.c.u32("variable offset")? as usize,
        };
        vars.push(Variable {
            name,
            dims: ids,
            attrs,
            kind,
            begin,
        });
    }
    Ok(Header { dims, attrs, vars })
}

impl Header {
    /// The coordinate variable of a dimension: one-dimensional, over the
    /// dimension of its own name.
    fn coordinate(&self, name: &str) -> Option<&Variable> {
        self.vars
            .iter()
            .find(|v| v.name == name && v.dims.len() == 1 && self.dims[v.dims[0]].0 == name)
    }

    /// Spacing (m) and unit of an axis of `n` points: its coordinate's
    /// `length` over the points, or the step of the coordinate values; NaN
    /// without a coordinate.
    fn axis(&self, bytes: &Bytes, name: &str, n: usize) -> Result<(f64, Option<String>)> {
        let Some(v) = self.coordinate(name) else {
            return Ok((f64::NAN, None));
        };
        let unit = unit_of(v);
        let scale = unit.as_deref().and_then(length).unwrap_or(f64::NAN);
        if let Some(l) = v.attrs.get("length").and_then(Value::number) {
            return Ok((l * scale / n as f64, unit));
        }
        let s = sample(v.kind).ok_or_else(|| {
            bytes.error(
                STRUCTURE,
                v.begin,
                format!("coordinate '{name}' is not numeric"),
            )
        })?;
        let g = crate::ingest::binary::decode::decode(
            bytes,
            v.begin,
            n,
            &Conversion::raw(s).big_endian(),
            &format!("netCDF variable '{name}'"),
        )?;
        let step = if n > 1 {
            (g.values[n - 1] - g.values[0]) / (n - 1) as f64
        } else {
            f64::NAN
        };
        Ok((step.abs() * scale, unit))
    }
}

/// A variable's `unit` or `units` attribute.
fn unit_of(v: &Variable) -> Option<String> {
    v.attrs
        .get("unit")
        .or(v.attrs.get("units"))
        .map(Value::text)
}

/// How a channel's variable is stored: the variable, its sample type,
/// whether it is laid out (x, y) rather than (y, x), and its unit.
type Layout<'h> = (&'h Variable, Sample, bool, String);

/// A grid (without data) for every numeric variable of one or two
/// dimensions that is not a coordinate or the mask, and its layout.
fn channels<'h>(bytes: &Bytes, h: &'h Header) -> Result<(Vec<Grid>, Vec<Layout<'h>>)> {
    let dim = |i: usize| h.dims[i].clone();
    let mut grids = Vec::new();
    let mut layout = Vec::new();
    for v in &h.vars {
        let Some(s) = sample(v.kind) else { continue };
        let names: Vec<String> = v.dims.iter().map(|&i| dim(i).0).collect();
        let lens: Vec<usize> = v.dims.iter().map(|&i| dim(i).1).collect();
        if h.coordinate(&v.name).is_some()
            || v.name == "mask"
            || !(1..=2).contains(&v.dims.len())
            || lens.contains(&0)
        {
            continue;
        }
        let xy = names.len() == 2 && names[0] == "x" && names[1] == "y";
        let (nx, ny, xname, yname) = match (lens.len(), xy) {
            (1, _) => (lens[0], 1, names[0].clone(), String::new()),
            (_, true) => (lens[0], lens[1], names[0].clone(), names[1].clone()),
            _ => (lens[1], lens[0], names[1].clone(), names[0].clone()),
        };
        let (dx, xunit) = h.axis(bytes, &xname, nx)?;
        let (dy, _) = if ny > 1 {
            h.axis(bytes, &yname, ny)?
        } else {
            (dx, None)
        };
        let unit = unit_of(v).or(xunit).unwrap_or_default();
        let is_length = length(&unit).is_some();
        let mut g = Grid::heights(&v.name, nx, ny, dx, dy);
        g.height =
            is_length || matches!(v.name.as_str(), "heights" | "height" | "z" | "topography");
        g.unit = if is_length { "m".into() } else { unit.clone() };
        if g.dx.is_finite() && g.dy.is_finite() {
            check_grid(bytes, STRUCTURE, v.begin, &g)?;
        }
        grids.push(g);
        layout.push((v, s, xy, unit));
    }
    Ok((grids, layout))
}

/// Marks as not measured the heights where the `mask` variable over the
/// same dimensions is set.
fn apply_mask(
    bytes: &Bytes,
    mask: &Variable,
    size: (usize, usize),
    order: Order,
    data: &mut GridData,
) -> Result<()> {
    let ms = sample(mask.kind)
        .ok_or_else(|| bytes.error(STRUCTURE, mask.begin, "mask is not numeric"))?;
    let mk = decode_grid(
        bytes,
        mask.begin,
        size,
        &Conversion::raw(ms).big_endian(),
        "netCDF variable 'mask'",
        order,
    )?;
    for (z, m) in data.values.iter_mut().zip(&mk.values) {
        if m.abs() > 0.0 || m.is_nan() {
            *z = f64::NAN;
        }
    }
    data.n_invalid = count_nan(&data.values);
    Ok(())
}

/// The file's attributes and the channel's, the instrument from a `json`
/// attribute when it names one.
fn metadata(h: &Header, v: &Variable, unit: &str) -> Vec<MetaEntry> {
    let mut m: Vec<MetaEntry> = Vec::new();
    if let Some(t) = h.attrs.get("json").map(Value::text) {
        if let Some(inst) = serde_json::from_str::<serde_json::Value>(&t)
            .ok()
            .and_then(|j| j.get("instrument").cloned())
        {
            m.push(meta(keys::INSTRUMENT, inst.to_string()));
        }
    }
    m.push(meta(keys::HEIGHT_UNIT, unit));
    for (k, a) in &h.attrs {
        m.push(meta(k, a.text()));
    }
    for (k, a) in &v.attrs {
        m.push(meta(&format!("{}:{k}", v.name), a.text()));
    }
    m
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let h = header(bytes)?;
    let (mut grids, layout) = channels(bytes, &h)?;
    if grids.is_empty() {
        return Err(bytes.error(STRUCTURE, 0, "no numeric variable of one or two dimensions"));
    }
    let i = select_channel(bytes, &grids, options)?;
    let (v, s, xy, unit) = &layout[i];
    let to_m = length(unit).unwrap_or(1.0);
    let num = |k: &str| v.attrs.get(k).and_then(Value::number);
    let fill = num("_FillValue")
        .or(num("missing_value"))
        .or(default_fill(v.kind));
    let conv = Conversion::raw(*s)
        .big_endian()
        .scaled(
            num("scale_factor").unwrap_or(1.0) * to_m,
            num("add_offset").unwrap_or(0.0) * to_m,
        )
        .invalid(fill.map_or(Invalid::None, Invalid::Equal));
    let g = &grids[i];
    let order = Order {
        column_major: *xy,
        flip_y: false,
    };
    let structure = format!("netCDF variable '{}'", v.name);
    let mut data = decode_grid(bytes, v.begin, (g.nx, g.ny), &conv, &structure, order)?;
    let mask = h.vars.iter().find(|m| m.name == "mask" && m.dims == v.dims);
    if let Some(mask) = mask.filter(|_| grids[i].height) {
        apply_mask(bytes, mask, (g.nx, g.ny), order, &mut data)?;
    }
    grids[i].data = Some(data);
    Ok(Decoded {
        preamble: metadata(&h, v, unit),
        sections: Vec::new(),
        grids,
    })
}

/// netCDF's default fill value of a type: what a point never written
/// holds when the variable declares no `_FillValue` (NC_FILL_*).
fn default_fill(kind: u32) -> Option<f64> {
    Some(match kind {
        1 => -127.0,
        3 => -32767.0,
        4 => -2147483647.0,
        5 => f32::from_bits(0x7cf0_0000) as f64,
        6 => 9.969_209_968_386_869e36,
        7 => 255.0,
        8 => 65535.0,
        9 => 4294967295.0,
        _ => return None,
    })
}
