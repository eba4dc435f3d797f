//! Wear figures (MODELS.md §9): the profile across the track with the
//! track's edges and the worn area's figures in the title.

use super::{file_name, numbers, Figure};
use crate::extract::roughness::input::Surface;
use crate::plot::{Axis, Chart, Colour};
use crate::table::Table;

/// One figure per profile; `rows` are the file's rows of the `wear` table.
pub fn figures(source: &str, surfaces: &[Surface], rows: &Table) -> Vec<Figure> {
    let name = file_name(source);
    let at = |col: &str, k: usize| numbers(rows, col).get(k).copied().unwrap_or(f64::NAN);
    let mut out = Vec::new();
    for (k, s) in surfaces.iter().enumerate() {
        let Surface::Profile(p) = s else { continue };
        let (area, depth) = (at("area_m2", k), at("depth_m", k));
        let mut c = Chart::new(
            format!(
                "{name}: wear track, A = {:.4} µm², depth {:.3} µm",
                area * 1e12,
                depth * 1e6
            ),
            Axis::linear("x [mm]"),
            Axis::linear("height [µm]"),
        );
        let (l, r) = (at("edge_left_m", k) * 1e3, at("edge_right_m", k) * 1e3);
        if l.is_finite() && r.is_finite() {
            c.span("worn track (between the edges)", (l, r), Colour::Orange);
        }
        let x: Vec<f64> = (0..p.z.len()).map(|i| p.x(i) * 1e3).collect();
        let z: Vec<f64> = p.z.iter().map(|v| v * 1e6).collect();
        c.line("profile", &x, &z, Colour::Black);
        let part = if surfaces.len() > 1 {
            format!("{}", k + 1)
        } else {
            String::new()
        };
        out.push(Figure::draw(source, &part, "track", &c));
    }
    out
}
