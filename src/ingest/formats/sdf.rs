//! ISO 25178-71 surface data file (SDF), ASCII (`aISO-1.0`) and binary
//! (`bISO-1.0`). The ASCII file: `Key = value` header lines, `*`, the
//! values (NumProfiles rows of NumPoints, `BAD` where not measured), `*`,
//! a trailer of tagged metadata, `*`. The binary file: a packed
//! little-endian header (magic, ManufacID 10 bytes, CreateDate and
//! ModDate 12 bytes each, NumPoints and NumProfiles u16, Xscale, Yscale,
//! Zscale, Zresolution f64, Compression, DataType, CheckType u8), then the
//! values: DataType 0 to 7 (u8, u16, u32, f32, i8, i16, i32, f64, as
//! Gwyddion numbers them); NaN, or the minimum of int16 and int32 (as
//! SurfaceTopography reads them), where not measured. Heights are value · Zscale (m); spacings
//! Xscale, Yscale (m).

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Invalid, Sample};
use crate::ingest::binary::{check_grid, keys, meta, Bytes};
use crate::ingest::grid::{Grid, GridData};
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Sdf;

const ASCII: &[u8] = b"aISO-1.0";
const BINARY: &[u8] = b"bISO-1.0";
const BINARY_HEADER: usize = 81;

impl Reader for Sdf {
    fn name(&self) -> &'static str {
        "sdf"
    }
    fn description(&self) -> &'static str {
        "ISO 25178-71 SDF surface data file, ASCII (aISO-1.0) and binary (bISO-1.0)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(ASCII) || data.starts_with(BINARY)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(match bytes.data.starts_with(BINARY) {
            true => binary(bytes),
            false => ascii(bytes),
        })
    }
}

/// What the header gives.
struct Header {
    nx: usize,
    ny: usize,
    scale: [f64; 3],
    meta: Vec<MetaEntry>,
}

impl Header {
    fn grid(&self, bytes: &Bytes, at: usize, data: GridData) -> Result<Decoded> {
        let mut g = Grid::heights(
            "Z",
            self.nx,
            self.ny,
            self.scale[0],
            if self.ny == 1 {
                self.scale[0]
            } else {
                self.scale[1]
            },
        );
        check_grid(bytes, "SDF header", at, &g)?;
        g.data = Some(data);
        let mut m = vec![
            meta(keys::LATERAL_UNIT, "m"),
            meta(keys::HEIGHT_UNIT, "m"),
            meta(
                keys::LATERAL_SCALE,
                format!("{:e} {:e}", self.scale[0], self.scale[1]),
            ),
            meta(keys::HEIGHT_SCALE, format!("{:e}", self.scale[2])),
        ];
        m.extend(self.meta.iter().cloned());
        Ok(Decoded {
            preamble: m,
            sections: Vec::new(),
            grids: vec![g],
        })
    }
}

fn binary(bytes: &Bytes) -> Result<Decoded> {
    let mut c = bytes.le(8, "SDF binary header");
    let manufacturer = c.text(10, "ManufacID")?;
    let created = c.text(12, "CreateDate")?;
    let modified = c.text(12, "ModDate")?;
    let nx = c.u16("NumPoints")? as usize;
    let ny = c.u16("NumProfiles")? as usize;
    let scale = [c.f64("Xscale")?, c.f64("Yscale")?, c.f64("Zscale")?];
    let resolution = c.f64("Zresolution")?;
    let compression = c.u8("Compression")?;
    if compression != 0 {
        return Err(c.bad(
            "Compression",
            1,
            format!("{compression}; uncompressed (0) is read"),
        ));
    }
    let data_type = c.u8("DataType")?;
    let (sample, invalid) = match data_type {
        0 => (Sample::U8, Invalid::None),
        1 => (Sample::U16, Invalid::None),
        2 => (Sample::U32, Invalid::None),
        3 => (Sample::F32, Invalid::None),
        4 => (Sample::I8, Invalid::None),
        5 => (Sample::I16, Invalid::Equal(i16::MIN as f64)),
        6 => (Sample::I32, Invalid::Equal(i32::MIN as f64)),
        7 => (Sample::F64, Invalid::None),
        t => {
            return Err(c.bad(
                "DataType",
                1,
                format!("{t}; 0 to 7 (u8, u16, u32, f32, i8, i16, i32, f64) expected"),
            ))
        }
    };
    let h = Header {
        nx,
        ny,
        scale,
        meta: vec![
            meta("DataType", data_type),
            meta(keys::INSTRUMENT, &manufacturer),
            meta("CreateDate", created),
            meta("ModDate", modified),
            meta("Zresolution", resolution),
        ],
    };
    let conv = Conversion::raw(sample)
        .scaled(scale[2], 0.0)
        .invalid(invalid);
    let data = decode(bytes, BINARY_HEADER, nx * ny, &conv, "SDF data")?;
    h.grid(bytes, 8, data)
}

/// The `n` values after the header's `*` line (`BAD` or NaN: not
/// measured), scaled by `z_scale`; `body_at` is where they start in the
/// file.
fn ascii_values(
    bytes: &Bytes,
    body: &str,
    body_at: usize,
    n: usize,
    z_scale: f64,
) -> Result<Vec<f64>> {
    let mut values = Vec::with_capacity(n.min(body.len() / 2 + 1));
    for token in body.split_ascii_whitespace() {
        let at = body_at + (token.as_ptr() as usize - body.as_ptr() as usize);
        if values.len() == n {
            return Err(bytes.error(
                "SDF data",
                at,
                format!("more than NumPoints × NumProfiles = {n} values"),
            ));
        }
        let v = match token {
            "BAD" | "bad" | "NaN" | "nan" => f64::NAN,
            t => {
                t.parse::<f64>()
                    .map_err(|_| bytes.error("SDF data", at, format!("'{t}' is not a number")))?
                    * z_scale
            }
        };
        values.push(if v.is_finite() { v } else { f64::NAN });
    }
    if values.len() != n {
        return Err(bytes.error(
            "SDF data",
            body_at,
            format!(
                "{} values; NumPoints × NumProfiles = {n} expected",
                values.len()
            ),
        ));
    }
    Ok(values)
}

fn ascii(bytes: &Bytes) -> Result<Decoded> {
    let text = String::from_utf8_lossy(bytes.data);
    let mut parts = text.splitn(3, "\n*");
    let head = parts.next().unwrap_or("");
    let body = parts
        .next()
        .ok_or_else(|| bytes.error("SDF file", head.len(), "no '*' line after the header"))?;
    let body_at = head.len() + 2;
    let mut get = std::collections::BTreeMap::new();
    let mut m = Vec::new();
    for (n, line) in head.lines().enumerate().skip(1) {
        if let Some((k, v)) = line.split_once('=') {
            get.insert(k.trim().to_string(), (v.trim().to_string(), n + 1));
            m.push(MetaEntry {
                key: k.trim().into(),
                value: v.trim().into(),
                line: n + 1,
            });
        }
    }
    let field = |k: &str| -> Result<&(String, usize)> {
        get.get(k)
            .ok_or_else(|| bytes.error("SDF header", 0, format!("no {k}")))
    };
    let number = |k: &str| -> Result<f64> {
        let (v, line) = field(k)?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                bytes.error(
                    "SDF header",
                    0,
                    format!("{k} = '{v}' (line {line}) is not a number"),
                )
            })
    };
    let count = |k: &str| -> Result<usize> {
        let (v, line) = field(k)?;
        v.parse::<usize>().map_err(|_| {
            bytes.error(
                "SDF header",
                0,
                format!("{k} = '{v}' (line {line}) is not a count"),
            )
        })
    };
    let h = Header {
        nx: count("NumPoints")?,
        ny: count("NumProfiles")?,
        scale: [number("Xscale")?, number("Yscale")?, number("Zscale")?],
        meta: m,
    };
    let n =
        h.nx.checked_mul(h.ny)
            .ok_or_else(|| bytes.error("SDF header", 0, "too many points"))?;
    let values = ascii_values(bytes, body, body_at, n, h.scale[2])?;
    h.grid(bytes, 0, GridData::new(values))
}
