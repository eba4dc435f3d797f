//! Wear figures (MODELS.md §9): the profile across the track with the
//! track's edges and the worn area's figures in the title.

use super::{file_name, num, Figure};
use crate::extract::roughness::input::Surface;
use crate::extract::wear::WearRow;
use crate::plot::{Axis, Chart, Colour};

/// One figure per profile; `rows` are the file's wear rows, one per
/// profile.
pub fn figures(source: &str, surfaces: &[Surface], rows: &[WearRow]) -> Vec<Figure> {
    let name = file_name(source);
    let mut out = Vec::new();
    for (k, s) in surfaces.iter().enumerate() {
        let Surface::Profile(p) = s else { continue };
        let row = rows.get(k).map(|r| &r.section);
        let at = |get: fn(&crate::extract::wear::track::TrackSection) -> f64| num(row.map(get));
        let (area, depth) = (at(|s| s.area), at(|s| s.depth));
        let mut c = Chart::new(
            format!(
                "{name}: wear track, A = {:.4} µm², depth {:.3} µm",
                area * 1e12,
                depth * 1e6
            ),
            Axis::linear("x [mm]"),
            Axis::linear("height [µm]"),
        );
        let (l, r) = (at(|s| s.edges.0) * 1e3, at(|s| s.edges.1) * 1e3);
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
