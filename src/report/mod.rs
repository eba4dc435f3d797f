//! The report: one self-contained `report.html` (inline SVG and CSS, no
//! scripts, fonts or network) that shows what tribo decided — a first page
//! with every input file and its status, then a section per file and per
//! model stage with its figures and rows.
//!
//! Figures are drawn by the stages ([`figures`]) and kept in the output
//! set as `<stage>_figures` tables; the report only assembles the set's
//! tables, so a report is the same whether the pipeline writes it or
//! `tribo report` redoes it from an output folder.

mod figure_files;
pub mod figures;
mod html;
mod index;
pub mod numbers;
mod overview;
pub mod pages;
mod summary;

pub use figure_files::FigureFiles;
pub use html::{render, render_paged, Report};
pub use pages::{FILES_PER_PAGE, PAGES_DIR};
pub use summary::{doubts, Doubt, RowStatus};
