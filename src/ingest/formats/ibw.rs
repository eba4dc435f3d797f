//! Igor Pro binary wave, version 5 (`.ibw`; Asylum Research / Oxford
//! Instruments AFMs), after WaveMetrics' Technical Note PTN003: a 64-byte
//! BinHeader5 (version 5, checksum, the sizes of the sections that follow
//! the data), a 320-byte WaveHeader5 (points, type, dimensions, scale
//! factors sfA/sfB, units), the data, then formula, note, extended units
//! and dimension labels. The byte order is the writer's: the version reads
//! 5 in one of them; the 16-bit words of both headers sum to 0.
//!
//! An AFM image is one wave of nx × ny × layers, the first dimension (x)
//! varying fastest; each layer is a channel, named by the third
//! dimension's labels (32 bytes each, the first naming the dimension),
//! `no name (N)` where a label is missing (SurfaceTopography's naming).
//! The spacing is sfA (x0, y0 from sfB); rows are oriented as
//! SurfaceTopography and Gwyddion orient them (the wave's last column is
//! row 0), so that a point is the same point in all three. The wave has one data
//! unit for all its layers: Asylum writes `m` for height, amplitude and
//! deflection alike, so a layer is a height channel by its name
//! (`Height…`, `ZSensor…`, `Topography…`; else a lone layer), the others
//! keep the unit as written. The note (`key: value` lines) is kept as
//! metadata; `MicroscopeModel`, `Date` and `Time` give the standard keys.

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Order, Sample};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{
    check_grid_or_unspaced, iso_date, keys, latin1_or_utf8, meta, select_channel, Bytes, Cursor,
};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Ibw;

const STRUCTURE: &str = "IBW header";
/// BinHeader5 and WaveHeader5: where the data starts.
const HEADERS: usize = 64 + 320;
const LABEL: usize = 32;

impl Reader for Ibw {
    fn name(&self) -> &'static str {
        "ibw"
    }
    fn description(&self) -> &'static str {
        "Igor Pro binary wave v5 (Asylum Research AFM): one channel per layer"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.len() >= HEADERS && byte_order(data).is_some() && checksum(data, big(data)) == 0
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// Whether the version reads 5 big-endian (else little-endian).
fn big(data: &[u8]) -> bool {
    data.get(..2) == Some(&[0, 5])
}

/// `Some` when the first two bytes are version 5 in one byte order.
fn byte_order(data: &[u8]) -> Option<bool> {
    match data.get(..2)? {
        [5, 0] => Some(false),
        [0, 5] => Some(true),
        _ => None,
    }
}

/// The sum of the headers' 16-bit words (0 in a sound file).
fn checksum(data: &[u8], big: bool) -> u16 {
    data[..HEADERS].chunks_exact(2).fold(0u16, |s, w| {
        let v = match big {
            true => u16::from_be_bytes([w[0], w[1]]),
            false => u16::from_le_bytes([w[0], w[1]]),
        };
        s.wrapping_add(v)
    })
}

/// The sizes BinHeader5 gives, in file order after the data.
struct Sizes {
    wave: usize,
    formula: usize,
    note: usize,
    data_units: usize,
    dim_units: [usize; 4],
    dim_labels: [usize; 4],
}

fn sizes(c: &mut Cursor) -> Result<Sizes> {
    let size = |c: &mut Cursor, field: &str| -> Result<usize> {
        let v = c.i32(field)?;
        usize::try_from(v).map_err(|_| c.bad(field, 4, format!("{v}; a size ≥ 0 expected")))
    };
    let wave = size(c, "wfmSize")?;
    let formula = size(c, "formulaSize")?;
    let note = size(c, "noteSize")?;
    let data_units = size(c, "dataEUnitsSize")?;
    let mut dim_units = [0; 4];
    for d in &mut dim_units {
        *d = size(c, "dimEUnitsSize")?;
    }
    let mut dim_labels = [0; 4];
    for d in &mut dim_labels {
        *d = size(c, "dimLabelsSize")?;
    }
    Ok(Sizes {
        wave,
        formula,
        note,
        data_units,
        dim_units,
        dim_labels,
    })
}

/// What WaveHeader5 says of the wave.
struct Wave {
    name: String,
    points: usize,
    sample: Sample,
    dims: [usize; 4],
    step: [f64; 2],
    start: [f64; 2],
    /// Data unit and the x and y units, as in the header (extended units
    /// replace them where given).
    units: [String; 3],
}

fn sample_type(c: &Cursor, t: i16) -> Result<Sample> {
    Ok(match t {
        2 => Sample::F32,
        4 => Sample::F64,
        8 => Sample::I8,
        0x10 => Sample::I16,
        0x20 => Sample::I32,
        0x48 => Sample::U8,
        0x50 => Sample::U16,
        0x60 => Sample::U32,
        _ => {
            return Err(c.bad(
                "type",
                2,
                format!("{t:#x}; real numeric waves (2, 4, 8, 0x10, 0x20, unsigned 0x40+) are read, not text or complex"),
            ))
        }
    })
}

fn wave_header(bytes: &Bytes, big: bool) -> Result<Wave> {
    let mut c = cursor(bytes, 64, big);
    c.skip(12);
    let points = c.i32("npnts")?;
    let t = c.i16("type")?;
    let sample = sample_type(&c, t)?;
    c.skip(10);
    let name = c.text(32, "bname")?;
    c.seek(64 + 68);
    let mut dims = [0usize; 4];
    for d in &mut dims {
        let v = c.i32("nDim")?;
        *d = usize::try_from(v).map_err(|_| c.bad("nDim", 4, format!("{v} points")))?;
    }
    let (mut step, mut start) = ([0.0; 2], [0.0; 2]);
    step[0] = c.f64("sfA")?;
    step[1] = c.f64("sfA")?;
    c.skip(16);
    start[0] = c.f64("sfB")?;
    start[1] = c.f64("sfB")?;
    c.skip(16);
    let data = c.text(4, "dataUnits")?;
    let (x, y) = (c.text(4, "dimUnits")?, c.text(4, "dimUnits")?);
    Ok(Wave {
        name,
        points: usize::try_from(points).unwrap_or(usize::MAX),
        sample,
        dims,
        step,
        start,
        units: [data, x, y],
    })
}

fn cursor<'a>(bytes: &Bytes<'a>, at: usize, big: bool) -> Cursor<'a> {
    match big {
        true => bytes.be(at, STRUCTURE),
        false => bytes.le(at, STRUCTURE),
    }
}

/// The sections after the data: note, extended units, layer labels.
struct Tail {
    note: String,
    units: [Option<String>; 3],
    labels: Vec<String>,
}

fn tail(bytes: &Bytes, s: &Sizes, mut at: usize) -> Result<Tail> {
    let mut take = |n: usize, what: &str| -> Result<&[u8]> {
        let b = bytes.slice(at, n, &format!("IBW {what}"))?;
        at += n;
        Ok(b)
    };
    take(s.formula, "formula")?;
    let note = latin1_or_utf8(take(s.note, "note")?);
    let unit = |b: &[u8]| Some(latin1_or_utf8(b)).filter(|u| !u.is_empty());
    let data = unit(take(s.data_units, "extended data units")?);
    let mut dim = [None, None, None, None];
    for (d, &n) in dim.iter_mut().zip(&s.dim_units) {
        *d = unit(take(n, "extended dimension units")?);
    }
    take(s.dim_labels[0] + s.dim_labels[1], "dimension labels")?;
    let labels = take(s.dim_labels[2], "layer labels")?
        .chunks(LABEL)
        .skip(1)
        .map(latin1_or_utf8)
        .collect();
    let [x, y, ..] = dim;
    Ok(Tail {
        note,
        units: [data, x, y],
        labels,
    })
}

/// Layer names: the labels, `no name (N)` where one is missing or empty.
fn layer_names(labels: &[String], layers: usize) -> Vec<String> {
    let mut unnamed = 0;
    (0..layers)
        .map(|k| match labels.get(k).filter(|l| !l.is_empty()) {
            Some(l) => l.clone(),
            None => {
                unnamed += 1;
                format!("no name ({unnamed})")
            }
        })
        .collect()
}

/// Whether a layer holds heights, by its (Asylum) name.
fn is_height(name: &str) -> bool {
    let n = name.to_ascii_lowercase();
    ["height", "zsensor", "topography"]
        .iter()
        .any(|p| n.starts_with(p))
}

/// The note's `key: value` lines (CR, LF or CR LF) as metadata, and the
/// standard keys they give.
fn note_meta(note: &str) -> Vec<MetaEntry> {
    let pairs: Vec<(&str, &str)> = note
        .split(['\r', '\n'])
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim(), v.trim()))
        .filter(|(k, _)| !k.is_empty())
        .collect();
    let get = |key: &str| pairs.iter().find(|(k, _)| *k == key).map(|(_, v)| *v);
    let mut m = vec![meta(
        keys::INSTRUMENT,
        match get("MicroscopeModel") {
            Some(model) => format!("Asylum Research {model}"),
            None => "Igor Pro (Asylum Research)".into(),
        },
    )];
    if let Some(d) = get("Date").zip(get("Time")).and_then(|(d, t)| date(d, t)) {
        m.push(meta(keys::DATE, d));
    }
    m.extend(pairs.iter().map(|(k, v)| meta(k, v)));
    m
}

/// `2019-10-24` and `12:14:13 PM` (or 24-hour) as ISO 8601.
fn date(d: &str, t: &str) -> Option<String> {
    let n = |s: &str| s.trim().parse::<i64>().ok();
    let mut ymd = d.split('-').map(n);
    let (y, mo, da) = (ymd.next()??, ymd.next()??, ymd.next()??);
    let (clock, pm) = match t.trim().split_once(' ') {
        Some((c, half)) => (c, Some(half.eq_ignore_ascii_case("PM"))),
        None => (t.trim(), None),
    };
    let mut hms = clock.split(':').map(n);
    let (h, mi, s) = (hms.next()??, hms.next()??, hms.next()??);
    let h = match pm {
        Some(true) if h < 12 => h + 12,
        Some(false) if h == 12 => 0,
        _ => h,
    };
    iso_date(y, mo, da, h, mi, s)
}

/// Metres per unit for a length unit; `None` (values kept as written)
/// for any other.
fn metres(unit: &str) -> Option<f64> {
    length_m(unit)
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let head = bytes.slice(0, HEADERS, STRUCTURE)?;
    let Some(big) = byte_order(head) else {
        let v = u16::from_le_bytes([head[0], head[1]]);
        return Err(bytes.error(
            "IBW header (version)",
            0,
            format!("version {v} (either byte order); version 5 is read"),
        ));
    };
    if checksum(head, big) != 0 {
        return Err(bytes.error(
            "IBW header (checksum)",
            2,
            "the headers' 16-bit words do not sum to 0 (corrupted?)",
        ));
    }
    let s = sizes(&mut cursor(bytes, 4, big))?;
    let w = wave_header(bytes, big)?;
    let [nx, ny, layers, extra] = w.dims;
    let (ny, layers) = (ny.max(1), layers.max(1));
    let n = nx.checked_mul(ny).and_then(|p| p.checked_mul(layers));
    if extra > 1
        || n != Some(w.points)
        || n.and_then(|n| n.checked_mul(w.sample.size())) > s.wave.checked_sub(320)
    {
        return Err(bytes.error(
            "IBW wave header (nDim)",
            64 + 68,
            format!(
                "dimensions {:?} for {} points of {} bytes in a wave of {} bytes",
                w.dims,
                w.points,
                w.sample.size(),
                s.wave
            ),
        ));
    }
    let t = tail(bytes, &s, 64 + s.wave)?;
    let mut grids = channels(bytes, &w, &t, layers)?;
    let i = select_channel(bytes, &grids, options)?;
    let unit = t.units[0].clone().unwrap_or_else(|| w.units[0].clone());
    let scale = match grids[i].height {
        true => metres(&unit).unwrap_or(1.0),
        false => 1.0,
    };
    let mut conv = Conversion::raw(w.sample).scaled(scale, 0.0);
    if big {
        conv = conv.big_endian();
    }
    let at = HEADERS + i * nx * ny * w.sample.size();
    let order = Order {
        column_major: false,
        flip_y: true,
    };
    let what = format!("IBW layer '{}'", grids[i].name);
    grids[i].data = Some(decode_grid(bytes, at, (nx, ny), &conv, &what, order)?);
    let mut m = note_meta(&t.note);
    m.insert(1, meta("wave", &w.name));
    m.push(meta(keys::HEIGHT_UNIT, &unit));
    m.push(meta(
        keys::LATERAL_UNIT,
        t.units[1].clone().unwrap_or(w.units[1].clone()),
    ));
    m.push(meta(
        keys::LATERAL_SCALE,
        format!("{} {}", w.step[0], w.step[1]),
    ));
    Ok(Decoded {
        preamble: m,
        sections: Vec::new(),
        grids,
    })
}

/// One grid per layer, described (none decoded yet).
fn channels(bytes: &Bytes, w: &Wave, t: &Tail, layers: usize) -> Result<Vec<Grid>> {
    let unit = |k: usize| t.units[k].clone().unwrap_or_else(|| w.units[k].clone());
    let lateral = |k: usize| metres(&unit(k + 1)).map_or(f64::NAN, |f| f * w.step[k]);
    let z = unit(0);
    let names = layer_names(&t.labels, layers);
    let any_height = names.iter().any(|n| is_height(n));
    let mut grids = Vec::new();
    for name in names {
        let dy = if w.dims[1] == 0 {
            lateral(0)
        } else {
            lateral(1)
        };
        let mut g = Grid::heights(&name, w.dims[0], w.dims[1].max(1), lateral(0), dy);
        g.x0 = metres(&unit(1)).map_or(0.0, |f| f * w.start[0]);
        g.y0 = metres(&unit(2)).map_or(0.0, |f| f * w.start[1]);
        g.height = is_height(&name) || (!any_height && layers == 1);
        if !g.height || metres(&z).is_none() {
            g.unit = z.clone();
        }
        check_grid_or_unspaced(bytes, "IBW wave header (sfA)", 64 + 84, &g)?;
        grids.push(g);
    }
    Ok(grids)
}
