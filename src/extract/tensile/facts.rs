//! What a file states about its specimen and the instrument's own results,
//! read from the preamble its reader kept (SI units).
//!
//! Keys are matched after folding: lower case, ASCII letters and digits
//! only (`Probenbreite b0` → `probenbreiteb0`, `Rp0,2` → `rp02`, `Länge`
//! and the `L�nge` of a mangled export both → `lnge`), so spellings and
//! encodings of one family agree. A value's unit decides what it is where
//! a key is ambiguous: testXpert's `Kraftmaximum` is the maximum force in
//! N, or the strength when the template prints it in N/mm².

use crate::ingest::dialect::parse_number;
use crate::ingest::Dataset;
use crate::status::{Code, Status};
use crate::units::{parse_unit, Quantity, Unit};

use super::class::MaterialClass;
use super::records::InstrumentResults;

/// What the file itself states about the specimen and its results (SI).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FileFacts {
    /// The instrument's own results.
    pub instrument: InstrumentResults,
    /// Specimen diameter, m (T150 SpecimenDiameter, testXpert d0, MTS
    /// Durchmesser).
    pub diameter_m: Option<f64>,
    /// Gauge length, m (Bluehill Length, testXpert L0 or Messlänge, the
    /// Instron `Specimen Length`, the MTS specimen length).
    pub gauge_length_m: Option<f64>,
    /// Width and thickness of a rectangular section, m (Bluehill Width,
    /// Thickness; testXpert b0, a0).
    pub width_m: Option<f64>,
    /// See `width_m`.
    pub thickness_m: Option<f64>,
    /// Section area, m², when the file states it (Instron `Area` or
    /// `Specimen Cross-section`, often cm²; testXpert S0).
    pub area_m2: Option<f64>,
    /// Density, kg/m³, when the file states the specimen's mass and
    /// dimensions (MTS `Masse` of a cylinder).
    pub density_kg_per_m3: Option<f64>,
    /// The specimen's id as the file states it.
    pub specimen_id: Option<String>,
    /// A class the instrument implies (a T150 is a fibre tester).
    pub implied_class: Option<MaterialClass>,
    /// What was assumed reading the facts (a value without a unit).
    pub notes: Status,
}

/// Folds a key for matching (module doc).
pub fn fold(key: &str) -> String {
    key.chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .map(|c| c.to_ascii_lowercase())
        .collect()
}

/// The preamble values whose folded key is one of `keys`, in file order:
/// each one's number (with the file's decimal mark or a point), its unit
/// when the value has one, and its key as written.
fn entries<'a>(
    ds: &'a Dataset,
    keys: &'a [&str],
) -> impl Iterator<Item = (f64, Option<Unit>, String)> + 'a {
    ds.preamble.iter().filter_map(move |m| {
        if !keys.contains(&fold(&m.key).as_str()) {
            return None;
        }
        let mut parts = m.value.split_whitespace();
        let first = parts.next()?;
        let decimal = ds.dialect.as_ref().map_or('.', |d| d.decimal);
        let number = parse_number(first, decimal)
            .or_else(|| parse_number(first, '.'))
            .filter(|v| v.is_finite())?;
        let unit = parts.collect::<Vec<_>>().join(" ");
        Some((number, parse_unit(&unit), m.key.clone()))
    })
}

/// The first of [`entries`].
fn entry(ds: &Dataset, keys: &[&str]) -> Option<(f64, Option<Unit>, String)> {
    entries(ds, keys).next()
}

/// The first preamble value among `keys` whose unit measures `quantity`,
/// in SI.
fn si(ds: &Dataset, quantity: Quantity, keys: &[&str]) -> Option<f64> {
    entries(ds, keys).find_map(|(v, u, _)| {
        let u = u?;
        let u = match quantity {
            Quantity::Force => u.as_force(),
            _ => u,
        };
        (u.quantity == quantity).then(|| u.to_si(v))
    })
}

/// A preamble value as text, trimmed of quotes.
fn text(ds: &Dataset, keys: &[&str]) -> Option<String> {
    let m = ds
        .preamble
        .iter()
        .find(|m| keys.contains(&fold(&m.key).as_str()))?;
    let v = m.value.trim().trim_matches('"').trim();
    (!v.is_empty()).then(|| v.to_string())
}

/// The instrument results, geometry and id stated in the file.
pub fn file_facts(ds: &Dataset) -> FileFacts {
    match ds.format {
        "t150-nanosuite" => t150(ds),
        "instron-bluehill" | "instron-blocks" => instron(ds),
        "instron-parameters" => instron_parameters(ds),
        "zwick-testxpert" => testxpert(ds),
        "mts-793" => mts793(ds),
        _ => FileFacts {
            diameter_m: ds
                .preamble
                .iter()
                .find(|m| m.key.to_ascii_lowercase().contains("diameter"))
                .and_then(|m| si(ds, Quantity::Length, &[fold(&m.key).as_str()])),
            ..Default::default()
        },
    }
}

fn t150(ds: &Dataset) -> FileFacts {
    FileFacts {
        instrument: InstrumentResults {
            strength_pa: si(ds, Quantity::Stress, &["stressatbreak"]),
            strain_at_break: si(ds, Quantity::Dimensionless, &["strainatbreak"]),
            // "Toughness 218.498 MPa": MPa = MJ/m³, so Pa = J/m³
            energy_density_j_per_m3: si(ds, Quantity::Stress, &["toughness"]),
            modulus_pa: si(ds, Quantity::Stress, &["modulus"]),
            yield_pa: si(ds, Quantity::Stress, &["offsetyieldstress"]),
            ..Default::default()
        },
        diameter_m: si(ds, Quantity::Length, &["specimendiameter"]),
        specimen_id: text(ds, &["specimenname"]).map(|n| match text(ds, &["testnumber"]) {
            Some(t) => format!("{n}_{t}"),
            None => n,
        }),
        implied_class: Some(MaterialClass::Fibre),
        ..Default::default()
    }
}

/// Bluehill raw data and Instron metadata blocks share their names.
fn instron(ds: &Dataset) -> FileFacts {
    let strength = [
        "tensilestressattensilestrength",
        "tensilestressatmaximumload",
    ];
    let strain = [
        "tensilestrainstrain1attensilestrength",
        "tensilestrainattensilestrength",
        "tensilestrainatmaximumload",
    ];
    FileFacts {
        instrument: InstrumentResults {
            strength_pa: si(ds, Quantity::Stress, &strength),
            strain_at_max: si(ds, Quantity::Dimensionless, &strain),
            modulus_pa: si(
                ds,
                Quantity::Stress,
                &["modulusautomaticyoungs", "modulusautomatic", "modulus"],
            ),
            yield_pa: si(ds, Quantity::Stress, &["tensilestressatyieldoffset02"]),
            max_force_n: si(ds, Quantity::Force, &["maximumload", "loadatmaximumload"]),
            ..Default::default()
        },
        diameter_m: si(ds, Quantity::Length, &["diameter"]),
        gauge_length_m: si(ds, Quantity::Length, &["length", "gaugelength"]),
        width_m: si(ds, Quantity::Length, &["width"]),
        thickness_m: si(ds, Quantity::Length, &["thickness"]),
        area_m2: si(ds, Quantity::Area, &["area"]),
        specimen_id: text(ds, &["specimenid", "specimenlabel"]),
        ..Default::default()
    }
}

fn instron_parameters(ds: &Dataset) -> FileFacts {
    FileFacts {
        width_m: si(ds, Quantity::Length, &["specimenwidth"]),
        thickness_m: si(ds, Quantity::Length, &["specimenthickness"]),
        area_m2: si(
            ds,
            Quantity::Area,
            &["specimencrosssection", "crosssection"],
        ),
        gauge_length_m: si(ds, Quantity::Length, &["specimenlength", "gaugelength"]),
        diameter_m: si(ds, Quantity::Length, &["specimendiameter"]),
        ..Default::default()
    }
}

/// testXpert in German and English, results table or parameter lines.
fn testxpert(ds: &Dataset) -> FileFacts {
    let maximum = [
        "rm",
        "fm",
        "fmax",
        "kraftmaximum",
        "hchstkraft",
        "maximumforce",
        "tensilestrength",
        "zugfestigkeit",
    ];
    FileFacts {
        instrument: InstrumentResults {
            strength_pa: si(ds, Quantity::Stress, &maximum),
            max_force_n: si(ds, Quantity::Force, &maximum),
            strain_at_max: si(
                ds,
                Quantity::Dimensionless,
                &[
                    "agt",
                    "dehnungbeifmax",
                    "strainatfmax",
                    "em",
                    "dehnungbeikraftmaximum",
                ],
            ),
            strain_at_break: si(
                ds,
                Quantity::Dimensionless,
                &[
                    "at",
                    "dehnungbeibruch",
                    "strainatbreak",
                    "nominalstrainatbreak",
                    "eb",
                ],
            ),
            modulus_pa: si(
                ds,
                Quantity::Stress,
                &["e", "emodul", "modulus", "youngsmodulus", "et"],
            ),
            yield_pa: si(ds, Quantity::Stress, &["rp02"]),
            upper_yield_pa: si(
                ds,
                Quantity::Stress,
                &[
                    "reh",
                    "oberestreckgrenze",
                    "upperyieldpoint",
                    "upperyieldstrength",
                ],
            ),
            ..Default::default()
        },
        diameter_m: si(
            ds,
            Quantity::Length,
            &["d0", "probendurchmesser", "probendurchmesserd0", "diameter"],
        ),
        gauge_length_m: si(
            ds,
            Quantity::Length,
            &["l0", "lo", "messlnge", "gaugelength"],
        ),
        width_m: si(
            ds,
            Quantity::Length,
            &["b0", "probenbreite", "probenbreiteb0", "specimenwidth"],
        ),
        thickness_m: si(
            ds,
            Quantity::Length,
            &["a0", "probendicke", "probendickea0", "specimenthickness"],
        ),
        area_m2: si(
            ds,
            Quantity::Area,
            &["s0", "anfangsquerschnitt", "querschnitt", "crosssection"],
        ),
        specimen_id: text(ds, &["probenkennung", "specimenid"]),
        ..Default::default()
    }
}

/// MTS 793: the operator's entries, usually without units. A length
/// without a unit is read in mm and a mass in g (the template's units),
/// with an `assumed_unit` note; the density they give is kept only when
/// it is that of a solid (0.05–25 g/cm³), which also vouches for the
/// assumption.
fn mts793(ds: &Dataset) -> FileFacts {
    let mut notes = Status::ok();
    let mut assumed = Vec::new();
    let mut length = |keys: &[&str], quantity: Quantity, unit: &str, scale: f64| {
        let (v, u, key) = entry(ds, keys)?;
        match u {
            Some(u) => (u.quantity == quantity).then(|| u.to_si(v)),
            None => {
                assumed.push(format!("{key} {v} as {unit}"));
                Some(v * scale)
            }
        }
    };
    let diameter = length(&["durchmesser", "diameter"], Quantity::Length, "mm", 1e-3);
    let len = length(
        &["lnge", "lange", "laenge", "length"],
        Quantity::Length,
        "mm",
        1e-3,
    );
    let mass = length(&["masse", "mass"], Quantity::Mass, "g", 1e-3);
    if !assumed.is_empty() {
        notes.push(
            Code::AssumedUnit,
            format!("no unit stated: read {}", assumed.join(", ")),
        );
    }
    let density = match (mass, diameter, len) {
        (Some(m), Some(d), Some(l)) => Some(m / (std::f64::consts::PI * d * d / 4.0 * l))
            .filter(|r| (50.0..=25_000.0).contains(r)),
        _ => None,
    };
    FileFacts {
        diameter_m: diameter,
        gauge_length_m: len,
        density_kg_per_m3: density,
        specimen_id: text(ds, &["probenbezeichnung", "specimenname", "specimen"]),
        notes,
        ..Default::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_fold_across_spellings_and_encodings() {
        assert_eq!(fold("Probenbreite b0"), "probenbreiteb0");
        assert_eq!(fold("Rp0,2"), "rp02");
        assert_eq!(fold("Länge"), fold("L\u{fffd}nge"));
        assert_eq!(
            fold("Modulus (Automatic Young's)"),
            "modulusautomaticyoungs"
        );
    }
}
