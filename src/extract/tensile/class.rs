//! Material classes: which modulus window, break definition and strain
//! bound a specimen is analysed with (MODELS.md §9: "E is the slope on a
//! stated strain or stress window (state it; instruments differ)").
//!
//! | class | modulus window | strain at break | yield | strain bound |
//! |---|---|---|---|---|
//! | `fibre` | steepest sliding window of `modulus_window` · ε_m (thesis Ch. 5) | thesis: last point before the final drop | unknotted | 5 |
//! | `plastic` | ISO 527-1 §10.3: regression over ε = 0.0005 … 0.0025 of the first loading | ISO 527-1: last recorded point before σ ≤ `break_level` · σ_m | yes | 20 |
//! | `metal` | regression over 10–40 % of σ_m on the first loading (the elastic part of a metal curve lies below about half its strength) | as plastic (ISO 6892-1 A_t at fracture) | yes | 1 |
//! | `elastomer` | secant at 100 % elongation, σ(ε = 1) / 1 (the "M100" of rubber data sheets; ASTM D412 stress at 100 % elongation) | as plastic | no | 20 |
//! | `brittle` | ASTM C469 chord: from the stress at ε = 50 · 10⁻⁶ to 40 % of σ_m | as plastic | no | 0.05 |
//! | none | as `fibre` (tribo's default), with the status `default_modulus_window` | as `fibre` | yes | 20 |
//!
//! The strain bounds are what no specimen of the class reaches in a test
//! to fracture (metals: superplastic forming excepted; concrete and
//! ceramics break below 1 %): a strain beyond it is a unit or channel
//! error, reported as `impossible_value`.

use std::fmt;

/// A material class, as a manifest's `material_class` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MaterialClass {
    /// Single fibres (silk, yarn): the thesis's protocol.
    Fibre,
    /// Thermoplastics, thermosets and films (ISO 527).
    Plastic,
    /// Metals (ISO 6892-1, ASTM E8).
    Metal,
    /// Rubbers and silicones (ISO 37, ASTM D412).
    Elastomer,
    /// Concrete, rock, ceramics, glass (ASTM C469 for the modulus).
    Brittle,
}

/// How the modulus is taken for a class ([`MaterialClass::window`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Window {
    /// The steepest least-squares slope over sliding strain windows of
    /// `modulus_window` · ε_m (thesis Ch. 5, [`super::modulus`]).
    MaxSlope,
    /// Least-squares slope over the first loading between two strains.
    Strain(f64, f64),
    /// Least-squares slope over the first loading between two fractions of
    /// the maximum stress.
    StressFraction(f64, f64),
    /// σ(ε) / ε at one strain (secant from the origin).
    Secant(f64),
    /// Chord from the stress at a strain to a fraction of the maximum
    /// stress (ASTM C469).
    Chord(f64, f64),
}

impl MaterialClass {
    /// Every class, for documentation and messages.
    pub const ALL: [MaterialClass; 5] = [
        MaterialClass::Fibre,
        MaterialClass::Plastic,
        MaterialClass::Metal,
        MaterialClass::Elastomer,
        MaterialClass::Brittle,
    ];

    /// Parses a manifest value: the class names and a few common words
    /// (`polymer`, `steel`, `rubber`, `concrete`, `ceramic`, `silk`),
    /// case-insensitive. `None` for anything else.
    pub fn parse(text: &str) -> Option<MaterialClass> {
        Some(match text.trim().to_ascii_lowercase().as_str() {
            "fibre" | "fiber" | "silk" | "yarn" => MaterialClass::Fibre,
            "plastic" | "polymer" | "thermoplastic" | "film" => MaterialClass::Plastic,
            "metal" | "metallic" | "steel" | "alloy" => MaterialClass::Metal,
            "elastomer" | "rubber" | "silicone" => MaterialClass::Elastomer,
            "brittle" | "concrete" | "ceramic" | "rock" | "glass" => MaterialClass::Brittle,
            _ => return None,
        })
    }

    /// The canonical name written in tables.
    pub fn name(self) -> &'static str {
        match self {
            MaterialClass::Fibre => "fibre",
            MaterialClass::Plastic => "plastic",
            MaterialClass::Metal => "metal",
            MaterialClass::Elastomer => "elastomer",
            MaterialClass::Brittle => "brittle",
        }
    }

    /// The modulus window of the class (module table).
    pub fn window(self) -> Window {
        match self {
            MaterialClass::Fibre => Window::MaxSlope,
            MaterialClass::Plastic => Window::Strain(0.0005, 0.0025),
            MaterialClass::Metal => Window::StressFraction(0.1, 0.4),
            MaterialClass::Elastomer => Window::Secant(1.0),
            MaterialClass::Brittle => Window::Chord(50e-6, 0.4),
        }
    }

    /// Whether the strain at break is the thesis's (last point before the
    /// final drop) rather than ISO's (last recorded point before the
    /// stress falls to near zero).
    pub fn thesis_break(self) -> bool {
        self == MaterialClass::Fibre
    }

    /// Whether a yield point is defined: metals (ISO 6892-1), plastics
    /// (ISO 527-1, ASTM D638 offset yield) and fibres; not elastomers nor
    /// brittle materials.
    pub fn yields(self) -> bool {
        !matches!(self, MaterialClass::Elastomer | MaterialClass::Brittle)
    }

    /// The largest strain a specimen of the class reaches (module table).
    pub fn strain_bound(self) -> f64 {
        match self {
            MaterialClass::Fibre => 5.0,
            MaterialClass::Plastic | MaterialClass::Elastomer => 20.0,
            MaterialClass::Metal => 1.0,
            MaterialClass::Brittle => 0.05,
        }
    }
}

/// The strain bound without a class: no solid specimen stretches twenty
/// times its length in a tensile test.
pub const DEFAULT_STRAIN_BOUND: f64 = 20.0;

impl fmt::Display for MaterialClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The test's direction: tension, or compression (reported as magnitudes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Direction {
    /// The specimen is pulled.
    #[default]
    Tension,
    /// The specimen is pressed; stress and strain are given as magnitudes.
    Compression,
}

impl Direction {
    /// Parses a manifest value (`tension`, `compression`, `tensile`,
    /// `compressive`, `Zug`, `Druck`).
    pub fn parse(text: &str) -> Option<Direction> {
        match text.trim().to_ascii_lowercase().as_str() {
            "tension" | "tensile" | "zug" => Some(Direction::Tension),
            "compression" | "compressive" | "druck" => Some(Direction::Compression),
            _ => None,
        }
    }
    /// The name written in tables.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Tension => "tension",
            Direction::Compression => "compression",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_and_directions_round_trip() {
        for c in MaterialClass::ALL {
            assert_eq!(MaterialClass::parse(c.name()), Some(c));
        }
        assert_eq!(MaterialClass::parse(" Steel "), Some(MaterialClass::Metal));
        assert_eq!(MaterialClass::parse("wood"), None);
        assert_eq!(Direction::parse("Druck"), Some(Direction::Compression));
        assert_eq!(Direction::parse("x"), None);
    }
}
