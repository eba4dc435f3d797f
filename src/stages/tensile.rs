//! The `tensile` stage (MODELS.md §3 and §9): per specimen (fibre,
//! coupon, bar, film, cylinder; tension or compression) maximum force,
//! strength, modulus, yield, strains and toughness, checked against the
//! file's printed results and redundant channels; for fibres also
//! friction stress, knot release and the toughness ratios (Eq. 5.1–5.4),
//! as the table `tensile`. The ratios against a control
//! fibre (Eq. 5.4) span files: they are resolved once every file's row is
//! in ([`StagePlan::assemble`]).
//!
//! ```toml
//! [tensile]                        # every key optional (TensileParams)
//! effective_threshold = 0.08
//! modulus_stress_window_mpa = [20.0, 50.0]   # modulus by regression on a stated window
//! yield_offset = 0.002             # R_p0.2
//! ```

use super::{settings, Consumes, FileInput, Output, PlanContext, Stage, StagePlan, Tables};
use crate::error::Result;
use crate::extract::tensile::{
    apply_controls_table, batch::analyze_with_curve, tensile_table, TensileParams,
};
use crate::ingest::kind::DataKind;
use crate::report::figures::{self, file_figures_table};
use crate::schema::{Show, TableDef};

/// The registry entry.
pub struct Tensile;

/// The stage's name in pipeline files.
const NAME: &str = "tensile";

/// One row per fibre (specimen).
pub static TENSILE: TableDef = TableDef::new(
    "tensile",
    include_str!("../../schemas/tensile.toml"),
    Show::PerFile(&[
        ("sample_id", "sample"),
        ("strength_MPa", "strength"),
        ("max_force_N", "Fmax"),
        ("strain_at_break", "ε_f"),
        ("modulus_GPa", "E"),
        ("yield_stress_MPa", "Rp0.2"),
        ("toughness_J_per_g", "toughness"),
        ("status", "status"),
    ]),
);

/// The stress–strain curve of every fibre with what was decided on it.
pub static TENSILE_FIGURES: TableDef = file_figures_table("tensile_figures");

/// Equations and sources of the tensile stages.
pub const REFERENCES: [&str; 3] = [
    "MODELS.md §3 (silk fibres with slip knots)",
    "thesis Ch. 5, Eq. 5.1-5.4, Tables 5.1-5.8",
    "MODELS.md §9 (tensile yield, sections); ISO 527-1, ISO 6892-1, ASTM C469 windows (docs/tensile.md)",
];

/// Every table of the stage.
static TABLES: &[&TableDef] = &[&TENSILE, &TENSILE_FIGURES];

impl Stage for Tensile {
    fn name(&self) -> &'static str {
        NAME
    }
    fn about(&self) -> &'static str {
        "tension and compression tests of any specimen: maximum force, strength, modulus on a stated or standard window, yield, strains, toughness; for fibres also friction stress, knot release and toughness ratios"
    }
    fn tables(&self) -> &'static [&'static TableDef] {
        TABLES
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let params: TensileParams = settings(NAME, table)?;
        params.validate()?;
        Ok(Box::new(TensilePlan {
            params,
            figures: ctx.figures,
        }))
    }
}

struct TensilePlan {
    params: TensileParams,
    figures: bool,
}

impl StagePlan for TensilePlan {
    fn name(&self) -> &'static str {
        NAME
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::TensileCurve])
    }
    fn produces(&self) -> Vec<&'static TableDef> {
        match self.figures {
            true => vec![&TENSILE, &TENSILE_FIGURES],
            false => vec![&TENSILE],
        }
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::to_value(self.params).unwrap_or_default()
    }
    fn references(&self) -> Vec<String> {
        REFERENCES.iter().map(|s| s.to_string()).collect()
    }
    fn run_file(&self, file: FileInput) -> Result<Tables> {
        let (record, curve) = analyze_with_curve(&file.dataset, file.manifest, &self.params)?;
        let record = [record];
        let table = tensile_table(&record)?;
        if !self.figures {
            return Ok(vec![(&TENSILE, table)]);
        }
        // Without a curve (a bad diameter, in the row's status) the figure
        // says there is nothing to draw.
        let (strain, stress) = curve.map_or_else(Default::default, |c| (c.strain, c.stress_pa));
        let source = file.path.display().to_string();
        let drawn = figures::tensile::figures(&source, &strain, &stress, &record[0]);
        Ok(vec![
            (&TENSILE, table),
            (&TENSILE_FIGURES, figures::to_table(&drawn)?),
        ])
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        let mut out = Output::default();
        for (def, t) in tables {
            if def != &TENSILE {
                out.tables.push((def, t));
                continue;
            }
            let t = apply_controls_table(t)?;
            // A specimen without a toughness has no result (its status says
            // why); the toughness per volume, since the toughness per mass
            // needs a density only the fibre protocol defaults.
            out.without_result += t.null_count("energy_density_MJ_per_m3")?;
            out.tables.push((def, t));
        }
        Ok(out)
    }
}
