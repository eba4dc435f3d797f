//! Simulation figures: spring-block friction force against time and the
//! static μ against pressure beside the measured Coulomb fits (the
//! thesis's Fig. 4.10; MODELS.md §7); ALSFM μ over the sliding path and
//! the adhesion R_xy against load (MODELS.md §5).

use std::collections::BTreeMap;

use super::{num, Figure};
use crate::plot::{Axis, Band, Chart, Colour, Style};
use crate::simulate::alsfm::rows::{AdhesionRow, SeriesRow};
use crate::simulate::spring_block::compare::CompareRow;
use crate::simulate::spring_block::output::{SummaryRow, SweepTables};

/// Distinct values in first-seen order.
fn distinct<'a>(v: impl Iterator<Item = &'a String>) -> Vec<&'a String> {
    let mut out: Vec<&String> = Vec::new();
    for s in v {
        if !out.contains(&s) {
            out.push(s);
        }
    }
    out
}

/// T(t) of the first run at each pattern and pressure; μ_s(p) with the
/// measured μ where the study has a comparison. Drawn for the report's
/// section of `model`.
pub fn spring_block(
    model: &str,
    sweep: &SweepTables,
    compare: Option<&[CompareRow]>,
) -> Vec<Figure> {
    let mut out = Vec::new();
    let curves: Vec<_> = sweep
        .curve_runs
        .iter()
        .filter(|c| !c.points.is_empty())
        .collect();
    let first_run = curves.first().map(|c| c.run);
    for pat in distinct(curves.iter().map(|c| &c.pattern)) {
        let mut c = Chart::new(
            format!("Spring-block model, pattern {pat}: friction force"),
            Axis::linear("time [ms]"),
            Axis::linear("friction force [N]"),
        );
        let mut by_p: BTreeMap<u64, Vec<(f64, f64)>> = BTreeMap::new();
        for run in curves
            .iter()
            .filter(|r| &r.pattern == pat && Some(r.run) == first_run)
        {
            let points = run
                .points
                .iter()
                .map(|&(t, f)| (num(Some(t)), num(Some(f))));
            by_p.entry(num(Some(run.pressure)).to_bits())
                .or_default()
                .extend(points);
        }
        for (k, (bits, pts)) in by_p.iter().enumerate() {
            let xs: Vec<f64> = pts.iter().map(|p| p.0 * 1e3).collect();
            let ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
            let name = format!("p = {:.3} kPa", f64::from_bits(*bits) * 1e-3);
            c.line(name, &xs, &ys, Colour::cycle(k));
        }
        out.push(Figure::draw(model, pat, "force", &c));
    }
    out.push(Figure::draw(
        model,
        "",
        "static",
        &static_chart(&sweep.summary_rows, compare),
    ));
    out
}

fn static_chart(summary: &[SummaryRow], compare: Option<&[CompareRow]>) -> Chart {
    let mut c = Chart::new(
        "Spring-block model: static μ against pressure (simulated ± sd, measured ×)",
        Axis::linear("nominal pressure p [kPa]"),
        Axis::linear("static μ"),
    );
    let p = |r: &SummaryRow| num(Some(r.pressure));
    for (k, pat) in distinct(summary.iter().map(|r| &r.pattern))
        .iter()
        .enumerate()
    {
        let mut rows: Vec<&SummaryRow> = summary.iter().filter(|r| &&r.pattern == pat).collect();
        rows.sort_by(|a, b| p(a).total_cmp(&p(b)));
        let colour = Colour::cycle(k);
        let (mean, sd) = (
            |r: &SummaryRow| num(r.mu_static_mean),
            |r: &SummaryRow| num(r.mu_static_sd),
        );
        c.bands.push(Band {
            name: String::new(),
            points: rows
                .iter()
                .map(|r| (p(r) * 1e-3, mean(r) - sd(r), mean(r) + sd(r)))
                .collect(),
            colour,
        });
        c.push(
            format!("{pat} simulated"),
            rows.iter().map(|r| (p(r) * 1e-3, mean(r))).collect(),
            colour,
            Style::Line,
        );
        if let Some(cmp) = compare {
            let pts: Vec<(f64, f64)> = cmp
                .iter()
                .filter(|r| &&r.pattern == pat && r.regime == "static")
                .map(|r| (num(Some(r.pressure)) * 1e-3, num(r.meas)))
                .collect();
            if !pts.is_empty() {
                c.push(format!("{pat} measured"), pts, colour, Style::Crosses);
            }
        }
    }
    c
}

/// μ along the path per direction and load; R_xy against load. Drawn for
/// the report's section of `model`.
pub fn alsfm(model: &str, series: &[SeriesRow], adhesion: &[AdhesionRow]) -> Vec<Figure> {
    let mut out = Vec::new();
    if !series.is_empty() {
        let key = |r: &SeriesRow| (num(Some(r.beta_deg)).to_bits(), num(Some(r.load)).to_bits());
        let mut c = Chart::new(
            "ALSFM: μ along the sliding path",
            Axis::linear("distance [µm]"),
            Axis::linear("μ"),
        );
        let mut keys: Vec<(u64, u64)> = series.iter().map(key).collect();
        keys.dedup();
        keys.sort();
        keys.dedup();
        for (k, (b, l)) in keys.iter().enumerate().take(8) {
            let rows: Vec<&SeriesRow> = series.iter().filter(|r| key(r) == (*b, *l)).collect();
            let xs: Vec<f64> = rows.iter().map(|r| num(Some(r.distance_m)) * 1e6).collect();
            let ys: Vec<f64> = rows.iter().map(|r| num(r.mu)).collect();
            let name = format!("β = {}°, L = {}", f64::from_bits(*b), f64::from_bits(*l));
            c.line(name, &xs, &ys, Colour::cycle(k));
        }
        out.push(Figure::draw(model, "", "mu", &c));
    }
    if !adhesion.is_empty() {
        let beta = |r: &AdhesionRow| num(Some(r.beta_deg));
        let load = |r: &AdhesionRow| num(Some(r.load));
        let mut c = Chart::new(
            "ALSFM: adhesion R_xy against load",
            Axis::linear("load"),
            Axis::linear("R_xy [N]"),
        );
        let mut betas: Vec<u64> = adhesion.iter().map(|r| beta(r).to_bits()).collect();
        betas.sort();
        betas.dedup();
        for (k, b) in betas.iter().enumerate() {
            let mut rows: Vec<&AdhesionRow> = adhesion
                .iter()
                .filter(|r| beta(r).to_bits() == *b)
                .collect();
            rows.sort_by(|x, y| load(x).total_cmp(&load(y)));
            let pts = rows.iter().map(|r| (load(r), num(r.r_xy))).collect();
            c.push(
                format!("β = {}°", f64::from_bits(*b)),
                pts,
                Colour::cycle(k),
                Style::Line,
            );
        }
        out.push(Figure::draw(model, "", "adhesion", &c));
    }
    out
}
