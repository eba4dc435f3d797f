//! Keyence ZON (VR-series wide-area profilers): an 8-byte header (`KPK`,
//! a version digit, the preview's size), a BMP preview, then a zip archive
//! whose offsets count from its own start (zip64 end records). Its stored
//! entries, named by UUIDs, are each a Zstandard frame (`KPK1`; frames
//! without a content size) or plain (`KPK0`), and hold either an XML
//! document (UTF-8, BOM optional) or an array: a 16-byte header (columns,
//! rows, bytes per item, bytes per row; u32 LE) and rows that may be
//! padded. Items of 4 bytes are heights, i32 counts ×
//! `Calibration/ZCalibration/MeterPerUnit`; of 1 byte a mask, nonzero where
//! nothing was measured; of 3 bytes a colour image. The spacing is
//! `Calibration/XYCalibration/MeterPerPixel` along x and y.
//!
//! After the public descriptions of the format (Gwyddion's `zonfile.c`,
//! SurfaceTopography's `ZON.py`, surfalize's `zon.py`). Arrays are told
//! apart by their item size, not by their UUID names (SurfaceTopography
//! takes the names as fixed; they are not documented as such).

use std::io::Read;

use crate::error::Result;
use crate::ingest::binary::decode::{Conversion, Sample, Stream};
use crate::ingest::binary::xml::{self, Element};
use crate::ingest::binary::zip::{Entry, Zip};
use crate::ingest::binary::{check_grid, iso_date, keys, meta, select_channel, Bytes};
use crate::ingest::grid::{count_nan, Grid, GridData};
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Zon;

const ZSTD: [u8; 4] = [0x28, 0xB5, 0x2F, 0xFD];
const BOM: &[u8] = b"\xEF\xBB\xBF";
/// Largest XML document read (they are a few kB).
const XML_LIMIT: u64 = 16 << 20;

impl Reader for Zon {
    fn name(&self) -> &'static str {
        "zon"
    }
    fn description(&self) -> &'static str {
        "Keyence ZON (VR series): heights, mask and colour image in a zip after a preview"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(b"KPK") && data.get(8..10) == Some(b"BM")
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// Most bytes a Zstandard frame of `packed` bytes decodes to: an RLE
/// block of 4 bytes holds at most 128 KiB. A corrupted array header does
/// not allocate what its entry cannot hold.
fn unpacked_at_most(packed: u64) -> usize {
    usize::try_from(packed.saturating_mul(32 << 10).saturating_add(1 << 10)).unwrap_or(usize::MAX)
}

/// An array entry's header.
#[derive(Debug, Clone, Copy)]
struct Array {
    entry: usize,
    nx: usize,
    ny: usize,
    item: usize,
    stride: usize,
}

/// An XML document of the archive, with where its entry starts.
struct Doc {
    root: Element,
    entry: String,
    at: usize,
}

fn structure(e: &Entry) -> String {
    format!("ZON entry '{}'", e.name)
}

/// Fills `buf` as far as the stream goes; the count read.
fn read_full(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut k = 0;
    while k < buf.len() {
        match r.read(&mut buf[k..]) {
            Ok(0) => break,
            Ok(n) => k += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(k)
}

/// An entry's content as a stream: through the Zstandard decoder when it
/// starts with a frame's magic. Also where the entry starts in the file.
fn content<'b>(bytes: &Bytes<'b>, zip: &Zip, e: &Entry) -> Result<(Box<dyn Read + 'b>, usize)> {
    let mut r = zip.open_entry(bytes, e)?;
    let at = r.start;
    let mut head = [0u8; 4];
    let k =
        read_full(&mut r, &mut head).map_err(|m| bytes.error(&structure(e), at, m.to_string()))?;
    let whole = std::io::Cursor::new(head[..k].to_vec()).chain(r);
    if head[..k] != ZSTD {
        return Ok((Box::new(whole), at));
    }
    let d = ruzstd::decoding::StreamingDecoder::new(whole).map_err(|m| {
        bytes.error(
            &format!("{} (zstd frame header)", structure(e)),
            at,
            m.to_string(),
        )
    })?;
    Ok((Box::new(d), at))
}

/// The archive's documents and array headers.
fn scan(bytes: &Bytes, zip: &Zip) -> Result<(Vec<Doc>, Vec<Array>, usize)> {
    let (mut docs, mut arrays, mut unparsed) = (Vec::new(), Vec::new(), 0);
    for (i, e) in zip.entries.iter().enumerate() {
        let (mut r, at) = content(bytes, zip, e)?;
        let bad =
            |m: std::io::Error| bytes.error(&structure(e), at, format!("cannot be decoded: {m}"));
        let mut head = [0u8; 16];
        let k = read_full(&mut r, &mut head).map_err(bad)?;
        let text = head[..k].strip_prefix(BOM).unwrap_or(&head[..k]);
        if text.first() == Some(&b'<') {
            let mut doc = head[..k].to_vec();
            r.take(XML_LIMIT).read_to_end(&mut doc).map_err(bad)?;
            let body = doc.strip_prefix(BOM).unwrap_or(&doc);
            // Documents that do not parse (none needed so far) are counted.
            match xml::parse(body) {
                Ok(root) => docs.push(Doc {
                    root,
                    entry: e.name.clone(),
                    at,
                }),
                Err(_) => unparsed += 1,
            }
        } else if k == 16 && !head.starts_with(b"PK") {
            let w = |j: usize| {
                u32::from_le_bytes(head[4 * j..4 * j + 4].try_into().expect("4 bytes")) as usize
            };
            arrays.push(Array {
                entry: i,
                nx: w(0),
                ny: w(1),
                item: w(2),
                stride: w(3),
            });
        }
    }
    Ok((docs, arrays, unparsed))
}

/// A number of the document whose root is `root`, at `path` below it.
fn number(bytes: &Bytes, docs: &[Doc], root: &str, path: &str) -> Result<f64> {
    let doc = docs.iter().find(|d| d.root.name == root).ok_or_else(|| {
        bytes.error(
            "ZON archive",
            0,
            format!("no {root} document (with {root}/{path}) among its entries"),
        )
    })?;
    let t = doc.root.text_at(path).unwrap_or("");
    t.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| {
            bytes.error(
                &format!("ZON entry '{}' ({root} document)", doc.entry),
                doc.at,
                format!("{root}/{path} is '{t}'; a number > 0 expected"),
            )
        })
}

/// Where a channel's values come from.
#[derive(Clone, Copy)]
enum Source {
    Heights(Array),
    Colour(Array, usize),
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let head = bytes.slice(0, 10, "ZON header")?;
    let zip = Zip::open(bytes)?;
    let (docs, arrays, unparsed) = scan(bytes, &zip)?;
    let step = number(bytes, &docs, "Calibration", "XYCalibration/MeterPerPixel")?;
    let per_unit = number(bytes, &docs, "Calibration", "ZCalibration/MeterPerUnit")?;
    let (mut grids, mut sources) = (Vec::new(), Vec::new());
    let heights: Vec<Array> = arrays.iter().copied().filter(|a| a.item == 4).collect();
    let images: Vec<Array> = arrays.iter().copied().filter(|a| a.item == 3).collect();
    for (k, a) in heights.iter().enumerate() {
        let name = match k {
            0 => "Height".to_string(),
            _ => format!("Height {}", k + 1),
        };
        grids.push(Grid::heights(&name, a.nx, a.ny, step, step));
        sources.push(Source::Heights(*a));
    }
    for (k, a) in images.iter().enumerate() {
        for c in 0..3 {
            let mut g = Grid::heights(&format!("Image {} byte {c}", k + 1), a.nx, a.ny, step, step);
            (g.height, g.unit) = (false, String::new());
            grids.push(g);
            sources.push(Source::Colour(*a, c));
        }
    }
    if heights.is_empty() {
        return Err(bytes.error(
            "ZON archive",
            0,
            format!(
                "no height array (items of 4 bytes) among its {} arrays",
                arrays.len()
            ),
        ));
    }
    for (g, s) in grids.iter().zip(&sources) {
        let (Source::Heights(a) | Source::Colour(a, _)) = s;
        check_grid(bytes, &structure(&zip.entries[a.entry]), 0, g)?;
    }
    let sel = select_channel(bytes, &grids, options)?;
    let mask = arrays.iter().find(|a| a.item == 1);
    let mut notes = Vec::new();
    grids[sel].data = Some(match sources[sel] {
        Source::Heights(a) => {
            let conv = Conversion::raw(Sample::I32).scaled(per_unit, 0.0);
            let mut d = values(bytes, &zip, &a, conv, 0)?;
            if let Some(m) = mask {
                notes.extend(apply_mask(bytes, &zip, m, &a, &mut d)?);
            }
            d
        }
        Source::Colour(a, c) => values(bytes, &zip, &a, Conversion::raw(Sample::U8), c)?,
    });
    let mut preamble = metadata(&docs, head, (step, per_unit));
    preamble.extend(notes);
    if unparsed > 0 {
        preamble.push(meta("xml_documents_not_parsed", unparsed));
    }
    Ok(Decoded {
        preamble,
        sections: Vec::new(),
        grids,
    })
}

/// Reads an array's rows, each `stride` bytes (the last may lack its
/// padding), giving `f` each row's items; the entry is read to its end
/// (its CRC-32 checked).
fn rows(bytes: &Bytes, zip: &Zip, a: &Array, mut f: impl FnMut(&[u8])) -> Result<()> {
    let e = &zip.entries[a.entry];
    let (mut r, at) = content(bytes, zip, e)?;
    let s = structure(e);
    let row = a.nx.checked_mul(a.item).filter(|&r| r <= a.stride);
    let row = row
        .filter(|_| a.stride <= unpacked_at_most(e.size))
        .ok_or_else(|| {
            bytes.error(
                &format!("{s} (array header)"),
                at,
                format!(
                    "rows of {} items of {} bytes in {} bytes per row: they do not fit",
                    a.nx, a.item, a.stride
                ),
            )
        })?;
    let bad = |m: std::io::Error| bytes.error(&s, at, format!("cannot be decoded: {m}"));
    let mut buf = vec![0u8; a.stride.max(16)];
    read_full(&mut r, &mut buf[..16]).map_err(bad)?;
    for y in 0..a.ny {
        let k = read_full(&mut r, &mut buf[..a.stride]).map_err(bad)?;
        if k < row || (k < a.stride && y + 1 < a.ny) {
            return Err(bytes.error(
                &s,
                at,
                format!(
                    "holds {y} whole rows of {}; {} expected (truncated?)",
                    a.stride, a.ny
                ),
            ));
        }
        f(&buf[..row]);
    }
    std::io::copy(&mut r, &mut std::io::sink()).map_err(bad)?;
    Ok(())
}

/// An array's values (the `pick`-th byte of each item for a colour plane).
fn values(bytes: &Bytes, zip: &Zip, a: &Array, conv: Conversion, pick: usize) -> Result<GridData> {
    let e = &zip.entries[a.entry];
    let n = a.nx * a.ny;
    let mut s = Stream::new(conv, n, unpacked_at_most(e.size));
    match conv.sample {
        Sample::U8 => {
            let mut plane = Vec::with_capacity(a.nx);
            rows(bytes, zip, a, |row| {
                plane.clear();
                plane.extend(row.iter().skip(pick).step_by(3));
                s.push(&plane);
            })?
        }
        _ => rows(bytes, zip, a, |row| s.push(row))?,
    }
    s.finish()
        .ok_or_else(|| bytes.error(&structure(e), 0, format!("fewer than {n} values")))
}

/// Points the mask marks (nonzero) are not measured. A mask of another
/// size than the heights is not applied, and the metadata says so.
fn apply_mask(
    bytes: &Bytes,
    zip: &Zip,
    m: &Array,
    h: &Array,
    d: &mut GridData,
) -> Result<Option<MetaEntry>> {
    if (m.nx, m.ny) != (h.nx, h.ny) {
        return Ok(Some(meta(
            "mask",
            format!(
                "not applied: {} × {}, the heights {} × {}",
                m.nx, m.ny, h.nx, h.ny
            ),
        )));
    }
    let mut i = 0;
    rows(bytes, zip, m, |row| {
        for &b in row {
            if b != 0 {
                d.values[i] = f64::NAN;
            }
            i += 1;
        }
    })?;
    d.n_invalid = count_nan(&d.values);
    Ok(None)
}

/// `12/18/2025 12:47:39 -06:00` (month first; day first when the first
/// number is over 12) or `2025-12-18 12:47:39` as ISO 8601.
fn scan_date(t: &str) -> Option<String> {
    let mut parts = t.split_whitespace();
    let (date, time) = (parts.next()?, parts.next()?);
    let zone = parts
        .next()
        .filter(|z| z.starts_with(['+', '-']) && z.len() == 6);
    let num = |s: &str| s.parse::<i64>().ok();
    let d: Vec<i64> = date.split(['/', '-']).map(num).collect::<Option<_>>()?;
    let c: Vec<i64> = time.split(':').map(num).collect::<Option<_>>()?;
    let (&[a, b, y], &[h, mi, s]) = (d.as_slice(), c.as_slice()) else {
        return None;
    };
    let ymd = match (date.contains('-'), a > 12) {
        (true, _) => (a, b, y),
        (false, false) => (y, a, b),
        (false, true) => (y, b, a),
    };
    iso_date(ymd.0, ymd.1, ymd.2, h, mi, s).map(|d| d + zone.unwrap_or(""))
}

fn metadata(docs: &[Doc], head: &[u8], (step, per_unit): (f64, f64)) -> Vec<MetaEntry> {
    let get = |root: &str, path: &str| {
        docs.iter().find_map(|d| {
            (d.root.name == root)
                .then(|| d.root.text_at(path))
                .flatten()
        })
    };
    let model = get("DeviceIndivisuals", "DeviceModelName");
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!("Keyence {}", model.unwrap_or("(model not stated)")),
    )];
    let scanned = get("ScanInformations", "ScanDateTime");
    if let Some(d) = scanned.and_then(scan_date) {
        m.push(meta(keys::DATE, d));
    }
    m.extend([
        meta("version", String::from_utf8_lossy(&head[..4])),
        meta(keys::LATERAL_UNIT, "m"),
        meta(keys::HEIGHT_UNIT, "m"),
        meta(keys::LATERAL_SCALE, format!("{step:e} {step:e}")),
        meta(keys::HEIGHT_SCALE, format!("{per_unit:e}")),
    ]);
    for (key, root, path) in [
        ("scan_date_time", "ScanInformations", "ScanDateTime"),
        ("serial", "DeviceIndivisuals", "DeviceSerialId"),
        ("application", "Version", "LastSavedApplication"),
        ("display_unit", "DisplayUnit", "Unit"),
        ("lens", "Magnification", "Lens"),
        ("zoom", "Magnification", "Zoom"),
    ] {
        if let Some(v) = get(root, path) {
            m.push(meta(key, v));
        }
    }
    m
}

#[cfg(test)]
mod tests {
    #[test]
    fn scan_dates() {
        let d = super::scan_date;
        assert_eq!(
            d("12/18/2025 12:47:39 -06:00").as_deref(),
            Some("2025-12-18T12:47:39-06:00")
        );
        assert_eq!(
            d("18/12/2025 12:47:39").as_deref(),
            Some("2025-12-18T12:47:39")
        );
        assert_eq!(
            d("2025-02-03 01:02:03 +01:00").as_deref(),
            Some("2025-02-03T01:02:03+01:00")
        );
        assert_eq!(d("12/18/2025"), None);
        assert_eq!(d("13/13/2025 00:00:00"), None);
    }
}
