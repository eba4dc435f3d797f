//! Ice fits over a stepped-velocity table: one group per pin ×
//! temperature, both bounds, as the tables `ice_fit` and `ice_residuals`.
//!
//! Input columns (`friction_steps` table, Parquet or CSV with a header):
//! `velocity_m_per_s`, `mu_mean`, `temperature_C`, and optionally `pin`
//! (else one pin), `Rdq_deg` (the pin's slope) and `a_bearing_m` (the
//! bearing-curve estimate of a). When `Rdq_deg` is absent it is taken from
//! a roughness table (`pin`, `Rdq_deg`; mean over the pin's rows).

use std::collections::BTreeMap;
use std::path::Path;

use super::{fit_ice, IceFitParams, IceObservation};
use crate::error::{Error, Location, Result};
use crate::models::makkonen::Bound;
use crate::table::{ColumnType, Table, TableBuilder};

/// Reads a table from Parquet, or from CSV when the extension is `.csv`
/// (columns whose every non-empty cell parses as a number become f64).
pub fn read_table(path: &Path) -> Result<Table> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
    {
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
        let mut lines = text.lines().filter(|l| !l.trim().is_empty());
        let split = |l: &str| -> Vec<String> {
            l.split(',')
                .map(|c| c.trim().trim_matches('"').to_string())
                .collect()
        };
        let header = split(
            lines
                .next()
                .ok_or_else(|| Error::input(Location::file(path), "empty CSV"))?,
        );
        let mut cols: Vec<Vec<String>> = vec![vec![]; header.len()];
        for (i, l) in lines.enumerate() {
            let c = split(l);
            if c.len() != header.len() {
                return Err(Error::input(
                    Location::line(path, i + 2),
                    format!("{} cells, header has {}", c.len(), header.len()),
                ));
            }
            for (k, v) in c.into_iter().enumerate() {
                cols[k].push(v);
            }
        }
        let mut b = TableBuilder::new();
        for (name, c) in header.iter().zip(cols) {
            let nums: Option<Vec<Option<f64>>> = c
                .iter()
                .map(|s| {
                    if s.is_empty() {
                        Some(None)
                    } else {
                        s.parse::<f64>().ok().map(Some)
                    }
                })
                .collect();
            b = match nums {
                Some(v) => b.f64(name, v),
                None => b.str(name, c.iter().map(|s| (!s.is_empty()).then_some(s))),
            };
        }
        b.build()
    } else {
        Ok(Table::read_parquet(path)?.0)
    }
}

fn has(t: &Table, c: &str) -> bool {
    t.column_names().iter().any(|n| n == c)
}

fn text_col(t: &Table, c: &str) -> Result<Vec<Option<String>>> {
    Ok(match t.column_type(c) {
        Some(ColumnType::Str) => t.str(c)?,
        _ => t
            .f64(c)?
            .into_iter()
            .map(|v| v.map(|v| v.to_string()))
            .collect(),
    })
}

/// Mean `Rdq_deg` per pin of a roughness table.
pub fn rdq_by_pin(roughness: &Table) -> Result<BTreeMap<String, f64>> {
    if !has(roughness, "pin") || !has(roughness, "Rdq_deg") {
        return Err(Error::Config(format!(
            "roughness table needs columns 'pin' and 'Rdq_deg'; found {:?}",
            roughness.column_names()
        )));
    }
    let pins = text_col(roughness, "pin")?;
    let rdq = roughness.f64("Rdq_deg")?;
    let mut acc: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for (p, r) in pins.into_iter().zip(rdq) {
        if let (Some(p), Some(r)) = (p, r) {
            let e = acc.entry(p).or_insert((0.0, 0));
            e.0 += r;
            e.1 += 1;
        }
    }
    Ok(acc
        .into_iter()
        .map(|(k, (s, n))| (k, s / n as f64))
        .collect())
}

#[derive(Default)]
struct Out {
    group: Vec<String>,
    bound: Vec<String>,
    a: Vec<Option<f64>>,
    a_se: Vec<Option<f64>>,
    rmse: Vec<Option<f64>>,
    n: Vec<i64>,
    status: Vec<String>,
    pin: Vec<String>,
    temp: Vec<f64>,
    phi: Vec<Option<f64>>,
    thermal: Vec<String>,
    dt: Vec<Option<f64>>,
    dt_se: Vec<Option<f64>>,
    corr: Vec<Option<f64>>,
    rel: Vec<Option<f64>>,
    misfit: Vec<Option<bool>>,
    bearing: Vec<Option<f64>>,
    n_excluded: Vec<i64>,
    message: Vec<Option<String>>,
}

/// Fits every pin × temperature group for both bounds (rows without a
/// temperature belong to no group). Returns the
/// `ice_fit` and `ice_residuals` tables.
pub fn ice_tables(
    steps: &Table,
    rdq: &BTreeMap<String, f64>,
    p: &IceFitParams,
) -> Result<(Table, Table)> {
    for c in ["velocity_m_per_s", "mu_mean", "temperature_C"] {
        if !has(steps, c) {
            return Err(Error::Config(format!(
                "steps table has no column '{c}'; found {:?}",
                steps.column_names()
            )));
        }
    }
    let v = steps.f64("velocity_m_per_s")?;
    let mu = steps.f64("mu_mean")?;
    let temp = steps.f64("temperature_C")?;
    let pin = if has(steps, "pin") {
        text_col(steps, "pin")?
    } else {
        vec![Some("1".into()); steps.height()]
    };
    let rdq_col = if has(steps, "Rdq_deg") {
        Some(steps.f64("Rdq_deg")?)
    } else {
        None
    };
    let bearing_col = if has(steps, "a_bearing_m") {
        Some(steps.f64("a_bearing_m")?)
    } else {
        None
    };
    // Group key: (pin, temperature bits) in a stable order.
    let mut groups: BTreeMap<(String, i64), Vec<usize>> = BTreeMap::new();
    for i in 0..steps.height() {
        match temp[i] {
            Some(t) if t.is_finite() => groups
                .entry((
                    pin[i].clone().unwrap_or_else(|| "<missing>".into()),
                    (t * 1e6).round() as i64,
                ))
                .or_default()
                .push(i),
            _ => {}
        }
    }
    let mut o = Out::default();
    let (mut rg, mut rb, mut rv, mut rm, mut rmod, mut rres) =
        (vec![], vec![], vec![], vec![], vec![], vec![]);
    let thermal = if p.fit_delta_t {
        "fitted".to_string()
    } else {
        serde_json::to_string(&p.thermal).unwrap_or_default()
    };
    for ((pin_name, _), rows) in &groups {
        let t_c = temp[rows[0]].unwrap_or(f64::NAN);
        let key = format!("pin={pin_name},temperature_C={t_c}");
        let phi_deg = rdq_col
            .as_ref()
            .and_then(|c| rows.iter().find_map(|&i| c[i]))
            .or_else(|| rdq.get(pin_name).copied());
        let bearing = bearing_col
            .as_ref()
            .and_then(|c| rows.iter().find_map(|&i| c[i]));
        let obs: Vec<IceObservation> = rows
            .iter()
            .map(|&i| IceObservation {
                velocity_m_per_s: v[i].unwrap_or(f64::NAN),
                mu: mu[i].unwrap_or(f64::NAN),
            })
            .collect();
        let usable = obs
            .iter()
            .filter(|o| {
                o.velocity_m_per_s.is_finite() && o.velocity_m_per_s > 0.0 && o.mu.is_finite()
            })
            .count();
        for bound in [Bound::Upper, Bound::Lower] {
            o.group.push(key.clone());
            o.bound.push(bound.name().into());
            o.pin.push(pin_name.clone());
            o.temp.push(t_c);
            o.phi.push(phi_deg);
            o.thermal.push(thermal.clone());
            o.bearing.push(bearing);
            o.n_excluded.push((obs.len() - usable) as i64);
            let res = match phi_deg {
                None => Err(Error::Config(format!(
                    "no Rdq_deg for pin '{pin_name}' (steps column or --roughness)"
                ))),
                Some(phi) => fit_ice(&obs, t_c, phi.to_radians(), bound, p),
            };
            match res {
                Ok(f) => {
                    o.a.push(Some(f.a_m));
                    o.a_se.push(f.a_se_m);
                    o.rmse.push(Some(f.rmse));
                    o.n.push(f.n as i64);
                    o.status.push(if f.status.is_converged() {
                        "converged".into()
                    } else {
                        f.status.label().into()
                    });
                    o.dt.push(Some(f.delta_t_k));
                    o.dt_se.push(f.delta_t_se_k);
                    o.corr.push(f.corr_a_delta_t);
                    o.rel.push(Some(f.rel_rmse));
                    o.misfit.push(Some(f.misfit));
                    o.message
                        .push((!f.status.is_converged()).then(|| f.status.to_string()));
                    let used = obs.iter().filter(|o| {
                        o.velocity_m_per_s.is_finite()
                            && o.velocity_m_per_s > 0.0
                            && o.mu.is_finite()
                    });
                    for (k, ob) in used.enumerate() {
                        rg.push(key.clone());
                        rb.push(bound.name().to_string());
                        rv.push(ob.velocity_m_per_s);
                        rm.push(ob.mu);
                        rmod.push(f.mu_model[k]);
                        rres.push(f.residuals[k]);
                    }
                }
                Err(e) => {
                    o.a.push(None);
                    o.a_se.push(None);
                    o.rmse.push(None);
                    o.n.push(usable as i64);
                    o.status.push(if e.is_bad_input() {
                        "bad_input".into()
                    } else {
                        "not_applicable".into()
                    });
                    o.dt.push(None);
                    o.dt_se.push(None);
                    o.corr.push(None);
                    o.rel.push(None);
                    o.misfit.push(None);
                    o.message.push(Some(e.to_string()));
                }
            }
        }
    }
    let fit = TableBuilder::new()
        .str("group", o.group.iter().map(Some))
        .str("bound", o.bound.iter().map(Some))
        .f64("a_m", o.a)
        .f64("a_se_m", o.a_se)
        .f64("rmse", o.rmse)
        .i64("n", o.n.iter().map(|v| Some(*v)))
        .str("status", o.status.iter().map(Some))
        .str("pin", o.pin.iter().map(Some))
        .f64_values("temperature_C", o.temp)
        .f64("phi_deg", o.phi)
        .str("thermal", o.thermal.iter().map(Some))
        .f64("delta_T_K", o.dt)
        .f64("delta_T_se_K", o.dt_se)
        .f64("corr_a_delta_T", o.corr)
        .f64("rel_rmse", o.rel)
        .bool("misfit", o.misfit)
        .f64("a_bearing_m", o.bearing)
        .i64("n_excluded", o.n_excluded.iter().map(|v| Some(*v)))
        .str("message", o.message)
        .build()?;
    let residuals = TableBuilder::new()
        .str("group", rg.iter().map(Some))
        .str("bound", rb.iter().map(Some))
        .f64_values("velocity_m_per_s", rv)
        .f64_values("mu_measured", rm)
        .f64_values("mu_model", rmod)
        .f64_values("residual", rres)
        .build()?;
    Ok((fit, residuals))
}
