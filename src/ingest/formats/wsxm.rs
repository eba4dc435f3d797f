//! WSxM images (`.top`, `.stp`, `.ch1`, ...; Nanotec / UAM's SPM
//! software): `WSxM file copyright …`, `SxM Image file` and
//! `Image header size: N` lines, then `[Section]`s of `key: value` lines
//! up to `[Header end]`; the data start at byte N: `Number of rows` rows
//! of `Number of columns` little-endian values of `Image Data Type`
//! (`short`/`integer` 16-bit, `float`, `double`). The lateral sizes are
//! `[Control]` `X Amplitude`/`Y Amplitude` with their unit; heights are
//! raw · `Z Amplitude` / (`Maximum` − `Minimum`) of `[Miscellaneous]`,
//! in Z Amplitude's unit, as SurfaceTopography reads them.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::keyed::{quantity, Keyed, Split};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid, keys, meta, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Wsxm;

const MAGIC: &[u8] = b"WSxM file copyright";
const STRUCTURE: &str = "WSxM header";
const INFO: &str = "General Info";

impl Reader for Wsxm {
    fn name(&self) -> &'static str {
        "wsxm"
    }
    fn description(&self) -> &'static str {
        "WSxM SPM image (.top, .stp, ...): 16-bit, float or double map"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes))
    }
}

/// A length with its unit (`600 nm`) in metres, or an error naming it.
fn length(h: &Keyed, section: &str, key: &str) -> Result<(f64, String)> {
    let v = h.text(section, key)?;
    quantity(v)
        .and_then(|(x, u)| Some((x * length_m(u)?, u.to_string())))
        .ok_or_else(|| {
            h.error(
                section,
                key,
                format!("'{v}'; a length with its unit expected"),
            )
        })
}

fn read(bytes: &Bytes) -> Result<Decoded> {
    let end = bytes
        .data
        .windows(12)
        .position(|w| w == b"[Header end]")
        .ok_or_else(|| bytes.error(STRUCTURE, 0, "no [Header end] line: not WSxM, or truncated"))?;
    let h = Keyed::parse(*bytes, STRUCTURE, (&bytes.data[..end], 0), Split::At(':'));
    if h.get("", "SxM Image file").is_none()
        && !bytes.data[..end]
            .windows(14)
            .any(|w| w == b"SxM Image file")
    {
        return Err(bytes.error(STRUCTURE, 0, "no 'SxM Image file' line: not a WSxM image"));
    }
    let start: usize = h.number("", "Image header size")?;
    let sample = match h.text(INFO, "Image Data Type")? {
        "short" | "integer" => Sample::I16,
        "float" => Sample::F32,
        "double" => Sample::F64,
        t => {
            return Err(h.error(
                INFO,
                "Image Data Type",
                format!("'{t}'; short, integer, float or double expected"),
            ))
        }
    };
    let (nx, ny): (usize, usize) = (
        h.number(INFO, "Number of columns")?,
        h.number(INFO, "Number of rows")?,
    );
    let (sx, _) = length(&h, "Control", "X Amplitude")?;
    let (sy, _) = length(&h, "Control", "Y Amplitude")?;
    let (z, z_unit) = length(&h, INFO, "Z Amplitude")?;
    let misc = "Miscellaneous";
    let (max, min): (f64, f64) = (h.number(misc, "Maximum")?, h.number(misc, "Minimum")?);
    if max.partial_cmp(&min) != Some(std::cmp::Ordering::Greater) {
        return Err(h.error(
            misc,
            "Maximum",
            format!("maximum {max} not above minimum {min}: heights cannot be scaled"),
        ));
    }
    let mut g = Grid::heights("Topography", nx, ny, sx / nx as f64, sy / ny as f64);
    if let Some(name) = h.get(INFO, "Acquisition channel") {
        g.name = name.to_string();
    }
    check_grid(bytes, STRUCTURE, 0, &g)?;
    let conv = Conversion::raw(sample).scaled(z / (max - min), 0.0);
    g.data = Some(decode(bytes, start, nx * ny, &conv, "WSxM data")?);
    Ok(Decoded {
        preamble: metadata(&h, &z_unit),
        sections: Vec::new(),
        grids: vec![g],
    })
}

fn metadata(h: &Keyed, z_unit: &str) -> Vec<MetaEntry> {
    let head = h.get(INFO, "Head type").unwrap_or("");
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!("WSxM {head}").trim().to_string(),
    )];
    if let Some(d) = h.get(INFO, "Acquisition time").and_then(date) {
        m.push(meta(keys::DATE, d));
    }
    let xy = h
        .get("Control", "X Amplitude")
        .and_then(quantity)
        .map_or("", |(_, u)| u);
    m.push(meta(keys::LATERAL_UNIT, xy));
    m.push(meta(keys::HEIGHT_UNIT, z_unit));
    for s in [INFO, "Control", "Miscellaneous"] {
        m.extend(h.meta_of(s));
    }
    m
}

/// `03/11/2011, 20:23:46.484` (day/month/year, as WSxM writes it in
/// Spain) as ISO 8601, to the second.
fn date(s: &str) -> Option<String> {
    let (d, t) = s.split_once(',')?;
    let n = |x: &str| x.trim().split('.').next()?.parse::<i64>().ok();
    let d: Vec<_> = d.split('/').map(n).collect();
    let t: Vec<_> = t.split(':').map(n).collect();
    match (&d[..], &t[..]) {
        ([Some(da), Some(mo), Some(y)], [Some(hh), Some(mi), Some(ss)]) => {
            crate::ingest::binary::iso_date(*y, *mo, *da, *hh, *mi, *ss)
        }
        _ => None,
    }
}
