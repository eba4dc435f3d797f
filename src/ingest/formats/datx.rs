//! Zygo DATX (Mx, MetroPro 8+): an HDF5 container
//! ([`crate::ingest::binary::hdf5`]).
//!
//! Channels: every dataset in the group `Data/Surface` (heights) and
//! `Data/Intensity`, or the datasets `Measurement/Surface` and
//! `Measurement/Intensity`; rows are y, as stored (the
//! dataset's `Coordinates` attribute names its width and height so).
//! A surface dataset's attributes give:
//! - points not measured: values equal to `No Data` (the f64 maximum in
//!   the files seen), and non-finite values;
//! - lateral spacing: `X Converter` / `Y Converter`, compounds
//!   (Category, BaseUnit, Parameters); with BaseUnit `Pixels` the second
//!   parameter is the pixel size in metres (SurfaceTopography's `DATX.py`,
//!   MIT), with a length unit it is the size in that unit;
//! - heights: the unit is `Z Converter`'s BaseUnit (or `Unit`): lengths
//!   (`Meters`, `MilliMeters`, `MicroMeters`, `NanoMeters`, the names
//!   SurfaceTopography maps) are scaled to metres; `Fringes` are
//!   wavelength · interferometric scale factor · obliquity factor metres
//!   (the dataset's `Wavelength`, `Interferometric Scale Factor`,
//!   `Obliquity Factor` attributes, else the converter's parameters 2–4,
//!   which hold the same numbers): the conversion of prysm's
//!   `read_zygo_datx` (MIT; "the usual conversion per Malacara") and of
//!   MetroPro's phase maps. Any other unit is kept, not as heights.
//!
//! Metadata: the attributes of the groups under `Attributes` (instrument
//! `System Type` and `System Serial Number`, `Software Info Name` and
//! `Version`, `Objective`, `Wavelength`, `Time Stamp`: seconds since 1970
//! UTC with a timezone in minutes west, as C's `struct timeb`), read when
//! they can be; a part that cannot is named in the metadata, not an error.

use crate::error::Result;
use crate::ingest::binary::decode::{Conversion, Invalid};
use crate::ingest::binary::hdf5::attr::attributes;
use crate::ingest::binary::hdf5::data::{dataset, sample, Dataset};
use crate::ingest::binary::hdf5::types::Value;
use crate::ingest::binary::hdf5::{find_signature, group, H5};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid_or_unspaced, keys, meta, select_channel, unix_date, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Datx;

const STRUCTURE: &str = "DATX surface";

impl Reader for Datx {
    fn name(&self) -> &'static str {
        "datx"
    }
    fn description(&self) -> &'static str {
        "Zygo DATX (HDF5): surface and intensity maps"
    }
    /// An HDF5 file holding `Data/Surface` or `Measurement`; one that
    /// cannot be parsed is taken when its bytes name a `Surface` (a
    /// damaged DATX file, whose error is then reported), left to others
    /// otherwise.
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        if find_signature(data).is_none() {
            return false;
        }
        let bytes = Bytes::new(std::path::Path::new(""), data);
        let found = H5::open(bytes).and_then(|f| {
            Ok(f.find("Data/Surface")?.is_some() || f.find("Measurement")?.is_some())
        });
        found.unwrap_or_else(|_| memchr::memmem::find(data, b"Surface").is_some())
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// A channel's dataset, its attributes and what they say.
struct Channel {
    ds: Dataset,
    attrs: Vec<(String, Value)>,
    /// Metres per stored value for heights; 1 otherwise.
    scale: f64,
    unit: String,
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let f = H5::open(*bytes)?;
    let mut grids = Vec::new();
    let mut channels = Vec::new();
    for (name, height, addr) in datasets(&f)? {
        let Some(ds) = dataset(&f, addr)? else {
            continue;
        };
        let (g, ch) = channel(&f, &name, height, ds)?;
        grids.push(g);
        channels.push(ch);
    }
    if grids.is_empty() {
        return Err(bytes.error(
            STRUCTURE,
            f.root,
            "no Surface dataset (Data/Surface/… or Measurement/Surface)",
        ));
    }
    // Channels without converters (intensity images) share the
    // surface's pixels.
    let (dx, dy) = (grids[0].dx, grids[0].dy);
    for g in grids.iter_mut().filter(|g| g.dx.is_nan() && g.dy.is_nan()) {
        (g.dx, g.dy) = (dx, dy);
    }
    let i = select_channel(bytes, &grids, options)?;
    let ch = &channels[i];
    let (s, big) = sample(&ch.ds.ty).ok_or_else(|| {
        bytes.error(
            STRUCTURE,
            ch.ds.addr,
            format!("'{}' is not numeric ({:?})", grids[i].name, ch.ds.ty.kind),
        )
    })?;
    let no_data = number(&ch.attrs, "No Data");
    let mut conv = Conversion::raw(s)
        .scaled(ch.scale, 0.0)
        .invalid(no_data.map_or(Invalid::None, Invalid::Equal));
    if big {
        conv = conv.big_endian();
    }
    let structure = format!("DATX dataset '{}'", grids[i].name);
    grids[i].data = Some(ch.ds.read(&f, &conv, &structure)?);
    Ok(Decoded {
        preamble: metadata(&f, ch),
        sections: Vec::new(),
        grids,
    })
}

/// The channel datasets: (name, whether heights, object header).
fn datasets(f: &H5) -> Result<Vec<(String, bool, usize)>> {
    let mut out = Vec::new();
    for (kind, height) in [("Surface", true), ("Intensity", false)] {
        if let Some(g) = f.find(&format!("Data/{kind}"))? {
            let links = group::links(f, g)?;
            let many = links.len() > 1;
            for (i, (_, addr)) in links.into_iter().enumerate() {
                let name = match many {
                    true => format!("{kind} {}", i + 1),
                    false => kind.to_string(),
                };
                out.push((name, height, addr));
            }
        } else if let Some(addr) = f.find(&format!("Measurement/{kind}"))? {
            out.push((kind.to_string(), height, addr));
        }
    }
    Ok(out)
}

/// A channel's grid (without values) from its dataset and attributes.
fn channel(f: &H5, name: &str, height: bool, ds: Dataset) -> Result<(Grid, Channel)> {
    let attrs: Vec<(String, Value)> = attributes(f, ds.addr)?
        .into_iter()
        .map(|a| Ok((a.name.clone(), a.value(f)?)))
        .collect::<Result<_>>()?;
    let (ny, nx) = ds.shape().ok_or_else(|| {
        f.bytes.error(
            STRUCTURE,
            ds.addr,
            format!("'{name}' has {} dimensions; 1 or 2 expected", ds.dims.len()),
        )
    })?;
    let dx = spacing(&attrs, "X Converter");
    let dy = match ny {
        1 => dx,
        _ => spacing(&attrs, "Y Converter"),
    };
    let mut g = Grid::heights(name, nx, ny, dx, dy);
    let unit = z_unit(&attrs);
    let scale = match height {
        true => height_scale(&attrs, &unit),
        false => None,
    };
    g.height = scale.is_some();
    g.unit = match scale {
        Some(_) => "m".into(),
        None => unit.clone(),
    };
    check_grid_or_unspaced(&f.bytes, STRUCTURE, ds.addr, &g)?;
    let ch = Channel {
        ds,
        attrs,
        scale: scale.unwrap_or(1.0),
        unit,
    };
    Ok((g, ch))
}

fn find<'v>(attrs: &'v [(String, Value)], name: &str) -> Option<&'v Value> {
    attrs.iter().find(|(n, _)| n == name).map(|(_, v)| v)
}

fn number(attrs: &[(String, Value)], name: &str) -> Option<f64> {
    find(attrs, name).and_then(Value::number)
}

/// A converter's parameters.
fn parameters(attrs: &[(String, Value)], name: &str) -> Vec<f64> {
    match find(attrs, name).and_then(|v| v.field("Parameters")) {
        Some(Value::List(p)) => p.iter().filter_map(Value::number).collect(),
        _ => Vec::new(),
    }
}

/// Metres per `unit` as DATX names lengths (`MicroMeters`), or as SI.
fn unit_m(unit: &str) -> Option<f64> {
    match unit.trim() {
        "Meters" => Some(1.0),
        "MilliMeters" | "MiliMeters" => Some(1e-3),
        "MicroMeters" => Some(1e-6),
        "NanoMeters" => Some(1e-9),
        "Angstroms" => Some(1e-10),
        u => length_m(u),
    }
}

/// Pixel size (m) from an X or Y converter; NaN when it gives none.
fn spacing(attrs: &[(String, Value)], name: &str) -> f64 {
    let base = find(attrs, name)
        .and_then(|v| v.field("BaseUnit"))
        .and_then(Value::text)
        .unwrap_or("");
    let per = match base {
        "Pixels" => Some(1.0),
        u => unit_m(u),
    };
    match (per, parameters(attrs, name).get(1)) {
        (Some(m), Some(&p)) if p > 0.0 && p.is_finite() => p * m,
        _ => f64::NAN,
    }
}

/// The height unit: `Z Converter`'s BaseUnit, else `Unit`.
fn z_unit(attrs: &[(String, Value)]) -> String {
    find(attrs, "Z Converter")
        .and_then(|v| v.field("BaseUnit"))
        .and_then(Value::text)
        .or_else(|| find(attrs, "Unit").and_then(Value::text))
        .unwrap_or("")
        .to_string()
}

/// Metres per stored value, when the unit is a length or fringes.
fn height_scale(attrs: &[(String, Value)], unit: &str) -> Option<f64> {
    if unit != "Fringes" {
        return unit_m(unit);
    }
    let p = parameters(attrs, "Z Converter");
    let pick = |name: &str, i: usize| number(attrs, name).or(p.get(i).copied());
    let w = pick("Wavelength", 1)?;
    let s = pick("Interferometric Scale Factor", 2).unwrap_or(1.0);
    let o = pick("Obliquity Factor", 3).unwrap_or(1.0);
    let scale = w * s * o;
    (scale.is_finite() && scale > 0.0).then_some(scale)
}

/// The file's metadata: the channel's attributes, and the instrument's
/// from the `Attributes` groups where they can be read.
fn metadata(f: &H5, ch: &Channel) -> Vec<MetaEntry> {
    let mut m = Vec::new();
    let mut all = Vec::new();
    if let Err(e) = instrument_attributes(f, &mut all) {
        m.push(meta("attributes not read", e.to_string()));
    }
    let text = |k: &str| {
        all.iter()
            .find(|(n, _): &&(String, Value)| n == k)
            .and_then(|(_, v)| v.text().map(str::to_string))
            .filter(|s| !s.is_empty())
    };
    let system = text("System Type");
    let serial = text("System Serial Number");
    let instrument = match (system, serial) {
        (Some(t), Some(s)) => format!("Zygo {t} (serial {s})"),
        (Some(t), None) => format!("Zygo {t}"),
        (None, Some(s)) => format!("Zygo (serial {s})"),
        (None, None) => "Zygo".to_string(),
    };
    m.push(meta(keys::INSTRUMENT, instrument));
    if let Some(d) = date(&all) {
        m.push(meta(keys::DATE, d));
    }
    if let Some(o) = text("Objective") {
        m.push(meta(keys::OBJECTIVE, o));
    }
    if let Some(s) = text("Software Info Name") {
        let v = text("Software Info Version").unwrap_or_default();
        m.push(meta("software", format!("{s} {v}").trim()));
    }
    m.push(meta(keys::LATERAL_UNIT, "m"));
    m.push(meta(keys::HEIGHT_UNIT, &ch.unit));
    m.push(meta(keys::HEIGHT_SCALE, format!("{:e}", ch.scale)));
    for (k, v) in ch.attrs.iter().chain(&all) {
        m.push(meta(k, v.display()));
    }
    m
}

/// `Data Context.` attributes of the groups under `Attributes`, names
/// without that prefix (the `Surface Data Context.` copies left out).
fn instrument_attributes(f: &H5, out: &mut Vec<(String, Value)>) -> Result<()> {
    let Some(g) = f.find("Attributes")? else {
        return Ok(());
    };
    for (_, addr) in group::links(f, g)? {
        for a in attributes(f, addr)? {
            let Some(name) = a.name.strip_prefix("Data Context.") else {
                continue;
            };
            let name = name.strip_prefix("Data Attributes.").unwrap_or(name);
            out.push((name.to_string(), a.value(f)?));
        }
    }
    Ok(())
}

/// The acquisition date: `Time Stamp`'s seconds (UTC) when plausible
/// (after 1990; files also hold 719529, a day count of 1970-01-01).
fn date(all: &[(String, Value)]) -> Option<String> {
    let t = all
        .iter()
        .find(|(n, _)| n == "Time Stamp")
        .and_then(|(_, v)| v.field("time"))
        .and_then(Value::number)?;
    (t >= 631_152_000.0 && t < i32::MAX as f64)
        .then(|| unix_date(t as i32))
        .flatten()
}
