//! Agilent / Keysight (Molecular Imaging, PicoView) MI images: a text
//! header of lines holding a 14-character key and its value
//! (`xPixels       256`), `fileType      Image` first; the channels are
//! the `bufferLabel` blocks (label, `bufferRange`, `bufferUnit`,
//! `direction`, ...); the line `data          BINARY` (16-bit) or
//! `BINARY_32` ends the header and the channels' blocks of xPixels ×
//! yPixels little-endian integers follow, one after the other.
//! z = raw / 2^15 (2^31) · bufferRange in bufferUnit; the lateral sizes
//! are `xLength` and `yLength` in metres. Rows are oriented as
//! SurfaceTopography and Gwyddion orient them (flipped when `scanUp` is
//! TRUE). Spectroscopy files and ASCII data are refused, saying so.

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Order, Sample};
use crate::ingest::binary::keyed::{Entry, Keyed, Split};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid, keys, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Mi;

const MAGIC: &[u8] = b"fileType      ";
const STRUCTURE: &str = "MI header";
const KEY: usize = 14;

impl Reader for Mi {
    fn name(&self) -> &'static str {
        "mi"
    }
    fn description(&self) -> &'static str {
        "Agilent / Keysight MI (PicoView AFM image): every buffer as a channel"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC) && data_line(data).is_some()
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// The `data` line: where it starts and where the data begins after it.
fn data_line(data: &[u8]) -> Option<(usize, usize)> {
    let at = data.windows(15).position(|w| w == b"\ndata          ")? + 1;
    let end = data[at..].iter().position(|&b| b == b'\n')? + at + 1;
    Some((at, end))
}

/// A buffer: its entries, from `bufferLabel` to the next.
fn buffers<'a>(h: &'a Keyed) -> Vec<&'a [Entry]> {
    let starts: Vec<usize> = (0..h.entries.len())
        .filter(|&i| h.entries[i].key == "bufferLabel")
        .collect();
    starts
        .iter()
        .enumerate()
        .map(|(k, &s)| &h.entries[s..starts.get(k + 1).copied().unwrap_or(h.entries.len())])
        .collect()
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let (line, start) = data_line(bytes.data).ok_or_else(|| {
        bytes.error(
            STRUCTURE,
            0,
            "no 'data' line ending the header: not MI, or truncated",
        )
    })?;
    let h = Keyed::parse(
        *bytes,
        STRUCTURE,
        (&bytes.data[..line], 0),
        Split::Column(KEY),
    );
    let kind = h.text("", "fileType")?;
    if kind != "Image" {
        return Err(h.error(
            "",
            "fileType",
            format!("'{kind}'; only Image files hold maps"),
        ));
    }
    let encoding = crate::ingest::binary::latin1_or_utf8(&bytes.data[line + KEY..start]);
    let (sample, full) = match encoding.as_str() {
        "BINARY" => (Sample::I16, 32768.0),
        "BINARY_32" => (Sample::I32, 2147483648.0),
        e => {
            return Err(bytes.error(
                "MI header (data)",
                line,
                format!("'{e}'; BINARY or BINARY_32 data expected (ASCII MI files are not read)"),
            ))
        }
    };
    let (nx, ny): (usize, usize) = (h.number("", "xPixels")?, h.number("", "yPixels")?);
    let (sx, sy): (f64, f64) = (h.number("", "xLength")?, h.number("", "yLength")?);
    let (mut grids, scales) = buffer_grids(bytes, &h, (nx, ny), (sx, sy), full)?;
    if grids.is_empty() {
        return Err(bytes.error(STRUCTURE, line, "no bufferLabel: no channel"));
    }
    // Every buffer's data must be there, not only the one decoded.
    let block = nx * ny * sample.size();
    bytes.slice(start, block.saturating_mul(grids.len()), "MI data")?;
    let i = select_channel(bytes, &grids, options)?;
    let at = start + i * block;
    let order = Order {
        column_major: false,
        flip_y: h.get("", "scanUp") == Some("TRUE"),
    };
    let conv = Conversion::raw(sample).scaled(scales[i], 0.0);
    let what = format!("MI data of '{}'", grids[i].name);
    grids[i].data = Some(decode_grid(bytes, at, (nx, ny), &conv, &what, order)?);
    Ok(Decoded {
        preamble: metadata(&h),
        sections: Vec::new(),
        grids,
    })
}

/// One grid per buffer (none decoded yet) and each one's metres (or
/// unit) per count.
fn buffer_grids(
    bytes: &Bytes,
    h: &Keyed,
    (nx, ny): (usize, usize),
    (sx, sy): (f64, f64),
    full: f64,
) -> Result<(Vec<Grid>, Vec<f64>)> {
    let mut grids = Vec::new();
    let mut scales = Vec::new();
    for b in buffers(h) {
        let get = |k: &str| b.iter().find(|e| e.key == k).map(|e| e.value.as_str());
        let label = get("bufferLabel").unwrap_or("");
        let name = match get("direction") {
            Some(d) if !d.is_empty() => format!("{label} {d}"),
            _ => label.to_string(),
        };
        let unit = get("bufferUnit").unwrap_or("");
        let range: f64 = get("bufferRange")
            .and_then(|r| r.parse().ok())
            .ok_or_else(|| {
                bytes.error(
                    "MI buffer (bufferRange)",
                    b[0].offset,
                    format!("buffer '{label}' has no numeric bufferRange"),
                )
            })?;
        let mut g = Grid::heights(&name, nx, ny, sx / nx as f64, sy / ny as f64);
        g.height = length_m(unit).is_some();
        let f = length_m(unit).unwrap_or_else(|| {
            g.unit = unit.to_string();
            1.0
        });
        check_grid(bytes, STRUCTURE, 0, &g)?;
        scales.push(range / full * f);
        grids.push(g);
    }
    Ok((grids, scales))
}

/// The header before the first buffer, with the standard keys.
fn metadata(h: &Keyed) -> Vec<MetaEntry> {
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!("Agilent / Keysight {}", h.get("", "version").unwrap_or(""))
            .trim()
            .to_string(),
    )];
    if let Some(d) = h.get("", "dateAcquired").and_then(ctime_date) {
        m.push(meta(keys::DATE, d));
    }
    m.push(meta(keys::LATERAL_UNIT, "m"));
    let first = h
        .entries
        .iter()
        .position(|e| e.key == "bufferLabel")
        .unwrap_or(h.entries.len());
    m.extend(h.entries[..first].iter().map(|e| meta(&e.key, &e.value)));
    m
}

/// `Tue Feb 18 15:00:51 2014` (C's ctime) as ISO 8601.
fn ctime_date(s: &str) -> Option<String> {
    let w: Vec<&str> = s.split_whitespace().collect();
    let [_, mon, day, time, year] = w[..] else {
        return None;
    };
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    let mo = MONTHS.iter().position(|m| *m == mon)? as i64 + 1;
    let t: Vec<i64> = time.split(':').filter_map(|x| x.parse().ok()).collect();
    let [hh, mi, ss] = t[..] else { return None };
    crate::ingest::binary::iso_date(year.parse().ok()?, mo, day.parse().ok()?, hh, mi, ss)
}
