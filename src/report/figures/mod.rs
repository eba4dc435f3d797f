//! The figures of each stage, drawn where the stage has its data (the
//! full trace, the curve, the profile) and kept as rows of a
//! `<stage>_figures` table (schema `schemas/figures.toml`): cached,
//! sharded and published with the rest of the set, so the report is only
//! their assembly and `tribo report` can redo it from an output folder.

pub mod cycles;
pub mod fits;
pub mod friction;
pub mod roughness;
pub mod simulations;
pub mod tensile;
pub mod wear;

use crate::error::Result;
use crate::plot::Chart;
use crate::schema::{Show, TableDef};
use crate::table::{Table, TableBuilder};

/// One drawn figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// The input file, or the model stage's name for a model figure.
    pub source: String,
    /// Section or group within the source; empty for none.
    pub part: String,
    /// Short stable name (`force`, `mu`, `steps`, …).
    pub name: &'static str,
    /// Title as drawn.
    pub title: String,
    /// The SVG document.
    pub svg: String,
}

impl Figure {
    /// Draws `chart` as the figure `name` of `source`.
    pub fn draw(source: &str, part: &str, name: &'static str, chart: &Chart) -> Figure {
        Figure {
            source: source.into(),
            part: part.into(),
            name,
            title: chart.title.clone(),
            svg: chart.svg(),
        }
    }
}

/// The schema every `<stage>_figures` table shares.
const FIGURES_SCHEMA: &str = include_str!("../../../schemas/figures.toml");

/// Declares a table stage's figures table `name` (`<stage>_figures`):
/// every one has the schema `schemas/figures.toml`.
pub const fn figures_table(name: &'static str) -> TableDef {
    TableDef::new(name, FIGURES_SCHEMA, Show::Figures)
}

/// Declares a per-file stage's figures table `name`, published as a
/// dataset (a file per input): its SVGs are the largest rows a run makes
/// (about 10 kB per profile), so a run that adds one input to thousands
/// writes one input's figures, not every input's again.
pub const fn file_figures_table(name: &'static str) -> TableDef {
    TableDef::dataset(name, FIGURES_SCHEMA, Show::Figures)
}

/// Figures as a table (schema `figures`).
pub fn to_table(figures: &[Figure]) -> Result<Table> {
    TableBuilder::new()
        .str("source", figures.iter().map(|f| Some(&f.source)))
        .str("part", figures.iter().map(|f| Some(&f.part)))
        .str("figure", figures.iter().map(|f| Some(f.name)))
        .str("title", figures.iter().map(|f| Some(&f.title)))
        .str("svg", figures.iter().map(|f| Some(&f.svg)))
        .build()
}

/// The file name of a source path, for titles.
pub fn file_name(source: &str) -> String {
    std::path::Path::new(source)
        .file_name()
        .map_or(source.to_string(), |n| n.to_string_lossy().to_string())
}

/// A value as drawn: a missing or non-finite one is NaN (not drawn), as
/// the table holds it (null).
pub fn num(v: Option<f64>) -> f64 {
    v.filter(|v| v.is_finite()).unwrap_or(f64::NAN)
}

/// A text column, null as empty.
pub fn texts(t: &Table, column: &str) -> Vec<String> {
    t.str(column)
        .map(|v| v.into_iter().map(Option::unwrap_or_default).collect())
        .unwrap_or_default()
}
