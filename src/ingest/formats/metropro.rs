//! Zygo MetroPro `.dat`: a big-endian header (834 bytes for formats 1
//! and 2, 4096 for format 3), then the intensity buckets (16-bit
//! unsigned, one image per bucket) and the phase map (32-bit signed).
//!
//! Heights (the phase map, channel `Height`): z = raw · S · O · λ / R
//! (interferometric scale factor S, obliquity factor O, wavelength λ in
//! metres, R = 4096, 32768 or 131072 for phase resolution 0, 1, 2),
//! negated when the header's `sign` is set; raw values ≥ 2147483640 are
//! points not measured. Lateral resolution (m per pixel) gives Δx = Δy.
//! Intensity buckets (`Intensity`, `Intensity 2`, ...) are channels in
//! counts, values ≥ 65412 not measured (Gwyddion's reading of the
//! MetroPro Reference Guide, 0347M).

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Invalid, Sample};
use crate::ingest::binary::{check_grid, keys, meta, select_channel, unix_date, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct MetroPro;

const MAGIC: [[u8; 4]; 3] = [
    [0x88, 0x1b, 0x03, 0x6f],
    [0x88, 0x1b, 0x03, 0x70],
    [0x88, 0x1b, 0x03, 0x71],
];

impl Reader for MetroPro {
    fn name(&self) -> &'static str {
        "metropro"
    }
    fn description(&self) -> &'static str {
        "Zygo MetroPro .dat: phase (height) map and intensity images"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.len() >= 4 && MAGIC.iter().any(|m| data[..4] == *m)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

struct Header {
    size: usize,
    ac: (usize, usize, usize),
    cn: (usize, usize),
    scale: f64,
    lateral: f64,
    meta: Vec<MetaEntry>,
}

fn header(bytes: &Bytes) -> Result<Header> {
    let mut c = bytes.be(0, "MetroPro header");
    let magic = c.take(4, "magic")?;
    let format = MAGIC.iter().position(|m| magic == m).map(|i| i + 1);
    let Some(format) = format else {
        return Err(c.bad("magic", 4, "not a MetroPro file"));
    };
    c.skip(2);
    let size = c.u32("header size")? as usize;
    let want = if format == 3 { 4096 } else { 834 };
    if size != want {
        return Err(c.bad(
            "header size",
            4,
            format!("{size} bytes; format {format} has {want}"),
        ));
    }
    c.seek(12);
    let software_date = c.text(30, "software date")?;
    let version = [c.i16("version")?, c.i16("version")?, c.i16("version")?];
    c.seek(52);
    let ac = (
        c.u16("intensity width")? as usize,
        c.u16("intensity height")? as usize,
        c.u16("buckets")? as usize,
    );
    c.seek(68);
    let cn = (
        c.u16("phase width")? as usize,
        c.u16("phase height")? as usize,
    );
    c.seek(76);
    let time = c.i32("time stamp")?;
    let comment = c.text(82, "comment")?;
    c.seek(164);
    let intf = c.f32("interferometric scale factor")? as f64;
    let wavelength = c.f32("wavelength")? as f64;
    let aperture = c.f32("numerical aperture")? as f64;
    let obliquity = c.f32("obliquity factor")? as f64;
    let magnification = c.f32("magnification")? as f64;
    let lateral = c.f32("lateral resolution")? as f64;
    c.seek(218);
    let phase_res = c.i16("phase resolution")?;
    let levels = match phase_res {
        0 => 4096.0,
        1 => 32768.0,
        2 => 131072.0,
        r => return Err(c.bad("phase resolution", 2, format!("{r}; 0, 1 or 2 expected"))),
    };
    c.seek(232);
    let sign = c.i16("sign")?;
    c.seek(242);
    let serial = c.u16("system serial")?;
    c.seek(246);
    let objective = c.text(12, "objective name")?;
    let part = c.text(40, "part name")?;
    let mut scale = intf * obliquity * wavelength / levels;
    if sign != 0 {
        scale = -scale;
    }
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!(
            "Zygo MetroPro {}.{}.{} (system {serial})",
            version[0], version[1], version[2]
        ),
    )];
    if let Some(d) = unix_date(time) {
        m.push(meta(keys::DATE, d));
    }
    if !objective.is_empty() {
        m.push(meta(keys::OBJECTIVE, &objective));
    }
    m.push(meta(keys::LATERAL_UNIT, "m"));
    m.push(meta(keys::HEIGHT_UNIT, "m"));
    m.push(meta(keys::LATERAL_SCALE, format!("{lateral:e}")));
    m.push(meta(keys::HEIGHT_SCALE, format!("{scale:e}")));
    for (k, v) in [
        ("header format", format.to_string()),
        ("software date", software_date),
        ("comment", comment),
        ("part name", part),
        ("wavelength (m)", format!("{wavelength:e}")),
        ("numerical aperture", aperture.to_string()),
        ("magnification", magnification.to_string()),
        ("obliquity factor", obliquity.to_string()),
        ("interferometric scale factor", intf.to_string()),
        ("phase resolution", phase_res.to_string()),
        ("sign", sign.to_string()),
    ] {
        if !v.is_empty() {
            m.push(meta(k, v));
        }
    }
    Ok(Header {
        size,
        ac,
        cn,
        scale,
        lateral,
        meta: m,
    })
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let h = header(bytes)?;
    let (aw, ah, buckets) = h.ac;
    let (cw, ch) = h.cn;
    let d = if h.lateral > 0.0 { h.lateral } else { f64::NAN };
    let mut grids = Vec::new();
    let mut at = Vec::new();
    let mut pos = h.size;
    for b in 0..if aw * ah > 0 { buckets } else { 0 } {
        let mut g = Grid::heights(
            &match b {
                0 => "Intensity".to_string(),
                _ => format!("Intensity {}", b + 1),
            },
            aw,
            ah,
            d,
            d,
        );
        g.height = false;
        g.unit = String::new();
        grids.push(g);
        at.push((pos, Sample::U16, Invalid::AtLeast(65412.0), 1.0));
        pos += 2 * aw * ah;
    }
    if cw * ch > 0 {
        grids.push(Grid::heights("Height", cw, ch, d, d));
        at.push((pos, Sample::I32, Invalid::AtLeast(2_147_483_640.0), h.scale));
    }
    if grids.is_empty() {
        return Err(bytes.error(
            "MetroPro header",
            52,
            "neither intensity nor phase data (zero sizes)",
        ));
    }
    let i = select_channel(bytes, &grids, options)?;
    let g = &grids[i];
    if g.dx.is_finite() {
        check_grid(bytes, "MetroPro header", 184, g)?;
    }
    let (offset, sample, invalid, scale) = at[i];
    let conv = Conversion::raw(sample)
        .big_endian()
        .scaled(scale, 0.0)
        .invalid(invalid);
    let data = decode(
        bytes,
        offset,
        g.nx * g.ny,
        &conv,
        &format!("MetroPro {} data", g.name),
    )?;
    grids[i].data = Some(data);
    Ok(Decoded {
        preamble: h.meta,
        sections: Vec::new(),
        grids,
    })
}
