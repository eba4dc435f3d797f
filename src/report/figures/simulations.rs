//! Simulation figures: spring-block friction force against time and the
//! static μ against pressure beside the measured Coulomb fits (the
//! thesis's Fig. 4.10; MODELS.md §7); ALSFM μ over the sliding path and
//! the adhesion R_xy against load (MODELS.md §5).

use std::collections::BTreeMap;

use super::{numbers, texts, Figure};
use crate::plot::{Axis, Band, Chart, Colour, Style};
use crate::table::Table;

/// Distinct values in first-seen order.
fn distinct(v: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for s in v {
        if !out.contains(s) {
            out.push(s.clone());
        }
    }
    out
}

/// T(t) of the first run at each pattern and pressure; μ_s(p) with the
/// measured μ where the study has a comparison.
pub fn spring_block(
    curves: Option<&Table>,
    summary: Option<&Table>,
    compare: Option<&Table>,
) -> Vec<Figure> {
    let mut out = Vec::new();
    if let Some(t) = curves {
        let (pattern, p, run, time, force) = (
            texts(t, "pattern"),
            numbers(t, "pressure_Pa"),
            numbers(t, "run"),
            numbers(t, "time_s"),
            numbers(t, "friction_N"),
        );
        for pat in distinct(&pattern) {
            let mut c = Chart::new(
                format!("Spring-block model, pattern {pat}: friction force"),
                Axis::linear("time [ms]"),
                Axis::linear("friction force [N]"),
            );
            let mut by_p: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
            for i in (0..pattern.len())
                .filter(|&i| pattern[i] == pat && run[i].to_bits() == run[0].to_bits())
            {
                by_p.entry(p[i].to_bits()).or_default().push(i);
            }
            for (k, (bits, idx)) in by_p.iter().enumerate() {
                let xs: Vec<f64> = idx.iter().map(|&i| time[i] * 1e3).collect();
                let ys: Vec<f64> = idx.iter().map(|&i| force[i]).collect();
                let name = format!("p = {:.3} kPa", f64::from_bits(*bits) * 1e-3);
                c.line(name, &xs, &ys, Colour::cycle(k));
            }
            out.push(Figure::draw("spring-block", &pat, "force", &c));
        }
    }
    if let Some(s) = summary {
        out.push(Figure::draw(
            "spring-block",
            "",
            "static",
            &static_chart(s, compare),
        ));
    }
    out
}

fn static_chart(s: &Table, compare: Option<&Table>) -> Chart {
    let mut c = Chart::new(
        "Spring-block model: static μ against pressure (simulated ± sd, measured ×)",
        Axis::linear("nominal pressure p [kPa]"),
        Axis::linear("static μ"),
    );
    let (pattern, p, mean, sd) = (
        texts(s, "pattern"),
        numbers(s, "pressure_Pa"),
        numbers(s, "mu_static_mean"),
        numbers(s, "mu_static_sd"),
    );
    for (k, pat) in distinct(&pattern).iter().enumerate() {
        let mut idx: Vec<usize> = (0..p.len()).filter(|&i| &pattern[i] == pat).collect();
        idx.sort_by(|&a, &b| p[a].total_cmp(&p[b]));
        let colour = Colour::cycle(k);
        c.bands.push(Band {
            name: String::new(),
            points: idx
                .iter()
                .map(|&i| (p[i] * 1e-3, mean[i] - sd[i], mean[i] + sd[i]))
                .collect(),
            colour,
        });
        c.push(
            format!("{pat} simulated"),
            idx.iter().map(|&i| (p[i] * 1e-3, mean[i])).collect(),
            colour,
            Style::Line,
        );
        if let Some(cmp) = compare {
            let (cp, pp, mm, regime) = (
                texts(cmp, "pattern"),
                numbers(cmp, "pressure_Pa"),
                numbers(cmp, "mu_measured"),
                texts(cmp, "regime"),
            );
            let pts: Vec<(f64, f64)> = (0..cp.len())
                .filter(|&i| &cp[i] == pat && regime[i] == "static")
                .map(|i| (pp[i] * 1e-3, mm[i]))
                .collect();
            if !pts.is_empty() {
                c.push(format!("{pat} measured"), pts, colour, Style::Crosses);
            }
        }
    }
    c
}

/// μ along the path per direction and load; R_xy against load.
pub fn alsfm(series: Option<&Table>, adhesion: Option<&Table>) -> Vec<Figure> {
    let mut out = Vec::new();
    if let Some(t) = series {
        let (beta, load, d, mu) = (
            numbers(t, "beta_deg"),
            numbers(t, "load"),
            numbers(t, "distance_m"),
            numbers(t, "mu"),
        );
        let mut c = Chart::new(
            "ALSFM: μ along the sliding path",
            Axis::linear("distance [µm]"),
            Axis::linear("μ"),
        );
        let mut keys: Vec<(u64, u64)> = beta
            .iter()
            .zip(&load)
            .map(|(b, l)| (b.to_bits(), l.to_bits()))
            .collect();
        keys.dedup();
        keys.sort();
        keys.dedup();
        for (k, (b, l)) in keys.iter().enumerate().take(8) {
            let idx: Vec<usize> = (0..beta.len())
                .filter(|&i| beta[i].to_bits() == *b && load[i].to_bits() == *l)
                .collect();
            let xs: Vec<f64> = idx.iter().map(|&i| d[i] * 1e6).collect();
            let ys: Vec<f64> = idx.iter().map(|&i| mu[i]).collect();
            let name = format!("β = {}°, L = {}", f64::from_bits(*b), f64::from_bits(*l));
            c.line(name, &xs, &ys, Colour::cycle(k));
        }
        out.push(Figure::draw("alsfm", "", "mu", &c));
    }
    if let Some(t) = adhesion {
        let (beta, load, r) = (
            numbers(t, "beta_deg"),
            numbers(t, "load"),
            numbers(t, "r_xy_N"),
        );
        let mut c = Chart::new(
            "ALSFM: adhesion R_xy against load",
            Axis::linear("load"),
            Axis::linear("R_xy [N]"),
        );
        let mut betas: Vec<u64> = beta.iter().map(|b| b.to_bits()).collect();
        betas.sort();
        betas.dedup();
        for (k, b) in betas.iter().enumerate() {
            let mut idx: Vec<usize> = (0..beta.len())
                .filter(|&i| beta[i].to_bits() == *b)
                .collect();
            idx.sort_by(|&x, &y| load[x].total_cmp(&load[y]));
            let pts = idx.iter().map(|&i| (load[i], r[i])).collect();
            c.push(
                format!("β = {}°", f64::from_bits(*b)),
                pts,
                Colour::cycle(k),
                Style::Line,
            );
        }
        out.push(Figure::draw("alsfm", "", "adhesion", &c));
    }
    out
}
