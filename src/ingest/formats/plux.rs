//! Sensofar PLUX (SensoSCAN / SensoVIEW): a zip holding `index.xml` (root
//! `xml`; a UTF-8 BOM optional) and one f32 file per layer. `GENERAL`
//! gives the grid (`IMAGE_SIZE_X`, `IMAGE_SIZE_Y`), the pixel size in µm
//! (`FOV_X`, `FOV_Y`: SurfaceTopography and Gwyddion take the size as
//! points × FOV) and the `DATE`; `LAYER_n/FILENAME_Z` names layer n's
//! heights: row by row, little-endian f32 in µm, NaN where nothing was
//! measured. `INFO/ITEM_k` holds `NAME`/`VALUE` pairs (Device,
//! Objective, Technique, ...). After SurfaceTopography's `PLUX.py` and
//! Gwyddion's `sensofarx.c`.

use crate::error::Result;
use crate::ingest::binary::decode::{decode_stream, Conversion, Sample};
use crate::ingest::binary::xml::{self, Element};
use crate::ingest::binary::zip::{is_zip, Entry, Zip};
use crate::ingest::binary::{check_grid, keys, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Plux;

const STRUCTURE: &str = "PLUX index.xml";
const UM: f64 = 1e-6;

impl Reader for Plux {
    fn name(&self) -> &'static str {
        "plux"
    }
    fn description(&self) -> &'static str {
        "Sensofar PLUX (zip of index.xml and f32 height layers, µm)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        is_zip(data)
            && Zip::open(&Bytes::new("".as_ref(), data)).is_ok_and(|z| {
                z.find("index.xml").is_some()
                    && z.entries
                        .iter()
                        .any(|e| e.name.starts_with("LAYER_") && e.name.ends_with(".raw"))
            })
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// A value of `GENERAL`, parsed; an error names the element.
fn general<T: std::str::FromStr>(bytes: &Bytes, root: &Element, key: &str, at: usize) -> Result<T> {
    let t = root.text_at(&format!("GENERAL/{key}")).unwrap_or("");
    t.trim().parse::<T>().map_err(|_| {
        let offset = root.find(&format!("GENERAL/{key}")).map_or(0, |e| e.offset);
        bytes.error(
            STRUCTURE,
            at,
            format!("GENERAL/{key} is '{t}' (byte {offset} of the document); a number expected"),
        )
    })
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let zip = Zip::open(bytes)?;
    let index = zip
        .find("index.xml")
        .ok_or_else(|| bytes.error("PLUX container", 0, "no index.xml in the zip archive"))?;
    let at = index.local as usize;
    let doc = zip.read_small(bytes, index, 16 << 20)?;
    let body = doc.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&doc);
    let root = xml::parse(body)
        .map_err(|(o, m)| bytes.error(STRUCTURE, at, format!("byte {o} of the document: {m}")))?;
    let nx: usize = general(bytes, &root, "IMAGE_SIZE_X", at)?;
    let ny: usize = general(bytes, &root, "IMAGE_SIZE_Y", at)?;
    let fov_x: f64 = general(bytes, &root, "FOV_X", at)?;
    let fov_y: f64 = general(bytes, &root, "FOV_Y", at)?;
    let mut grids = Vec::new();
    let mut layers: Vec<&Entry> = Vec::new();
    while let Some(layer) = root.child(&format!("LAYER_{}", layers.len())) {
        let k = layers.len();
        let name = layer.text_at("FILENAME_Z").unwrap_or("").trim();
        let e = zip.find(name).ok_or_else(|| {
            bytes.error(
                STRUCTURE,
                at,
                format!("LAYER_{k}/FILENAME_Z '{name}' is not in the zip archive"),
            )
        })?;
        if e.size != (nx * ny * 4) as u64 {
            return Err(bytes.error(
                &format!("PLUX layer '{}'", e.name),
                e.local as usize,
                format!(
                    "holds {} bytes; {nx} × {ny} f32 need {}",
                    e.size,
                    nx * ny * 4
                ),
            ));
        }
        let g = Grid::heights(&format!("Layer {k}"), nx, ny, fov_x * UM, fov_y * UM);
        check_grid(bytes, STRUCTURE, at, &g)?;
        grids.push(g);
        layers.push(e);
    }
    if layers.is_empty() {
        return Err(bytes.error(STRUCTURE, at, "no LAYER_0 element: no height layer"));
    }
    let sel = select_channel(bytes, &grids, options)?;
    let e = layers[sel];
    let r = zip.open_entry(bytes, e)?;
    let start = r.start;
    let conv = Conversion::raw(Sample::F32).scaled(UM, 0.0);
    let s = format!("PLUX layer '{}'", e.name);
    grids[sel].data = Some(decode_stream(
        bytes,
        r,
        (nx * ny, e.size as usize),
        &conv,
        &s,
        start,
    )?);
    Ok(Decoded {
        preamble: metadata(&root, (fov_x, fov_y)),
        sections: Vec::new(),
        grids,
    })
}

fn metadata(root: &Element, (fov_x, fov_y): (f64, f64)) -> Vec<MetaEntry> {
    let items: Vec<(&str, &str)> = root
        .child("INFO")
        .map(|info| {
            info.children
                .iter()
                .filter_map(|i| Some((i.text_at("NAME")?.trim(), i.text_at("VALUE")?.trim())))
                .collect()
        })
        .unwrap_or_default();
    let item = |n: &str| items.iter().find(|(k, _)| *k == n).map(|(_, v)| *v);
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!(
            "Sensofar {}",
            item("Device").unwrap_or("(device not stated)")
        ),
    )];
    if let Some(o) = item("Objective") {
        m.push(meta(keys::OBJECTIVE, o));
    }
    m.extend([
        meta(keys::LATERAL_UNIT, "µm"),
        meta(keys::HEIGHT_UNIT, "µm"),
        meta(keys::LATERAL_SCALE, format!("{fov_x} {fov_y}")),
    ]);
    if let Some(d) = root.text_at("GENERAL/DATE") {
        m.push(meta("date", d.trim()));
    }
    for (k, v) in items {
        m.push(meta(&format!("INFO/{k}"), v));
    }
    m
}
