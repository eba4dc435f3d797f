//! ISO 25178-72 / ISO 5436-2 XML 3D surface profile (X3P): a zip holding
//! `main.xml` (possibly inside a folder) and the binary point data it
//! links to (`bindata/data.bin`), or the points listed in the XML itself.
//!
//! Read: feature types SUR (a map) and PRF (a profile); incremental x and
//! y axes (`AxisType` I) with their `Increment` and `Offset`, so pixels
//! may be non-square; an absolute z axis of data type `I` (16-bit signed
//! integer), `L` (32-bit signed), `F` (float) or `D` (double), scaled by
//! its `Increment` and `Offset` when given. Units are metres (the
//! standard's). Points not measured: NaN in float data, and the optional
//! valid-points mask (`ValidPointsLink`, one bit per point, least
//! significant bit first, 1 = measured). Record2 (date, instrument,
//! probing system) is kept as metadata.
//!
//! SurfaceTopography and surfalize read `I` and `L` as unsigned; openGPS,
//! the reference implementation of ISO 5436-2, declares them `Int16` and
//! `Int32`, which is what is read here (the two differ only for raw
//! values ≥ 2¹⁵ or 2³¹).

use crate::error::Result;
use crate::ingest::binary::decode::{decode_stream, inflated_at_most, Conversion, Invalid, Sample};
use crate::ingest::binary::xml::{self, Element};
use crate::ingest::binary::zip::{is_zip, Entry, Zip};
use crate::ingest::binary::{check_grid, keys, meta, Bytes};
use crate::ingest::grid::{count_nan, Grid, GridData};
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct X3p;

impl Reader for X3p {
    fn name(&self) -> &'static str {
        "x3p"
    }
    fn description(&self) -> &'static str {
        "ISO 25178-72 X3P (zip of main.xml and binary point data): areal maps and profiles"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        is_zip(data)
            && Zip::open(&Bytes::new("".as_ref(), data)).is_ok_and(|z| main_xml(&z).is_some())
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// `main.xml`, at the top or in one folder.
fn main_xml(z: &Zip) -> Option<&Entry> {
    z.find("main.xml").or_else(|| {
        z.entries
            .iter()
            .find(|e| e.name.ends_with("/main.xml") && e.name.matches('/').count() == 1)
    })
}

const STRUCTURE: &str = "X3P main.xml";

fn read(bytes: &Bytes, _options: &IngestOptions) -> Result<Decoded> {
    let zip = Zip::open(bytes)?;
    let entry = main_xml(&zip)
        .ok_or_else(|| bytes.error("X3P container", 0, "no main.xml in the zip archive"))?;
    let folder = entry
        .name
        .strip_suffix("main.xml")
        .unwrap_or("")
        .to_string();
    let doc = zip.read_small(bytes, entry, 64 << 20)?;
    let at = |(o, m): xml::ParseError| bytes.error(STRUCTURE, o, m);
    let root = xml::parse(&doc).map_err(at)?;
    let h = Header::from_xml(bytes, &root)?;
    let mut grid = Grid::heights("Z", h.nx, h.ny, h.dx, h.dy);
    grid.x0 = h.x0;
    grid.y0 = h.y0;
    check_grid(bytes, STRUCTURE, 0, &grid)?;
    let n = h.nx * h.ny;
    let conv = Conversion::raw(h.sample)
        .scaled(h.z_scale, h.z_offset)
        .invalid(Invalid::None);
    let mut data = match root.text_at("Record3/DataLink/PointDataLink") {
        Some(link) => {
            let e = linked(bytes, &zip, &folder, link)?;
            let r = zip.open_entry(bytes, e)?;
            let start = r.start;
            let structure = format!("X3P point data '{}'", e.name);
            let most = (e.size as usize).min(inflated_at_most(e.compressed as usize));
            decode_stream(bytes, r, (n, most), &conv, &structure, start)?
        }
        None => data_list(bytes, &root, n, &h)?,
    };
    if let Some(link) = root.text_at("Record3/DataLink/ValidPointsLink") {
        let e = linked(bytes, &zip, &folder, link)?;
        let mask = zip.read_small(bytes, e, (n as u64).div_ceil(8) + 64)?;
        apply_mask(bytes, e, &mask, &mut data)?;
    }
    grid.data = Some(data);
    Ok(Decoded {
        preamble: metadata(&root, &h),
        sections: Vec::new(),
        grids: vec![grid],
    })
}

/// A linked entry, by its path as written or relative to main.xml's folder.
fn linked<'z>(bytes: &Bytes, zip: &'z Zip, folder: &str, link: &str) -> Result<&'z Entry> {
    let link = link.trim().trim_start_matches("./").replace('\\', "/");
    zip.find(&link)
        .or_else(|| zip.find(&format!("{folder}{link}")))
        .ok_or_else(|| {
            bytes.error(
                STRUCTURE,
                0,
                format!("links to '{link}', which is not in the zip archive"),
            )
        })
}

/// The valid-points mask: bit i (least significant first) clear = not
/// measured.
fn apply_mask(bytes: &Bytes, e: &Entry, mask: &[u8], data: &mut GridData) -> Result<()> {
    let n = data.values.len();
    if mask.len() < n.div_ceil(8) {
        return Err(bytes.error(
            &format!("X3P valid points '{}'", e.name),
            0,
            format!(
                "holds {} bits; {n} points need {} bytes",
                mask.len() * 8,
                n.div_ceil(8)
            ),
        ));
    }
    for (i, v) in data.values.iter_mut().enumerate() {
        if mask[i / 8] >> (i % 8) & 1 == 0 {
            *v = f64::NAN;
        }
    }
    data.n_invalid = count_nan(&data.values);
    Ok(())
}

/// Points listed in the XML (`Record3/DataList/Datum`), one height per
/// datum (the z of `x;y;z` when it holds three values); an empty datum is a
/// point not measured.
fn data_list(bytes: &Bytes, root: &Element, n: usize, h: &Header) -> Result<GridData> {
    let list = root.find("Record3/DataList").ok_or_else(|| {
        bytes.error(
            STRUCTURE,
            root.offset,
            "Record3 has neither a DataLink nor a DataList",
        )
    })?;
    let data: Vec<&Element> = list.children.iter().filter(|d| d.name == "Datum").collect();
    if data.len() != n {
        return Err(bytes.error(
            STRUCTURE,
            list.offset,
            format!("DataList holds {} points; {n} expected", data.len()),
        ));
    }
    let mut values = Vec::with_capacity(n);
    for d in data {
        let z = d.text.rsplit(';').next().unwrap_or("").trim();
        let v = match z.is_empty() {
            true => f64::NAN,
            false => {
                z.parse::<f64>().map_err(|_| {
                    bytes.error(
                        STRUCTURE,
                        d.offset,
                        format!("Datum '{}' is not a number", d.text),
                    )
                })? * h.z_scale
                    + h.z_offset
            }
        };
        values.push(if v.is_finite() { v } else { f64::NAN });
    }
    Ok(GridData::new(values))
}

/// What Record1 and Record3 say about the grid.
struct Header {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    x0: f64,
    y0: f64,
    sample: Sample,
    z_scale: f64,
    z_offset: f64,
    feature: String,
}

/// The main document of an X3P file, read with errors that point at the
/// element they concern (or the root).
struct Doc<'a> {
    bytes: &'a Bytes<'a>,
    root: &'a Element,
}

impl<'a> Doc<'a> {
    fn err(&self, e: Option<&Element>, m: String) -> crate::error::Error {
        let at = e.map_or(self.root.offset, |e| e.offset);
        self.bytes.error(STRUCTURE, at, m)
    }

    /// The text at `path`; an error names the missing path at its parent.
    fn text(&self, path: &str) -> Result<&'a str> {
        self.root.text_at(path).ok_or_else(|| {
            let parent = self.root.find(path.rsplit_once('/').map_or("", |p| p.0));
            self.err(parent, format!("no {path}"))
        })
    }

    /// A finite number at `path`, or `default` when the path is absent.
    fn number(&self, path: &str, default: Option<f64>) -> Result<f64> {
        let t = match (self.root.text_at(path), default) {
            (None, Some(d)) => return Ok(d),
            (t, _) => t.map_or_else(|| self.text(path), Ok)?,
        };
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| {
                self.err(
                    self.root.find(path),
                    format!("{path} '{t}' is not a number"),
                )
            })
    }

    /// A count at `path`.
    fn count(&self, path: &str) -> Result<usize> {
        let t = self.text(path)?;
        t.trim()
            .parse::<usize>()
            .map_err(|_| self.err(self.root.find(path), format!("{path} '{t}' is not a count")))
    }
}

impl Header {
    fn from_xml(bytes: &Bytes, root: &Element) -> Result<Header> {
        let doc = Doc { bytes, root };
        let feature = doc.text("Record1/FeatureType")?.trim().to_string();
        if feature != "SUR" && feature != "PRF" {
            return Err(doc.err(
                root.find("Record1/FeatureType"),
                format!("feature type '{feature}'; areal maps (SUR) and profiles (PRF) are read"),
            ));
        }
        for axis in ["CX", "CY"] {
            let t = doc.text(&format!("Record1/Axes/{axis}/AxisType"))?;
            if t.trim() != "I" {
                return Err(doc.err(
                    root.find(&format!("Record1/Axes/{axis}")),
                    format!("{axis} axis type '{t}'; incremental axes (I) are read"),
                ));
            }
        }
        let dt = doc.text("Record1/Axes/CZ/DataType")?.trim();
        let sample = match dt {
            "I" => Sample::I16,
            "L" => Sample::I32,
            "F" => Sample::F32,
            "D" => Sample::F64,
            t => {
                return Err(doc.err(
                    root.find("Record1/Axes/CZ/DataType"),
                    format!("data type '{t}'; I, L, F or D expected"),
                ))
            }
        };
        let layers = doc.count("Record3/MatrixDimension/SizeZ")?;
        if layers != 1 {
            return Err(doc.err(
                root.find("Record3/MatrixDimension/SizeZ"),
                format!("{layers} layers; one layer is read"),
            ));
        }
        let ny = doc.count("Record3/MatrixDimension/SizeY")?;
        let dx = doc.number("Record1/Axes/CX/Increment", None)?;
        Ok(Header {
            nx: doc.count("Record3/MatrixDimension/SizeX")?,
            ny,
            dx,
            // A profile's y increment may be absent or zero.
            dy: match ny {
                1 => doc.number("Record1/Axes/CY/Increment", Some(dx)).map(|d| {
                    if d > 0.0 {
                        d
                    } else {
                        dx
                    }
                })?,
                _ => doc.number("Record1/Axes/CY/Increment", None)?,
            },
            x0: doc.number("Record1/Axes/CX/Offset", Some(0.0))?,
            y0: doc.number("Record1/Axes/CY/Offset", Some(0.0))?,
            sample,
            z_scale: doc.number("Record1/Axes/CZ/Increment", Some(1.0))?,
            z_offset: doc.number("Record1/Axes/CZ/Offset", Some(0.0))?,
            feature,
        })
    }
}

/// Record2 as it is, with the common keys.
fn metadata(root: &Element, h: &Header) -> Vec<MetaEntry> {
    let mut out = Vec::new();
    let get = |p: &str| {
        root.text_at(p)
            .map(str::trim)
            .filter(|t| !matches!(*t, "" | "unknown" | "not available"))
    };
    let instrument: Vec<&str> = ["Manufacturer", "Model", "Version"]
        .iter()
        .filter_map(|k| get(&format!("Record2/Instrument/{k}")))
        .collect();
    if !instrument.is_empty() {
        out.push(meta(keys::INSTRUMENT, instrument.join(" ")));
    }
    if let Some(d) = get("Record2/Date") {
        out.push(meta(keys::DATE, d));
    }
    // The probe: a stylus tip (Contacting) or an objective (NonContacting);
    // a Software probing system is a computed surface.
    let probe = match get("Record2/ProbingSystem/Type") {
        Some("Contacting") => Some(keys::TIP),
        Some("NonContacting") => Some(keys::OBJECTIVE),
        _ => None,
    };
    if let (Some(key), Some(p)) = (probe, get("Record2/ProbingSystem/Identification")) {
        out.push(meta(key, p));
    }
    out.push(meta(keys::LATERAL_UNIT, "m"));
    out.push(meta(keys::HEIGHT_UNIT, "m"));
    out.push(meta(keys::LATERAL_SCALE, format!("{:e} {:e}", h.dx, h.dy)));
    out.push(meta(keys::HEIGHT_SCALE, format!("{:e}", h.z_scale)));
    out.push(meta("feature_type", &h.feature));
    if let Some(r2) = root.child("Record2") {
        for (k, v) in r2.leaves() {
            out.push(meta(&format!("Record2/{k}"), v));
        }
    }
    out
}
