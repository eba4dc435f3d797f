//! Ice fits over a stepped-velocity table: one group per pin ×
//! temperature, both bounds, as the tables `ice_fit` and `ice_residuals`.
//!
//! Input columns (`friction_steps` table, Parquet or CSV with a header):
//! `velocity_m_per_s`, `mu_mean`, `temperature_C`, and optionally `pin`
//! (else one pin), `Rdq_deg` (the pin's slope) and `a_bearing_m` (the
//! bearing-curve estimate of a). When they are absent they come from a
//! roughness table (`pin`, `Rdq_deg`, optional `a_bearing_m`; mean over the
//! pin's rows), see [`PinRoughness`].

use std::collections::BTreeMap;

use super::{fit_ice, IceFitParams, IceObservation};
use crate::error::{Error, Result};
use crate::models::makkonen::Bound;
use crate::table::{ColumnType, Table, TableBuilder};

/// Reads the input table: Parquet, or CSV with a header (see
/// [`crate::ingest::csv_table::read_table_file`]).
pub use crate::ingest::csv_table::read_table_file as read_table;

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

/// Per-pin means of a roughness table column (`Rdq_deg`, `a_bearing_m`);
/// an empty map when the column is absent.
pub fn mean_by_pin(roughness: &Table, column: &str) -> Result<BTreeMap<String, f64>> {
    if !has(roughness, "pin") {
        return Err(Error::Config(format!(
            "roughness table needs a 'pin' column; found {:?}",
            roughness.column_names()
        )));
    }
    if !has(roughness, column) {
        return Ok(BTreeMap::new());
    }
    let pins = text_col(roughness, "pin")?;
    if pins.iter().all(Option::is_none) {
        return Err(Error::Config(
            "the roughness table's 'pin' column is empty: run the roughness stage with a \
             sample manifest (`samples` in the pipeline's [input]) that gives each profile \
             file its pin"
                .into(),
        ));
    }
    let vals = roughness.f64(column)?;
    let mut acc: BTreeMap<String, (f64, usize)> = BTreeMap::new();
    for (p, r) in pins.into_iter().zip(vals) {
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

/// Per-pin roughness inputs of the ice fit.
#[derive(Debug, Clone, Default)]
pub struct PinRoughness {
    /// Rdq (φ) per pin, degrees.
    pub rdq_deg: BTreeMap<String, f64>,
    /// Bearing-curve contact length per pin, m.
    pub a_bearing_m: BTreeMap<String, f64>,
}

impl PinRoughness {
    /// From a roughness table with `pin`, `Rdq_deg` and optionally
    /// `a_bearing_m` or `contact_length_m` (as `tribo roughness` writes it).
    pub fn from_table(t: &Table) -> Result<Self> {
        if !has(t, "Rdq_deg") {
            return Err(Error::Config(format!(
                "roughness table needs a 'Rdq_deg' column; found {:?}",
                t.column_names()
            )));
        }
        // `tribo roughness` writes the bearing-curve estimate as
        // `contact_length_m` (Eq. 3.14, 3.15).
        let bearing = if has(t, "a_bearing_m") {
            "a_bearing_m"
        } else {
            "contact_length_m"
        };
        // A pin measured only by areal maps has its Sdq (the roughness
        // table's S columns) in place of a profile's Rdq.
        let mut rdq_deg = mean_by_pin(t, "Rdq_deg")?;
        for (pin, sdq) in mean_by_pin(t, "Sdq_deg")? {
            rdq_deg.entry(pin).or_insert(sdq);
        }
        Ok(PinRoughness {
            rdq_deg,
            a_bearing_m: mean_by_pin(t, bearing)?,
        })
    }
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
pub fn ice_tables(steps: &Table, rough: &PinRoughness, p: &IceFitParams) -> Result<(Table, Table)> {
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
            .or_else(|| rough.rdq_deg.get(pin_name).copied());
        let bearing = bearing_col
            .as_ref()
            .and_then(|c| rows.iter().find_map(|&i| c[i]))
            .or_else(|| rough.a_bearing_m.get(pin_name).copied());
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

#[cfg(test)]
mod roughness_input_tests {
    use super::*;

    /// The contact length `tribo roughness` writes is read as the
    /// bearing-curve a, averaged per pin.
    #[test]
    fn contact_length_from_the_roughness_table_is_the_bearing_estimate() {
        let t = TableBuilder::new()
            .str("pin", [Some("1"), Some("1"), Some("2")])
            .f64("Rdq_deg", [Some(7.0), Some(7.6), Some(27.2)])
            .f64("contact_length_m", [Some(1e-4), Some(3e-4), None])
            .build()
            .unwrap();
        let r = PinRoughness::from_table(&t).unwrap();
        assert!((r.rdq_deg["1"] - 7.3).abs() < 1e-12);
        assert!((r.a_bearing_m["1"] - 2e-4).abs() < 1e-18);
        assert!(!r.a_bearing_m.contains_key("2"));
    }
}
