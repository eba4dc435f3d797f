//! Wear of a track from a stylus profile measured across it (MODELS.md §9):
//! the cross-section area below the reference line between the track edges
//! ([`track`]), the wear volume A · L, the specific wear rate
//! V / (F_N · s) and, with a hardness, Archard's K = V·H / (F_N · s)
//! ([`volume`]), and the `wear` table.
//!
//! The track length, normal load and sliding distance come from the file's
//! row in the sample manifest, else from the stage's settings:
//!
//! | manifest column | setting | meaning |
//! |---|---|---|
//! | `track_radius_mm` | `track_radius` | pin-on-disc track radius r: L = 2π r |
//! | `stroke_length_mm` | `stroke_length` | reciprocating stroke: L = stroke |
//! | `normal_force_N` | `normal_force` | F_N |
//! | `sliding_distance_m` | `sliding_distance` | s |
//! | `laps` | — | s = laps · L when no sliding distance is given |
//! | `hardness_GPa` or `hardness_HV` | `hardness` | H of the worn body (Vickers: HV × 9.80665 MPa) |

pub mod track;
pub mod volume;

use serde::{Deserialize, Serialize};

use self::track::{track_section, TrackParams, TrackSection};
use self::volume::{
    archard_coefficient, specific_wear_rate, wear_volume, TrackLength, MM3_PER_M3, PA_PER_HV,
};
use super::roughness::input::{assumed_units, surfaces_from_dataset, AxisUnits, Surface};
use crate::error::{Error, Location, Result};
use crate::ingest::manifest::{Manifest, ManifestRow};
use crate::ingest::Dataset;
use crate::status::{Code, Status};
use crate::table::{Table, TableBuilder};
use crate::units::{parse_quantity, Quantity};

/// The `[wear]` table of a pipeline file.
///
/// ```toml
/// [wear]
/// x_unit = "mm"                 # when the file gives none
/// z_unit = "um"
/// edges = ["0.74 mm", "0.81 mm"]  # omit to find them
/// margin = 0.5                  # track widths beyond each edge left out of the reference
/// smoothing_fraction = 0.005    # moving average for finding the edges
/// band_factor = 3.0             # band = 3 × RMS of the smoothed reference
/// track_radius = "5 mm"         # defaults for files whose manifest row lacks them
/// normal_force = "3 N"
/// sliding_distance = "100 m"
/// ```
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WearSpec {
    /// Unit of x when the file gives none.
    #[serde(default)]
    pub x_unit: Option<String>,
    /// Unit of the heights when the file gives none.
    #[serde(default)]
    pub z_unit: Option<String>,
    /// Track edges `[left, right]` with units; found when omitted.
    #[serde(default)]
    pub edges: Option<[String; 2]>,
    /// Track widths beyond each edge left out of the reference fit.
    #[serde(default)]
    pub margin: Option<f64>,
    /// Moving-average window for the edges, a fraction of the points.
    #[serde(default)]
    pub smoothing_fraction: Option<f64>,
    /// Band half-width in RMS deviations of the reference part.
    #[serde(default)]
    pub band_factor: Option<f64>,
    /// Band half-width as a length with unit, instead of `band_factor`.
    #[serde(default)]
    pub band: Option<String>,
    /// Pin-on-disc track radius with unit (default for every file).
    #[serde(default)]
    pub track_radius: Option<String>,
    /// Reciprocating stroke length with unit (default for every file).
    #[serde(default)]
    pub stroke_length: Option<String>,
    /// Normal load with unit (default for every file).
    #[serde(default)]
    pub normal_force: Option<String>,
    /// Sliding distance with unit (default for every file).
    #[serde(default)]
    pub sliding_distance: Option<String>,
    /// Hardness of the worn body with unit, e.g. "2 GPa" (default for
    /// every file), for Archard's K.
    #[serde(default)]
    pub hardness: Option<String>,
}

/// Test conditions of a track: the length, load and sliding distance.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct WearConditions {
    /// Track radius r (m), pin-on-disc.
    pub track_radius: Option<f64>,
    /// Stroke length (m), reciprocating.
    pub stroke_length: Option<f64>,
    /// F_N (N).
    pub normal_force: Option<f64>,
    /// s (m).
    pub sliding_distance: Option<f64>,
    /// H of the worn body (Pa).
    pub hardness: Option<f64>,
}

/// Everything the stage needs besides the files.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WearPlan {
    /// Track finding.
    pub track: TrackParams,
    /// Axis units.
    pub units: AxisUnits,
    /// Defaults for files whose manifest row lacks them.
    pub defaults: WearConditions,
}

impl WearSpec {
    /// Validates the settings.
    pub fn plan(&self) -> Result<WearPlan> {
        let q = |v: &Option<String>, quantity, what| {
            v.as_ref()
                .map(|s| parse_quantity(s, quantity, what))
                .transpose()
        };
        let d = TrackParams::default();
        let edges = match &self.edges {
            Some([a, b]) => Some((
                parse_quantity(a, Quantity::Length, "edges left")?,
                parse_quantity(b, Quantity::Length, "edges right")?,
            )),
            None => None,
        };
        let track = TrackParams {
            margin: self.margin.unwrap_or(d.margin),
            smoothing_fraction: self.smoothing_fraction.unwrap_or(d.smoothing_fraction),
            band_factor: self.band_factor.unwrap_or(d.band_factor),
            band: q(&self.band, Quantity::Length, "band")?,
            edges,
        };
        track.validate()?;
        let defaults = WearConditions {
            track_radius: q(&self.track_radius, Quantity::Length, "track_radius")?,
            stroke_length: q(&self.stroke_length, Quantity::Length, "stroke_length")?,
            normal_force: q(&self.normal_force, Quantity::Force, "normal_force")?,
            sliding_distance: q(&self.sliding_distance, Quantity::Length, "sliding_distance")?,
            hardness: q(&self.hardness, Quantity::Stress, "hardness")?,
        };
        if defaults.track_radius.is_some() && defaults.stroke_length.is_some() {
            return Err(Error::Config(
                "[wear]: give track_radius (pin-on-disc) or stroke_length (reciprocating), not both"
                    .into(),
            ));
        }
        for (name, v) in [
            ("track_radius", defaults.track_radius),
            ("stroke_length", defaults.stroke_length),
            ("normal_force", defaults.normal_force),
            ("sliding_distance", defaults.sliding_distance),
            ("hardness", defaults.hardness),
        ] {
            if v.is_some_and(|v| v <= 0.0) {
                return Err(Error::Config(format!("[wear]: {name} must be > 0")));
            }
        }
        Ok(WearPlan {
            track,
            units: AxisUnits {
                x: self.x_unit.clone(),
                z: self.z_unit.clone(),
                spacing: None,
            },
            defaults,
        })
    }
}

/// One row of the `wear` table.
#[derive(Debug, Clone, PartialEq)]
pub struct WearRow {
    /// The profile's label.
    pub source: String,
    /// The manifest's sample id.
    pub sample_id: Option<String>,
    /// The cross-section.
    pub section: TrackSection,
    /// The conditions used.
    pub conditions: WearConditions,
    /// Track length and how it was obtained.
    pub track: Option<TrackLength>,
    /// V (m³).
    pub volume: Option<f64>,
    /// s actually used (m).
    pub sliding_distance: Option<f64>,
    /// k (m³/(N·m)).
    pub rate: Option<f64>,
    /// Archard's K = k · H (with a hardness).
    pub archard_k: Option<f64>,
    /// `ok`, or why a value is missing.
    pub status: Status,
}

/// The conditions of a file: its manifest row's values (columns in the
/// module table), else the defaults; and the number of laps if given.
fn conditions(
    manifest: Option<&Manifest>,
    row: Option<&ManifestRow>,
    defaults: &WearConditions,
) -> Result<(WearConditions, Option<f64>)> {
    let (Some(m), Some(r)) = (manifest, row) else {
        return Ok((*defaults, None));
    };
    let get = |c: &str, scale: f64| -> Result<Option<f64>> {
        let v = m.f64(r, c)?.map(|v| v * scale);
        if v.is_some_and(|v| v <= 0.0) {
            return Err(Error::input(
                Location::line(&m.path, r.line).with_column(c),
                "expected a value > 0",
            ));
        }
        Ok(v)
    };
    let radius = get("track_radius_mm", 1e-3)?;
    let stroke = get("stroke_length_mm", 1e-3)?;
    let own_length = radius.is_some() || stroke.is_some();
    let c = WearConditions {
        track_radius: if own_length {
            radius
        } else {
            defaults.track_radius
        },
        stroke_length: if own_length {
            stroke
        } else {
            defaults.stroke_length
        },
        normal_force: get("normal_force_N", 1.0)?.or(defaults.normal_force),
        sliding_distance: get("sliding_distance_m", 1.0)?.or(defaults.sliding_distance),
        hardness: hardness(m, r, &get)?.or(defaults.hardness),
    };
    if c.track_radius.is_some() && c.stroke_length.is_some() {
        return Err(Error::input(
            Location::line(&m.path, r.line),
            "the row gives both track_radius_mm and stroke_length_mm; give the one of its test",
        ));
    }
    Ok((c, get("laps", 1.0)?))
}

/// The row's `hardness_GPa` or `hardness_HV` (kgf/mm²) in Pa; not both.
fn hardness(
    m: &Manifest,
    r: &ManifestRow,
    get: &dyn Fn(&str, f64) -> Result<Option<f64>>,
) -> Result<Option<f64>> {
    match (get("hardness_GPa", 1e9)?, get("hardness_HV", PA_PER_HV)?) {
        (Some(_), Some(_)) => Err(Error::input(
            Location::line(&m.path, r.line),
            "the row gives both hardness_GPa and hardness_HV; give one",
        )),
        (gpa, hv) => Ok(gpa.or(hv)),
    }
}

/// The wear row of a cross-section under given conditions.
pub fn wear_row(
    source: &str,
    section: TrackSection,
    c: WearConditions,
    laps: Option<f64>,
) -> WearRow {
    let mut status = Status::ok();
    let track = match (c.track_radius, c.stroke_length) {
        (Some(r), _) => Some(TrackLength::Radius(r)),
        (None, Some(s)) => Some(TrackLength::Stroke(s)),
        (None, None) => None,
    };
    if track.is_none() {
        status.push(
            Code::MissingLengths,
            "no track length: give track_radius_mm or stroke_length_mm in the manifest \
             (or [wear] track_radius / stroke_length); volume and wear rate left out",
        );
    }
    let volume = track.map(|t| wear_volume(section.area, t));
    let distance = c
        .sliding_distance
        .or_else(|| laps.zip(track).map(|(n, t)| n * t.length()));
    let rate = match (volume, c.normal_force, distance) {
        (Some(v), Some(f), Some(s)) => specific_wear_rate(v, f, s),
        _ => None,
    };
    if volume.is_some() && rate.is_none() {
        status.push(
            Code::WearRateUndefined,
            "the specific wear rate needs normal_force_N and sliding_distance_m (or laps) \
             in the manifest, or [wear] normal_force / sliding_distance",
        );
    }
    let archard_k = rate
        .zip(c.hardness)
        .and_then(|(k, h)| archard_coefficient(k, h));
    if c.hardness.is_some() && archard_k.is_none() && volume.is_some() {
        status.push(
            Code::WearRateUndefined,
            "Archard's K = V·H/(F_N·s) needs the specific wear rate",
        );
    }
    WearRow {
        source: source.to_string(),
        sample_id: None,
        section,
        conditions: c,
        track,
        volume,
        sliding_distance: distance,
        rate,
        archard_k,
        status,
    }
}

/// The wear rows of every profile in a file.
pub fn analyze_dataset(
    ds: &Dataset,
    plan: &WearPlan,
    manifest: Option<&Manifest>,
) -> Result<Vec<WearRow>> {
    analyze_surfaces(ds, &surfaces_from_dataset(ds, &plan.units)?, plan, manifest)
}

/// As [`analyze_dataset`], on the file's surfaces already taken from it
/// (the stage draws them too).
pub fn analyze_surfaces(
    ds: &Dataset,
    surfaces: &[Surface],
    plan: &WearPlan,
    manifest: Option<&Manifest>,
) -> Result<Vec<WearRow>> {
    let row = manifest.and_then(|m| m.find(&ds.source));
    let (c, laps) = conditions(manifest, row, &plan.defaults)?;
    let sample_id = row.and_then(|r| r.fields.get("sample_id").cloned());
    let mut rows = Vec::new();
    for s in surfaces {
        let Surface::Profile(p) = s else {
            return Err(Error::input(
                Location::file(&ds.source),
                "an areal map: the wear stage takes profiles measured across a track",
            ));
        };
        let x: Vec<f64> = (0..p.z.len()).map(|i| p.x(i)).collect();
        let section = track_section(&p.source, &x, &p.z, &plan.track)?;
        let mut r = wear_row(&p.source, section, c, laps);
        r.sample_id = sample_id.clone();
        r.status.extend(assumed_units(ds, &plan.units));
        rows.push(r);
    }
    Ok(rows)
}

/// The `wear` table (schema `schemas/wear.toml`).
pub fn wear_table(rows: &[WearRow], plan: &WearPlan) -> Result<Table> {
    let n = rows.len();
    let col = |f: fn(&WearRow) -> Option<f64>| rows.iter().map(f);
    TableBuilder::new()
        .str("source", rows.iter().map(|r| Some(r.source.clone())))
        .str("sample_id", rows.iter().map(|r| r.sample_id.clone()))
        .f64("area_m2", col(|r| Some(r.section.area)))
        .f64("depth_m", col(|r| Some(r.section.depth)))
        .f64("edge_left_m", col(|r| Some(r.section.edges.0)))
        .f64("edge_right_m", col(|r| Some(r.section.edges.1)))
        .f64(
            "width_m",
            col(|r| Some(r.section.edges.1 - r.section.edges.0)),
        )
        .str(
            "edges",
            rows.iter().map(|r| {
                Some(if r.section.edges_found {
                    "found"
                } else {
                    "given"
                })
            }),
        )
        .f64("band_m", col(|r| Some(r.section.band)))
        .f64("reference_slope", col(|r| Some(r.section.line.1)))
        .f64("track_length_m", col(|r| r.track.map(|t| t.length())))
        .str(
            "track_length_from",
            rows.iter().map(|r| r.track.map(|t| t.source())),
        )
        .f64("volume_m3", col(|r| r.volume))
        .f64("normal_force_N", col(|r| r.conditions.normal_force))
        .f64("sliding_distance_m", col(|r| r.sliding_distance))
        .f64(
            "specific_wear_rate_mm3_per_N_m",
            col(|r| r.rate.map(|k| k * MM3_PER_M3)),
        )
        .f64("hardness_Pa", col(|r| r.conditions.hardness))
        .f64("archard_K", col(|r| r.archard_k))
        .status(rows.iter().map(|r| &r.status))
        .i64(
            "reference_points",
            rows.iter().map(|r| Some(r.section.reference_points as i64)),
        )
        .f64("margin", std::iter::repeat_n(Some(plan.track.margin), n))
        .f64(
            "smoothing_fraction",
            std::iter::repeat_n(Some(plan.track.smoothing_fraction), n),
        )
        .build()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section() -> TrackSection {
        TrackSection {
            area: 1e-11,
            depth: 1e-6,
            edges: (1e-3, 2e-3),
            edges_found: true,
            band: 1e-8,
            line: (0.0, 0.0),
            reference_points: 100,
        }
    }

    #[test]
    fn laps_give_the_sliding_distance_and_missing_inputs_are_said() {
        let c = WearConditions {
            track_radius: Some(5e-3),
            normal_force: Some(3.0),
            ..Default::default()
        };
        let r = wear_row("p", section(), c, Some(100.0));
        let s = 100.0 * 2.0 * std::f64::consts::PI * 5e-3;
        assert!((r.sliding_distance.unwrap() / s - 1.0).abs() < 1e-15);
        let k = r.volume.unwrap() / (3.0 * s);
        assert!((r.rate.unwrap() / k - 1.0).abs() < 1e-15);
        assert_eq!(r.status.to_string(), "ok");
        let r = wear_row("p", section(), WearConditions::default(), None);
        assert!(r.volume.is_none() && r.status.to_string().starts_with("missing_lengths"));
        let c = WearConditions {
            stroke_length: Some(1e-2),
            ..Default::default()
        };
        let r = wear_row("p", section(), c, None);
        assert!((r.volume.unwrap() - 1e-13).abs() < 1e-27);
        assert!(
            r.status.to_string().starts_with("wear_rate_undefined"),
            "{}",
            r.status
        );
    }

    /// K = V·H/(F_N·s): V = 1e-11 m² × 1e-2 m, F_N 10 N, s 100 m, H 2 GPa
    /// give 2e-7; 200 HV is 1.96133 GPa; a hardness without k says so.
    #[test]
    fn archard_coefficient_is_volume_times_hardness_over_load_times_distance() {
        let mut c = WearConditions {
            stroke_length: Some(1e-2),
            normal_force: Some(10.0),
            sliding_distance: Some(100.0),
            hardness: Some(2e9),
            ..Default::default()
        };
        let r = wear_row("p", section(), c, None);
        assert!((r.archard_k.unwrap() / 2e-7 - 1.0).abs() < 1e-14, "{r:?}");
        assert_eq!(r.status.to_string(), "ok");
        c.hardness = Some(200.0 * PA_PER_HV);
        let k = wear_row("p", section(), c, None).archard_k.unwrap();
        assert!((k / (1e-13 * 1.96133e9 / 1e3) - 1.0).abs() < 1e-14);
        (c.hardness, c.normal_force) = (Some(2e9), None);
        let r = wear_row("p", section(), c, None);
        assert!(r.archard_k.is_none() && r.status.to_string().contains("Archard"));
    }

    #[test]
    fn spec_rejects_both_lengths_and_bad_units() {
        let s = WearSpec {
            track_radius: Some("5 mm".into()),
            stroke_length: Some("5 mm".into()),
            ..Default::default()
        };
        assert!(s.plan().is_err());
        let s = WearSpec {
            normal_force: Some("3 mm".into()),
            ..Default::default()
        };
        assert!(s.plan().is_err());
        let s = WearSpec {
            edges: Some(["0.8 mm".into(), "0.7 mm".into()]),
            ..Default::default()
        };
        assert!(s.plan().is_err());
    }
}
