//! Per-fibre features from one stress–strain curve (MODELS.md §3).

use crate::signal::integrate::{mean_within, trapezoid_within};
use crate::status::{Code, Note, Status};

use super::curve::{FibreMeta, StressStrainCurve};
use super::fracture::find_break;
use super::general::{analyze_general, is_reversed, GeneralFeatures};
use super::params::TensileParams;
use super::release::{find_release, Release, ReleaseStatus};

/// How the toughness ratio of a knotted fibre was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RatioMethod {
    /// T_k / T_u' with ε* from the same fibre (Eq. 5.3).
    Release,
    /// T_k / T_u of the adjacent control fibre (Eq. 5.4).
    Control,
}

impl RatioMethod {
    /// Name used in tables.
    pub fn name(self) -> &'static str {
        match self {
            RatioMethod::Release => "eq5.3_release",
            RatioMethod::Control => "eq5.4_control",
        }
    }
}

/// Features of one fibre, SI units. `None` means "not available"; the
/// reason is in `status`.
#[derive(Debug, Clone, PartialEq)]
pub struct FibreFeatures {
    /// Strength: maximum stress up to the break point, Pa.
    pub strength_pa: Option<f64>,
    /// Strain at break ε_f (fraction; relative to l0 for a knotted fibre).
    pub strain_at_break: Option<f64>,
    /// Strain at the maximum stress (fraction).
    pub strain_at_strength: Option<f64>,
    /// ∫_0^{ε_f} σ dε, J/m³ (slack excluded).
    pub energy_density_j_per_m3: Option<f64>,
    /// k1 = (l − l0)/l (Eq. 5.2); 0 for unknotted fibres.
    pub k1: Option<f64>,
    /// Toughness modulus T_u (Eq. 5.1) or T_k (Eq. 5.2), J/kg.
    pub toughness_j_per_kg: Option<f64>,
    /// Mean stress over 0 … 0.4 ε_f (strain-weighted), Pa.
    pub friction_stress_pa: Option<f64>,
    /// Friction stress / strength (fraction).
    pub friction_ratio: Option<f64>,
    /// friction_ratio > threshold (knotted fibres only).
    pub knot_effective: Option<bool>,
    /// How ε* was found.
    pub release_status: ReleaseStatus,
    /// Knot release strain ε*, when clear.
    pub release_strain: Option<f64>,
    /// T_u' = (1 − k1)/ρ ∫_{ε*}^{ε_f} σ dε (Eq. 5.3), J/kg.
    pub toughness_after_release_j_per_kg: Option<f64>,
    /// T_k / T_u' (Eq. 5.3) or T_k / T_u of the control (Eq. 5.4).
    pub toughness_ratio: Option<f64>,
    /// Which of the two gave `toughness_ratio`.
    pub ratio_method: Option<RatioMethod>,
    /// Stress drops in the plateau (knotted fibres).
    pub plateau_drops: Option<usize>,
    /// Stress drops in the final unfastening (knotted fibres).
    pub unfastening_drops: Option<usize>,
    /// Max-slope modulus, Pa (see [`super::modulus`]).
    pub modulus_pa: Option<f64>,
    /// The record ended during the final drop.
    pub truncated: bool,
    /// Maximum stress and force, offset and upper/lower yield, modulus and
    /// its method ([`super::general`]): reported for every curve, also one
    /// without a fracture.
    pub general: GeneralFeatures,
    /// Problems found, `ok` when all is well.
    pub status: Status,
}

impl FibreFeatures {
    /// Features that are all unknown, with one status entry.
    pub fn empty(status: Status) -> Self {
        FibreFeatures {
            strength_pa: None,
            strain_at_break: None,
            strain_at_strength: None,
            energy_density_j_per_m3: None,
            k1: None,
            toughness_j_per_kg: None,
            friction_stress_pa: None,
            friction_ratio: None,
            knot_effective: None,
            release_status: ReleaseStatus::NotApplicable,
            release_strain: None,
            toughness_after_release_j_per_kg: None,
            toughness_ratio: None,
            ratio_method: None,
            plateau_drops: None,
            unfastening_drops: None,
            modulus_pa: None,
            truncated: false,
            general: GeneralFeatures::default(),
            status,
        }
    }

    /// Eq. 5.4: when ε* is unclear, the ratio against the control fibre's
    /// toughness T_u (J/kg). Does nothing if a ratio is already known.
    pub fn apply_control(&mut self, control_toughness_j_per_kg: Option<f64>, control_id: &str) {
        if self.ratio_method.is_some() {
            return;
        }
        match control_outcome(
            self.toughness_j_per_kg,
            control_toughness_j_per_kg,
            control_id,
        ) {
            ControlOutcome::Ratio(r) => {
                self.toughness_ratio = Some(r);
                self.ratio_method = Some(RatioMethod::Control);
            }
            ControlOutcome::Note(n) => self.status.push(n.code, n.detail),
            ControlOutcome::Unchanged => {}
        }
    }
}

/// What Eq. 5.4 gives a knotted fibre of toughness `tk` against a control
/// of toughness `tu` (both in the same unit).
#[derive(Debug, Clone, PartialEq)]
pub enum ControlOutcome {
    /// T_k / T_u.
    Ratio(f64),
    /// No ratio, and why (a status entry).
    Note(Note),
    /// No ratio, nothing to say (the fibre itself has no toughness).
    Unchanged,
}

/// Eq. 5.4 for one fibre; see [`ControlOutcome`].
pub fn control_outcome(tk: Option<f64>, tu: Option<f64>, control_id: &str) -> ControlOutcome {
    match (tk, tu) {
        (Some(tk), Some(tu)) if tu > 0.0 => ControlOutcome::Ratio(tk / tu),
        (Some(_), Some(tu)) => ControlOutcome::Note(Note {
            code: Code::ControlUnusable,
            detail: format!("control '{control_id}' has toughness {tu} J/kg ≤ 0"),
        }),
        (Some(_), None) => ControlOutcome::Note(Note {
            code: Code::ControlUnusable,
            detail: format!("control '{control_id}' has no toughness"),
        }),
        (None, _) => ControlOutcome::Unchanged,
    }
}

/// The strain relative to l0, as Eq. 5.2 needs it for a knotted fibre:
/// converted when the curve says relative to what its strain is.
fn strain_over_l0(curve: &StressStrainCurve, meta: &FibreMeta, knotted: bool) -> Vec<f64> {
    match (knotted, curve.strain_reference_m, meta.end_distance_m) {
        (true, Some(r), Some(l0)) if l0 > 0.0 => curve.strain.iter().map(|e| e * r / l0).collect(),
        _ => curve.strain.clone(),
    }
}

/// k1 (noting the lengths it lacks) and (1 − k1)/ρ, the factor from energy
/// per volume to toughness per mass: only with a density (the fibre
/// protocol defaults to silk's).
fn k1_and_per_mass(meta: &FibreMeta, status: &mut Status) -> (Option<f64>, Option<f64>) {
    let k1 = match meta.k1() {
        Ok(k) => Some(k),
        Err(msg) => {
            status.push(Code::MissingLengths, msg);
            None
        }
    };
    let per_mass = match (k1, meta.density_kg_per_m3) {
        (Some(k), Some(rho)) => Some((1.0 - k) / rho),
        _ => None,
    };
    (k1, per_mass)
}

/// Analyses one fibre. Never fails: every problem becomes a status entry
/// and the affected features are `None`.
pub fn analyze_fibre(
    curve: &StressStrainCurve,
    meta: &FibreMeta,
    params: &TensileParams,
) -> FibreFeatures {
    if let Some(refused) = refusal(curve, meta, params) {
        return refused;
    }
    let knotted = meta.knot.is_knotted();
    let mut status = Status::ok();
    let strain = strain_over_l0(curve, meta, knotted);
    let stress = &curve.stress_pa;
    let class = meta.material_class;
    let general = analyze_general(&strain, stress, knotted, class, params);
    let bp = match find_break(&strain, stress, params) {
        Ok(b) => b,
        Err(nb) => return without_fracture(nb.status(), knotted, general),
    };
    if bp.truncated {
        status.push(Code::FractureTruncated, "record ends during the final drop");
    }
    // The fibre protocol breaks at the top of the final drop (thesis);
    // other classes at the last point before the stress falls near zero
    // (ISO 527-1, ISO 6892-1), where the instrument detects the break.
    let b = match class.is_none_or(|c| c.thesis_break()) {
        true => bp.index,
        false => bp.last_loaded,
    };
    let start = bp.start;
    let strength = stress[bp.max_index];
    let eps_f = strain[b];
    // integrals run over the path from the sample before ε ≥ 0 to b,
    // clipped to 0 ≤ ε ≤ ε_f
    let from = start.saturating_sub(1);
    let path_e = &strain[from..=b];
    let path_s = &stress[from..=b];
    let energy = trapezoid_within(path_e, path_s, 0.0, eps_f);
    let (k1, per_mass) = k1_and_per_mass(meta, &mut status);
    let toughness = per_mass.map(|c| c * energy);
    // Knot quantities only for a knotted fibre: null, not zero, otherwise.
    let friction_stress = knotted
        .then(|| mean_within(path_e, path_s, 0.0, params.friction_window * eps_f))
        .flatten();
    let friction_ratio = friction_stress.map(|f| f / strength);
    let knot_effective = friction_ratio.map(|r| r > params.effective_threshold);
    let modulus = general.modulus_pa;
    let mut f = FibreFeatures {
        strength_pa: Some(strength),
        strain_at_break: Some(eps_f),
        strain_at_strength: Some(strain[bp.max_index]),
        energy_density_j_per_m3: Some(energy),
        k1: k1.filter(|_| knotted),
        toughness_j_per_kg: toughness,
        friction_stress_pa: friction_stress,
        friction_ratio,
        knot_effective,
        release_status: ReleaseStatus::NotApplicable,
        release_strain: None,
        toughness_after_release_j_per_kg: None,
        toughness_ratio: None,
        ratio_method: None,
        plateau_drops: None,
        unfastening_drops: None,
        modulus_pa: modulus,
        truncated: bp.truncated,
        general,
        status,
    };
    if knotted {
        let r = find_release(&strain, stress, start, b, strength, params);
        let eps_star = r.index.map(|i| strain[i]);
        add_release(&mut f, &r, eps_star, (path_e, path_s), per_mass);
    }
    f
}

/// The knot release's columns: ε*, the toughness after it and the ratio of
/// Eq. 5.3 (where (1 − k1)/ρ, `per_mass`, cancels).
fn add_release(
    f: &mut FibreFeatures,
    r: &Release,
    eps_star: Option<f64>,
    (path_e, path_s): (&[f64], &[f64]),
    per_mass: Option<f64>,
) {
    f.release_status = r.status;
    f.plateau_drops = Some(r.plateau_drops);
    f.unfastening_drops = Some(r.unfastening_drops);
    let (Some(eps_star), Some(eps_f), Some(energy)) =
        (eps_star, f.strain_at_break, f.energy_density_j_per_m3)
    else {
        return;
    };
    f.release_strain = Some(eps_star);
    let after = trapezoid_within(path_e, path_s, eps_star, eps_f);
    f.toughness_after_release_j_per_kg = per_mass.map(|c| c * after);
    if after > 0.0 {
        f.toughness_ratio = Some(energy / after);
        f.ratio_method = Some(RatioMethod::Release);
    }
}

/// A fibre without a recorded fracture: no strength at break nor an
/// integral to it; the maximum stress, modulus and yield of the general
/// analysis still hold.
fn without_fracture(status: Status, knotted: bool, general: GeneralFeatures) -> FibreFeatures {
    let mut f = FibreFeatures::empty(status);
    f.release_status = if knotted {
        ReleaseStatus::Unclear
    } else {
        ReleaseStatus::NotApplicable
    };
    f.modulus_pa = general.modulus_pa;
    f.general = general;
    f
}

/// The features of a curve that cannot be analysed (invalid parameters,
/// empty or non-finite curve, bad density, reversed strain), or `None`.
fn refusal(
    curve: &StressStrainCurve,
    meta: &FibreMeta,
    params: &TensileParams,
) -> Option<FibreFeatures> {
    if let Err(e) = params.validate() {
        return Some(FibreFeatures::empty(Status::of(
            Code::InvalidParameters,
            e.to_string(),
        )));
    }
    if curve.is_empty() || curve.strain.len() != curve.stress_pa.len() {
        return Some(FibreFeatures::empty(Status::of(
            Code::EmptyCurve,
            "no samples",
        )));
    }
    let bad = curve.non_finite_count();
    if bad > 0 {
        return Some(FibreFeatures::empty(Status::of(
            Code::NonFinite,
            format!("{bad} samples with NaN or infinite strain or stress"),
        )));
    }
    if let Some(rho) = meta
        .density_kg_per_m3
        .filter(|r| !(*r > 0.0 && r.is_finite()))
    {
        return Some(FibreFeatures::empty(Status::of(
            Code::BadDensity,
            format!("{rho} kg/m3, expected > 0"),
        )));
    }
    if is_reversed(&curve.strain) {
        let first = curve.strain[0];
        let last = curve.strain[curve.strain.len() - 1];
        let mut f = FibreFeatures::empty(Status::of(
            Code::ReversedStrain,
            format!(
                "strain decreases through the record ({first} at the start, {last} at the end): \
                 reversed or sign-flipped; no modulus, yield or toughness"
            ),
        ));
        f.general.max_stress_pa = curve.stress_pa.iter().copied().reduce(f64::max);
        return Some(f);
    }
    None
}
