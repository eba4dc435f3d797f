//! Fit figures: τ against p with the fitted Coulomb lines and their ±1
//! standard-error bands per group (Eq. 4.1, MODELS.md §2); μ(v) with the
//! Makkonen model at both ALSFM roughness bounds and the fitted a
//! (MODELS.md §6), misfits marked.

use std::collections::BTreeMap;

use super::{num, Figure};
use crate::fit::coulomb::table::GroupFit;
use crate::fit::ice::table::IceRow;
use crate::plot::{Axis, Band, Chart, Colour, Style};

/// τ–p points of a group's rows (those with a finite p and τ), Pa.
fn group_points(g: &GroupFit) -> Vec<(f64, f64)> {
    g.points
        .iter()
        .map(|p| {
            (
                p.normal_force_n / p.area_m2,
                p.tangential_force_n / p.area_m2,
            )
        })
        .filter(|(p, tau)| p.is_finite() && tau.is_finite())
        .collect()
}

/// One figure per grouping and regime of the Coulomb fits, drawn for the
/// report's section of `model`.
pub fn coulomb(model: &str, fits: &[GroupFit]) -> Vec<Figure> {
    let mut charts: BTreeMap<(String, String), Chart> = BTreeMap::new();
    for g in fits {
        let c = charts
            .entry((g.grouping.clone(), g.regime.to_string()))
            .or_insert_with(|| {
                Chart::new(
                    format!("Coulomb fits by {}, {} friction", g.grouping, g.regime),
                    Axis::linear("nominal pressure p [kPa]"),
                    Axis::linear("shear stress τ [kPa]"),
                )
            });
        let colour = Colour::cycle(c.series.len() / 2);
        let pts: Vec<(f64, f64)> = group_points(g)
            .into_iter()
            .map(|(p, t)| (p * 1e-3, t * 1e-3))
            .collect();
        let status = g.status();
        let doubt = status != "ok";
        let label = match doubt {
            true => format!("{} ({})", g.group, status),
            false => g.group.clone(),
        };
        let style = if doubt { Style::Crosses } else { Style::Dots };
        let (lo, hi) = crate::plot::downsample::range(&pts.iter().map(|p| p.0).collect::<Vec<_>>())
            .unwrap_or((0.0, 1.0));
        let fit = g.fit.as_ref().ok();
        let value =
            |get: fn(&crate::fit::coulomb::CoulombFit) -> Option<f64>| num(fit.and_then(get));
        let (mu, mu_se, tau0, tau0_se) = (
            value(|f| Some(f.mu)),
            value(|f| f.mu_se),
            value(|f| Some(f.tau0_pa)),
            value(|f| f.tau0_se_pa),
        );
        if mu.is_finite() && tau0.is_finite() {
            let line: Vec<(f64, f64)> = [0.0, hi]
                .iter()
                .map(|&p| (p, tau0 * 1e-3 + mu * p))
                .collect();
            let mean_p = (lo + hi) / 2.0;
            let mean_p = if pts.is_empty() {
                mean_p
            } else {
                pts.iter().map(|p| p.0).sum::<f64>() / pts.len() as f64
            };
            if mu_se.is_finite() && tau0_se.is_finite() {
                c.bands.push(band(
                    mu,
                    tau0 * 1e-3,
                    mu_se,
                    tau0_se * 1e-3,
                    mean_p,
                    hi,
                    colour,
                ));
            }
            c.push(
                "",
                line,
                colour,
                if doubt { Style::Dashed } else { Style::Line },
            );
        } else {
            c.push("", Vec::new(), colour, Style::Line);
        }
        c.push(label, pts, colour, style);
    }
    charts
        .into_iter()
        .map(|((g, r), c)| Figure::draw(model, &format!("{g}, {r}"), "fit", &c))
        .collect()
}

/// ±1 standard error of the fitted line: for least squares
/// cov(τ0, μ) = −p̄ se(μ)², so se(τ(p))² = se(τ0)² + (p² − 2 p p̄) se(μ)².
fn band(
    mu: f64,
    tau0: f64,
    mu_se: f64,
    tau0_se: f64,
    mean_p: f64,
    hi: f64,
    colour: Colour,
) -> Band {
    let points = (0..=40)
        .map(|k| {
            let p = hi * k as f64 / 40.0;
            let var = tau0_se * tau0_se + (p * p - 2.0 * p * mean_p) * mu_se * mu_se;
            let se = var.max(0.0).sqrt();
            let tau = tau0 + mu * p;
            (p, tau - se, tau + se)
        })
        .collect();
    Band {
        name: String::new(),
        points,
        colour,
    }
}

/// μ(v) per ice-fit group: measured points and the model at each bound,
/// drawn for the report's section of `model`.
pub fn ice(model: &str, rows: &[IceRow]) -> Vec<Figure> {
    let mut groups: Vec<&String> = rows
        .iter()
        .filter(|r| !r.points.is_empty())
        .map(|r| &r.group)
        .collect();
    groups.sort();
    groups.dedup();
    let mut out = Vec::new();
    for g in groups {
        let mut c = Chart::new(
            format!("Makkonen model, {g}"),
            Axis::log("sliding velocity [m/s]"),
            Axis::linear("μ"),
        );
        let mut first = true;
        for (k, b) in ["lower", "upper"].iter().enumerate() {
            let of_bound = |r: &&IceRow| &r.group == g && r.bound.name() == *b;
            let mut pts: Vec<(f64, f64, f64)> = rows
                .iter()
                .filter(of_bound)
                .flat_map(|r| &r.points)
                .map(|p| (num(Some(p.0)), num(Some(p.1)), num(Some(p.2))))
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|x, y| x.0.total_cmp(&y.0));
            if first {
                let measured = pts.iter().map(|p| (p.0, p.1)).collect();
                c.push("measured", measured, Colour::Black, Style::Dots);
                first = false;
            }
            let fit = rows.iter().find(of_bound);
            let bad = fit.and_then(|r| r.misfit).unwrap_or(false);
            let a_um = fit.map_or(f64::NAN, |r| num(r.a_m) * 1e6);
            let label = format!(
                "{b} bound, a = {a_um:.1} µm{}",
                if bad { " (misfit)" } else { "" }
            );
            let style = if bad { Style::Dashed } else { Style::Line };
            let colour = if bad { Colour::Red } else { Colour::cycle(k) };
            c.push(
                label,
                pts.iter().map(|p| (p.0, p.2)).collect(),
                colour,
                style,
            );
        }
        out.push(Figure::draw(model, g, "fit", &c));
    }
    out
}
