//! The wear-track radius of each section of a rotary test, which turns a
//! rotational speed n into the sliding speed v = 2π·r·n (MODELS.md §1).
//!
//! A test may run several tracks, one per recipe step (an Rtec log moves
//! the stage 3 mm between steps); one radius per file then makes every step
//! but one wrong. Each section's radius is taken, first found:
//!
//! 1. from the manifest's per-step table `step_track_radius_mm`
//!    (`4:6 7:9 10:12` by the file's step numbers, or `6 9 12` in section
//!    order): `manifest_step`;
//! 2. from the section itself (a PCS MTM step's `Disc track radius used
//!    for this step (mm)`): `file_step`;
//! 3. when the sections state the stage's radial position
//!    (`tribo.radial_position`, written by the reader) and it moves between
//!    sections: r = |p − c| around the disc centre c, which is the
//!    manifest's `track_centre_mm` (`manifest_centre`), or follows from one
//!    reference radius of the first section: the manifest's
//!    `track_radius_mm` (`manifest_and_stage`), the file's own track radius
//!    (`file_and_stage`) or the file name's (`file_name_and_stage`). The
//!    centre lies beyond every track (a stage does not cross it): of the two
//!    centres a reference radius allows, the one inside the positions' span
//!    is ruled out; when both remain, a radius range in the file name
//!    (`6-15mm-radius`) chooses, else the radius is not known and the error
//!    says what to give;
//! 4. one radius for every section: the manifest's `track_radius_mm`
//!    (`manifest`), the file's preamble (`Track Radius (mm) = 10`, `file`),
//!    or the file name (`10mm-radius`, `file_name`).
//!
//! A radius taken from the file name is a guess about a name, so the rows
//! it gives say so ([`RadiusSource::from_file_name`]).

use std::path::Path;

use super::header::split_name_unit;
use super::manifest::Manifest;
use super::{Dataset, MetaEntry, Section};
use crate::error::{Error, Location, Result};
use crate::units::{parse_unit, Quantity};

/// The section metadata key of the stage's position along the disc radius
/// during a section (`-9.33 mm`), written by readers whose files state it.
pub const RADIAL_POSITION: &str = "tribo.radial_position";

/// Positions closer than this (m) are one track.
const SAME_TRACK_M: f64 = 1e-5;

/// A radius range in the file name must match the tracks' to this (m).
const NAME_TOLERANCE_M: f64 = 0.05e-3;

/// Where a section's track radius comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RadiusSource {
    /// The manifest's per-step table.
    ManifestStep,
    /// The section's own statement.
    FileStep,
    /// The stage position around the manifest's disc centre.
    ManifestCentre,
    /// The stage position, from the manifest's reference radius.
    ManifestAndStage,
    /// The stage position, from the file's own reference radius.
    FileAndStage,
    /// The stage position, from the radius in the file name.
    FileNameAndStage,
    /// The manifest's one radius.
    Manifest,
    /// The file's one radius.
    File,
    /// The file name's one radius.
    FileName,
}

impl RadiusSource {
    /// The stable text form, as in `friction_steps.track_radius_source`.
    pub fn as_str(self) -> &'static str {
        match self {
            RadiusSource::ManifestStep => "manifest_step",
            RadiusSource::FileStep => "file_step",
            RadiusSource::ManifestCentre => "manifest_centre",
            RadiusSource::ManifestAndStage => "manifest_and_stage",
            RadiusSource::FileAndStage => "file_and_stage",
            RadiusSource::FileNameAndStage => "file_name_and_stage",
            RadiusSource::Manifest => "manifest",
            RadiusSource::File => "file",
            RadiusSource::FileName => "file_name",
        }
    }
    /// Whether the radius rests on the file's name.
    pub fn from_file_name(self) -> bool {
        matches!(
            self,
            RadiusSource::FileName | RadiusSource::FileNameAndStage
        )
    }
}

/// A section's track radius and where it comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackRadius {
    /// r, m.
    pub radius_m: f64,
    /// Where it comes from.
    pub source: RadiusSource,
}

/// What the manifest row of a file says about its track radii, in m.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RadiusHints {
    /// `track_radius_mm`: the one radius, or the first section's.
    pub radius_m: Option<f64>,
    /// `track_centre_mm`: the disc centre in the stage's coordinate.
    pub centre_m: Option<f64>,
    /// `step_track_radius_mm`: (the file's step number, or none for
    /// section order; radius).
    pub steps: Vec<(Option<u32>, f64)>,
}

impl RadiusHints {
    /// The row of `input` in `manifest`; a value that does not read is an
    /// error naming the manifest's line and column.
    pub fn from_manifest(manifest: Option<&Manifest>, input: &Path) -> Result<RadiusHints> {
        let Some((m, row)) = manifest.and_then(|m| m.find(input).map(|r| (m, r))) else {
            return Ok(RadiusHints::default());
        };
        let radius_m = m.f64(row, "track_radius_mm")?.map(|r| r * 1e-3);
        if let Some(r) = radius_m.filter(|r| *r <= 0.0) {
            let at = Location::line(&m.path, row.line).with_column("track_radius_mm");
            return Err(Error::input(
                at,
                format!("expected a radius > 0, found {} mm", r * 1e3),
            ));
        }
        let centre_m = m.f64(row, "track_centre_mm")?.map(|c| c * 1e-3);
        let steps = match row.fields.get("step_track_radius_mm") {
            Some(text) => parse_steps(text).ok_or_else(|| {
                Error::input(
                    Location::line(&m.path, row.line).with_column("step_track_radius_mm"),
                    format!(
                        "expected radii in mm by step ('4:6 7:9' for steps 4 and 7) or in \
                         section order ('6 9 12'), each > 0, found {}",
                        super::text::quoted(text)
                    ),
                )
            })?,
            None => Vec::new(),
        };
        Ok(RadiusHints {
            radius_m,
            centre_m,
            steps,
        })
    }
}

/// `4:6 7:9` or `6 9 12` (mm; blanks, `;` or `|` between entries).
pub(super) fn parse_steps(text: &str) -> Option<Vec<(Option<u32>, f64)>> {
    let entries: Vec<&str> = text
        .split([' ', ';', '|', '\t'])
        .filter(|s| !s.is_empty())
        .collect();
    let keyed = entries.iter().all(|e| e.contains(':'));
    let out: Option<Vec<(Option<u32>, f64)>> = entries
        .iter()
        .map(|e| {
            let (step, r) = match keyed {
                true => e.split_once(':').map(|(s, r)| (s.trim().parse().ok(), r))?,
                false => (None, *e),
            };
            let r: f64 = r
                .trim()
                .parse()
                .ok()
                .filter(|r: &f64| *r > 0.0 && r.is_finite())?;
            (step.is_some() || !keyed).then_some((step, r * 1e-3))
        })
        .collect();
    out.filter(|v| !v.is_empty())
}

/// A `<number> <unit>` (or `<number>` with the unit in the key) of a
/// length, in m.
fn length_m(m: &MetaEntry, key_unit: &str) -> Option<f64> {
    let mut parts = m.value.split_whitespace();
    let (value, value_unit) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
    let unit = if key_unit.is_empty() {
        value_unit
    } else {
        key_unit
    };
    let r = super::dialect::parse_number(value, '.')?;
    let u = parse_unit(unit).filter(|u| u.quantity == Quantity::Length)?;
    r.is_finite().then(|| u.to_si(r))
}

/// The track radius metadata `entries` state (`Track Radius (mm) = 10`,
/// `track radius = 10 mm`, `Disc track radius used for this step (mm)`),
/// in m; `None` when they state none, an error naming the line when they
/// state one that is not a positive length with a unit.
pub fn declared_in(entries: &[MetaEntry], source: &Path) -> Result<Option<f64>> {
    for m in entries {
        let (name, key_unit) = split_name_unit(&m.key);
        let name = name.to_lowercase().replace('_', " ");
        let known = [
            "track radius",
            "wear track radius",
            "disc track radius",
            "disc track radius used for this step",
        ];
        if !known.contains(&name.trim()) {
            continue;
        }
        return match length_m(m, &key_unit) {
            Some(r) if r > 0.0 => Ok(Some(r)),
            _ => Err(Error::input(
                Location { path: source.to_path_buf(), line: Some(m.line), column: None },
                format!(
                    "the file states a track radius '{} = {}' that is not a positive length with a unit (e.g. 'Track Radius (mm) = 10')",
                    m.key, m.value
                ),
            )),
        };
    }
    Ok(None)
}

/// The stage's radial position a reader wrote for a section, in m.
fn radial_position(s: &Section) -> Option<f64> {
    let m = s.metadata.iter().find(|m| m.key == RADIAL_POSITION)?;
    length_m(m, "")
}

/// The file's step number of a section named `Step N`.
fn step_number(s: &Section) -> Option<u32> {
    s.name.strip_prefix("Step ")?.trim().parse().ok()
}

/// Radii stated in the file name, mm → m: `6-15mm-radius` (a range, the
/// first number the first track's), `10mm-radius`, `radius-10mm`,
/// `radius10mm`.
pub fn radius_in_name(path: &Path) -> Option<(f64, Option<f64>)> {
    let stem = path.file_stem()?.to_str()?.to_lowercase();
    stem.split(['_', ' ', ',']).find_map(|token| {
        let numbers = token
            .strip_suffix("mm-radius")
            .or_else(|| token.strip_suffix("mmradius"))
            .or_else(|| token.strip_suffix("mm_radius"))
            .or_else(|| {
                let rest = token.strip_prefix("radius")?;
                rest.trim_start_matches('-').strip_suffix("mm")
            })?;
        let mut parts = numbers.split('-').map(|n| n.parse::<f64>().ok());
        let first = parts.next()??;
        let second = match parts.next() {
            Some(n) => Some(n?),
            None => None,
        };
        (parts.next().is_none() && first > 0.0 && second.is_none_or(|s| s > 0.0))
            .then_some((first * 1e-3, second.map(|s| s * 1e-3)))
    })
}

/// Radii |p − c| of the positions around a centre c.
fn around(positions: &[Option<f64>], c: f64) -> Vec<Option<f64>> {
    positions.iter().map(|p| p.map(|p| (p - c).abs())).collect()
}

/// The radii from one reference radius of the first positioned section:
/// the centre beyond every track; when both sides are, the one whose radii
/// span `range` (the file name's first and last radius).
fn from_reference(
    positions: &[Option<f64>],
    reference: f64,
    range: Option<(f64, f64)>,
) -> Option<Vec<Option<f64>>> {
    let known: Vec<f64> = positions.iter().flatten().copied().collect();
    let (lo, hi) = known
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &p| {
            (a.min(p), b.max(p))
        });
    let first = *known.first()?;
    let candidates: Vec<Vec<Option<f64>>> = [first + reference, first - reference]
        .into_iter()
        .filter(|c| *c > hi || *c < lo)
        .map(|c| around(positions, c))
        .collect();
    let fits = |radii: &&Vec<Option<f64>>| {
        let Some((a, b)) = range else { return false };
        let (min, max) = radii
            .iter()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(x, y), &v| {
                (x.min(v), y.max(v))
            });
        (min - a.min(b)).abs() <= NAME_TOLERANCE_M && (max - a.max(b)).abs() <= NAME_TOLERANCE_M
    };
    match &candidates[..] {
        [one] => Some(one.clone()),
        [_, _] => {
            let fitting: Vec<&Vec<Option<f64>>> = candidates.iter().filter(|r| fits(r)).collect();
            (fitting.len() == 1).then(|| fitting[0].clone())
        }
        _ => None,
    }
}

/// The manifest's per-step radii for each section: by step number when
/// keyed ('4:6 7:9'), else in section order, one per section; all `None`
/// without a per-step table.
fn manifest_step_radii(ds: &Dataset, hints: &RadiusHints) -> Result<Vec<Option<f64>>> {
    let n = ds.sections.len();
    if hints.steps.is_empty() {
        return Ok(vec![None; n]);
    }
    let keyed = hints.steps.iter().all(|(s, _)| s.is_some());
    if !keyed && hints.steps.len() != n {
        return Err(Error::input(
            Location::file(&ds.source),
            format!(
                "the manifest's step_track_radius_mm lists {} radii in section order, but the file has {n} sections; \
                 give them by step number ('4:6 7:9')",
                hints.steps.len()
            ),
        ));
    }
    let radius = |k: usize, s: &Section| match keyed {
        true => hints
            .steps
            .iter()
            .find(|(st, _)| *st == step_number(s))
            .map(|x| x.1),
        false => Some(hints.steps[k].1),
    };
    Ok(ds
        .sections
        .iter()
        .enumerate()
        .map(|(k, s)| radius(k, s))
        .collect())
}

/// Every section's track radius (see the module documentation); `None`
/// where nothing gives it.
pub fn track_radii(ds: &Dataset, hints: &RadiusHints) -> Result<Vec<Option<TrackRadius>>> {
    let n = ds.sections.len();
    let with = |r: Option<f64>, source| r.map(|radius_m| TrackRadius { radius_m, source });
    let mut out: Vec<Option<TrackRadius>> = vec![None; n];
    // 1. The manifest's per-step table.
    for (o, r) in out.iter_mut().zip(manifest_step_radii(ds, hints)?) {
        *o = with(r, RadiusSource::ManifestStep);
    }
    // 2. Each section's own.
    for (k, s) in ds.sections.iter().enumerate() {
        if out[k].is_none() {
            out[k] = with(
                declared_in(&s.metadata, &ds.source)?,
                RadiusSource::FileStep,
            );
        }
    }
    if out.iter().all(Option::is_some) {
        return Ok(out);
    }
    let file = declared_in(&ds.preamble, &ds.source)?;
    let name = radius_in_name(&ds.source);
    // 3. Tracks at several stage positions.
    let positions: Vec<Option<f64>> = ds.sections.iter().map(radial_position).collect();
    let known: Vec<f64> = positions.iter().flatten().copied().collect();
    let moves = known.iter().any(|p| (p - known[0]).abs() > SAME_TRACK_M);
    let fill = |out: &mut Vec<Option<TrackRadius>>, radii: Vec<Option<f64>>, source| {
        for (o, r) in out.iter_mut().zip(radii) {
            if o.is_none() {
                *o = with(r, source);
            }
        }
    };
    if moves {
        let range = name.and_then(|(a, b)| b.map(|b| (a, b)));
        if let Some(c) = hints.centre_m {
            fill(
                &mut out,
                around(&positions, c),
                RadiusSource::ManifestCentre,
            );
        } else if let Some(r) = hints.radius_m {
            let radii = from_reference(&positions, r, range);
            fill(
                &mut out,
                radii.unwrap_or_default(),
                RadiusSource::ManifestAndStage,
            );
        } else if let Some(r) = file {
            let radii = from_reference(&positions, r, range);
            fill(
                &mut out,
                radii.unwrap_or_default(),
                RadiusSource::FileAndStage,
            );
        } else if let Some((a, _)) = name {
            let radii = from_reference(&positions, a, range);
            fill(
                &mut out,
                radii.unwrap_or_default(),
                RadiusSource::FileNameAndStage,
            );
        }
        return Ok(out);
    }
    // 4. One radius for every section.
    let one = with(hints.radius_m, RadiusSource::Manifest)
        .or(with(file, RadiusSource::File))
        .or(with(
            name.filter(|n| n.1.is_none()).map(|n| n.0),
            RadiusSource::FileName,
        ));
    fill(
        &mut out,
        vec![one.map(|r| r.radius_m); n],
        one.map_or(RadiusSource::Manifest, |r| r.source),
    );
    Ok(out)
}
