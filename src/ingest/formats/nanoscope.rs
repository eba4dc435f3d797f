//! Bruker / Veeco / Digital Instruments Nanoscope images (`.spm`, `.001`,
//! `.002`, ..., versions 4.3 to 10): a text header of `\Key: value` lines
//! in sections (`\*File list`, `\*Scanner list`, `\*Ciao scan list`, one
//! `\*Ciao image list` per channel, ... `\*File list end`), then each
//! channel's samples, little-endian signed integers of `Bytes/pixel` (2 or
//! 4) at its `Data offset`.
//!
//! A channel's value per count is its `@2:Z scale` hard value (the range of
//! 2^(8·bytes) counts, e.g. `V [Sens. Zsens] (0.0050354 V/LSB) 2.910461 V`)
//! divided by 2^(8·bytes), times the soft scale it names (`@Sens. Zsens:
//! V 20.82646 nm/V`), as in Gwyddion and SurfaceTopography. A channel in a
//! length unit that is not a deflection, amplitude or error signal is a
//! height map (in metres); the others keep their unit. Channels are named
//! by their `Image Data` (`Height`, `Phase`, ...), ` (retrace)` added for
//! retrace lines. Rows are kept in file order (the first row is the bottom
//! line of the scan); Nanoscope files have no marker for points not
//! measured. Force-curve files are not read.

use crate::error::Result;
use crate::ingest::binary::decode::{decode, Conversion, Sample};
use crate::ingest::binary::units::{length_m, prefixed_ratio};
use crate::ingest::binary::{check_grid, iso_date, keys, meta, select_channel, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, MetaEntry, Reader};

/// The registry entry.
pub struct Nanoscope;

const MAGICS: [&[u8]; 3] = [b"\\*File list", b"\\*EC File list", b"?*File list"];

impl Reader for Nanoscope {
    fn name(&self) -> &'static str {
        "nanoscope"
    }
    fn description(&self) -> &'static str {
        "Bruker/Veeco Nanoscope .spm/.001 AFM images: every channel, heights in metres"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        MAGICS.iter().any(|m| data.starts_with(m))
    }
    fn read_bytes(&self, bytes: &Bytes, options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes, options))
    }
}

/// One `\*Section` of the header: its lines as (lower-case key, value,
/// byte offset).
struct Section {
    name: String,
    at: usize,
    lines: Vec<(String, String, usize)>,
}

impl Section {
    fn get(&self, key: &str) -> Option<(&str, usize)> {
        self.lines
            .iter()
            .find(|(k, ..)| k == key)
            .map(|(_, v, at)| (v.as_str(), *at))
    }
}

/// The header's sections, up to `\*File list end`.
fn sections(bytes: &Bytes) -> Result<Vec<Section>> {
    let mut out: Vec<Section> = Vec::new();
    let mut pos = 0;
    let data = bytes.data;
    while pos < data.len() {
        let end = data[pos..]
            .iter()
            .position(|&c| c == b'\n')
            .map_or(data.len(), |k| pos + k);
        let line: String = data[pos..end]
            .iter()
            .map(|&c| c as char)
            .collect::<String>()
            .trim()
            .to_string();
        let at = pos;
        pos = end + 1;
        let Some(body) = line.strip_prefix(['\\', '?']) else {
            if line.is_empty() || line.starts_with('\u{1a}') {
                continue;
            }
            return Err(bytes.error(
                "Nanoscope header",
                at,
                "a line that does not start with '\\' before '\\*File list end' (truncated?)",
            ));
        };
        if let Some(name) = body.strip_prefix('*') {
            let name = name.trim().to_ascii_lowercase();
            if name == "file list end" {
                return Ok(out);
            }
            out.push(Section {
                name,
                at,
                lines: Vec::new(),
            });
        } else if let Some(s) = out.last_mut() {
            // Keys hold colons (`@2:Z scale`): the value follows ": ".
            let (k, v) = body
                .split_once(": ")
                .unwrap_or((body.trim_end_matches(':'), ""));
            s.lines
                .push((k.trim().to_ascii_lowercase(), v.trim().to_string(), at));
        }
    }
    Err(bytes.error(
        "Nanoscope header",
        data.len(),
        "no '\\*File list end' line (truncated?)",
    ))
}

/// A `V [Sens. X] (a u/LSB) b u` scale: the soft-scale name and the hard
/// value with its unit.
fn parse_scale(v: &str) -> Option<(Option<&str>, f64, &str)> {
    let v = v.trim().strip_prefix('V')?.trim();
    let (soft, v) = match v.strip_prefix('[') {
        Some(r) => {
            let (name, rest) = r.split_once(']')?;
            (Some(name.trim()), rest.trim())
        }
        None => (None, v),
    };
    let v = match v.strip_prefix('(') {
        Some(r) => r.split_once(')')?.1.trim(),
        None => v,
    };
    let (num, unit) = v.split_once(' ').unwrap_or((v, ""));
    Some((
        soft.filter(|s| !s.is_empty()),
        num.parse().ok()?,
        unit.trim(),
    ))
}

/// An image channel: where its samples are and how they scale.
struct Image {
    grid: Grid,
    offset: usize,
    sample: Sample,
    scale: f64,
}

/// The channel's name: the quoted signal of its `Image Data` line
/// (`"Height"`), else its number.
fn channel_name(s: &Section, n: usize) -> String {
    s.get("@2:image data")
        .or(s.get("image data"))
        .map(|(v, _)| {
            let quoted = v.split('"').nth(1).filter(|q| !q.is_empty());
            quoted.unwrap_or(v).to_string()
        })
        .unwrap_or_else(|| format!("Channel {n}"))
}

/// Whether a signal is not a height even when its unit is a length
/// (deflection, amplitude, error, friction, lateral force).
fn not_topography(name: &str) -> bool {
    let signal = name.to_ascii_lowercase();
    ["deflection", "amplitude", "error", "friction", "lateral"]
        .iter()
        .any(|w| signal.contains(w))
}

fn image(bytes: &Bytes, all: &[Section], s: &Section, n: usize) -> Result<Image> {
    let structure = format!("Nanoscope {} {n}", s.name);
    let need = |key: &str| {
        s.get(key).ok_or_else(|| {
            bytes.error(
                &structure,
                s.at,
                format!("no '{key}' line (corrupted header?)"),
            )
        })
    };
    let count = |key: &str| -> Result<usize> {
        let (v, at) = need(key)?;
        v.parse()
            .map_err(|_| bytes.error(&structure, at, format!("{key} '{v}' is not a count")))
    };
    let (nx, ny, offset) = (
        count("samps/line")?,
        count("number of lines")?,
        count("data offset")?,
    );
    let bpp = s
        .get("bytes/pixel")
        .map_or(Ok(2), |_| count("bytes/pixel"))?;
    let sample = match bpp {
        2 => Sample::I16,
        4 => Sample::I32,
        b => {
            return Err(bytes.error(
                &structure,
                need("bytes/pixel")?.1,
                format!("{b} bytes per pixel; 2 or 4 are read"),
            ))
        }
    };
    let length = count("data length")?;
    if length < nx.saturating_mul(ny).saturating_mul(bpp) {
        return Err(bytes.error(
            &structure,
            need("data length")?.1,
            format!("Data length {length} is less than {nx} × {ny} samples of {bpp} bytes"),
        ));
    }
    let (sx, sy, lateral) = scan_size(bytes, all, s, &structure)?;
    let (scale, unit) = z_scale(bytes, all, s, &structure, bpp)?;
    let name = channel_name(s, n);
    let mut grid = Grid::heights(
        &name,
        nx,
        ny,
        sx * lateral / nx as f64,
        sy * lateral / ny as f64,
    );
    if s.get("line direction")
        .is_some_and(|(v, _)| v.eq_ignore_ascii_case("retrace"))
    {
        grid.name.push_str(" (retrace)");
    }
    check_grid(bytes, &structure, s.at, &grid)?;
    let scale = match length_m(&unit) {
        Some(m) if !not_topography(&name) => scale * m,
        _ => {
            grid.height = false;
            grid.unit = unit;
            scale
        }
    };
    Ok(Image {
        grid,
        offset,
        sample,
        scale,
    })
}

/// The scan size (x, y) and metres per its unit: the image's `Scan Size`
/// (`500 500 nm`), else the scan list's (`500 nm`, y from the aspect
/// ratio).
fn scan_size(
    bytes: &Bytes,
    all: &[Section],
    s: &Section,
    structure: &str,
) -> Result<(f64, f64, f64)> {
    let scan = all.iter().find(|x| x.name.ends_with("scan list"));
    let (v, at) = s
        .get("scan size")
        .or_else(|| scan.and_then(|x| x.get("scan size")))
        .ok_or_else(|| bytes.error(structure, s.at, "no 'Scan Size' line"))?;
    let parts: Vec<&str> = v.split_whitespace().collect();
    let nums: Vec<f64> = parts.iter().map_while(|p| p.parse().ok()).collect();
    let unit = parts.get(nums.len()).copied().unwrap_or("");
    let lateral = length_m(unit).ok_or_else(|| {
        bytes.error(
            structure,
            at,
            format!("Scan Size '{v}': a length unit expected"),
        )
    })?;
    let (sx, sy) = match nums[..] {
        [x, y, ..] => (x, y),
        [x] => {
            let ratio = s
                .get("aspect ratio")
                .and_then(|(r, _)| r.split_once(':'))
                .and_then(|(a, b)| {
                    Some(a.trim().parse::<f64>().ok()? / b.trim().parse::<f64>().ok()?)
                })
                .filter(|r| r.is_finite() && *r > 0.0)
                .unwrap_or(1.0);
            (x, x / ratio)
        }
        [] => return Err(bytes.error(structure, at, format!("Scan Size '{v}' has no number"))),
    };
    Ok((sx, sy, lateral))
}

/// Value per count and its unit, from the Z scale and its soft scale.
fn z_scale(
    bytes: &Bytes,
    all: &[Section],
    s: &Section,
    structure: &str,
    bpp: usize,
) -> Result<(f64, String)> {
    let (v, at) = s
        .get("@2:z scale")
        .or(s.get("z scale"))
        .ok_or_else(|| bytes.error(structure, s.at, "no '@2:Z scale' line"))?;
    let bad = |m: String| bytes.error(&format!("{structure} (Z scale)"), at, m);
    let (soft, hard, hard_unit) = parse_scale(v)
        .ok_or_else(|| bad(format!("'{v}': 'V [Sens. name] (a V/LSB) b V' expected")))?;
    let per_count = hard / (1u64 << (8 * bpp)) as f64;
    let Some(soft) = soft else {
        return Ok((per_count, hard_unit.to_string()));
    };
    let key = format!("@{}", soft.to_ascii_lowercase());
    let found = all.iter().find_map(|x| x.get(&key));
    let Some((sv, sat)) = found else {
        return Err(bad(format!(
            "names the soft scale '{soft}', which is not in the header"
        )));
    };
    let mut it = sv.trim().strip_prefix('V').unwrap_or(sv).split_whitespace();
    let factor: f64 = it.next().and_then(|x| x.parse().ok()).ok_or_else(|| {
        bytes.error(
            &format!("Nanoscope {soft}"),
            sat,
            format!("'{sv}' has no number"),
        )
    })?;
    match it.next().and_then(|u| u.split_once('/')) {
        // A unit per hard unit (nm/V): the value is in the numerator.
        Some((num, den)) => {
            let ratio = prefixed_ratio(hard_unit, den).ok_or_else(|| {
                bad(format!(
                    "hard unit '{hard_unit}' and soft scale unit '{num}/{den}' do not agree"
                ))
            })?;
            Ok((per_count * factor * ratio, num.to_string()))
        }
        None => Ok((per_count * factor, hard_unit.to_string())),
    }
}

fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Decoded> {
    let all = sections(bytes)?;
    if all.first().is_some_and(|s| s.name.contains("force")) {
        return Err(bytes.error(
            "Nanoscope header",
            0,
            "a force-curve file; images (\\*File list) are read",
        ));
    }
    let mut images = Vec::new();
    for s in all.iter().filter(|s| s.name.ends_with("image list")) {
        images.push(image(bytes, &all, s, images.len() + 1)?);
    }
    if images.is_empty() {
        return Err(bytes.error("Nanoscope header", 0, "no image list section"));
    }
    let mut grids: Vec<Grid> = Vec::new();
    for im in &images {
        let mut g = im.grid.clone();
        let base = g.name.clone();
        let mut k = 2;
        while grids.iter().any(|o| o.name == g.name) {
            g.name = format!("{base} {k}");
            k += 1;
        }
        grids.push(g);
    }
    let i = select_channel(bytes, &grids, options)?;
    let im = &images[i];
    let conv = Conversion::raw(im.sample).scaled(im.scale, 0.0);
    let g = &grids[i];
    let structure = format!("Nanoscope image {} data", i + 1);
    grids[i].data = Some(decode(bytes, im.offset, g.nx * g.ny, &conv, &structure)?);
    Ok(Decoded {
        preamble: metadata(&all, &grids[i], im.scale),
        sections: Vec::new(),
        grids,
    })
}

/// `09:57:48 AM Tue Jan 12 2016` as ISO 8601.
fn date(v: &str) -> Option<String> {
    let p: Vec<&str> = v.split_whitespace().collect();
    let [time, ampm, _, mon, day, year] = p[..] else {
        return None;
    };
    let t: Vec<i64> = time
        .split(':')
        .map(|x| x.parse().ok())
        .collect::<Option<_>>()?;
    let [h, mi, s] = t[..] else { return None };
    let h = match (ampm.to_ascii_uppercase().as_str(), h) {
        ("AM", 12) => 0,
        ("PM", h) if h < 12 => h + 12,
        _ => h,
    };
    let months = [
        "jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec",
    ];
    let mo = months
        .iter()
        .position(|m| mon.to_ascii_lowercase().starts_with(m))? as i64
        + 1;
    iso_date(year.parse().ok()?, mo, day.parse().ok()?, h, mi, s)
}

fn metadata(all: &[Section], g: &Grid, scale: f64) -> Vec<MetaEntry> {
    let find = |sec: &str, key: &str| {
        all.iter()
            .filter(|s| s.name.contains(sec))
            .find_map(|s| s.get(key))
            .map(|(v, _)| v.to_string())
            .filter(|v| !v.is_empty())
    };
    let model = find("equipment", "microscope").or(find("equipment", "description"));
    let mut m = vec![meta(
        keys::INSTRUMENT,
        format!("Bruker Nanoscope {}", model.unwrap_or_default()).trim(),
    )];
    if let Some(d) = find("file list", "date").as_deref().and_then(date) {
        m.push(meta(keys::DATE, d));
    }
    if let Some(t) = find("scan list", "tip serial number") {
        m.push(meta(keys::TIP, t));
    }
    m.push(meta(keys::LATERAL_UNIT, "m"));
    m.push(meta(keys::HEIGHT_UNIT, &g.unit));
    m.push(meta(keys::LATERAL_SCALE, format!("{:e} {:e}", g.dx, g.dy)));
    m.push(meta(keys::HEIGHT_SCALE, format!("{scale:e}")));
    for (k, sec, key) in [
        ("version", "file list", "version"),
        ("date", "file list", "date"),
        ("operating mode", "scan list", "operating mode"),
        ("scan rate", "scan list", "scan rate"),
        ("scanner", "scanner list", "serial number"),
        ("tip radius", "scan list", "tip radius"),
    ] {
        if let Some(v) = find(sec, key) {
            m.push(meta(k, v));
        }
    }
    m
}
