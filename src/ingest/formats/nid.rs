//! Nanosurf NID / EZD (easyScan, FlexAFM, DriveAFM): an INI-style text
//! header (`[DataSet]` first, CR LF lines, Latin-1), then `#!` at the
//! start of a line and the binary data. `[DataSet]` lists groups
//! (`GroupCount`, `Gr{i}-Count`) and their channels (`Gr{i}-Ch{j}` =
//! section name); the data blocks follow in that order, only for the
//! channels listed. Each channel's section gives `Points` × `Lines`,
//! `SaveBits`/`SaveSign`/`SaveOrder` (Intel or Motorola), the lateral
//! ranges `Dim0Range`/`Dim1Range` (in `Dim0Unit`) and the value range:
//! z = raw · `Dim2Range` / 2^bits + `Dim2Min` (+ `Dim2Range`/2 for signed
//! data, so that the lowest count is `Dim2Min`; Gwyddion's reading).
//!
//! Channels are named `Frame (Dim2Name)` (`Scan forward (Z-Axis)`), as
//! SurfaceTopography names them; those in a length unit other than a
//! deflection or amplitude are heights, the first the default. Rows are
//! oriented as SurfaceTopography and Gwyddion orient them (the file's last
//! line is row 0), so that a point is the same point in all three.

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Order, Sample};
use crate::ingest::binary::keyed::{Keyed, Split};
use crate::ingest::binary::units::length_m;
use crate::ingest::binary::{check_grid_or_unspaced, iso_date, keys, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Nid;

const MAGIC: &[u8] = b"[DataSet]";
const STRUCTURE: &str = "NID header";

impl Reader for Nid {
    fn name(&self) -> &'static str {
        "nid"
    }
    fn description(&self) -> &'static str {
        "Nanosurf NID / EZD (AFM): every channel of every scan direction"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC) && data_start(data).is_some()
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// Where the header ends (`#!` at a line start) and the data begins.
fn data_start(data: &[u8]) -> Option<(usize, usize)> {
    let end = data.windows(3).position(|w| w == b"\n#!")?;
    Some((end + 1, end + 3))
}

/// One channel's block: its grid, where it lies and how to convert it.
struct Block {
    grid: Grid,
    at: usize,
    conv: Conversion,
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let (end, start) = data_start(bytes.data).ok_or_else(|| {
        bytes.error(
            STRUCTURE,
            0,
            "no '#!' line ending the header: not NID, or truncated",
        )
    })?;
    let h = Keyed::parse(*bytes, STRUCTURE, (&bytes.data[..end], 0), Split::At('='));
    let mut blocks = Vec::new();
    let mut at = start;
    for section in channel_sections(&h)? {
        let b = block(bytes, &h, &section, at)?;
        let n = b.grid.nx.saturating_mul(b.grid.ny);
        at = b.at.saturating_add(n.saturating_mul(b.conv.sample.size()));
        blocks.push(b);
    }
    // Every channel's data must be there, not only the one decoded.
    bytes.slice(start, at - start, "NID data")?;
    if blocks.is_empty() {
        return Err(h.error("DataSet", "GroupCount", "no channel listed"));
    }
    let mut grids: Vec<Grid> = blocks.iter().map(|b| b.grid.clone()).collect();
    let i = select_channel(bytes, &grids, options)?;
    let b = &blocks[i];
    let order = Order {
        column_major: false,
        flip_y: true,
    };
    let what = format!("NID data of '{}'", b.grid.name);
    grids[i].data = Some(decode_grid(
        bytes,
        b.at,
        (b.grid.nx, b.grid.ny),
        &b.conv,
        &what,
        order,
    )?);
    Ok(Decoded {
        preamble: metadata(&h),
        sections: Vec::new(),
        grids,
    })
}

/// The sections of the channels, in the order of their data blocks.
fn channel_sections(h: &Keyed) -> Result<Vec<String>> {
    let groups: usize = h.number("DataSet", "GroupCount")?;
    let mut out = Vec::new();
    for g in 0..groups.min(1 << 10) {
        let n: usize = h.number("DataSet", &format!("Gr{g}-Count"))?;
        for c in 0..n.min(1 << 10) {
            if let Some(s) = h.get("DataSet", &format!("Gr{g}-Ch{c}")) {
                out.push(s.to_string());
            }
        }
    }
    Ok(out)
}

fn block(bytes: &Bytes, h: &Keyed, s: &str, at: usize) -> Result<Block> {
    if h.text(s, "SaveMode")? != "Binary" {
        return Err(h.error(s, "SaveMode", "only Binary data is read"));
    }
    let bits: u32 = h.number(s, "SaveBits")?;
    let signed = h.text(s, "SaveSign")? == "Signed";
    let sample = match (bits, signed) {
        (16, true) => Sample::I16,
        (16, false) => Sample::U16,
        (32, true) => Sample::I32,
        (32, false) => Sample::U32,
        _ => return Err(h.error(s, "SaveBits", format!("{bits}; 16 or 32 expected"))),
    };
    let (nx, ny): (usize, usize) = (h.number(s, "Points")?, h.number(s, "Lines")?);
    let unit = h.text(s, "Dim2Unit")?;
    let z = length_m(unit);
    let name = format!("{} ({})", h.text(s, "Frame")?, h.text(s, "Dim2Name")?);
    let lower = name.to_ascii_lowercase();
    let lateral = length_m(h.text(s, "Dim0Unit")?).unwrap_or(f64::NAN);
    let (sx, sy): (f64, f64) = (h.number(s, "Dim0Range")?, h.number(s, "Dim1Range")?);
    let mut grid = Grid::heights(
        &name,
        nx,
        ny,
        sx * lateral / nx as f64,
        sy * lateral / ny.max(1) as f64,
    );
    grid.height = z.is_some()
        && !["deflection", "amplitude"]
            .iter()
            .any(|w| lower.contains(w));
    let f = match grid.height {
        true => z.unwrap_or(1.0),
        false => {
            grid.unit = unit.to_string();
            1.0
        }
    };
    let here = h
        .entries
        .iter()
        .find(|e| e.section == s)
        .map_or(0, |e| e.offset);
    check_grid_or_unspaced(bytes, &format!("{STRUCTURE} [{s}]"), here, &grid)?;
    let range: f64 = h.number(s, "Dim2Range")?;
    let min: f64 = h.number(s, "Dim2Min")?;
    let offset = min + if signed { range / 2.0 } else { 0.0 };
    let mut conv = Conversion::raw(sample).scaled(range / 2f64.powi(bits as i32) * f, offset * f);
    match h.text(s, "SaveOrder")? {
        "Intel" => {}
        "Motorola" => conv = conv.big_endian(),
        o => return Err(h.error(s, "SaveOrder", format!("'{o}'; Intel or Motorola expected"))),
    }
    Ok(Block { grid, at, conv })
}

/// The scan's settings (`[DataSet-Info]`) with the standard keys.
fn metadata(h: &Keyed) -> Vec<MetaEntry> {
    let info = "DataSet-Info";
    let mut m = vec![meta(
        keys::INSTRUMENT,
        match h.get(info, "Head type") {
            Some(head) => format!("Nanosurf {head}"),
            None => "Nanosurf".into(),
        },
    )];
    let date = h
        .get(info, "Date")
        .zip(h.get(info, "Time"))
        .and_then(|(d, t)| {
            let n = |s: &str| s.trim().parse::<i64>().ok();
            let d: Vec<_> = d.split('-').map(n).collect();
            let t: Vec<_> = t.split(':').map(n).collect();
            match (&d[..], &t[..]) {
                ([Some(da), Some(mo), Some(y)], [Some(hh), Some(mi), Some(ss)]) => {
                    iso_date(*y, *mo, *da, *hh, *mi, *ss)
                }
                _ => None,
            }
        });
    if let Some(d) = date {
        m.push(meta(keys::DATE, d));
    }
    if let Some(tip) = h.get(info, "Cantilever type") {
        m.push(meta(keys::TIP, tip));
    }
    m.extend(
        h.meta_of(info)
            .into_iter()
            .filter(|e| !e.value.starts_with("---")),
    );
    m
}
