//! Gwyddion native files (`.gwy`, magic `GWYP`): a serialised tree of
//! objects (Gwyddion's "gwyfile format", documented in its user guide).
//! An object is its type name (NUL-terminated), its size (u32) and its
//! components; a component is a name, a one-letter type and a value: `b`
//! `c` (one byte), `i` (i32), `q` (i64), `d` (f64), `s` (a NUL-terminated
//! string), `o` (an object), and arrays `C` `I` `Q` `D` `S` `O` (a u32
//! count, then the items). Everything is little-endian.
//!
//! The top `GwyContainer` holds each image channel as `/N/data` (a
//! `GwyDataField`: `xres`, `yres`, `xreal`, `yreal`, `xoff`, `yoff`,
//! `si_unit_xy`, `si_unit_z`, `data` as xres·yres doubles, row-major from
//! the top row), its title `/N/data/title` and metadata `/N/meta`. Every
//! channel is listed; a channel whose z unit is a length is a height map
//! (in metres, the unit's prefix applied). `/N/mask` is read as the points
//! not measured (mask value > 0.5), as SurfaceTopography does: Gwyddion's
//! importers mark missing data with it. Lateral sizes in a unit that is not
//! a length (pixels) give no spacing. Graphs, spectra, volume and XYZ data
//! are not read.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid, keys, latin1_or_utf8, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Gwy;

impl Reader for Gwy {
    fn name(&self) -> &'static str {
        "gwy"
    }
    fn description(&self) -> &'static str {
        "Gwyddion native .gwy: every image channel, masks as points not measured"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(b"GWYP")
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// Objects nested deeper than this are refused (a crafted file cannot
/// exhaust the stack).
const MAX_DEPTH: usize = 24;

/// A component's value; arrays are where they lie in the file.
#[derive(Debug)]
enum Value {
    Int(i64),
    Double(f64),
    Text(String),
    Object(Object),
    /// A numeric array: element type letter, count, byte offset of the items.
    Array(u8, usize, usize),
    Other,
}

#[derive(Debug)]
struct Object {
    name: String,
    at: usize,
    items: Vec<(String, Value)>,
}

impl Object {
    fn get(&self, key: &str) -> Option<&Value> {
        self.items.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
    fn int(&self, key: &str) -> Option<i64> {
        match self.get(key)? {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }
    fn double(&self, key: &str) -> Option<f64> {
        match self.get(key)? {
            Value::Double(d) => Some(*d),
            Value::Int(i) => Some(*i as f64),
            _ => None,
        }
    }
    fn text(&self, key: &str) -> Option<&str> {
        match self.get(key)? {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }
    fn object(&self, key: &str) -> Option<&Object> {
        match self.get(key)? {
            Value::Object(o) => Some(o),
            _ => None,
        }
    }
    /// A `GwySIUnit` component's unit string.
    fn unit(&self, key: &str) -> String {
        self.object(key)
            .and_then(|u| u.text("unitstr"))
            .unwrap_or("")
            .to_string()
    }
}

struct Parser<'a> {
    bytes: &'a Bytes<'a>,
    pos: usize,
}

impl Parser<'_> {
    /// A NUL-terminated string.
    fn cstr(&mut self, what: &str) -> Result<String> {
        let rest = self.bytes.data.get(self.pos..).unwrap_or(&[]);
        let Some(end) = rest.iter().position(|&c| c == 0) else {
            return Err(self.bytes.error(
                &format!("GWY {what}"),
                self.pos,
                "a string without its terminating NUL before the end of the file (truncated?)",
            ));
        };
        let s = latin1_or_utf8(&rest[..end]);
        self.pos += end + 1;
        Ok(s)
    }

    fn take<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let s = self.bytes.slice(self.pos, N, &format!("GWY {what}"))?;
        self.pos += N;
        Ok(s.try_into().expect("slice of N"))
    }

    fn u32(&mut self, what: &str) -> Result<usize> {
        Ok(u32::from_le_bytes(self.take(what)?) as usize)
    }

    fn object(&mut self, depth: usize) -> Result<Object> {
        let at = self.pos;
        if depth > MAX_DEPTH {
            return Err(self.bytes.error(
                "GWY object",
                at,
                format!("objects nested deeper than {MAX_DEPTH}"),
            ));
        }
        let name = self.cstr("object name")?;
        let size = self.u32("object size")?;
        let start = self.pos;
        let end = start
            .checked_add(size)
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| {
                self.bytes.error(
                    &format!("GWY object '{name}' (size)"),
                    start - 4,
                    format!(
                        "{size} bytes from byte {start}, but the file ends at byte {} (truncated?)",
                        self.bytes.len()
                    ),
                )
            })?;
        let mut items = Vec::new();
        while self.pos < end {
            let key = self.cstr("component name")?;
            let value = self.value(&key, depth)?;
            items.push((key, value));
        }
        if self.pos != end {
            return Err(self.bytes.error(
                &format!("GWY object '{name}'"),
                at,
                format!(
                    "its components end at byte {}, not at its stated end {end}",
                    self.pos
                ),
            ));
        }
        Ok(Object { name, at, items })
    }

    fn value(&mut self, key: &str, depth: usize) -> Result<Value> {
        let [kind] = self.take::<1>("component type")?;
        let what = |s: &str| format!("component '{key}' ({s})");
        Ok(match kind {
            b'b' | b'c' => Value::Int(self.take::<1>(&what("byte"))?[0] as i64),
            b'i' => Value::Int(i32::from_le_bytes(self.take(&what("i32"))?) as i64),
            b'q' => Value::Int(i64::from_le_bytes(self.take(&what("i64"))?)),
            b'd' => Value::Double(f64::from_le_bytes(self.take(&what("double"))?)),
            b's' => Value::Text(self.cstr(&what("string"))?),
            b'o' => Value::Object(self.object(depth + 1)?),
            b'C' | b'I' | b'Q' | b'D' => {
                let n = self.u32(&what("array length"))?;
                let size = match kind {
                    b'C' => 1,
                    b'I' => 4,
                    _ => 8,
                };
                let at = self.pos;
                self.bytes.slice(
                    at,
                    n.saturating_mul(size),
                    &format!("GWY {}", what("array")),
                )?;
                self.pos += n * size;
                Value::Array(kind, n, at)
            }
            b'S' => {
                for _ in 0..self.u32(&what("array length"))? {
                    self.cstr(&what("string array"))?;
                }
                Value::Other
            }
            b'O' => {
                for _ in 0..self.u32(&what("array length"))? {
                    self.object(depth + 1)?;
                }
                Value::Other
            }
            k => {
                return Err(self.bytes.error(
                    &format!("GWY {}", what("type")),
                    self.pos - 1,
                    format!(
                        "type '{}'; one of b c i q d s o C I Q D S O expected",
                        k.escape_ascii()
                    ),
                ))
            }
        })
    }
}

/// One image channel: its field, and where its data and mask lie.
struct Channel<'o> {
    index: u32,
    field: &'o Object,
    mask: Option<&'o Object>,
    title: String,
    meta: Option<&'o Object>,
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let magic = bytes.slice(0, 4, "GWY magic")?;
    if magic != b"GWYP" {
        let what = match magic {
            b"GWYO" => "a Gwyddion 1 file (GWYO)",
            _ => "not a Gwyddion file",
        };
        return Err(bytes.error("GWY magic", 0, format!("{what}; GWYP (Gwyddion 2) is read")));
    }
    let mut p = Parser { bytes, pos: 4 };
    let top = p.object(0)?;
    if top.name != "GwyContainer" {
        return Err(bytes.error(
            "GWY top object",
            4,
            format!("a '{}'; a GwyContainer expected", top.name),
        ));
    }
    let mut channels = channels(&top);
    channels.sort_by_key(|c| c.index);
    if channels.is_empty() {
        return Err(bytes.error(
            "GWY container",
            4,
            "no image channel (/N/data GwyDataField): graphs, spectra and volume data are not read",
        ));
    }
    let mut grids = Vec::new();
    let mut layout = Vec::new();
    for c in &channels {
        let (g, data) = grid(bytes, c)?;
        grids.push(g);
        layout.push(data);
    }
    let i = select_channel(bytes, &grids, options)?;
    let (at, n, scale) = layout[i];
    let conv = Conversion::raw(Sample::F64).scaled(scale, 0.0);
    let structure = format!("GWY channel {} data", channels[i].index);
    let mut data = decode(bytes, at, n, &conv, &structure)?;
    if let Some(mask) = channels[i].mask {
        let (mat, mn) = array(bytes, mask, "data")?;
        if mn != n {
            return Err(bytes.error(
                &format!("GWY channel {} mask", channels[i].index),
                mask.at,
                format!("{mn} points; the channel has {n}"),
            ));
        }
        let raw = bytes.slice(mat, 8 * n, "GWY mask data")?;
        for (v, m) in data.values.iter_mut().zip(raw.chunks_exact(8)) {
            let m = f64::from_le_bytes(m.try_into().expect("8 bytes"));
            if m > 0.5 && !v.is_nan() {
                *v = f64::NAN;
                data.n_invalid += 1;
            }
        }
    }
    grids[i].data = Some(data);
    Ok(Decoded {
        preamble: metadata(&channels[i], &grids[i]),
        sections: Vec::new(),
        grids,
    })
}

/// The `/N/data` data fields of the container, with their titles, masks
/// and metadata.
fn channels(top: &Object) -> Vec<Channel<'_>> {
    let index = |key: &str, tail: &str| -> Option<u32> {
        key.strip_prefix('/')?.strip_suffix(tail)?.parse().ok()
    };
    let find = |n: u32, tail: &str| top.object(&format!("/{n}{tail}"));
    top.items
        .iter()
        .filter_map(|(k, v)| match v {
            Value::Object(o) if o.name == "GwyDataField" => Some((index(k, "/data")?, o)),
            _ => None,
        })
        .map(|(n, field)| Channel {
            index: n,
            field,
            mask: find(n, "/mask").filter(|m| m.name == "GwyDataField"),
            title: top
                .text(&format!("/{n}/data/title"))
                .map(str::to_string)
                .unwrap_or_else(|| format!("Channel {n}")),
            meta: find(n, "/meta").filter(|m| m.name == "GwyContainer"),
        })
        .collect()
}

/// A field's `data` array: offset and count of its doubles.
fn array(bytes: &Bytes, field: &Object, key: &str) -> Result<(usize, usize)> {
    match field.get(key) {
        Some(Value::Array(b'D', n, at)) => Ok((*at, *n)),
        _ => Err(bytes.error(
            "GWY GwyDataField",
            field.at,
            format!("no '{key}' array of doubles"),
        )),
    }
}

/// The grid a channel describes, and (offset, count, scale) of its data.
fn grid(bytes: &Bytes, c: &Channel) -> Result<(Grid, (usize, usize, f64))> {
    let f = c.field;
    let structure = format!("GWY channel {} (GwyDataField)", c.index);
    let res = |k: &str| match f.int(k) {
        Some(v) if v > 0 => Ok(v as usize),
        v => Err(bytes.error(
            &structure,
            f.at,
            format!("{k} is {v:?}; a positive integer expected"),
        )),
    };
    let (nx, ny) = (res("xres")?, res("yres")?);
    let (at, n) = array(bytes, f, "data")?;
    if Some(n) != nx.checked_mul(ny) {
        return Err(bytes.error(
            &structure,
            f.at,
            format!("{n} data points for xres × yres = {nx} × {ny}"),
        ));
    }
    let (xy, z) = (f.unit("si_unit_xy"), f.unit("si_unit_z"));
    let lateral = length_m(&xy);
    let real = |k: &str| f.double(k).unwrap_or(1.0);
    let step = |len: f64, res: usize| lateral.map_or(f64::NAN, |s| len * s / res as f64);
    let mut g = Grid::heights(
        &c.title,
        nx,
        ny,
        step(real("xreal"), nx),
        step(real("yreal"), ny),
    );
    let off = |k: &str| f.double(k).unwrap_or(0.0) * lateral.unwrap_or(0.0);
    (g.x0, g.y0) = (off("xoff"), off("yoff"));
    let scale = match length_m(&z) {
        Some(s) => s,
        None => {
            g.height = false;
            g.unit = z;
            1.0
        }
    };
    if lateral.is_some() {
        check_grid(bytes, &structure, f.at, &g)?;
    }
    Ok((g, (at, n, scale)))
}

fn metadata(c: &Channel, g: &Grid) -> Vec<MetaEntry> {
    let f = c.field;
    let mut m = vec![
        meta(keys::LATERAL_UNIT, f.unit("si_unit_xy")),
        meta(keys::HEIGHT_UNIT, f.unit("si_unit_z")),
        meta(
            keys::LATERAL_SCALE,
            format!(
                "{} {}",
                f.double("xreal").unwrap_or(1.0),
                f.double("yreal").unwrap_or(1.0)
            ),
        ),
        meta("channel", &g.name),
    ];
    for (k, v) in c.meta.iter().flat_map(|o| o.items.iter()) {
        if let Value::Text(s) = v {
            m.push(meta(k, s));
        }
    }
    m
}
