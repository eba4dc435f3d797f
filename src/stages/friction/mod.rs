//! The `friction` stage (MODELS.md §1): for each friction trace, the SI
//! trace of every section and its features — static peak, dynamic
//! plateau, stick-slip, strokes, velocity steps — as the tables
//! `friction`, `friction_steps`, `stickslip` and `traces` ([`tables`]).
//!
//! ```toml
//! [friction]                      # every key optional (FrictionParams)
//! peak_noise_factor = 3.0
//! files = ["traces/*.csv"]        # optional: these files, whatever their kind
//! ```

pub mod analysis;
pub mod cycle_tables;
pub mod series;
pub mod tables;

use self::analysis::analyse_file;
use self::cycle_tables::{cycles_table, tests_table, FRICTION_CYCLES, FRICTION_TESTS};
use self::tables::{
    friction_table, steps_table, stickslip_table, traces_table, FRICTION, FRICTION_FIGURES,
    FRICTION_STEPS, STICKSLIP, TRACES,
};
use super::{settings, Consumes, FileInput, Output, PlanContext, Stage, StagePlan, Tables};
use crate::error::Result;
use crate::extract::friction::FrictionParams;
use crate::ingest::kind::DataKind;
use crate::report::figures;
use crate::schema::TableDef;

/// The registry entry.
pub struct Friction;

/// The stage's name in pipeline files.
const NAME: &str = "friction";

/// Every table of the stage.
static TABLES: &[&TableDef] = &[
    &FRICTION,
    &FRICTION_STEPS,
    &FRICTION_CYCLES,
    &FRICTION_TESTS,
    &STICKSLIP,
    &TRACES,
    &FRICTION_FIGURES,
];

impl Stage for Friction {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "static and dynamic friction, stick-slip, strokes and velocity steps of friction traces; cycles, running-in and steady state of each test"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let params: FrictionParams = settings(NAME, table)?;
        params.validate()?;
        Ok(Box::new(FrictionPlan {
            params,
            traces: ctx.traces,
            figures: ctx.figures,
        }))
    }
}

struct FrictionPlan {
    params: FrictionParams,
    traces: bool,
    figures: bool,
}

impl StagePlan for FrictionPlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::FrictionTrace])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        let mut defs: Vec<&'static TableDef> = vec![
            &FRICTION,
            &FRICTION_STEPS,
            &FRICTION_CYCLES,
            &FRICTION_TESTS,
            &STICKSLIP,
        ];
        if self.traces {
            defs.push(&TRACES);
        }
        if self.figures {
            defs.push(&FRICTION_FIGURES);
        }
        defs
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(&self.params).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        vec![
            "MODELS.md §1 (friction traces)".into(),
            "MODELS.md §11 (friction through a test)".into(),
        ]
    }
    fn run_file(&self, file: FileInput) -> Result<Tables> {
        let f = analyse_file(file, &self.params)?;
        let one = std::slice::from_ref(&f);
        let mut out: Tables = vec![
            (&FRICTION, friction_table(one)?),
            (&FRICTION_STEPS, steps_table(one)?),
            (&FRICTION_CYCLES, cycles_table(one)?),
            (&FRICTION_TESTS, tests_table(one)?),
            (&STICKSLIP, stickslip_table(one)?),
        ];
        if self.figures {
            let mut drawn = figures::friction::figures(&f.source, &f.traces, &f.features);
            drawn.extend(figures::cycles::figures(
                &f.source,
                &f.traces,
                &f.features,
                &f.tests,
            ));
            out.push((&FRICTION_FIGURES, figures::to_table(&drawn)?));
        }
        if self.traces {
            out.push((&TRACES, traces_table(vec![f])?));
        }
        Ok(out)
    }
    fn assemble(&self, mut tables: Tables) -> Result<Output> {
        // Tests exported as several files: numbered on through their files.
        series::join_series(&mut tables, &self.params.steady())?;
        // A segment without either coefficient has no result.
        let without = both_null(&tables)?;
        let mut out = Output::new(tables);
        out.without_result = without;
        Ok(out)
    }
}

/// Segments without either coefficient, except the whole-trace row of a
/// stepped test, whose coefficients are its steps'.
fn both_null(tables: &Tables) -> Result<usize> {
    let Some((_, t)) = tables.iter().find(|(d, _)| *d == &FRICTION) else {
        return Ok(0);
    };
    let (s, d) = (t.f64("mu_static")?, t.f64("mu_dynamic")?);
    let none: Vec<usize> = (0..s.len())
        .filter(|&i| s[i].is_none() && d[i].is_none())
        .collect();
    if none.is_empty() {
        return Ok(0);
    }
    let step = |stepped: &mut bool, c| *stepped |= c == crate::status::Code::SteppedTest;
    let stepped = t.fold_status_codes(false, step)?;
    Ok(none.into_iter().filter(|&i| !stepped[i]).count())
}
