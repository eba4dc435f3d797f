//! From an ingested [`Dataset`] to the profiles and maps the roughness
//! analysis takes, converting to metres once, here.
//!
//! - A section with two channels is a profile: the first channel is x, the
//!   second z (Dektak `Lateral`/`Raw`, `Distance`/`Profile`, generic x,z).
//! - Three channels x, y, z (one section, or several that are the scan lines
//!   of one map) form an areal map on a regular grid: rows are runs of equal
//!   y (or of equal x, then the map is transposed so that rows run along the
//!   scan direction).
//! - A table of more than three columns without a header is a z matrix: one
//!   row of heights per y, one column per x (Gwyddion's text export, or any
//!   plain matrix). The spacing comes from [`AxisUnits::spacing`], else from
//!   the file's `Width` and `Height` (the scan size: Δx = Width / columns,
//!   Gwyddion's convention); the height unit from [`AxisUnits::z`], else the
//!   file's `Value units`.
//!
//! - A binary or structured file (X3P, SUR, ...) holds its maps and profiles
//!   as [`Grid`]s: the decoded channel (the height channel, or the one the
//!   ingest options select) becomes the map (or the profile, one row), its
//!   buffer moved, not copied, when the dataset is given away
//!   ([`take_surfaces`]). Heights are already in metres; points not
//!   measured are NaN.
//!
//! Units come from the file, or from [`AxisUnits`] (command line or pipeline
//! file) when it has none or they must be overridden. A missing unit is an
//! error that says how to give it; it is never guessed.

use std::borrow::Cow;

use rayon::prelude::*;
use serde::Serialize;

use super::map::AreaMap;
use super::surface::{Profile, UNIFORM_TOLERANCE};
use crate::error::{Error, Location, Result};
use crate::ingest::grid::Grid;
use crate::ingest::{Channel, Dataset, Section, ASSUMED_UNIT};
use crate::status::{Code, Status};
use crate::units::{parse_unit, Quantity};

/// Units of the axes given by the user, overriding the file's.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct AxisUnits {
    /// Unit of the lateral positions x (and y), e.g. `mm`.
    pub x: Option<String>,
    /// Unit of the heights z, e.g. `um`.
    pub z: Option<String>,
    /// Spacing (Δx, Δy) of a z matrix in metres, when the file does not
    /// state it (or to override it).
    pub spacing: Option<(f64, f64)>,
}

/// A profile or a map.
#[derive(Debug, Clone, PartialEq)]
pub enum Surface {
    /// A stylus profile.
    Profile(Profile),
    /// An areal map.
    Map(AreaMap),
}

fn scale_of(
    ds: &Dataset,
    c: &Channel,
    given: &Option<String>,
    axis: &str,
    flag: &str,
) -> Result<f64> {
    let loc = || Location::file(&ds.source).with_column(&c.name);
    let unit = match given {
        Some(u) => parse_unit(u).ok_or_else(|| Error::Unit {
            location: loc(),
            unit: u.clone(),
            expected: "a length unit (m, mm, um, nm, angstrom, in)".into(),
        })?,
        None => match c.unit(&ds.source)? {
            Some(u) => u,
            None => {
                return Err(Error::input(
                    loc(),
                    format!(
                        "the file gives no unit for the {axis} column '{}'; give it with \
                         {flag} (for example {flag} mm) or in the pipeline file's `units`",
                        c.name
                    ),
                ))
            }
        },
    };
    if unit.quantity != Quantity::Length {
        return Err(Error::Unit {
            location: loc(),
            unit: unit.symbol.into(),
            expected: format!("a length unit for the {axis} column (m, mm, um, nm)"),
        });
    }
    Ok(unit.scale)
}

/// The units a reader took from its format's layout ([`ASSUMED_UNIT`]) for
/// the axes the user gave none for, as a status (`assumed_unit`; `ok` when
/// there are none). A column is an axis by its place: the last of its
/// section is z.
pub fn assumed_units(ds: &Dataset, units: &AxisUnits) -> Status {
    let given = |column: &str| {
        ds.sections.iter().any(|s| {
            let last = s.channels.len().saturating_sub(1);
            let at = s.channels.iter().position(|c| c.name == column);
            at.is_some_and(|i| match i == last {
                true => units.z.is_some(),
                false => units.x.is_some(),
            })
        })
    };
    let read: Vec<&str> = ds
        .preamble
        .iter()
        .filter(|m| m.key == ASSUMED_UNIT)
        .map(|m| m.value.as_str())
        .filter(|v| !given(v.split(" as ").next().unwrap_or(v)))
        .collect();
    if read.is_empty() {
        return Status::ok();
    }
    let detail = format!(
        "no unit stated: read {}, the units of the file's layout (give them to override)",
        read.join(", ")
    );
    Status::of(Code::AssumedUnit, detail)
}

fn label(ds: &Dataset, section: &Section, many: bool) -> String {
    if many {
        format!("{}#{}", ds.source.display(), section.name)
    } else {
        ds.source.display().to_string()
    }
}

/// Profiles and maps in a dataset (see the module documentation).
pub fn surfaces_from_dataset(ds: &Dataset, units: &AxisUnits) -> Result<Vec<Surface>> {
    if !ds.grids.is_empty() {
        let g = decoded_grid(ds)?;
        let values = g.values().unwrap_or_default().to_vec();
        return Ok(vec![grid_surface(ds, g, values, units)?]);
    }
    let three: Vec<&Section> = ds
        .sections
        .iter()
        .filter(|s| s.channels.len() == 3)
        .collect();
    let mut out = Vec::new();
    if !three.is_empty() {
        out.push(Surface::Map(map_from_sections(ds, &three, units)?));
    }
    let matrices: Vec<&Section> = ds
        .sections
        .iter()
        .filter(|s| s.channels.len() > 3 && s.header_line.is_none())
        .collect();
    for s in &matrices {
        let many = matrices.len() > 1;
        out.push(Surface::Map(map_from_matrix(
            ds,
            s,
            units,
            label(ds, s, many),
        )?));
    }
    let two: Vec<&Section> = ds
        .sections
        .iter()
        .filter(|s| s.channels.len() == 2)
        .collect();
    for s in &two {
        let (cx, cz) = (&s.channels[0], &s.channels[1]);
        let sx = scale_of(ds, cx, &units.x, "x", "--x-unit")?;
        let sz = scale_of(ds, cz, &units.z, "height", "--z-unit")?;
        // To SI on all threads (the same product per value).
        let x: Vec<f64> = cx.values.par_iter().map(|v| v * sx).collect();
        let z: Vec<f64> = cz.values.par_iter().map(|v| v * sz).collect();
        out.push(Surface::Profile(Profile::from_xz(
            &label(ds, s, two.len() > 1),
            x,
            z,
        )?));
    }
    if out.is_empty() {
        let widths: Vec<usize> = ds.sections.iter().map(|s| s.channels.len()).collect();
        return Err(Error::input(
            Location::file(&ds.source),
            format!(
                "found tables with {widths:?} columns; a roughness input needs x,z \
                 (2 columns), x,y,z (3 columns) or a z matrix without a header row"
            ),
        ));
    }
    Ok(out)
}

/// As [`surfaces_from_dataset`]; from a dataset given away, a grid's
/// buffer becomes the map's heights without a copy (the grid is left
/// without its values; the rest of the dataset stays as it was).
pub fn take_surfaces(ds: &mut Cow<'_, Dataset>, units: &AxisUnits) -> Result<Vec<Surface>> {
    let Cow::Owned(owned) = ds else {
        return surfaces_from_dataset(ds, units);
    };
    if owned.grids.is_empty() {
        return surfaces_from_dataset(owned, units);
    }
    let i = decoded_index(owned)?;
    let values = owned.grids[i]
        .data
        .as_mut()
        .map(|d| std::mem::take(&mut d.values))
        .unwrap_or_default();
    Ok(vec![grid_surface(owned, &owned.grids[i], values, units)?])
}

/// The decoded grid of a binary file (the reader decodes one channel).
fn decoded_grid(ds: &Dataset) -> Result<&Grid> {
    decoded_index(ds).map(|i| &ds.grids[i])
}

fn decoded_index(ds: &Dataset) -> Result<usize> {
    ds.grids
        .iter()
        .position(|g| g.data.is_some())
        .ok_or_else(|| {
            Error::input(
                Location::file(&ds.source),
                "no channel of the file was decoded",
            )
        })
}

/// A profile (one row) or a map from a grid channel, its `values` in the
/// grid's unit: metres for heights, else converted with the channel's
/// length unit or `--z-unit`. A spacing the file does not state (NaN)
/// comes from `--spacing`.
fn grid_surface(
    ds: &Dataset,
    g: &Grid,
    mut values: Vec<f64>,
    units: &AxisUnits,
) -> Result<Surface> {
    let loc = || Location::file(&ds.source).with_column(&g.name);
    let unit = units.z.clone().unwrap_or_else(|| g.unit.clone());
    if unit.is_empty() {
        return Err(Error::input(
            loc(),
            format!(
                "the file gives no unit for the channel '{}'; give it with --z-unit (for \
                 example --z-unit um) or `z_unit` in the pipeline file",
                g.name
            ),
        ));
    }
    let scale = match parse_unit(&unit) {
        Some(u) if u.quantity == Quantity::Length => u.scale,
        _ => {
            return Err(Error::Unit {
                location: loc(),
                unit,
                expected: format!(
                    "a length: the roughness stage takes height channels, and '{}' is not one \
                     (choose another with --channel, or `channel` in [ingest])",
                    g.name
                ),
            })
        }
    };
    if scale.to_bits() != 1f64.to_bits() {
        values.par_iter_mut().for_each(|v| *v *= scale);
    }
    let (dx, dy) = match (g.dx.is_nan() || g.dy.is_nan(), units.spacing) {
        (_, Some(d)) => d,
        (false, None) => (g.dx, g.dy),
        (true, None) => {
            return Err(Error::input(
                loc(),
                format!(
                    "a grid of {} × {} points with no sample spacing in the file; give it with \
                     --spacing DX,DY (for example --spacing 0.5um,0.5um) or `spacing` in the \
                     pipeline file",
                    g.nx, g.ny
                ),
            ))
        }
    };
    let label = ds.source.display().to_string();
    Ok(match g.ny {
        1 => Surface::Profile(Profile::new(&label, g.x0, dx, values)?),
        _ => {
            Surface::Map(AreaMap::new(&label, dx, dy, g.nx, g.ny, values)?.with_origin(g.x0, g.y0))
        }
    })
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(f64::MIN_POSITIVE)
}

/// A regular grid from x,y,z points grouped in runs of equal y (or of
/// equal x).
fn map_from_sections(ds: &Dataset, sections: &[&Section], units: &AxisUnits) -> Result<AreaMap> {
    let c0 = &sections[0].channels;
    let sx = scale_of(ds, &c0[0], &units.x, "x", "--x-unit")?;
    let sy = scale_of(ds, &c0[1], &units.x, "y", "--x-unit")?;
    let sz = scale_of(ds, &c0[2], &units.z, "height", "--z-unit")?;
    let (mut x, mut y, mut z) = (Vec::new(), Vec::new(), Vec::new());
    for s in sections {
        x.extend(s.channels[0].values.iter().map(|v| v * sx));
        y.extend(s.channels[1].values.iter().map(|v| v * sy));
        z.extend(s.channels[2].values.iter().map(|v| v * sz));
    }
    let src = ds.source.display().to_string();
    let bad = |m: String| Error::input(Location::file(&ds.source), m);
    if x.len() < 4 {
        return Err(bad(format!("{} x,y,z points; a map needs a grid", x.len())));
    }
    // Rows are runs of equal y; if y changes at once, the runs are of x.
    let by_y = close(y[0], y[1]);
    let (fast, slow) = if by_y { (&x, &y) } else { (&y, &x) };
    let run = slow.iter().take_while(|v| close(**v, slow[0])).count();
    if run < 2 || slow.len() % run != 0 {
        return Err(bad(format!(
            "x,y,z points do not form a regular grid: the first scan line has {run} points \
             and there are {} points in all",
            slow.len()
        )));
    }
    let lines = slow.len() / run;
    for l in 0..lines {
        let seg = &slow[l * run..(l + 1) * run];
        if seg.iter().any(|v| !close(*v, seg[0])) {
            return Err(bad(format!(
                "scan line {} does not have a constant {} coordinate; expected a regular grid \
                 with {run} points per line",
                l + 1,
                if by_y { "y" } else { "x" }
            )));
        }
    }
    let spacing = |v: &[f64], what: &str| -> Result<f64> {
        let p = Profile::from_xz(&src, v.to_vec(), vec![0.0; v.len()])
            .map_err(|e| bad(format!("{what} positions: {e}")))?;
        Ok(p.dx)
    };
    let d_fast = spacing(&fast[..run], "in-line")?;
    for l in 1..lines {
        let seg = &fast[l * run..(l + 1) * run];
        for (a, b) in seg.iter().zip(&fast[..run]) {
            if (a - b).abs() > UNIFORM_TOLERANCE * d_fast {
                return Err(bad(format!(
                    "scan line {} has positions that differ from the first line's; expected \
                     the same positions on every line",
                    l + 1
                )));
            }
        }
    }
    let starts: Vec<f64> = (0..lines).map(|l| slow[l * run]).collect();
    let d_slow = spacing(&starts, "line")?;
    let origin = (x[0], y[0]);
    if by_y {
        Ok(AreaMap::new(&src, d_fast, d_slow, run, lines, z)?.with_origin(origin.0, origin.1))
    } else {
        // Points run along y within a line: transpose to row-major in y.
        let mut t = vec![0.0; z.len()];
        for l in 0..lines {
            for k in 0..run {
                t[k * lines + l] = z[l * run + k];
            }
        }
        Ok(AreaMap::new(&src, d_slow, d_fast, lines, run, t)?.with_origin(origin.0, origin.1))
    }
}

/// A metadata value of the file (preamble or the section's own), by key,
/// ignoring case and a leading comment mark (`# Width: 5 µm`).
fn meta<'a>(ds: &'a Dataset, s: &'a Section, key: &str) -> Option<&'a crate::ingest::MetaEntry> {
    ds.preamble.iter().chain(&s.metadata).find(|m| {
        m.key
            .trim_start_matches('#')
            .trim()
            .eq_ignore_ascii_case(key)
    })
}

/// A z matrix: row r holds the heights at y = r·Δy, column c those at
/// x = c·Δx (see the module documentation for spacing and units).
fn map_from_matrix(ds: &Dataset, s: &Section, units: &AxisUnits, label: String) -> Result<AreaMap> {
    let (nx, ny) = (s.channels.len(), s.rows());
    let loc = || Location::file(&ds.source);
    let size = |key: &str, n: usize| -> Result<Option<f64>> {
        let Some(m) = meta(ds, s, key) else {
            return Ok(None);
        };
        let v = crate::units::parse_quantity(&m.value, Quantity::Length, key).map_err(|_| {
            Error::input(
                Location::line(&ds.source, m.line),
                format!(
                    "scan {key} '{}' is not a length with a unit (expected e.g. '5.000 µm')",
                    m.value
                ),
            )
        })?;
        if v.is_nan() || v <= 0.0 {
            return Err(Error::input(
                Location::line(&ds.source, m.line),
                format!("scan {key} '{}'; expected a length > 0", m.value),
            ));
        }
        Ok(Some(v / n as f64))
    };
    let (dx, dy) = match units.spacing {
        Some(d) => d,
        None => match (size("Width", nx)?, size("Height", ny)?) {
            (Some(dx), Some(dy)) => (dx, dy),
            _ => {
                return Err(Error::input(
                    loc(),
                    format!(
                        "a z matrix of {nx} columns × {ny} rows with no sample spacing: the \
                         file states no Width and Height; give it with --spacing DX,DY (for \
                         example --spacing 0.5um,0.5um) or `spacing` in the pipeline file"
                    ),
                ))
            }
        },
    };
    let z_unit = match &units.z {
        Some(u) => u.clone(),
        None => match meta(ds, s, "Value units") {
            Some(m) => m.value.clone(),
            None => {
                return Err(Error::input(
                    loc(),
                    "the z matrix states no height unit (no 'Value units' line); give it with \
                     --z-unit (for example --z-unit um) or `z_unit` in the pipeline file",
                ))
            }
        },
    };
    let sz = match parse_unit(&z_unit) {
        Some(u) if u.quantity == Quantity::Length => u.scale,
        _ => {
            return Err(Error::Unit {
                location: loc(),
                unit: z_unit,
                expected: "a length unit for the heights of the z matrix (m, mm, um, nm)".into(),
            })
        }
    };
    let z: Vec<f64> = (0..ny)
        .flat_map(|r| s.channels.iter().map(move |c| c.values[r] * sz))
        .collect();
    AreaMap::new(&label, dx, dy, nx, ny, z)
}
