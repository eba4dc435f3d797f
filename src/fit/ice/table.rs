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
use std::rc::Rc;

use super::{fit_ice, IceFit, IceFitParams, IceObservation};
use crate::error::{Error, Result};
use crate::models::makkonen::Bound;
use crate::status::{Code, InputRow, Status};
use crate::table::{ColumnType, Table, TableBuilder};

/// Reads the input table: Parquet, or CSV with a header (see
/// [`crate::ingest::csv_table::read_table_file`]).
pub use crate::ingest::csv_table::read_table_file as read_table;

fn has(t: &Table, c: &str) -> bool {
    t.column_names().iter().any(|n| n == c)
}

fn text_col(t: &Table, c: &str) -> Result<Vec<Option<String>>> {
    Ok(match t.column_type(c) {
        Some(ColumnType::Str | ColumnType::Cat) => t.str(c)?,
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

/// The step table's columns the ice fit reads.
struct StepColumns {
    v: Vec<Option<f64>>,
    mu: Vec<Option<f64>>,
    temp: Vec<Option<f64>>,
    pin: Vec<Option<String>>,
    rdq_deg: Option<Vec<Option<f64>>>,
    bearing_m: Option<Vec<Option<f64>>>,
    /// Each row for people, with the warnings of its own status.
    inputs: Vec<InputRow>,
}

impl StepColumns {
    fn read(steps: &Table) -> Result<Self> {
        for c in ["velocity_m_per_s", "mu_mean", "temperature_C"] {
            if !has(steps, c) {
                return Err(Error::Config(format!(
                    "steps table has no column '{c}'; found {:?}",
                    steps.column_names()
                )));
            }
        }
        let optional = |c: &str| has(steps, c).then(|| steps.f64(c)).transpose();
        Ok(StepColumns {
            v: steps.f64("velocity_m_per_s")?,
            mu: steps.f64("mu_mean")?,
            temp: steps.f64("temperature_C")?,
            pin: if has(steps, "pin") {
                text_col(steps, "pin")?
            } else {
                vec![Some("1".into()); steps.height()]
            },
            rdq_deg: optional("Rdq_deg")?,
            bearing_m: optional("a_bearing_m")?,
            inputs: steps.input_rows()?,
        })
    }

    /// Row indices per (pin, temperature) in a stable order; rows without
    /// a finite temperature belong to no group.
    fn groups(&self) -> BTreeMap<(String, i64), Vec<usize>> {
        let mut groups: BTreeMap<(String, i64), Vec<usize>> = BTreeMap::new();
        for (i, t) in self.temp.iter().enumerate() {
            if let Some(t) = t.filter(|t| t.is_finite()) {
                let pin = self.pin[i].clone().unwrap_or_else(|| "<missing>".into());
                groups
                    .entry((pin, (t * 1e6).round() as i64))
                    .or_default()
                    .push(i);
            }
        }
        groups
    }

    /// One group's inputs: its observations, and φ and the bearing a from
    /// the step table's own columns or else the pin's roughness.
    fn group(&self, pin: &str, rows: &[usize], rough: &PinRoughness) -> Group {
        let first_of =
            |c: &Option<Vec<Option<f64>>>| c.as_ref().and_then(|c| rows.iter().find_map(|&i| c[i]));
        let t_c = self.temp[rows[0]].unwrap_or(f64::NAN);
        let obs: Vec<IceObservation> = rows
            .iter()
            .map(|&i| IceObservation {
                velocity_m_per_s: self.v[i].unwrap_or(f64::NAN),
                mu: self.mu[i].unwrap_or(f64::NAN),
            })
            .collect();
        let used = rows
            .iter()
            .zip(&obs)
            .filter(|(_, o)| o.usable())
            .map(|(&i, _)| self.inputs[i].clone())
            .collect();
        Group {
            key: format!("pin={pin},temperature_C={t_c}"),
            pin: pin.to_string(),
            t_c,
            phi_deg: first_of(&self.rdq_deg).or_else(|| rough.rdq_deg.get(pin).copied()),
            bearing_m: first_of(&self.bearing_m).or_else(|| rough.a_bearing_m.get(pin).copied()),
            obs,
            used,
        }
    }
}

/// One pin × temperature group, shared by the rows of both bounds.
struct Group {
    key: String,
    pin: String,
    t_c: f64,
    phi_deg: Option<f64>,
    bearing_m: Option<f64>,
    obs: Vec<IceObservation>,
    /// The usable observations' rows, with the warnings of their own.
    used: Vec<InputRow>,
}

impl Group {
    /// The observations the fit uses (positive finite velocity, finite μ),
    /// in input order.
    fn usable(&self) -> impl Iterator<Item = &IceObservation> {
        self.obs.iter().filter(|o| o.usable())
    }

    fn fit(&self, bound: Bound, p: &IceFitParams) -> Result<IceFit> {
        match self.phi_deg {
            None => Err(Error::Config(format!(
                "no Rdq_deg for pin '{}' (steps column or --roughness)",
                self.pin
            ))),
            Some(phi) => fit_ice(&self.obs, self.t_c, phi.to_radians(), bound, p),
        }
    }
}

/// The fit's cells of one `ice_fit` row: the result, or why there is none.
struct FitCells {
    a: Option<f64>,
    a_se: Option<f64>,
    rmse: Option<f64>,
    n: i64,
    status: Status,
    delta_t: Option<f64>,
    delta_t_se: Option<f64>,
    corr: Option<f64>,
    rel_rmse: Option<f64>,
    misfit: Option<bool>,
}

impl FitCells {
    fn of(res: &Result<IceFit>, usable: usize, misfit_tol: f64) -> Self {
        match res {
            Ok(f) => FitCells {
                a: Some(f.a_m),
                a_se: f.a_se_m,
                rmse: Some(f.rmse),
                n: f.n as i64,
                status: fit_status(f, misfit_tol),
                delta_t: Some(f.delta_t_k),
                delta_t_se: f.delta_t_se_k,
                corr: f.corr_a_delta_t,
                rel_rmse: Some(f.rel_rmse),
                misfit: Some(f.misfit),
            },
            Err(e) => FitCells {
                a: None,
                a_se: None,
                rmse: None,
                n: usable as i64,
                status: e.status(),
                delta_t: None,
                delta_t_se: None,
                corr: None,
                rel_rmse: None,
                misfit: None,
            },
        }
    }
}

/// The status of a fit: the solver's, and `misfit` when a converged fit
/// does not describe the data.
fn fit_status(f: &IceFit, misfit_tol: f64) -> Status {
    let mut s = f.status.status();
    if f.misfit && s.is_ok() {
        s.push(
            Code::Misfit,
            format!(
                "relative RMS residual {:.3} above misfit_tol = {misfit_tol}",
                f.rel_rmse
            ),
        );
    }
    s
}

/// The `ice_residuals` columns.
#[derive(Default)]
struct Residuals {
    group: Vec<String>,
    bound: Vec<String>,
    v: Vec<f64>,
    measured: Vec<f64>,
    model: Vec<f64>,
    residual: Vec<f64>,
}

impl Residuals {
    fn push(&mut self, g: &Group, bound: Bound, f: &IceFit) {
        for (k, ob) in g.usable().enumerate() {
            self.group.push(g.key.clone());
            self.bound.push(bound.name().to_string());
            self.v.push(ob.velocity_m_per_s);
            self.measured.push(ob.mu);
            self.model.push(f.mu_model[k]);
            self.residual.push(f.residuals[k]);
        }
    }

    fn table(self) -> Result<Table> {
        TableBuilder::new()
            .str("group", self.group.iter().map(Some))
            .str("bound", self.bound.iter().map(Some))
            .f64_values("velocity_m_per_s", self.v)
            .f64_values("mu_measured", self.measured)
            .f64_values("mu_model", self.model)
            .f64_values("residual", self.residual)
            .build()
    }
}

/// One fit of one group at one bound, typed: what the figures draw.
#[derive(Debug, Clone)]
pub struct IceRow {
    /// The group, `pin=…,temperature_C=…`.
    pub group: String,
    /// The roughness bound.
    pub bound: Bound,
    /// The fitted contact length a, m.
    pub a_m: Option<f64>,
    /// Whether the fit is flagged as a misfit.
    pub misfit: Option<bool>,
    /// Velocity (m/s), measured μ and model μ of each observation used.
    pub points: Vec<(f64, f64, f64)>,
}

/// The ice fits: the `ice_fit` and `ice_residuals` tables and their rows.
pub struct IceFits {
    /// `ice_fit`: one row per group and bound.
    pub fit: Table,
    /// `ice_residuals`: one row per observation used.
    pub residuals: Table,
    /// The fits, typed.
    pub rows: Vec<IceRow>,
}

/// Fits every pin × temperature group for both bounds (rows without a
/// temperature belong to no group). Returns the
/// `ice_fit` and `ice_residuals` tables.
pub fn ice_tables(steps: &Table, rough: &PinRoughness, p: &IceFitParams) -> Result<(Table, Table)> {
    ice_fits(steps, rough, p).map(|f| (f.fit, f.residuals))
}

/// As [`ice_tables`], with the fits typed.
pub fn ice_fits(steps: &Table, rough: &PinRoughness, p: &IceFitParams) -> Result<IceFits> {
    let cols = StepColumns::read(steps)?;
    let mut rows: Vec<(Rc<Group>, Bound, FitCells)> = Vec::new();
    let mut residuals = Residuals::default();
    let mut typed = Vec::new();
    for ((pin, _), idx) in &cols.groups() {
        let g = Rc::new(cols.group(pin, idx, rough));
        for bound in [Bound::Upper, Bound::Lower] {
            let res = g.fit(bound, p);
            let mut points = Vec::new();
            if let Ok(f) = &res {
                residuals.push(&g, bound, f);
                points = g
                    .usable()
                    .enumerate()
                    .map(|(k, o)| (o.velocity_m_per_s, o.mu, f.mu_model[k]))
                    .collect();
            }
            let mut cells = FitCells::of(&res, g.usable().count(), p.misfit_tol);
            if res.is_ok() {
                cells.status.inherit(&g.used);
            }
            typed.push(IceRow {
                group: g.key.clone(),
                bound,
                a_m: cells.a,
                misfit: cells.misfit,
                points,
            });
            rows.push((g.clone(), bound, cells));
        }
    }
    let thermal = if p.fit_delta_t {
        "fitted".to_string()
    } else {
        serde_json::to_string(&p.thermal).unwrap_or_default()
    };
    Ok(IceFits {
        fit: fit_table(&rows, &thermal)?,
        residuals: residuals.table()?,
        rows: typed,
    })
}

/// The `ice_fit` table, one row per group and bound.
fn fit_table(rows: &[(Rc<Group>, Bound, FitCells)], thermal: &str) -> Result<Table> {
    let g = |f: fn(&Group) -> Option<f64>| rows.iter().map(move |(g, _, _)| f(g));
    let c = |f: fn(&FitCells) -> Option<f64>| rows.iter().map(move |(_, _, c)| f(c));
    TableBuilder::new()
        .str("group", rows.iter().map(|(g, _, _)| Some(&g.key)))
        .str("bound", rows.iter().map(|(_, b, _)| Some(b.name())))
        .f64("a_m", c(|c| c.a))
        .f64("a_se_m", c(|c| c.a_se))
        .f64("rmse", c(|c| c.rmse))
        .i64("n", rows.iter().map(|(_, _, c)| Some(c.n)))
        .status(rows.iter().map(|(_, _, c)| &c.status))
        .str("pin", rows.iter().map(|(g, _, _)| Some(&g.pin)))
        .f64("temperature_C", g(|g| Some(g.t_c)))
        .f64("phi_deg", g(|g| g.phi_deg))
        .str("thermal", rows.iter().map(|_| Some(thermal)))
        .f64("delta_T_K", c(|c| c.delta_t))
        .f64("delta_T_se_K", c(|c| c.delta_t_se))
        .f64("corr_a_delta_T", c(|c| c.corr))
        .f64("rel_rmse", c(|c| c.rel_rmse))
        .bool("misfit", rows.iter().map(|(_, _, c)| c.misfit))
        .f64("a_bearing_m", g(|g| g.bearing_m))
        .i64(
            "n_excluded",
            rows.iter()
                .map(|(g, _, _)| Some((g.obs.len() - g.usable().count()) as i64)),
        )
        .build()
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
