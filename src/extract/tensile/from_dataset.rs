//! From an ingested file to a stress–strain curve and the instrument's own
//! results.
//!
//! Channels are recognised by unit and name: strain (a dimensionless unit
//! such as `mm/mm` or `%`, name containing "strain"), stress (a stress
//! unit), force (a force unit, name containing "load" or "force"), and
//! extension (a length unit, name containing "extension", "displacement",
//! "elongation" or "position").
//!
//! - **Stress**: the stress column when there is one, rescaled by
//!   (d_file / d)² when the manifest's diameter d differs from the file's;
//!   otherwise σ = F / (π d² / 4) from the force column and the diameter
//!   (manifest first, else file).
//! - **Strain**: the strain column when there is one; otherwise
//!   (x − x₀) / L from the extension, with x₀ its first sample and L the
//!   gauge length (l0 for a knotted fibre, else l, else the file's).
//! - **Strain reference length** (for the conversion to l0 of Eq. 5.2): the
//!   file's gauge length when stated (Bluehill `Length`), else the
//!   least-squares slope of extension against strain (T150).

use std::f64::consts::PI;
use std::path::Path;

use crate::error::{Error, Location, Result};
use crate::ingest::dialect::parse_number;
use crate::ingest::roles::{tensile_channel, TensileRole};
use crate::ingest::{Channel, Dataset};
use crate::units::{parse_unit, Quantity, Unit};

use super::curve::{FibreMeta, StressStrainCurve};
use super::records::InstrumentResults;

/// What the file itself states about the specimen and its results (SI).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FileFacts {
    /// The instrument's own results.
    pub instrument: InstrumentResults,
    /// Specimen diameter, m (T150 SpecimenDiameter).
    pub diameter_m: Option<f64>,
    /// Gauge length, m (Bluehill Length).
    pub gauge_length_m: Option<f64>,
    /// Width and thickness of a rectangular section, m (Bluehill Width,
    /// Thickness).
    pub width_m: Option<f64>,
    /// See `width_m`.
    pub thickness_m: Option<f64>,
    /// Section area, m², when the file states it (Instron `Area`, cm²).
    pub area_m2: Option<f64>,
    /// The specimen's id as the file states it (Bluehill `Specimen ID`,
    /// T150 `SpecimenName` with its `TestNumber`).
    pub specimen_id: Option<String>,
}

/// A preamble value as text, trimmed of quotes.
fn meta_text(ds: &Dataset, key: &str) -> Option<String> {
    let m = ds.preamble.iter().find(|m| m.key == key)?;
    let v = m.value.trim().trim_matches('"').trim();
    (!v.is_empty()).then(|| v.to_string())
}

/// A preamble value `number unit` (thousands separators allowed) in SI, if
/// the key is present and its unit measures `quantity`.
fn meta_si(ds: &Dataset, quantity: Quantity, key: impl Fn(&str) -> bool) -> Option<f64> {
    let m = ds.preamble.iter().find(|m| key(&m.key))?;
    let mut parts = m.value.split_whitespace();
    let number = parse_number(parts.next()?, '.').filter(|v| v.is_finite())?;
    let unit = parse_unit(&parts.collect::<Vec<_>>().join(" "))?;
    (unit.quantity == quantity).then(|| unit.to_si(number))
}

/// The instrument results, diameter and gauge length stated in the file.
pub fn file_facts(ds: &Dataset) -> FileFacts {
    match ds.format {
        "t150-nanosuite" => FileFacts {
            instrument: InstrumentResults {
                strength_pa: meta_si(ds, Quantity::Stress, |k| k == "StressAtBreak"),
                strain: meta_si(ds, Quantity::Dimensionless, |k| k == "StrainAtBreak"),
                // "Toughness 218.498 MPa": MPa = MJ/m³, so Pa = J/m³
                energy_density_j_per_m3: meta_si(ds, Quantity::Stress, |k| k == "Toughness"),
                modulus_pa: meta_si(ds, Quantity::Stress, |k| k == "Modulus"),
                yield_pa: meta_si(ds, Quantity::Stress, |k| k == "OffsetYieldStress"),
            },
            diameter_m: meta_si(ds, Quantity::Length, |k| k == "SpecimenDiameter"),
            gauge_length_m: None,
            specimen_id: meta_text(ds, "SpecimenName").map(|n| match meta_text(ds, "TestNumber") {
                Some(t) => format!("{n}_{t}"),
                None => n,
            }),
            ..Default::default()
        },
        "instron-bluehill" => FileFacts {
            instrument: InstrumentResults {
                strength_pa: meta_si(ds, Quantity::Stress, |k| {
                    k.starts_with("Tensile stress at Tensile strength")
                }),
                strain: meta_si(ds, Quantity::Dimensionless, |k| {
                    k.starts_with("Tensile strain") && k.ends_with("at Tensile strength")
                }),
                energy_density_j_per_m3: None,
                modulus_pa: meta_si(ds, Quantity::Stress, |k| k.starts_with("Modulus")),
                yield_pa: None,
            },
            diameter_m: None,
            gauge_length_m: meta_si(ds, Quantity::Length, |k| k == "Length"),
            width_m: meta_si(ds, Quantity::Length, |k| k == "Width"),
            thickness_m: meta_si(ds, Quantity::Length, |k| k == "Thickness"),
            area_m2: None,
            specimen_id: meta_text(ds, "Specimen ID"),
        },
        "instron-blocks" => FileFacts {
            instrument: InstrumentResults {
                strength_pa: meta_si(ds, Quantity::Stress, |k| {
                    k == "Tensile stress at Maximum Load"
                }),
                strain: meta_si(ds, Quantity::Dimensionless, |k| {
                    k == "Tensile strain at Maximum Load"
                }),
                energy_density_j_per_m3: None,
                modulus_pa: meta_si(ds, Quantity::Stress, |k| k.starts_with("Modulus")),
                yield_pa: meta_si(ds, Quantity::Stress, |k| {
                    k.starts_with("Tensile stress at Yield (Offset")
                }),
            },
            diameter_m: meta_si(ds, Quantity::Length, |k| k == "Diameter"),
            gauge_length_m: meta_si(ds, Quantity::Length, |k| k == "Gauge length"),
            width_m: meta_si(ds, Quantity::Length, |k| k == "Width"),
            thickness_m: meta_si(ds, Quantity::Length, |k| k == "Thickness"),
            area_m2: meta_si(ds, Quantity::Area, |k| k == "Area"),
            specimen_id: meta_text(ds, "Specimen label"),
        },
        "zwick-testxpert" => FileFacts {
            instrument: InstrumentResults {
                strength_pa: meta_si(ds, Quantity::Stress, |k| k == "Rm"),
                strain: meta_si(ds, Quantity::Dimensionless, |k| k == "Ag"),
                energy_density_j_per_m3: None,
                modulus_pa: meta_si(ds, Quantity::Stress, |k| k == "E"),
                yield_pa: meta_si(ds, Quantity::Stress, |k| k == "Rp0,2" || k == "Rp0.2"),
            },
            diameter_m: meta_si(ds, Quantity::Length, |k| k == "d0"),
            gauge_length_m: meta_si(ds, Quantity::Length, |k| k == "L0" || k == "Lo"),
            width_m: meta_si(ds, Quantity::Length, |k| k == "b0"),
            thickness_m: meta_si(ds, Quantity::Length, |k| k == "a0"),
            area_m2: meta_si(ds, Quantity::Area, |k| k == "S0"),
            specimen_id: meta_text(ds, "Probenkennung"),
        },
        _ => FileFacts {
            diameter_m: meta_si(ds, Quantity::Length, |k| {
                k.to_ascii_lowercase().contains("diameter")
            }),
            ..Default::default()
        },
    }
}

/// The channel with a tensile role and its unit ([`tensile_channel`]).
/// Stress in Pa: the stress column (rescaled by (d_file / d)² when the
/// manifest's diameter differs from the file's), else force over the
/// section (circular, rectangular or the file's area).
fn stress_pa(
    source: &Path,
    stress_ch: Option<(&Channel, Unit)>,
    force_ch: Option<(&Channel, Unit)>,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<Vec<f64>> {
    let loc = || Location::file(source);
    let diameter = meta.diameter_m.or(facts.diameter_m);
    if let Some(d) = diameter {
        if !(d > 0.0 && d.is_finite()) {
            return Err(Error::input(
                loc(),
                format!("fibre diameter {} um: expected a value > 0", d * 1e6),
            ));
        }
    }
    Ok(match (stress_ch, force_ch, diameter) {
        (Some((c, u)), _, _) => {
            let s = si(c, &u);
            match (meta.diameter_m, facts.diameter_m) {
                (Some(d), Some(df)) => {
                    let k = (df / d).powi(2);
                    s.into_iter().map(|v| v * k).collect()
                }
                _ => s,
            }
        }
        (None, Some((c, u)), Some(d)) => {
            let area = PI * d * d / 4.0;
            si(c, &u).into_iter().map(|f| f / area).collect()
        }
        (None, Some((c, u)), None) => {
            let w = meta.width_m.or(facts.width_m);
            let t = meta.thickness_m.or(facts.thickness_m);
            let area = match (w, t) {
                (Some(w), Some(t)) => Some(w * t),
                _ => meta.area_m2.or(facts.area_m2),
            };
            match area {
                Some(a) if a > 0.0 && a.is_finite() => {
                    si(c, &u).into_iter().map(|f| f / a).collect()
                }
                _ => {
                    return Err(Error::input(
                        loc().with_column(&c.name),
                        "force column but no section: give diameter_um (circular) or \
                         width_mm and thickness_mm (rectangular, each > 0) in the manifest",
                    ))
                }
            }
        }
        (None, None, _) => {
            return Err(Error::input(
                loc(),
                "no stress column (unit Pa, kPa, MPa, GPa) and no force column \
                 (unit N, mN, ...; name containing 'load' or 'force')",
            ))
        }
    })
}

/// Strain, and the length it is relative to when known: the strain column
/// (reference from the file's gauge length or the extension), else the
/// extension over the gauge length.
fn strain_and_reference(
    source: &Path,
    strain_ch: Option<(&Channel, Unit)>,
    ext: Option<Vec<f64>>,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<(Vec<f64>, Option<f64>)> {
    let loc = || Location::file(source);
    Ok(match (strain_ch, &ext) {
        (Some((c, u)), _) => {
            let e = si(c, &u);
            let r = facts
                .gauge_length_m
                .or_else(|| ext.as_ref().and_then(|x| reference_from_extension(&e, x)));
            (e, r)
        }
        (None, Some(x)) => {
            let gauge = if meta.knot.is_knotted() {
                meta.end_distance_m
            } else {
                meta.fibre_length_m.or(meta.end_distance_m)
            }
            .or(facts.gauge_length_m)
            .ok_or_else(|| {
                Error::input(
                    loc(),
                    "extension but no strain column and no gauge length: give \
                     fibre_length_mm / end_distance_mm in the manifest",
                )
            })?;
            let x0 = x.iter().copied().find(|v| v.is_finite()).unwrap_or(0.0);
            (x.iter().map(|v| (v - x0) / gauge).collect(), Some(gauge))
        }
        (None, None) => {
            return Err(Error::input(
                loc(),
                "no strain column (unit mm/mm, %, 1; name containing 'strain') and no \
                 extension column (unit mm, um, ...)",
            ))
        }
    })
}

fn find(channels: &[Channel], role: TensileRole) -> Option<(&Channel, Unit)> {
    tensile_channel(channels, role).map(|(i, u)| (&channels[i], u))
}

fn si(c: &Channel, u: &Unit) -> Vec<f64> {
    c.values.iter().map(|&v| u.to_si(v)).collect()
}

/// Least-squares slope of extension (m) on strain over samples with ε ≥ 0.
fn reference_from_extension(strain: &[f64], ext: &[f64]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = strain
        .iter()
        .zip(ext)
        .filter(|(e, x)| **e >= 0.0 && e.is_finite() && x.is_finite())
        .map(|(e, x)| (*e, *x))
        .collect();
    let n = pts.len() as f64;
    if pts.len() < 3 {
        return None;
    }
    let me = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let mx = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let see: f64 = pts.iter().map(|p| (p.0 - me) * (p.0 - me)).sum();
    let sex: f64 = pts.iter().map(|p| (p.0 - me) * (p.1 - mx)).sum();
    (see > 0.0).then(|| sex / see).filter(|l| *l > 0.0)
}

/// Builds the stress–strain curve of a fibre from its file (first section).
pub fn curve_from_dataset(
    ds: &Dataset,
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Result<StressStrainCurve> {
    let loc = || Location::file(&ds.source);
    let section = ds
        .sections
        .iter()
        .max_by_key(|s| s.rows())
        .ok_or_else(|| Error::input(loc(), "no data section"))?;
    let ch = &section.channels;
    // English and German names (testXpert: Dehnung, Standardkraft,
    // Standardweg): ingest::roles::TensileRole.
    let strain_ch = find(ch, TensileRole::Strain);
    let stress_ch = find(ch, TensileRole::Stress);
    let force_ch = find(ch, TensileRole::Force);
    let ext_ch = find(ch, TensileRole::Extension);
    let stress = stress_pa(&ds.source, stress_ch, force_ch, meta, facts)?;
    let ext = ext_ch.map(|(c, u)| si(c, &u));
    let (strain, reference) = strain_and_reference(&ds.source, strain_ch, ext, meta, facts)?;
    let mut curve = StressStrainCurve::new(strain, stress)?;
    curve.strain_reference_m = reference;
    Ok(curve)
}
