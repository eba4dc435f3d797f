//! The `tensile` stage (MODELS.md §3): per fibre, strength, toughness
//! (Eq. 5.1/5.2), friction stress, knot release and the toughness ratios
//! (Eq. 5.3/5.4), as the table `tensile`. The ratios against a control
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
use crate::report::figures;

/// The registry entry.
pub struct Tensile;

/// Equations and sources of the tensile stages.
pub const REFERENCES: [&str; 2] = [
    "MODELS.md §3 (silk fibres with slip knots)",
    "thesis Ch. 5, Eq. 5.1-5.4, Tables 5.1-5.8",
];

impl Stage for Tensile {
    fn name(&self) -> &'static str {
        "tensile"
    }
    fn about(&self) -> &'static str {
        "strength, toughness, friction stress, knot release and toughness ratios of fibre tensile curves"
    }
    fn plan(&self, table: toml::Table, ctx: &PlanContext) -> Result<Box<dyn StagePlan>> {
        let params: TensileParams = settings("tensile", table)?;
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
        "tensile"
    }
    fn consumes(&self) -> Consumes {
        Consumes::Files(&[DataKind::TensileCurve])
    }
    fn produces(&self) -> Vec<&'static str> {
        match self.figures {
            true => vec!["tensile", "tensile_figures"],
            false => vec!["tensile"],
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
        let table = tensile_table(&[record])?;
        if !self.figures {
            return Ok(vec![("tensile", table)]);
        }
        // Without a curve (a bad diameter, in the row's status) the figure
        // says there is nothing to draw.
        let (strain, stress) = curve.map_or_else(Default::default, |c| (c.strain, c.stress_pa));
        let source = file.path.display().to_string();
        let drawn = figures::tensile::figures(&source, &strain, &stress, &table);
        Ok(vec![
            ("tensile", table),
            ("tensile_figures", figures::to_table(&drawn)?),
        ])
    }
    fn assemble(&self, tables: Tables) -> Result<Output> {
        let mut out = Output::default();
        for (name, t) in tables {
            if name != "tensile" {
                out.tables.push((name, t));
                continue;
            }
            let t = apply_controls_table(t)?;
            // A specimen without a toughness has no result (its status says
            // why); the toughness per volume, since the toughness per mass
            // needs a density only the fibre protocol defaults.
            out.without_result += t.null_count("energy_density_MJ_per_m3")?;
            out.tables.push((name, t));
        }
        Ok(out)
    }
}
