//! The `film` stage (MODELS.md §11): the film parameter λ = h_min / σ of
//! each velocity step whose film thickness the friction stage estimated
//! (`friction_steps.film_min_m`, Hamrock–Dowson from the manifest's
//! lubricant and contact), with the composite roughness
//! σ = √(Rq₁² + Rq₂²) of the two bodies as the same run measured them: the
//! roughness table's rows of the step's `sample_id` without a pin (the
//! counterface) and of its `pin` (Rq of a profile, else Sq of a map; the
//! mean when a body has several rows). The table `film`, one row per step
//! with a film.
//!
//! ```toml
//! stages = ["friction", "roughness", "film"]
//! ```

use std::collections::BTreeMap;

use super::friction::tables::FRICTION_STEPS;
use super::roughness::ROUGHNESS;
use super::{
    settings, Consumes, Need, Output, PlanContext, Progress, Stage, StagePlan, TableInputs,
};
use crate::error::Result;
use crate::models::stribeck::film_parameter;
use crate::schema::{Show, TableDef};
use crate::status::{Code, Status};
use crate::table::{Table, TableBuilder};

/// The registry entry.
pub struct Film;

const NAME: &str = "film";

/// One row per velocity step with a film thickness.
pub static FILM: TableDef = TableDef::new(
    "film",
    include_str!("../../schemas/film.toml"),
    Show::PerFile(&[
        ("step", "step"),
        ("film_min_m", "h min"),
        ("composite_rq_m", "σ"),
        ("film_parameter", "λ"),
        ("status", "status"),
    ]),
);

static TABLES: &[&TableDef] = &[&FILM];

impl Stage for Film {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "film parameter lambda of each velocity step from the roughness the same run measured"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, _ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let _: FilmSettings = settings(NAME, table)?;
        Ok(Box::new(FilmPlan))
    }
}

/// The stage has no settings: any key in `[film]` is a mistake.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct FilmSettings {}

struct FilmPlan;

/// The mean Rq (else Sq) of the roughness rows, by the body they measured:
/// (counterfaces by sample_id, pins by pin).
type Bodies = (BTreeMap<String, f64>, BTreeMap<String, f64>);

fn bodies(t: &Table) -> Result<Bodies> {
    let (sample, pin) = (t.str("sample_id")?, t.str("pin")?);
    let (rq, sq) = (t.f64("Rq_m")?, t.f64("Sq_m")?);
    let mut acc: [BTreeMap<String, (f64, usize)>; 2] = Default::default();
    for i in 0..t.height() {
        let Some(v) = rq[i].or(sq[i]).filter(|v| v.is_finite()) else {
            continue;
        };
        let (body, key) = match (&pin[i], &sample[i]) {
            (Some(p), _) => (1, p),
            (None, Some(s)) => (0, s),
            (None, None) => continue,
        };
        let e = acc[body].entry(key.clone()).or_insert((0.0, 0));
        (e.0, e.1) = (e.0 + v, e.1 + 1);
    }
    let mean = |m: &BTreeMap<String, (f64, usize)>| {
        m.iter()
            .map(|(k, (s, n))| (k.clone(), s / *n as f64))
            .collect::<BTreeMap<_, _>>()
    };
    Ok((mean(&acc[0]), mean(&acc[1])))
}

/// σ and λ of one step, with its status.
fn lambda(
    film: f64,
    counterface: Option<f64>,
    pin: Option<f64>,
) -> (Option<f64>, Option<f64>, Status) {
    let sigma = match (counterface, pin) {
        (None, None) => {
            let why = "neither body's roughness is in the roughness table (rows of the step's \
                       sample_id without a pin, or of its pin)";
            return (None, None, Status::of(Code::ParameterUndefined, why));
        }
        (a, b) => (a.unwrap_or(0.0).powi(2) + b.unwrap_or(0.0).powi(2)).sqrt(),
    };
    let mut status = Status::ok();
    if counterface.is_none() || pin.is_none() {
        let missing = if pin.is_none() { "pin" } else { "counterface" };
        status.push(
            Code::PartialRoughness,
            format!("the {missing} is not measured: σ is the other body's Rq alone, so λ is an upper bound"),
        );
    }
    (Some(sigma), film_parameter(film, sigma), status)
}

impl StagePlan for FilmPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Tables(vec![
            Need::required(&FRICTION_STEPS),
            Need::required(&ROUGHNESS),
        ])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        vec![&FILM]
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({})
    }
    fn references(&self) -> Vec<String> {
        vec!["MODELS.md §11 (film parameter)".into()]
    }
    fn run_tables(&self, inputs: &TableInputs, _progress: &dyn Progress) -> Result<Output> {
        let steps = inputs.required(&FRICTION_STEPS)?;
        let (faces, pins) = bodies(inputs.required(&ROUGHNESS)?)?;
        let film = steps.f64("film_min_m")?;
        let (sample, pin) = (steps.str("sample_id")?, steps.str("pin")?);
        let keep: Vec<usize> = (0..steps.height()).filter(|&i| film[i].is_some()).collect();
        let mut rows = Vec::new();
        for &i in &keep {
            let c = sample[i].as_ref().and_then(|s| faces.get(s)).copied();
            let p = pin[i].as_ref().and_then(|s| pins.get(s)).copied();
            let (sigma, l, status) = lambda(film[i].unwrap_or(f64::NAN), c, p);
            rows.push((c, p, sigma, l, status));
        }
        let pick = |c: &str| -> Result<Vec<Option<String>>> {
            let v = steps.str(c)?;
            Ok(keep.iter().map(|&i| v[i].clone()).collect())
        };
        let step = steps.i64("step")?;
        let v = steps.f64("velocity_m_per_s")?;
        let table = TableBuilder::new()
            .str("source", pick("source")?)
            .str("section", pick("section")?)
            .i64("step", keep.iter().map(|&i| step[i]))
            .str("sample_id", pick("sample_id")?)
            .str("pin", pick("pin")?)
            .f64("velocity_m_per_s", keep.iter().map(|&i| v[i]))
            .f64("film_min_m", keep.iter().map(|&i| film[i]))
            .f64("rq_counterface_m", rows.iter().map(|r| r.0))
            .f64("rq_pin_m", rows.iter().map(|r| r.1))
            .f64("composite_rq_m", rows.iter().map(|r| r.2))
            .f64("film_parameter", rows.iter().map(|r| r.3))
            .status(rows.iter().map(|r| &r.4))
            .build()?;
        let mut out = Output::new(vec![(&FILM, table)]);
        out.without_result = rows.iter().filter(|r| r.3.is_none()).count();
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// λ = h / √(Rq₁² + Rq₂²): 60 nm over 30 and 40 nm is 1.2; one body
    /// measured gives an upper bound that says so; none, no λ.
    #[test]
    fn lambda_over_the_composite_roughness() {
        let (s, l, st) = lambda(60e-9, Some(30e-9), Some(40e-9));
        assert!((s.unwrap() - 50e-9).abs() < 1e-22);
        assert!((l.unwrap() - 1.2).abs() < 1e-12 && st.is_ok());
        let (s, l, st) = lambda(60e-9, Some(30e-9), None);
        assert!((s.unwrap() - 30e-9).abs() < 1e-22 && (l.unwrap() - 2.0).abs() < 1e-12);
        assert!(st.to_string().starts_with("partial_roughness"), "{st}");
        let (s, l, st) = lambda(60e-9, None, None);
        assert!(s.is_none() && l.is_none());
        assert!(st.to_string().starts_with("parameter_undefined"));
    }
}
