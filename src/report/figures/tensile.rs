//! Tensile figures (MODELS.md §3): the stress–strain curve with the
//! strength (or the maximum stress of a record without fracture), the
//! 0.2 % offset yield, the break, the knot release strain ε* and the window
//! of the friction stress (0 … 0.4 ε_f, Eq. 5.3's plateau mean).

use super::{num, Figure};
use crate::extract::tensile::FibreRecord;
use crate::plot::{Axis, Chart, Colour, Style};

/// Pa as MPa.
fn mpa(pa: Option<f64>) -> f64 {
    num(pa.map(|v| v * 1e-6))
}

/// The curve's figure; `record` is the file's analysed fibre.
pub fn figures(
    source: &str,
    strain: &[f64],
    stress_pa: &[f64],
    record: &FibreRecord,
) -> Vec<Figure> {
    let name = super::file_name(source);
    let mut c = Chart::new(
        format!("{name}: stress–strain"),
        Axis::linear("strain"),
        Axis::linear("stress [MPa]"),
    );
    let (f, g) = (&record.features, &record.features.general);
    let (eps_f, eps_star) = (num(f.strain_at_break), num(f.release_strain));
    let friction = mpa(f.friction_stress_pa);
    if eps_f.is_finite() && friction.is_finite() {
        c.span("friction-stress window", (0.0, 0.4 * eps_f), Colour::Blue);
        let level = vec![(0.0, friction), (0.4 * eps_f, friction)];
        c.push("friction stress", level, Colour::Blue, Style::Dashed);
    }
    if eps_star.is_finite() {
        c.span("knot release ε*", (eps_star, eps_star), Colour::Purple);
    }
    if eps_f.is_finite() {
        c.span("break ε_f", (eps_f, eps_f), Colour::Red);
    }
    let stress_mpa: Vec<f64> = stress_pa.iter().map(|s| s * 1e-6).collect();
    c.line("σ(ε)", strain, &stress_mpa, Colour::Black);
    let modulus = num(f.modulus_pa.map(|m| m * 1e-9));
    let peak = (num(f.strain_at_strength), mpa(f.strength_pa));
    let label = match modulus.is_finite() {
        true => format!("strength (E = {modulus:.3} GPa)"),
        false => "strength".into(),
    };
    c.push(label, vec![peak], Colour::Red, Style::Crosses);
    let max = (num(g.strain_at_max_stress), mpa(g.max_stress_pa));
    if !peak.1.is_finite() && max.1.is_finite() {
        c.push(
            "maximum stress (no fracture)",
            vec![max],
            Colour::Red,
            Style::Dots,
        );
    }
    let yield_point = (num(g.yield_strain), mpa(g.yield_stress_pa));
    if yield_point.1.is_finite() {
        c.push(
            "0.2 % offset yield",
            vec![yield_point],
            Colour::Purple,
            Style::Crosses,
        );
    }
    vec![Figure::draw(source, "", "curve", &c)]
}
