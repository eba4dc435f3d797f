//! Tensile figures (MODELS.md §3): the stress–strain curve with the
//! strength (or the maximum stress of a record without fracture), the
//! 0.2 % offset yield, the break, the knot release strain ε* and the window
//! of the friction stress (0 … 0.4 ε_f, Eq. 5.3's plateau mean).

use super::{numbers, Figure};
use crate::plot::{Axis, Chart, Colour, Style};
use crate::table::Table;

/// The curve's figure; `row` is the file's row of the `tensile` table.
pub fn figures(source: &str, strain: &[f64], stress_pa: &[f64], table: &Table) -> Vec<Figure> {
    let name = super::file_name(source);
    let mut c = Chart::new(
        format!("{name}: stress–strain"),
        Axis::linear("strain"),
        Axis::linear("stress [MPa]"),
    );
    let first = |col: &str| numbers(table, col).first().copied().unwrap_or(f64::NAN);
    let (eps_f, eps_star) = (first("strain_at_break"), first("release_strain"));
    let friction = first("friction_stress_MPa");
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
    let mpa: Vec<f64> = stress_pa.iter().map(|s| s * 1e-6).collect();
    c.line("σ(ε)", strain, &mpa, Colour::Black);
    let modulus = first("modulus_GPa");
    let peak = (first("strain_at_strength"), first("strength_MPa"));
    let label = match modulus.is_finite() {
        true => format!("strength (E = {modulus:.3} GPa)"),
        false => "strength".into(),
    };
    c.push(label, vec![peak], Colour::Red, Style::Crosses);
    let max = (first("strain_at_max_stress"), first("max_stress_MPa"));
    if !peak.1.is_finite() && max.1.is_finite() {
        c.push(
            "maximum stress (no fracture)",
            vec![max],
            Colour::Red,
            Style::Dots,
        );
    }
    let yield_point = (first("yield_strain"), first("yield_stress_MPa"));
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
