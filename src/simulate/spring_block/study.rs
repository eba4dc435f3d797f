//! Entry point for files given to `tribo simulate spring-block`: a single
//! scene, or a comparison study that lists scenes and the measured fits to
//! compare them with (thesis Fig. 4.10).
//!
//! A study file:
//! ```toml
//! scenes = ["spring_block/flat.toml", "spring_block/A.toml"]  # relative to this file
//! [measured]
//! coulomb = "../out/coulomb.parquet"  # optional; default: thesis Table 4.2
//! flat_group = "F"                    # group of the flat reference (Eq. 4.2)
//! [[measured.fit]]                    # optional fits given directly (override)
//! group = "F"
//! regime = "static"
//! mu = 4.76
//! tau0_Pa = 23450.0
//! [groups]                            # scene name → measured group
//! flat = "F"
//! ```

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::compare::{
    compare_rows, compare_rows_table, read_coulomb, thesis_table_4_2, CompareRow, CoulombFit,
    MeasuredFits, PatternLink,
};
use super::output::{summarise, sweep_tables, SweepTables};
use super::scene::{ScenePlan, SceneSpec};
use super::sweep::{run_one, run_sweep, sweep_jobs, SweepRun};
use crate::error::{Error, Result};
use crate::hash::InputHash;
use crate::models::spring_block::Lattice;
use crate::table::Table;

/// A fit given directly in the study file.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FitSpec {
    /// Measured group (F, A, B, C, "S (x)", …).
    pub group: String,
    /// `static` or `dynamic`.
    pub regime: String,
    /// μ.
    pub mu: f64,
    /// τ0 \[Pa\].
    #[serde(rename = "tau0_Pa")]
    pub tau0: f64,
}

/// `[measured]` of a study.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct MeasuredSpec {
    /// `coulomb.parquet` of `tribo fit coulomb`, relative to the study file.
    pub coulomb: Option<String>,
    /// Group of the flat reference.
    pub flat_group: String,
    /// Fits given directly; they replace fits of the same group and regime.
    pub fit: Vec<FitSpec>,
}

impl Default for MeasuredSpec {
    fn default() -> Self {
        MeasuredSpec {
            coulomb: None,
            flat_group: "F".into(),
            fit: Vec::new(),
        }
    }
}

/// A comparison study file.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StudySpec {
    /// Scene files, relative to the study file.
    pub scenes: Vec<String>,
    /// Measured fits.
    #[serde(default)]
    pub measured: MeasuredSpec,
    /// Scene name → measured group; by default the scene's own name, or
    /// flat → F, Sx → "S (x)", Sy → "S (y)".
    #[serde(default)]
    pub groups: BTreeMap<String, String>,
}

/// What a file holds, validated.
pub enum SimulationInput {
    /// One scene.
    Scene(Box<ScenePlan>),
    /// Several scenes and the measurements to compare with.
    Study(Box<StudyPlan>),
}

/// A validated study.
#[derive(Clone)]
pub struct StudyPlan {
    /// The scenes.
    pub scenes: Vec<ScenePlan>,
    /// Pattern → measured group and AF.
    pub links: Vec<PatternLink>,
    /// The measured fits.
    pub measured: super::compare::MeasuredFits,
    /// Flat reference group.
    pub flat_group: String,
    /// The spec as read.
    pub spec: StudySpec,
}

fn read(path: &Path) -> Result<(String, InputHash)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let hash = InputHash::of_bytes(path, &bytes);
    let text = String::from_utf8(bytes).map_err(|_| {
        Error::Config(format!(
            "{}: not UTF-8 text; expected a TOML file",
            path.display()
        ))
    })?;
    Ok((text, hash))
}

/// Reads and validates a scene or study file. Returns it with the hashes of
/// the files read.
pub fn load_input(path: &Path) -> Result<(SimulationInput, Vec<InputHash>)> {
    let (text, hash) = read(path)?;
    let value: toml::Table = toml::from_str(&text)
        .map_err(|e| Error::Config(format!("{}: not valid TOML: {e}", path.display())))?;
    if !value.contains_key("scenes") {
        let plan = SceneSpec::from_toml(&text, path)?.plan()?;
        return Ok((SimulationInput::Scene(Box::new(plan)), vec![hash]));
    }
    let spec: StudySpec = toml::from_str(&text).map_err(|e| {
        Error::Config(format!(
            "{}: not a valid spring-block study: {e}",
            path.display()
        ))
    })?;
    let base = path.parent().unwrap_or(Path::new(""));
    let mut hashes = vec![hash];
    let mut scenes = Vec::new();
    if spec.scenes.is_empty() {
        return Err(Error::Config(format!(
            "{}: scenes is empty; expected at least one scene file",
            path.display()
        )));
    }
    for s in &spec.scenes {
        let p = base.join(s);
        let (t, h) = read(&p)?;
        hashes.push(h);
        scenes.push(SceneSpec::from_toml(&t, &p)?.plan()?);
    }
    let mut names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(Error::Config(format!(
            "{}: two scenes are named '{}'; expected distinct names",
            path.display(),
            w[0]
        )));
    }
    let mut measured = match &spec.measured.coulomb {
        Some(c) => {
            let p: PathBuf = base.join(c);
            let (_, h) = read(&p)?;
            hashes.push(h);
            read_coulomb(&p)?
        }
        None => thesis_table_4_2(),
    };
    for f in &spec.measured.fit {
        if f.regime != "static" && f.regime != "dynamic" {
            return Err(Error::Config(format!(
                "{}: measured fit regime '{}'; expected static or dynamic",
                path.display(),
                f.regime
            )));
        }
        measured.fits.insert(
            (f.group.clone(), f.regime.clone()),
            CoulombFit {
                mu: f.mu,
                tau0: f.tau0,
            },
        );
        if !measured.source.contains("study file") {
            measured.source.push_str(" + fits in the study file");
        }
    }
    let links = link_patterns(&scenes, &spec, &measured);
    let flat_group = spec.measured.flat_group.clone();
    Ok((
        SimulationInput::Study(Box::new(StudyPlan {
            scenes,
            links,
            measured,
            flat_group,
            spec,
        })),
        hashes,
    ))
}

/// How each scene's pattern maps to a measured group: the study's
/// `[groups]`, else a group named as the scene, else `pattern=NAME` (the
/// coulomb stage's group names), else the thesis aliases (flat → F, Sx →
/// "S (x)", Sy → "S (y)").
fn link_patterns(
    scenes: &[ScenePlan],
    spec: &StudySpec,
    measured: &MeasuredFits,
) -> Vec<PatternLink> {
    let has = |g: &str| measured.fits.keys().any(|(k, _)| k == g);
    scenes
        .iter()
        .map(|s| {
            let alias = match s.name.as_str() {
                "flat" => Some("F"),
                "Sx" => Some("S (x)"),
                "Sy" => Some("S (y)"),
                _ => None,
            };
            let group = spec
                .groups
                .get(&s.name)
                .cloned()
                .or_else(|| has(&s.name).then(|| s.name.clone()))
                .or_else(|| {
                    let g = format!("pattern={}", s.name);
                    has(&g).then_some(g)
                })
                .or_else(|| alias.filter(|a| has(a)).map(str::to_string));
            PatternLink {
                pattern: s.name.clone(),
                group,
                area_fraction: s.pattern.area_fraction(),
            }
        })
        .collect()
}

impl StudyPlan {
    /// Compares with other measured fits (a coulomb table of the same
    /// pipeline) instead of the study file's, keeping the fits given in the
    /// study file itself.
    pub fn with_measured(&mut self, mut measured: MeasuredFits) {
        for f in &self.spec.measured.fit {
            measured.fits.insert(
                (f.group.clone(), f.regime.clone()),
                CoulombFit {
                    mu: f.mu,
                    tau0: f.tau0,
                },
            );
        }
        self.links = link_patterns(&self.scenes, &self.spec, &measured);
        self.measured = measured;
    }
}

/// What a simulation produced.
pub struct SimulationOutcome {
    /// The runs, summary and curves tables with their typed rows.
    pub tables: SweepTables,
    /// A study's comparison with the measured fits: its table and rows.
    pub compare: Option<(Table, Vec<CompareRow>)>,
    /// Runs made.
    pub runs: usize,
    /// Runs that did not complete (diverged or max time).
    pub failures: usize,
    /// Messages of the failed runs (pattern, pressure, run, message).
    pub failure_messages: Vec<String>,
}

impl SimulationInput {
    /// Total number of runs.
    pub fn runs(&self) -> usize {
        let n = |p: &ScenePlan| p.pressures.len() * p.repetitions;
        match self {
            SimulationInput::Scene(p) => n(p),
            SimulationInput::Study(s) => s.scenes.iter().map(n).sum(),
        }
    }

    /// Runs every sweep on the current rayon pool and builds the tables:
    /// `spring_block`, `spring_block_summary`, `spring_block_curves` and,
    /// for a study, `spring_block_compare`. `progress` is called once per
    /// run.
    pub fn compute(&self, progress: &(dyn Fn() + Sync)) -> Result<SimulationOutcome> {
        let mut results: Vec<Vec<SweepRun>> = Vec::new();
        for p in self.plans() {
            results.push(run_sweep(p, progress)?);
        }
        self.compute_from(results)
    }

    fn plans(&self) -> Vec<&ScenePlan> {
        match self {
            SimulationInput::Scene(p) => vec![p.as_ref()],
            SimulationInput::Study(s) => s.scenes.iter().collect(),
        }
    }

    /// Every run as (scene, pressure index, repetition), in table order:
    /// the units a cluster can spread over its tasks.
    pub fn units(&self) -> Vec<(usize, usize, usize)> {
        self.plans()
            .iter()
            .enumerate()
            .flat_map(|(s, p)| sweep_jobs(p).into_iter().map(move |(k, r)| (s, k, r)))
            .collect()
    }

    /// The lattice size of a unit's scene (its cost, roughly).
    pub fn unit_blocks(&self, unit: (usize, usize, usize)) -> usize {
        let p = self.plans()[unit.0];
        p.params.nx * p.params.ny
    }

    /// Runs one unit; the same result wherever it runs.
    pub fn run_unit(&self, unit: (usize, usize, usize)) -> Result<SweepRun> {
        let p = self.plans()[unit.0];
        run_one(p, &Lattice::new(&p.params), unit.1, unit.2)
    }

    /// The tables from every unit's run, in [`Self::units`] order.
    pub fn compute_from_units(&self, runs: Vec<SweepRun>) -> Result<SimulationOutcome> {
        let mut results: Vec<Vec<SweepRun>> = self.plans().iter().map(|_| Vec::new()).collect();
        for ((s, _, _), run) in self.units().into_iter().zip(runs) {
            results[s].push(run);
        }
        self.compute_from(results)
    }

    fn compute_from(&self, results: Vec<Vec<SweepRun>>) -> Result<SimulationOutcome> {
        let plans = self.plans();
        let pairs: Vec<(&ScenePlan, &[SweepRun])> = plans
            .iter()
            .zip(&results)
            .map(|(p, r)| (*p, r.as_slice()))
            .collect();
        let tables = sweep_tables(&pairs)?;
        let compare = match self {
            SimulationInput::Study(s) => {
                let summary: Vec<_> = pairs.iter().flat_map(|(p, r)| summarise(p, r)).collect();
                let rows = compare_rows(&summary, &s.links, &s.measured, &s.flat_group);
                Some((compare_rows_table(&rows, &s.measured)?, rows))
            }
            SimulationInput::Scene(_) => None,
        };
        let mut failure_messages = Vec::new();
        for (p, rs) in &pairs {
            for r in rs.iter() {
                if r.report.mu_static.is_none() || r.report.stop.error().is_some() {
                    failure_messages.push(format!(
                        "{} at {} Pa, run {}: {} {}",
                        p.name,
                        r.pressure,
                        r.run,
                        r.report.stop.status(),
                        r.report.stop.message()
                    ));
                }
            }
        }
        Ok(SimulationOutcome {
            tables,
            compare,
            runs: results.iter().map(Vec::len).sum(),
            failures: failure_messages.len(),
            failure_messages,
        })
    }
}
