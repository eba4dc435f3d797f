//! The figures of each stage, drawn where the stage has its data (the
//! full trace, the curve, the profile) and kept as rows of a
//! `<stage>_figures` table (schema `schemas/figures.toml`): cached,
//! sharded and published with the rest of the set, so the report is only
//! their assembly and `tribo report` can redo it from an output folder.

pub mod fits;
pub mod friction;
pub mod roughness;
pub mod simulations;
pub mod tensile;
pub mod wear;

use crate::error::Result;
use crate::plot::Chart;
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

/// The table name of a stage's figures.
pub fn table_name(stage: &str) -> Option<&'static str> {
    FIGURE_TABLES
        .iter()
        .copied()
        .find(|t| t.strip_suffix("_figures") == Some(&stage.replace('-', "_")))
}

/// Every figures table, one per stage that draws.
pub const FIGURE_TABLES: [&str; 8] = [
    "friction_figures",
    "roughness_figures",
    "wear_figures",
    "tensile_figures",
    "coulomb_figures",
    "ice_figures",
    "alsfm_figures",
    "spring_block_figures",
];

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

/// Columns of a table read as numbers, null as NaN (for drawing only).
pub fn numbers(t: &Table, column: &str) -> Vec<f64> {
    t.f64(column)
        .map(|v| v.into_iter().map(|x| x.unwrap_or(f64::NAN)).collect())
        .unwrap_or_default()
}

/// A text column, null as empty.
pub fn texts(t: &Table, column: &str) -> Vec<String> {
    t.str(column)
        .map(|v| v.into_iter().map(Option::unwrap_or_default).collect())
        .unwrap_or_default()
}

/// The rows of `t` whose `column` equals `value`.
pub fn rows_where(t: &Table, column: &str, value: &str) -> Vec<usize> {
    texts(t, column)
        .iter()
        .enumerate()
        .filter(|(_, v)| *v == value)
        .map(|(i, _)| i)
        .collect()
}
