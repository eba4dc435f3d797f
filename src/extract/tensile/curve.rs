//! The inputs of the tensile analysis: a stress–strain curve and the fibre's
//! metadata (what the manifest or the file says about the specimen).
//!
//! Units inside tribo are SI: strain is a fraction (m/m), stress in Pa,
//! lengths in m, density in kg/m³. Tables convert to the units in their
//! column names (MPa, µm, mm, g/cm³, J/g) at the boundary.

use std::fmt;

use super::class::{Direction, MaterialClass};
use crate::error::{Error, Result};

/// Knot topology (thesis §5.3, Fig. 5.5), as written in a manifest.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Knot {
    /// Unknotted fibre (control).
    None,
    /// Single-turned slip knot ("Noose").
    Noose,
    /// Double-turned slip knot.
    DoubleNoose,
    /// Overhand loop.
    OverhandLoop,
    /// Chain knot with 2 chains.
    Chain2,
    /// Chain knot with 4 chains.
    Chain4,
    /// Chain knot with 6 chains.
    Chain6,
    /// X-knot.
    XKnot,
    /// Any other name, kept as written (trimmed).
    Other(String),
}

impl Knot {
    /// Parses a manifest value. Known names are matched case-insensitively,
    /// with spaces, `-` and `_` treated alike; an empty value is `None`.
    pub fn parse(text: &str) -> Knot {
        let key: String = text
            .trim()
            .to_ascii_lowercase()
            .chars()
            .map(|c| if c == ' ' || c == '-' { '_' } else { c })
            .collect();
        match key.as_str() {
            "" | "none" | "unknotted" | "control" => Knot::None,
            "noose" | "single_noose" | "stsk" => Knot::Noose,
            "double_noose" | "dtsk" => Knot::DoubleNoose,
            "overhand_loop" | "o.l." | "ol" => Knot::OverhandLoop,
            "chain2" | "chain_2" => Knot::Chain2,
            "chain4" | "chain_4" => Knot::Chain4,
            "chain6" | "chain_6" => Knot::Chain6,
            "x_knot" | "xknot" => Knot::XKnot,
            _ => Knot::Other(text.trim().to_string()),
        }
    }

    /// The canonical name written in tables.
    pub fn name(&self) -> &str {
        match self {
            Knot::None => "none",
            Knot::Noose => "noose",
            Knot::DoubleNoose => "double_noose",
            Knot::OverhandLoop => "overhand_loop",
            Knot::Chain2 => "chain2",
            Knot::Chain4 => "chain4",
            Knot::Chain6 => "chain6",
            Knot::XKnot => "x_knot",
            Knot::Other(s) => s,
        }
    }

    /// Whether the fibre carries a knot.
    pub fn is_knotted(&self) -> bool {
        !matches!(self, Knot::None)
    }
}

impl fmt::Display for Knot {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Default silk density ρ, kg/m³ (1.4 g/cm³, thesis §5.7).
pub const DEFAULT_DENSITY_KG_PER_M3: f64 = 1400.0;

/// What is known about one fibre specimen.
#[derive(Debug, Clone, PartialEq)]
pub struct FibreMeta {
    /// Sample identifier (manifest `sample_id`).
    pub sample_id: String,
    /// Material, free text (for example `raw`, `degummed`).
    pub material: String,
    /// Knot topology.
    pub knot: Knot,
    /// Fibre diameter d, m (> 0). Needed only to turn force into stress.
    pub diameter_m: Option<f64>,
    /// Whole fibre length l, m (> 0). Needed for k1 of a knotted fibre.
    pub fibre_length_m: Option<f64>,
    /// Distance between the fibre ends l0, m (0 < l0 ≤ l). Needed for k1.
    pub end_distance_m: Option<f64>,
    /// Volumetric density ρ, kg/m³ (> 0). [`FibreMeta::new`] gives silk's
    /// 1400 (1.4 g/cm³, the fibre protocol's default); a specimen of
    /// another class has none unless it is given, and then no toughness per
    /// mass.
    pub density_kg_per_m3: Option<f64>,
    /// `sample_id` of the adjacent unknotted control fibre, if any.
    pub control_id: Option<String>,
    /// Width of a rectangular section, m (> 0; manifest `width_mm`, else the
    /// file's, as Bluehill's `Width`).
    pub width_m: Option<f64>,
    /// Thickness of a rectangular section, m (> 0; manifest `thickness_mm`,
    /// else the file's).
    pub thickness_m: Option<f64>,
    /// Section area, m², when the file states only the area (Instron
    /// `Area`, often in cm²); a diameter or width × thickness takes
    /// precedence.
    pub area_m2: Option<f64>,
    /// Gauge length, m (manifest `gauge_length_mm`, else the file's): the
    /// length an extension is divided by.
    pub gauge_length_m: Option<f64>,
    /// Material class (manifest `material_class`), choosing the modulus
    /// window, the break definition and the strain bound
    /// ([`super::class`]); `None`: the fibre conventions, tribo's default.
    pub material_class: Option<MaterialClass>,
    /// Test direction when stated (manifest `test_direction`); else it is
    /// found from the sign of the largest load.
    pub direction: Option<Direction>,
}

impl FibreMeta {
    /// Metadata with only an identifier: unknotted, no class (the fibre
    /// conventions), silk's default density.
    pub fn new(sample_id: impl Into<String>) -> Self {
        FibreMeta {
            sample_id: sample_id.into(),
            material: String::new(),
            knot: Knot::None,
            diameter_m: None,
            fibre_length_m: None,
            end_distance_m: None,
            density_kg_per_m3: Some(DEFAULT_DENSITY_KG_PER_M3),
            control_id: None,
            width_m: None,
            thickness_m: None,
            area_m2: None,
            gauge_length_m: None,
            material_class: None,
            direction: None,
        }
    }

    /// The section: `circular` (a diameter), `rectangular` (width and
    /// thickness) or `area` (only its area stated), with its area, m²;
    /// `None` when none is known.
    pub fn section(&self) -> Option<(&'static str, f64)> {
        match (
            self.diameter_m,
            self.width_m,
            self.thickness_m,
            self.area_m2,
        ) {
            (Some(d), ..) => Some(("circular", std::f64::consts::PI * d * d / 4.0)),
            (None, Some(w), Some(t), _) => Some(("rectangular", w * t)),
            (None, _, _, Some(a)) => Some(("area", a)),
            _ => None,
        }
    }

    /// k1 = (l − l0) / l (Eq. 5.2). 0 for an unknotted fibre; `Err` with the
    /// reason when a knotted fibre lacks l or l0 or they are inconsistent.
    pub fn k1(&self) -> std::result::Result<f64, String> {
        if !self.knot.is_knotted() {
            return Ok(0.0);
        }
        match (self.fibre_length_m, self.end_distance_m) {
            (Some(l), Some(l0)) if l.is_finite() && l0.is_finite() && l0 > 0.0 && l >= l0 => {
                Ok((l - l0) / l)
            }
            (Some(l), Some(l0)) => Err(format!(
                "fibre length l = {l} m and end distance l0 = {l0} m: need 0 < l0 ≤ l"
            )),
            _ => Err(
                "knotted fibre without fibre_length_mm (l) and end_distance_mm (l0): \
                 k1 of Eq. 5.2 is unknown"
                    .into(),
            ),
        }
    }
}

/// A measured stress–strain curve in test order.
///
/// `strain` is engineering strain as a fraction, `stress_pa` engineering
/// stress in Pa. `strain_reference_m` is the length the strain is relative
/// to (the instrument's gauge length), when the source states it; Eq. 5.2
/// needs strain relative to l0, and the analysis converts when both are known.
#[derive(Debug, Clone, PartialEq)]
pub struct StressStrainCurve {
    /// Engineering strain (fraction), one value per sample.
    pub strain: Vec<f64>,
    /// Engineering stress, Pa, one value per sample.
    pub stress_pa: Vec<f64>,
    /// Length the strain is relative to, m, when known.
    pub strain_reference_m: Option<f64>,
    /// Tension, or compression (stress and strain then as magnitudes).
    pub direction: Direction,
    /// The largest force magnitude of the file's force channel, N, when it
    /// has one (else the force is σ_m times the section).
    pub max_force_n: Option<f64>,
}

impl StressStrainCurve {
    /// A curve from strain (fraction) and stress (Pa). The slices must have
    /// the same length.
    pub fn new(strain: Vec<f64>, stress_pa: Vec<f64>) -> Result<Self> {
        if strain.len() != stress_pa.len() {
            return Err(Error::Config(format!(
                "stress–strain curve: {} strain values but {} stress values",
                strain.len(),
                stress_pa.len()
            )));
        }
        Ok(StressStrainCurve {
            strain,
            stress_pa,
            strain_reference_m: None,
            direction: Direction::Tension,
            max_force_n: None,
        })
    }

    /// A curve from force (N) and extension (m): σ = F / A with
    /// A = π d² / 4 (MODELS.md §3) and ε = x / L with L the gauge length.
    pub fn from_force(
        extension_m: &[f64],
        force_n: &[f64],
        gauge_length_m: f64,
        diameter_m: f64,
    ) -> Result<Self> {
        if !(diameter_m > 0.0 && diameter_m.is_finite()) {
            return Err(Error::Config(format!(
                "fibre diameter {diameter_m} m: expected a finite value > 0"
            )));
        }
        if !(gauge_length_m > 0.0 && gauge_length_m.is_finite()) {
            return Err(Error::Config(format!(
                "gauge length {gauge_length_m} m: expected a finite value > 0"
            )));
        }
        let area = std::f64::consts::PI * diameter_m * diameter_m / 4.0;
        let strain = extension_m.iter().map(|x| x / gauge_length_m).collect();
        let stress = force_n.iter().map(|f| f / area).collect();
        let mut c = Self::new(strain, stress)?;
        c.strain_reference_m = Some(gauge_length_m);
        Ok(c)
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.strain.len()
    }

    /// Whether the curve has no samples.
    pub fn is_empty(&self) -> bool {
        self.strain.is_empty()
    }

    /// The number of samples whose strain or stress is not finite.
    pub fn non_finite_count(&self) -> usize {
        self.strain
            .iter()
            .zip(&self.stress_pa)
            .filter(|(e, s)| !e.is_finite() || !s.is_finite())
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knot_names_round_trip() {
        for k in [
            Knot::None,
            Knot::Noose,
            Knot::DoubleNoose,
            Knot::OverhandLoop,
            Knot::Chain2,
            Knot::Chain4,
            Knot::Chain6,
            Knot::XKnot,
        ] {
            assert_eq!(Knot::parse(k.name()), k);
        }
        assert_eq!(Knot::parse(" X-Knot "), Knot::XKnot);
        assert_eq!(Knot::parse("Overhand loop"), Knot::OverhandLoop);
        assert_eq!(
            Knot::parse("figure eight"),
            Knot::Other("figure eight".into())
        );
        assert!(!Knot::parse("").is_knotted());
    }

    #[test]
    fn k1_follows_eq_5_2_and_refuses_missing_lengths() {
        let mut m = FibreMeta::new("a");
        assert_eq!(m.k1(), Ok(0.0));
        m.knot = Knot::Noose;
        assert!(m.k1().is_err());
        m.fibre_length_m = Some(0.030);
        m.end_distance_m = Some(0.020);
        // (30 − 20) / 30 = 1/3; two roundings
        assert!((m.k1().unwrap() - 1.0 / 3.0).abs() < 1e-15);
        m.end_distance_m = Some(0.040);
        assert!(m.k1().is_err());
    }

    #[test]
    fn force_becomes_stress_over_the_circular_area() {
        // 1 mN on d = 10 µm: A = 7.853981633974483e-11 m², σ = 12.732395447 MPa
        let c = StressStrainCurve::from_force(&[0.0, 1e-4], &[0.0, 1e-3], 0.01, 10e-6).unwrap();
        assert!((c.stress_pa[1] - 1e-3 / (std::f64::consts::PI * 25e-12)).abs() < 1e-6);
        assert!((c.strain[1] - 0.01).abs() < 1e-15);
        assert!(StressStrainCurve::from_force(&[0.0], &[0.0], 0.01, 0.0).is_err());
        assert!(StressStrainCurve::from_force(&[0.0], &[0.0], 0.01, -1e-6).is_err());
    }
}
