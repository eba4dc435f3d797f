//! Per-fibre records and the `tensile` table (`schemas/tensile.toml`).

use crate::status::{Code, Status};
use std::collections::HashMap;

use crate::error::Result;
use crate::table::{Table, TableBuilder};

use super::analyze::{control_outcome, ControlOutcome, FibreFeatures, RatioMethod};
use super::curve::{FibreMeta, Knot};

/// Results the instrument software computed itself, SI units (T150:
/// StressAtBreak, StrainAtBreak, Toughness, Modulus; Bluehill: tensile
/// strength, strain at tensile strength, modulus; testXpert: E, Rm or
/// Fmax, strain at Fmax and at break, Rp0,2, ReH).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InstrumentResults {
    /// Strength (maximum stress) or stress at break, Pa.
    pub strength_pa: Option<f64>,
    /// Maximum force, N.
    pub max_force_n: Option<f64>,
    /// Strain at the maximum force (fraction).
    pub strain_at_max: Option<f64>,
    /// Strain at break (fraction).
    pub strain_at_break: Option<f64>,
    /// ∫ σ dε, J/m³ (T150 "Toughness" in MPa = MJ/m³).
    pub energy_density_j_per_m3: Option<f64>,
    /// Modulus, Pa.
    pub modulus_pa: Option<f64>,
    /// Offset yield R_p0.2, Pa (testXpert `Rp0,2`, T150 `OffsetYieldStress`).
    pub yield_pa: Option<f64>,
    /// Upper yield R_eH, Pa (testXpert `ReH`, `obere Streckgrenze`).
    pub upper_yield_pa: Option<f64>,
}

/// One analysed fibre.
#[derive(Debug, Clone, PartialEq)]
pub struct FibreRecord {
    /// Input file (or other source) as given.
    pub source: String,
    /// What is known about the specimen.
    pub meta: FibreMeta,
    /// Our features.
    pub features: FibreFeatures,
    /// The instrument's own results, when the file states them.
    pub instrument: InstrumentResults,
}

/// Eq. 5.4 for every knotted fibre whose ε* is unclear: the ratio against
/// the toughness of the record whose `sample_id` is its `control_id`. A
/// control id that names no record becomes a status entry.
pub fn apply_controls(records: &mut [FibreRecord]) {
    let toughness: HashMap<String, Option<f64>> = records
        .iter()
        .map(|r| (r.meta.sample_id.clone(), r.features.toughness_j_per_kg))
        .collect();
    for r in records.iter_mut() {
        let Some(cid) = r.meta.control_id.clone() else {
            continue;
        };
        if !r.meta.knot.is_knotted() || r.features.ratio_method.is_some() {
            continue;
        }
        match toughness.get(&cid) {
            Some(t) => r.features.apply_control(*t, &cid),
            None => r.features.status.push(
                Code::ControlNotFound,
                format!("no fibre with sample_id '{cid}'"),
            ),
        }
    }
}

/// [`apply_controls`] on the `tensile` table itself (the rows of many
/// files joined): fills `toughness_ratio`, `toughness_ratio_method` and
/// `status` of the knotted fibres whose ε* was unclear. The toughness is
/// read in J/g; T_k / T_u is the same ratio in any unit.
pub fn apply_controls_table(t: Table) -> Result<Table> {
    let ids = t.str("sample_id")?;
    let tough = t.f64("toughness_J_per_g")?;
    let by_id: HashMap<&str, Option<f64>> = ids
        .iter()
        .zip(&tough)
        .filter_map(|(id, v)| id.as_deref().map(|id| (id, *v)))
        .collect();
    let (controls, knots) = (t.str("control_id")?, t.str("knot")?);
    let mut ratio = t.f64("toughness_ratio")?;
    let mut method = t.str("toughness_ratio_method")?;
    let mut status = t.statuses()?;
    for i in 0..t.height() {
        let (Some(cid), Some(knot)) = (&controls[i], &knots[i]) else {
            continue;
        };
        if !Knot::parse(knot).is_knotted() || method[i].is_some() {
            continue;
        }
        let note = match by_id.get(cid.as_str()) {
            None => Some(Status::of(
                Code::ControlNotFound,
                format!("no fibre with sample_id '{cid}'"),
            )),
            Some(tu) => match control_outcome(tough[i], *tu, cid) {
                ControlOutcome::Ratio(r) => {
                    ratio[i] = Some(r);
                    method[i] = Some(RatioMethod::Control.name().into());
                    None
                }
                ControlOutcome::Note(n) => {
                    Some(Status::of(n.code, n.detail.replace(" J/kg", " J/g")))
                }
                ControlOutcome::Unchanged => None,
            },
        };
        if let Some(n) = note {
            status[i].extend(n);
        }
    }
    t.update(
        TableBuilder::new()
            .f64("toughness_ratio", ratio)
            .str("toughness_ratio_method", method)
            .status(&status),
    )
}

fn mpa(x: Option<f64>) -> Option<f64> {
    x.map(|v| v * 1e-6)
}
fn j_per_g(x: Option<f64>) -> Option<f64> {
    x.map(|v| v * 1e-3)
}

/// The `tensile` table: one row per fibre, columns as in
/// `schemas/tensile.toml`.
pub fn tensile_table(records: &[FibreRecord]) -> Result<Table> {
    let b = knot_columns(TableBuilder::new(), records);
    let b = specimen_columns(b, records);
    let b = test_columns(b, records);
    let b = curve_columns(b, records);
    section_and_instrument_columns(b, records).build()
}

/// One optional float per record.
fn floats(records: &[FibreRecord], g: &dyn Fn(&FibreRecord) -> Option<f64>) -> Vec<Option<f64>> {
    records.iter().map(g).collect()
}

/// Identity and the knot analysis (thesis §3.3).
fn knot_columns(b: TableBuilder, records: &[FibreRecord]) -> TableBuilder {
    let f = |g: &dyn Fn(&FibreRecord) -> Option<f64>| floats(records, g);
    b.str("source", records.iter().map(|r| Some(&r.source)))
        .str("sample_id", records.iter().map(|r| Some(&r.meta.sample_id)))
        .str("material", records.iter().map(|r| Some(&r.meta.material)))
        .str("knot", records.iter().map(|r| Some(r.meta.knot.name())))
        .f64("strength_MPa", f(&|r| mpa(r.features.strength_pa)))
        .f64("strain_at_break", f(&|r| r.features.strain_at_break))
        .f64(
            "toughness_J_per_g",
            f(&|r| j_per_g(r.features.toughness_j_per_kg)),
        )
        .f64(
            "friction_stress_MPa",
            f(&|r| mpa(r.features.friction_stress_pa)),
        )
        .f64("friction_ratio", f(&|r| r.features.friction_ratio))
        .bool(
            "knot_effective",
            records.iter().map(|r| r.features.knot_effective),
        )
        .f64("release_strain", f(&|r| r.features.release_strain))
        .f64(
            "toughness_after_release_J_per_g",
            f(&|r| j_per_g(r.features.toughness_after_release_j_per_kg)),
        )
        .f64("toughness_ratio", f(&|r| r.features.toughness_ratio))
        .str(
            "release_method",
            records
                .iter()
                .map(|r| Some(r.features.release_status.name())),
        )
        .status(records.iter().map(|r| &r.features.status))
        .str(
            "toughness_ratio_method",
            records
                .iter()
                .map(|r| r.features.ratio_method.map(|m| m.name())),
        )
        .str(
            "control_id",
            records.iter().map(|r| r.meta.control_id.as_ref()),
        )
}

/// The specimen's geometry and density from the manifest or file.
fn specimen_columns(b: TableBuilder, records: &[FibreRecord]) -> TableBuilder {
    let f = |g: &dyn Fn(&FibreRecord) -> Option<f64>| floats(records, g);
    b.f64("diameter_um", f(&|r| r.meta.diameter_m.map(|d| d * 1e6)))
        .f64(
            "fibre_length_mm",
            f(&|r| r.meta.fibre_length_m.map(|l| l * 1e3)),
        )
        .f64(
            "end_distance_mm",
            f(&|r| r.meta.end_distance_m.map(|l| l * 1e3)),
        )
        .f64(
            "density_g_per_cm3",
            records
                .iter()
                .map(|r| r.meta.density_kg_per_m3.map(|d| d * 1e-3)),
        )
}

/// What kind of test it was: the material class (its windows), the
/// direction, and the length the extension was divided by.
fn test_columns(b: TableBuilder, records: &[FibreRecord]) -> TableBuilder {
    b.str(
        "material_class",
        records
            .iter()
            .map(|r| r.meta.material_class.map(|c| c.name())),
    )
    .str(
        "test_direction",
        records
            .iter()
            .map(|r| Some(r.features.general.direction.name())),
    )
    .f64(
        "gauge_length_mm",
        floats(records, &|r| r.meta.gauge_length_m.map(|l| l * 1e3)),
    )
}

/// The general curve analysis (MODELS.md §9): modulus, maximum, yield.
fn curve_columns(b: TableBuilder, records: &[FibreRecord]) -> TableBuilder {
    let f = |g: &dyn Fn(&FibreRecord) -> Option<f64>| floats(records, g);
    b.f64("k1", f(&|r| r.features.k1))
        .f64("strain_at_strength", f(&|r| r.features.strain_at_strength))
        .f64(
            "energy_density_MJ_per_m3",
            f(&|r| mpa(r.features.energy_density_j_per_m3)),
        )
        .f64(
            "modulus_GPa",
            f(&|r| r.features.modulus_pa.map(|m| m * 1e-9)),
        )
        .str(
            "modulus_method",
            records
                .iter()
                .map(|r| r.features.general.modulus_method.as_ref()),
        )
        .f64(
            "max_stress_MPa",
            f(&|r| mpa(r.features.general.max_stress_pa)),
        )
        .f64(
            "strain_at_max_stress",
            f(&|r| r.features.general.strain_at_max_stress),
        )
        .f64("max_force_N", f(&|r| r.features.general.max_force_n))
        .f64(
            "yield_stress_MPa",
            f(&|r| mpa(r.features.general.yield_stress_pa)),
        )
        .f64("yield_strain", f(&|r| r.features.general.yield_strain))
        .f64(
            "upper_yield_MPa",
            f(&|r| mpa(r.features.general.upper_yield_pa)),
        )
        .f64(
            "lower_yield_MPa",
            f(&|r| mpa(r.features.general.lower_yield_pa)),
        )
}

/// The section used, drop counts, and the instrument's own printed results.
fn section_and_instrument_columns(b: TableBuilder, records: &[FibreRecord]) -> TableBuilder {
    let f = |g: &dyn Fn(&FibreRecord) -> Option<f64>| floats(records, g);
    let count = |g: &dyn Fn(&FibreRecord) -> Option<usize>| {
        records
            .iter()
            .map(|r| g(r).map(|n| n as i64))
            .collect::<Vec<_>>()
    };
    b.str(
        "section",
        records.iter().map(|r| r.meta.section().map(|s| s.0)),
    )
    .f64("width_mm", f(&|r| r.meta.width_m.map(|w| w * 1e3)))
    .f64("thickness_mm", f(&|r| r.meta.thickness_m.map(|t| t * 1e3)))
    .f64("area_mm2", f(&|r| r.meta.section().map(|s| s.1 * 1e6)))
    .i64("plateau_drops", count(&|r| r.features.plateau_drops))
    .i64(
        "unfastening_drops",
        count(&|r| r.features.unfastening_drops),
    )
    .bool(
        "fracture_truncated",
        records.iter().map(|r| Some(r.features.truncated)),
    )
    .f64(
        "instrument_strength_MPa",
        f(&|r| mpa(r.instrument.strength_pa)),
    )
    .f64("instrument_max_force_N", f(&|r| r.instrument.max_force_n))
    .f64(
        "instrument_strain_at_max",
        f(&|r| r.instrument.strain_at_max),
    )
    .f64(
        "instrument_strain_at_break",
        f(&|r| r.instrument.strain_at_break),
    )
    .f64(
        "instrument_energy_density_MJ_per_m3",
        f(&|r| mpa(r.instrument.energy_density_j_per_m3)),
    )
    .f64(
        "instrument_modulus_GPa",
        f(&|r| r.instrument.modulus_pa.map(|m| m * 1e-9)),
    )
    .f64("instrument_yield_MPa", f(&|r| mpa(r.instrument.yield_pa)))
    .f64(
        "instrument_upper_yield_MPa",
        f(&|r| mpa(r.instrument.upper_yield_pa)),
    )
}
