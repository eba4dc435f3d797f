//! Keyence VK3/VK4 laser confocal maps, and VK6/VK7 (a zip after a short
//! header, holding the VK4 stream as its entry `Vk4File`).
//!
//! VK3/VK4: `VK3_`/`VK4_`, a version, four zero bytes; an offset table of
//! u32 (measurement conditions, two colour images, three light images,
//! three height images, thumbnails, ..., string data; 0 = absent); the
//! measurement conditions (u32: date and time, UTC offset in minutes, ...,
//! x and y length per pixel and z length per digit in picometres at fields
//! 42–44). A height or light image: width, height, bits per point (8, 16,
//! 32), compression, byte size, palette range, a 768-byte palette, then
//! rows of unsigned little-endian counts. Heights = counts × z per digit.
//! The spacing is the length per pixel (SurfaceTopography and Gwyddion
//! give the physical size as (n − 1) × it, the original software's field
//! of view). After the public descriptions: Gwyddion's `keyence.c`, the
//! OSTI report 1419732, SurfaceTopography's `VK.py`.

use crate::error::{Error, Result};
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::zip::Zip;
use crate::ingest::binary::{check_grid, iso_date, keys, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Vk;

const PM: f64 = 1e-12;
const STRUCTURE: &str = "VK4 header";
/// Bytes of the measurement conditions read (fields 0–44).
const CONDITIONS: usize = 45 * 4;

impl Reader for Vk {
    fn name(&self) -> &'static str {
        "vk"
    }
    fn description(&self) -> &'static str {
        "Keyence VK3/VK4 (and VK6/VK7 zip) laser confocal height and light images"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        let stream = (data.starts_with(b"VK4_") || data.starts_with(b"VK3_"))
            && data.get(8..12) == Some(&[0; 4]);
        let zipped = (data.starts_with(b"VK6") || data.starts_with(b"VK7"))
            && Zip::open(&Bytes::new("".as_ref(), data)).is_ok_and(|z| z.find("Vk4File").is_some());
        stream || zipped
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(
            match bytes.data.starts_with(b"VK6") || bytes.data.starts_with(b"VK7") {
                true => read_zipped(bytes, options),
                false => read(bytes, options),
            },
        )
    }
}

/// VK6/VK7: the `Vk4File` entry read whole, then as a VK4 stream; an error
/// inside it names the entry, with the offset in the entry.
fn read_zipped(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let zip = Zip::open(bytes)?;
    let e = zip
        .find("Vk4File")
        .ok_or_else(|| bytes.error("VK6 container", 0, "no entry 'Vk4File' in its zip archive"))?;
    let limit = crate::ingest::binary::decode::inflated_at_most(e.compressed as usize) as u64;
    let inner = zip.read_small(bytes, e, limit)?;
    let mut d = read(&Bytes::new(bytes.path, &inner), options).map_err(|err| match err {
        Error::Structure {
            path,
            structure,
            offset,
            message,
        } => Error::Structure {
            path,
            structure: format!("zip entry 'Vk4File', {structure}"),
            offset,
            message,
        },
        other => other,
    })?;
    d.preamble
        .push(meta("container", String::from_utf8_lossy(&bytes.data[..3])));
    Ok(d)
}

/// One height or light image of the offset table.
struct Image {
    name: String,
    height: bool,
    at: usize,
    nx: usize,
    ny: usize,
    sample: Sample,
}

/// The image header at `at`: its size, checked against its byte size.
fn image(bytes: &Bytes, name: String, height: bool, at: usize) -> Result<Image> {
    let s = format!("VK4 image '{name}'");
    let mut c = bytes.le(at, &s);
    let nx = c.u32("width")? as usize;
    let ny = c.u32("height")? as usize;
    let bits = c.u32("bits per point")?;
    let sample = match bits {
        8 => Sample::U8,
        16 => Sample::U16,
        32 => Sample::U32,
        b => return Err(c.bad("bits per point", 4, format!("{b}; 8, 16 or 32 expected"))),
    };
    c.skip(4);
    let size = c.u32("byte size")? as u64;
    if size != nx as u64 * ny as u64 * (bits / 8) as u64 {
        return Err(c.bad(
            "byte size",
            4,
            format!(
                "{size} bytes; {nx} × {ny} points of {bits} bits need {}",
                nx as u64 * ny as u64 * (bits / 8) as u64
            ),
        ));
    }
    Ok(Image {
        name,
        height,
        at: at + 28 + 768,
        nx,
        ny,
        sample,
    })
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let mut c = bytes.le(0, STRUCTURE);
    let magic = c.take(4, "magic")?;
    let version = String::from_utf8_lossy(&magic[..3]).into_owned();
    c.skip(4);
    if c.u32("file type")? != 0 {
        return Err(c.bad("file type", 4, "not 0 (a VK3/VK4 measurement file)"));
    }
    let mut t = bytes.le(12, "VK4 offset table");
    let mut table = [0usize; 18];
    for v in table.iter_mut() {
        *v = t.u32("offset")? as usize;
    }
    let at = table[0];
    let cond = bytes.slice(at, CONDITIONS, "VK4 measurement conditions")?;
    let field = |i: usize| u32::from_le_bytes(cond[4 * i..4 * i + 4].try_into().expect("4 bytes"));
    let (dx, dy, dz) = (
        field(42) as f64 * PM,
        field(43) as f64 * PM,
        field(44) as f64 * PM,
    );
    let mut images = Vec::new();
    for (slots, kind, height) in [(6..9, "Height", true), (3..6, "Light", false)] {
        for (k, &off) in table[slots].iter().enumerate().filter(|(_, &o)| o != 0) {
            let name = match k {
                0 => kind.to_string(),
                _ => format!("{kind} {}", k + 1),
            };
            images.push(image(bytes, name, height, off)?);
        }
    }
    let mut grids = Vec::new();
    for im in &images {
        let mut g = Grid::heights(&im.name, im.nx, im.ny, dx, dy);
        if !im.height {
            (g.height, g.unit) = (false, String::new());
        }
        check_grid(
            bytes,
            "VK4 measurement conditions (length per pixel)",
            at,
            &g,
        )?;
        grids.push(g);
    }
    if !images.iter().any(|i| i.height) {
        return Err(bytes.error("VK4 offset table", 12, "no height image (offsets 0)"));
    }
    if field(44) == 0 {
        return Err(bytes.error(
            "VK4 measurement conditions (z length per digit)",
            at + 176,
            "0 pm; a length > 0 expected",
        ));
    }
    let sel = select_channel(bytes, &grids, options)?;
    let im = &images[sel];
    let conv = match im.height {
        true => Conversion::raw(im.sample).scaled(dz, 0.0),
        false => Conversion::raw(im.sample),
    };
    let s = format!("VK4 image '{}' (points)", im.name);
    grids[sel].data = Some(decode(bytes, im.at, im.nx * im.ny, &conv, &s)?);
    let mut preamble = metadata(&version, &field, (dx, dy, dz));
    preamble.extend(strings(bytes, table[16])?);
    Ok(Decoded {
        preamble,
        sections: Vec::new(),
        grids,
    })
}

fn metadata(
    version: &str,
    field: &dyn Fn(usize) -> u32,
    (dx, dy, dz): (f64, f64, f64),
) -> Vec<MetaEntry> {
    let f = |i| field(i) as i64;
    let mut m = vec![
        meta(keys::INSTRUMENT, "Keyence VK"),
        meta("version", version),
    ];
    if let Some(d) = iso_date(f(1), f(2), f(3), f(4), f(5), f(6)) {
        let utc = field(7) as i32;
        let zone = format!(
            "{}{:02}:{:02}",
            if utc < 0 { '-' } else { '+' },
            utc.abs() / 60,
            utc.abs() % 60
        );
        m.push(meta(keys::DATE, d + &zone));
    }
    m.extend([
        meta(keys::LATERAL_UNIT, "pm"),
        meta(keys::HEIGHT_UNIT, "pm"),
        meta(keys::LATERAL_SCALE, format!("{} {}", field(42), field(43))),
        meta(keys::HEIGHT_SCALE, field(44)),
        meta("length_per_pixel_m", format!("{dx:e} {dy:e}")),
        meta("height_per_digit_m", format!("{dz:e}")),
        meta("optical_zoom", field(18) as f64 / 10.0),
        meta("lens_magnification", field(24) as f64 / 10.0),
    ]);
    m
}

/// The title and lens name (u32 count, UTF-16 LE), when the table has them.
fn strings(bytes: &Bytes, at: usize) -> Result<Vec<MetaEntry>> {
    if at == 0 {
        return Ok(Vec::new());
    }
    let mut c = bytes.le(at, "VK4 string data");
    let mut out = Vec::new();
    for key in ["title", keys::OBJECTIVE] {
        let n = c.u32("length")? as usize;
        let raw = c.take(n.saturating_mul(2), key)?;
        let units: Vec<u16> = raw
            .chunks_exact(2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
            .collect();
        let text = String::from_utf16_lossy(&units);
        if !text.trim().is_empty() {
            out.push(meta(key, text.trim()));
        }
    }
    Ok(out)
}
