//! Digital Surf SUR (MountainsMap, and the many instruments that export
//! it): one or more objects, each a 512-byte header, a comment, a private
//! zone and its points as 16- or 32-bit integers, uncompressed
//! (`DIGITAL SURF`) or in zlib streams (`DSCOMPRESSED`, listed in a
//! directory of raw and compressed lengths).
//!
//! Heights: z = raw · Δz (in the header's Z step unit) + Z offset (in its
//! Z length unit), converted to metres; lateral steps likewise. Points not
//! measured, when the header says there are some, are the raw value
//! zmin − 2 (the convention of MountainsMap's documentation, as read by
//! RosettaSciIO and surfalize). The unit-ratio fields are not applied
//! (Gwyddion and SurfaceTopography do not either; every file seen gives
//! its steps in the step units). Several objects (a multilayer file) are
//! channels named by their Z axis.

use crate::error::Result;
use crate::ingest::binary::decode::{
    decode, inflated_at_most, Conversion, Invalid, Sample, Stream,
};
use crate::ingest::binary::{check_grid, iso_date, keys, meta, select_channel, Bytes, Cursor};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};
use crate::units::{parse_unit, Quantity};

/// The registry entry.
pub struct Sur;

const PLAIN: &[u8] = b"DIGITAL SURF";
const COMPRESSED: &[u8] = b"DSCOMPRESSED";
const HEADER: usize = 512;

impl Reader for Sur {
    fn name(&self) -> &'static str {
        "sur"
    }
    fn description(&self) -> &'static str {
        "Digital Surf SUR (MountainsMap): maps and profiles, 16/32-bit, plain or compressed"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(PLAIN) || data.starts_with(COMPRESSED)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// One object: its header as read, where its points are.
struct Object {
    header: Header,
    grid: Grid,
    data_at: usize,
    data_len: usize,
}

struct Header {
    compressed: bool,
    objects: u16,
    kind: u16,
    non_measured: bool,
    bits: u16,
    zmin: i32,
    dz: f64,
    z_offset: f64,
    z_name: String,
    z_unit: String,
    xy_units: [String; 2],
    date: Option<String>,
    object_name: String,
    operator: String,
    acquisition: u16,
    comment: String,
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let first = object(bytes, 0)?;
    let count = first.header.objects.max(1) as usize;
    let mut objects = vec![first];
    while objects.len() < count {
        let last = &objects[objects.len() - 1];
        objects.push(object(bytes, last.data_at + last.data_len)?);
    }
    let mut grids: Vec<Grid> = objects.iter().map(|o| o.grid.clone()).collect();
    let i = select_channel(bytes, &grids, options)?;
    let o = &objects[i];
    let h = &o.header;
    let n = o.grid.nx * o.grid.ny;
    // Heights to metres; another channel keeps its values as written.
    let z_scale = length(&h.z_unit).unwrap_or(1.0);
    let conv = Conversion::raw(if h.bits == 16 {
        Sample::I16
    } else {
        Sample::I32
    })
    .scaled(h.dz * z_scale, h.z_offset * z_scale)
    .invalid(match h.non_measured {
        true => Invalid::Equal(h.zmin as f64 - 2.0),
        false => Invalid::None,
    });
    let structure = format!("SUR object {} points", i + 1);
    let data = match h.compressed {
        false => decode(bytes, o.data_at, n, &conv, &structure)?,
        true => inflate(bytes, o, n, &conv, &structure)?,
    };
    grids[i].data = Some(data);
    Ok(Decoded {
        preamble: metadata(&objects[0].header, &objects),
        sections: Vec::new(),
        grids,
    })
}

/// Metres per unit, for a length unit.
fn length(unit: &str) -> Option<f64> {
    parse_unit(unit)
        .filter(|u| u.quantity == Quantity::Length)
        .map(|u| u.scale)
}

/// The fields of an object header that say what it is and how its points
/// are stored (offsets 0–60).
struct Ident {
    compressed: bool,
    objects: u16,
    kind: u16,
    object_name: String,
    operator: String,
    acquisition: u16,
    non_measured: bool,
    bits: u16,
    zmin: i32,
}

/// The fields of an object header that place its points (offsets 60–478):
/// grid, steps and their units, date, zone sizes and offsets.
struct Geometry {
    nx: usize,
    ny: usize,
    step: [f64; 3],
    z_name: String,
    step_units: [String; 3],
    length_units: [String; 3],
    /// Seconds, minutes, hours, day, month, year.
    time: [i64; 6],
    packed: usize,
    comment_len: usize,
    private_len: usize,
    offset: [f64; 3],
}

/// Reads and checks the identifying fields at the cursor (the header's
/// start).
fn ident(c: &mut Cursor) -> Result<Ident> {
    let code = c.take(12, "signature")?;
    let compressed = match code {
        PLAIN => false,
        COMPRESSED => true,
        _ => return Err(c.bad("signature", 12, "not DIGITAL SURF nor DSCOMPRESSED")),
    };
    let format = c.u16("format")?;
    if format != 0 {
        return Err(c.bad(
            "format",
            2,
            format!("{format}; only PC files (0, little-endian) are read"),
        ));
    }
    let objects = c.u16("number of objects")?;
    let version = c.u16("version")?;
    if version != 1 {
        return Err(c.bad("version", 2, format!("{version}; version 1 is read")));
    }
    let kind = c.u16("object type")?;
    let object_name = c.text(30, "object name")?;
    let operator = c.text(30, "operator name")?;
    c.skip(2);
    let acquisition = c.u16("acquisition type")?;
    c.skip(2);
    let non_measured = c.u16("non-measured points")? == 1;
    c.skip(6);
    let w_size = c.i32("spectral size")?;
    if w_size > 1 {
        return Err(c.bad(
            "spectral size",
            4,
            format!("{w_size} values per point (a hyperspectral object); one is read"),
        ));
    }
    let bits = c.u16("bits per point")?;
    if bits != 16 && bits != 32 {
        return Err(c.bad("bits per point", 2, format!("{bits}; 16 or 32 expected")));
    }
    let zmin = c.i32("zmin")?;
    c.skip(4);
    Ok(Ident {
        compressed,
        objects,
        kind,
        object_name,
        operator,
        acquisition,
        non_measured,
        bits,
        zmin,
    })
}

/// Reads the placing fields at the cursor (after [`ident`]) of the object
/// header at `at`.
fn geometry(bytes: &Bytes, c: &mut Cursor, at: usize) -> Result<Geometry> {
    let dim_at = c.pos();
    let nx = c.i32("points per line")?;
    let ny = c.i32("lines")?;
    let total = c.i32("total points")?;
    if nx <= 0 || ny <= 0 || (nx as i64) * (ny as i64) != total as i64 {
        return Err(bytes.error(
            "SUR header (grid size)",
            dim_at,
            format!("{nx} points per line, {ny} lines and {total} points in all do not agree"),
        ));
    }
    let step = [c.f32("x step")?, c.f32("y step")?, c.f32("z step")?].map(f64::from);
    c.skip(32);
    let z_name = c.text(16, "z axis name")?;
    let step_units = [
        c.text(16, "x step unit")?,
        c.text(16, "y step unit")?,
        c.text(16, "z step unit")?,
    ];
    let length_units = [
        c.text(16, "x unit")?,
        c.text(16, "y unit")?,
        c.text(16, "z unit")?,
    ];
    c.seek(at + 306);
    let mut time = [0i64; 6];
    for (v, f) in time
        .iter_mut()
        .zip(["seconds", "minutes", "hours", "day", "month", "year"])
    {
        *v = c.u16(f)? as i64;
    }
    c.seek(at + 324);
    let packed = c.u32("compressed size")? as usize;
    c.seek(at + 334);
    let comment_len = c.u16("comment size")? as usize;
    let private_len = c.u16("private size")? as usize;
    c.seek(at + 466);
    let offset = [c.f32("x offset")?, c.f32("y offset")?, c.f32("z offset")?].map(f64::from);
    Ok(Geometry {
        nx: nx as usize,
        ny: ny as usize,
        step,
        z_name,
        step_units,
        length_units,
        time,
        packed,
        comment_len,
        private_len,
        offset,
    })
}

/// The object's grid in metres: steps and offsets in their units (x and y
/// steps must be lengths); heights only when z is a length and the object
/// is not an intensity or RGB image.
fn object_grid(bytes: &Bytes, at: usize, kind: u16, g: &Geometry) -> Result<Grid> {
    let scale = length;
    let (step_units, length_units) = (&g.step_units, &g.length_units);
    let (sx, sy) = match (scale(&step_units[0]), scale(&step_units[1])) {
        (Some(a), Some(b)) => (a, b),
        _ => {
            return Err(bytes.error(
                "SUR header (step units)",
                at + 180,
                format!(
                    "x and y step units '{}', '{}'; lengths expected",
                    step_units[0], step_units[1]
                ),
            ))
        }
    };
    let ox = scale(&length_units[0]).unwrap_or(sx);
    let oy = scale(&length_units[1]).unwrap_or(sy);
    let z_is_length = scale(&step_units[2]).is_some();
    let [dx, dy, _] = g.step;
    let mut grid = Grid::heights(
        if g.z_name.is_empty() { "Z" } else { &g.z_name },
        g.nx,
        g.ny,
        dx.abs() * sx,
        if g.ny == 1 {
            dx.abs() * sx
        } else {
            dy.abs() * sy
        },
    );
    grid.x0 = g.offset[0] * ox;
    grid.y0 = g.offset[1] * oy;
    // Intensity and RGB images are channels beside the heights.
    grid.height = z_is_length && !matches!(kind, 3 | 10 | 12 | 18);
    if !z_is_length {
        grid.unit = step_units[2].clone();
    }
    check_grid(bytes, "SUR header", at + 120, &grid)?;
    Ok(grid)
}

/// Reads the header of the object at `at`.
fn object(bytes: &Bytes, at: usize) -> Result<Object> {
    let mut c = bytes.le(at, "SUR header");
    let id = ident(&mut c)?;
    let g = geometry(bytes, &mut c, at)?;
    let comment = crate::ingest::binary::latin1_or_utf8(bytes.slice(
        at + HEADER,
        g.comment_len,
        "SUR comment",
    )?);
    bytes.slice(
        at + HEADER + g.comment_len,
        g.private_len,
        "SUR private zone",
    )?;
    let data_at = at + HEADER + g.comment_len + g.private_len;
    let data_len = match id.compressed {
        false => g.nx * g.ny * (id.bits as usize / 8),
        true => g.packed,
    };
    let grid = object_grid(bytes, at, id.kind, &g)?;
    let z_step_scale = length(&g.step_units[2]);
    let z_unit_scale = length(&g.length_units[2]).or(z_step_scale).unwrap_or(1.0);
    let t = g.time;
    Ok(Object {
        header: Header {
            compressed: id.compressed,
            objects: id.objects,
            kind: id.kind,
            non_measured: id.non_measured,
            bits: id.bits,
            zmin: id.zmin,
            dz: g.step[2],
            // The offset is in the Z length unit; heights go out in the step
            // unit's scale, so express it there.
            z_offset: g.offset[2] * z_unit_scale / z_step_scale.unwrap_or(1.0),
            z_name: g.z_name,
            z_unit: g.step_units[2].clone(),
            xy_units: [g.step_units[0].clone(), g.step_units[1].clone()],
            date: iso_date(t[5], t[4], t[3], t[2], t[1], t[0]),
            object_name: id.object_name,
            operator: id.operator,
            acquisition: id.acquisition,
            comment,
        },
        grid,
        data_at,
        data_len,
    })
}

/// The zlib streams of a compressed object, decoded into one buffer.
fn inflate(
    bytes: &Bytes,
    o: &Object,
    n: usize,
    conv: &Conversion,
    structure: &str,
) -> Result<crate::ingest::grid::GridData> {
    let mut c: Cursor = bytes.le(o.data_at, "SUR compressed directory");
    let count = c.u32("stream count")? as usize;
    if count == 0 || count > 4096 {
        return Err(c.bad(
            "stream count",
            4,
            format!("{count} streams; 1 to 4096 expected"),
        ));
    }
    let mut dir = Vec::with_capacity(count);
    for _ in 0..count {
        dir.push((
            c.u32("raw length")? as usize,
            c.u32("compressed length")? as usize,
        ));
    }
    let total: usize = 4 + 8 * count + dir.iter().map(|d| d.1).sum::<usize>();
    if total != o.data_len {
        return Err(bytes.error(
            "SUR compressed directory",
            o.data_at,
            format!(
                "streams of {total} bytes in all; the header says {}",
                o.data_len
            ),
        ));
    }
    let raw_total = dir.iter().map(|d| d.0).sum::<usize>();
    let most = raw_total.min(inflated_at_most(o.data_len));
    let mut s = Stream::new(*conv, n, most);
    let mut at = c.pos();
    let mut buf = vec![0u8; 256 << 10];
    for (k, (raw, packed)) in dir.into_iter().enumerate() {
        let input = bytes.slice(at, packed, structure)?;
        let mut z = flate2::read::ZlibDecoder::new(input);
        let mut got = 0;
        loop {
            let m = std::io::Read::read(&mut z, &mut buf).map_err(|e| {
                bytes.error(
                    structure,
                    at,
                    format!("zlib stream {} cannot be decoded: {e}", k + 1),
                )
            })?;
            if m == 0 {
                break;
            }
            got += m;
            s.push(&buf[..m]);
        }
        if got != raw {
            return Err(bytes.error(
                structure,
                at,
                format!(
                    "zlib stream {} holds {got} bytes; the directory says {raw}",
                    k + 1
                ),
            ));
        }
        bytes.release(at..at + packed);
        at += packed;
    }
    let got = s.len();
    s.finish()
        .ok_or_else(|| bytes.error(structure, o.data_at, format!("{got} points; {n} expected")))
}

fn metadata(h: &Header, objects: &[Object]) -> Vec<MetaEntry> {
    let mut out = vec![meta(keys::INSTRUMENT, "Digital Surf")];
    if let Some(d) = &h.date {
        out.push(meta(keys::DATE, d));
    }
    out.push(meta(
        keys::LATERAL_UNIT,
        format!("{} {}", h.xy_units[0], h.xy_units[1]),
    ));
    out.push(meta(keys::HEIGHT_UNIT, &h.z_unit));
    let g = &objects[0].grid;
    out.push(meta(
        keys::LATERAL_SCALE,
        format!("{:e} {:e} m", g.dx, g.dy),
    ));
    out.push(meta(keys::HEIGHT_SCALE, format!("{:e} {}", h.dz, h.z_unit)));
    for (k, v) in [
        ("object name", h.object_name.clone()),
        ("operator name", h.operator.clone()),
        ("object type", h.kind.to_string()),
        ("acquisition type", h.acquisition.to_string()),
        ("compressed", h.compressed.to_string()),
        ("bits per point", h.bits.to_string()),
        ("non-measured points", h.non_measured.to_string()),
        ("zmin", h.zmin.to_string()),
        (
            "z offset (m)",
            format!("{:e}", h.z_offset * length(&h.z_unit).unwrap_or(1.0)),
        ),
        ("objects", objects.len().to_string()),
        ("z axis name", h.z_name.clone()),
        ("comment", h.comment.clone()),
    ] {
        if !v.is_empty() {
            out.push(meta(k, v));
        }
    }
    out
}
