//! Alicona Imaging AL3D: the magic `AliconaImaging\0\r\n`, then tags of
//! 52 bytes (key 20, value 30, both NUL-padded text, CR LF): `Version`,
//! `TagCount`, then `TagCount` more (`Cols`, `Rows`, `PixelSizeXMeter`,
//! `PixelSizeYMeter`, `DepthImageOffset`, `InvalidPixelValue`,
//! `TextureImageOffset`, `NumberOfPlanes`, ...). The depth image is f32
//! metres, rows padded to 8 bytes; a value within 1.5e-7 (relative) of
//! `InvalidPixelValue`, or NaN, is not measured (as SurfaceTopography and
//! Gwyddion read it). The texture's planes (u8, rows padded to 8 bytes,
//! one plane after the other) are channels `Texture N`.

use std::collections::BTreeMap;

use crate::error::Result;
use crate::ingest::binary::decode::{Conversion, Sample};
use crate::ingest::binary::rows::decode_rows;
use crate::ingest::binary::{check_grid, keys, meta, select_channel, Bytes};
use crate::ingest::grid::{count_nan, Grid, GridData};
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Al3d;

const MAGIC: &[u8] = b"AliconaImaging\x00\r\n";
const STRUCTURE: &str = "AL3D tag";
const TAG: usize = 52;
const INVALID_RELTOL: f64 = 1.5e-7;

impl Reader for Al3d {
    fn name(&self) -> &'static str {
        "al3d"
    }
    fn description(&self) -> &'static str {
        "Alicona Imaging AL3D depth map (and texture planes as channels)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// The tags: key → (value, byte offset of the tag).
fn tags(bytes: &Bytes) -> Result<BTreeMap<String, (String, usize)>> {
    let text = |b: &[u8]| {
        let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
        String::from_utf8_lossy(&b[..end]).trim().to_string()
    };
    let mut out = BTreeMap::new();
    let mut at = MAGIC.len();
    let mut total = 2;
    let mut k = 0;
    while k < total {
        let tag = bytes.slice(at, TAG, STRUCTURE)?;
        if &tag[50..] != b"\r\n" {
            return Err(bytes.error(STRUCTURE, at + 50, "a tag ends with CR LF"));
        }
        let (key, value) = (text(&tag[..20]), text(&tag[20..50]));
        let want = ["Version", "TagCount"].get(k).copied();
        if want.is_some_and(|w| w != key) {
            return Err(bytes.error(
                STRUCTURE,
                at,
                format!("'{key}'; {} expected", want.unwrap_or("")),
            ));
        }
        if key == "TagCount" {
            let n: usize =
                value.parse().ok().filter(|&n| n < 10_000).ok_or_else(|| {
                    bytes.error(STRUCTURE, at + 20, format!("TagCount '{value}'"))
                })?;
            total = 2 + n;
        }
        out.insert(key, (value, at));
        at += TAG;
        k += 1;
    }
    Ok(out)
}

/// The depth image: f32 rows padded to 8 bytes, the invalid-pixel value
/// (to a relative tolerance) as not measured.
fn depth_image(
    bytes: &Bytes,
    at: usize,
    (nx, ny): (usize, usize),
    invalid: f64,
) -> Result<GridData> {
    let stride = (nx * 4).div_ceil(8) * 8;
    let mut d = decode_rows(
        bytes,
        at,
        (nx, ny),
        stride,
        &Conversion::raw(Sample::F32),
        "AL3D depth image",
    )?;
    if invalid.is_finite() {
        for v in d
            .values
            .iter_mut()
            .filter(|v| (**v - invalid).abs() < INVALID_RELTOL * invalid.abs())
        {
            *v = f64::NAN;
        }
        d.n_invalid = count_nan(&d.values);
    }
    Ok(d)
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let t = tags(bytes)?;
    let get = |k: &str| -> Result<&(String, usize)> {
        t.get(k)
            .ok_or_else(|| bytes.error(STRUCTURE, MAGIC.len(), format!("no tag {k}")))
    };
    let number = |k: &str| -> Result<f64> {
        let (v, at) = get(k)?;
        v.parse::<f64>()
            .map_err(|_| bytes.error(STRUCTURE, at + 20, format!("{k} '{v}' is not a number")))
    };
    let count = |k: &str| -> Result<usize> {
        let (v, at) = get(k)?;
        v.parse::<usize>()
            .map_err(|_| bytes.error(STRUCTURE, at + 20, format!("{k} '{v}' is not a count")))
    };
    let (nx, ny) = (count("Cols")?, count("Rows")?);
    let depth = Grid::heights(
        "Height",
        nx,
        ny,
        number("PixelSizeXMeter")?,
        number("PixelSizeYMeter")?,
    );
    check_grid(bytes, STRUCTURE, get("Cols")?.1, &depth)?;
    let mut grids = vec![depth.clone()];
    let texture_at = t
        .get("TextureImageOffset")
        .and_then(|(v, _)| v.parse::<usize>().ok())
        .unwrap_or(0);
    let planes = if texture_at > 0 {
        count("NumberOfPlanes").unwrap_or(0).min(16)
    } else {
        0
    };
    for p in 0..planes {
        let mut g = depth.clone();
        (g.name, g.height, g.unit) = (format!("Texture {p}"), false, String::new());
        grids.push(g);
    }
    let i = select_channel(bytes, &grids, options)?;
    let data = if i == 0 {
        let at = count("DepthImageOffset")?;
        depth_image(bytes, at, (nx, ny), number("InvalidPixelValue")?)?
    } else {
        let stride = nx.div_ceil(8) * 8;
        let at = texture_at + (i - 1) * stride * ny;
        decode_rows(
            bytes,
            at,
            (nx, ny),
            stride,
            &Conversion::raw(Sample::U8),
            "AL3D texture",
        )?
    };
    grids[i].data = Some(data);
    let mut m: Vec<MetaEntry> = vec![meta(keys::LATERAL_UNIT, "m"), meta(keys::HEIGHT_UNIT, "m")];
    let software = t.get("CreatingApplication").map_or("", |(v, _)| v.as_str());
    m.push(meta(
        keys::INSTRUMENT,
        format!("Alicona Imaging {software}").trim(),
    ));
    for (k, (v, _)) in &t {
        if v.chars().all(|c| !c.is_control()) {
            m.push(meta(k, v));
        }
    }
    Ok(Decoded {
        preamble: m,
        sections: Vec::new(),
        grids,
    })
}
