//! Wear volume and specific wear rate from a track cross-section
//! (MODELS.md §9).
//!
//! | quantity | formula | unit |
//! |---|---|---|
//! | track length L | pin-on-disc: 2π r (r the track radius); reciprocating: the stroke length | m |
//! | wear volume V | A · L | m³ |
//! | sliding distance s | given, or laps · L (pin-on-disc laps, or strokes · stroke length) | m |
//! | specific wear rate k | V / (F_N · s) | m³/(N·m); tables report mm³/(N·m) |
//! | Archard coefficient K | V · H / (F_N · s) = k · H (MODELS §11), H the hardness of the worn body | 1 |
//!
//! For a reciprocating test V = A · stroke neglects the track's rounded ends
//! (the usual convention; the ends add about one pin-contact width of
//! length). The cross-section is taken as the same all along the track.

use std::f64::consts::PI;

/// How the track length was obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrackLength {
    /// Pin-on-disc: circumference 2π r of the track radius r (m).
    Radius(f64),
    /// Linear reciprocating: the stroke length (m), ends neglected.
    Stroke(f64),
}

impl TrackLength {
    /// L (m).
    pub fn length(self) -> f64 {
        match self {
            TrackLength::Radius(r) => 2.0 * PI * r,
            TrackLength::Stroke(s) => s,
        }
    }
    /// `circumference` or `stroke`, for the table.
    pub fn source(self) -> &'static str {
        match self {
            TrackLength::Radius(_) => "circumference",
            TrackLength::Stroke(_) => "stroke",
        }
    }
}

/// V = A · L (m³) for a cross-section `area` (m²).
pub fn wear_volume(area: f64, track: TrackLength) -> f64 {
    area * track.length()
}

/// k = V / (F_N · s) in m³/(N·m); `None` unless F_N > 0 and s > 0.
pub fn specific_wear_rate(volume: f64, normal_force: f64, sliding_distance: f64) -> Option<f64> {
    (normal_force > 0.0 && sliding_distance > 0.0)
        .then(|| volume / (normal_force * sliding_distance))
}

/// Archard's dimensionless wear coefficient K = k · H (V = K F_N s / H,
/// MODELS §11) from the specific wear rate `k` (m³/(N·m)) and the hardness
/// `hardness` (Pa) of the worn body; `None` unless H > 0 and finite.
pub fn archard_coefficient(k: f64, hardness: f64) -> Option<f64> {
    (hardness.is_finite() && hardness > 0.0).then_some(k * hardness)
}

/// Pa per Vickers hardness number (kgf/mm² = 9.80665 N / 1e-6 m²).
pub const PA_PER_HV: f64 = 9.806_65e6;

/// m³/(N·m) to mm³/(N·m).
pub const MM3_PER_M3: f64 = 1e9;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn volume_and_rate_by_hand() {
        // A = 10 µm², r = 5 mm: V = 1e-11 · 2π · 5e-3 = π·1e-13 m³.
        let v = wear_volume(1e-11, TrackLength::Radius(5e-3));
        assert!((v / (PI * 1e-13) - 1.0).abs() < 1e-14);
        // 10 N over 100 m: k = π·1e-16 m³/(N·m) = π·1e-7 mm³/(N·m).
        let k = specific_wear_rate(v, 10.0, 100.0).unwrap();
        assert!((k * MM3_PER_M3 / (PI * 1e-7) - 1.0).abs() < 1e-14);
        assert!((wear_volume(2.0, TrackLength::Stroke(3.0)) - 6.0).abs() < 1e-15);
        assert!(specific_wear_rate(v, 0.0, 100.0).is_none());
        assert!(specific_wear_rate(v, 10.0, 0.0).is_none());
    }
}
