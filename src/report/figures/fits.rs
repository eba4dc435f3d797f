//! Fit figures: τ against p with the fitted Coulomb lines and their ±1
//! standard-error bands per group (Eq. 4.1, MODELS.md §2); μ(v) with the
//! Makkonen model at both ALSFM roughness bounds and the fitted a
//! (MODELS.md §6), misfits marked.

use std::collections::BTreeMap;

use super::{numbers, texts, Figure};
use crate::plot::{Axis, Band, Chart, Colour, Style};
use crate::table::Table;

/// τ–p points of the friction rows in one Coulomb group (`k=v,k=v`).
fn group_points(friction: &Table, group: &str, regime: &str) -> Vec<(f64, f64)> {
    let force = if regime == "static" {
        "static_force_N"
    } else {
        "dynamic_force_N"
    };
    let (n, t, a) = (
        numbers(friction, "normal_force_N"),
        numbers(friction, force),
        numbers(friction, "apparent_area_m2"),
    );
    let keys: Vec<(&str, Vec<String>)> = group
        .split(',')
        .filter_map(|kv| kv.split_once('='))
        .map(|(k, v)| (v, texts(friction, k)))
        .collect();
    (0..n.len())
        .filter(|&i| {
            keys.iter()
                .all(|(v, col)| col.get(i).is_some_and(|c| c == v))
        })
        .map(|i| (n[i] / a[i], t[i] / a[i]))
        .filter(|(p, tau)| p.is_finite() && tau.is_finite())
        .collect()
}

/// One figure per grouping and regime of the `coulomb` table.
pub fn coulomb(friction: &Table, coulomb: &Table) -> Vec<Figure> {
    let (grouping, group, regime, status) = (
        texts(coulomb, "grouping"),
        texts(coulomb, "group"),
        texts(coulomb, "regime"),
        texts(coulomb, "status"),
    );
    let (mu, mu_se, tau0, tau0_se) = (
        numbers(coulomb, "mu"),
        numbers(coulomb, "mu_se"),
        numbers(coulomb, "tau0_Pa"),
        numbers(coulomb, "tau0_se_Pa"),
    );
    let mut charts: BTreeMap<(String, String), Chart> = BTreeMap::new();
    for i in 0..group.len() {
        let c = charts
            .entry((grouping[i].clone(), regime[i].clone()))
            .or_insert_with(|| {
                Chart::new(
                    format!("Coulomb fits by {}, {} friction", grouping[i], regime[i]),
                    Axis::linear("nominal pressure p [kPa]"),
                    Axis::linear("shear stress τ [kPa]"),
                )
            });
        let colour = Colour::cycle(c.series.len() / 2);
        let pts: Vec<(f64, f64)> = group_points(friction, &group[i], &regime[i])
            .into_iter()
            .map(|(p, t)| (p * 1e-3, t * 1e-3))
            .collect();
        let doubt = status[i] != "ok";
        let label = match doubt {
            true => format!("{} ({})", group[i], status[i]),
            false => group[i].clone(),
        };
        let style = if doubt { Style::Crosses } else { Style::Dots };
        let (lo, hi) = crate::plot::downsample::range(&pts.iter().map(|p| p.0).collect::<Vec<_>>())
            .unwrap_or((0.0, 1.0));
        if mu[i].is_finite() && tau0[i].is_finite() {
            let line: Vec<(f64, f64)> = [0.0, hi]
                .iter()
                .map(|&p| (p, tau0[i] * 1e-3 + mu[i] * p))
                .collect();
            let mean_p = (lo + hi) / 2.0;
            let mean_p = if pts.is_empty() {
                mean_p
            } else {
                pts.iter().map(|p| p.0).sum::<f64>() / pts.len() as f64
            };
            if mu_se[i].is_finite() && tau0_se[i].is_finite() {
                c.bands.push(band(
                    mu[i],
                    tau0[i] * 1e-3,
                    mu_se[i],
                    tau0_se[i] * 1e-3,
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
        .map(|((g, r), c)| Figure::draw("coulomb", &format!("{g}, {r}"), "fit", &c))
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

/// μ(v) per ice-fit group: measured points and the model at each bound.
pub fn ice(fit: &Table, residuals: &Table) -> Vec<Figure> {
    let (group, bound, v, measured, model) = (
        texts(residuals, "group"),
        texts(residuals, "bound"),
        numbers(residuals, "velocity_m_per_s"),
        numbers(residuals, "mu_measured"),
        numbers(residuals, "mu_model"),
    );
    let (fgroup, fbound, a, misfit) = (
        texts(fit, "group"),
        texts(fit, "bound"),
        numbers(fit, "a_m"),
        fit.bool("misfit").unwrap_or_default(),
    );
    let mut groups: Vec<&String> = group.iter().collect();
    groups.dedup();
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
            let mut idx: Vec<usize> = (0..group.len())
                .filter(|&i| &group[i] == g && bound[i] == *b)
                .collect();
            if idx.is_empty() {
                continue;
            }
            idx.sort_by(|&x, &y| v[x].total_cmp(&v[y]));
            if first {
                let pts = idx.iter().map(|&i| (v[i], measured[i])).collect();
                c.push("measured", pts, Colour::Black, Style::Dots);
                first = false;
            }
            let j = (0..fgroup.len()).find(|&j| &fgroup[j] == g && fbound[j] == *b);
            let bad = j
                .and_then(|j| misfit.get(j).copied().flatten())
                .unwrap_or(false);
            let a_um = j.map_or(f64::NAN, |j| a[j] * 1e6);
            let label = format!(
                "{b} bound, a = {a_um:.1} µm{}",
                if bad { " (misfit)" } else { "" }
            );
            let style = if bad { Style::Dashed } else { Style::Line };
            let colour = if bad { Colour::Red } else { Colour::cycle(k) };
            c.push(
                label,
                idx.iter().map(|&i| (v[i], model[i])).collect(),
                colour,
                style,
            );
        }
        out.push(Figure::draw("ice", g, "fit", &c));
    }
    out
}
