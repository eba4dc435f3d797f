//! The report: one self-contained `report.html` (inline SVG and CSS, no
//! scripts, fonts or network) that shows what tribo decided — a first page
//! with every input file and its status, then a section per file and per
//! model stage with its figures and rows.
//!
//! Figures are drawn by the stages ([`figures`]) and kept in the output
//! set as `<stage>_figures` tables; the report only assembles the set's
//! tables, so a report is the same whether the pipeline writes it or
//! `tribo report` redoes it from an output folder.

pub mod figures;
mod html;
mod index;
mod summary;

pub use html::render;
pub use summary::{doubts, is_sound, Doubt};
