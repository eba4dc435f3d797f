//! Progress bars (binary only) and the run summary on stderr.

use std::process::ExitCode;

use indicatif::{ProgressBar, ProgressStyle};
use tribo::pipeline::RunReport;
use tribo::stages::Progress;

/// One bar, restarted for each phase of a run (files, then each table or
/// simulation stage). Hidden for a single step, and by indicatif when
/// stderr is not a terminal.
pub struct Bar(ProgressBar);

impl Bar {
    /// A hidden bar, until a phase begins.
    pub fn new() -> Self {
        let pb = ProgressBar::hidden();
        pb.set_style(
            ProgressStyle::with_template(
                "{spinner} {msg} [{bar:30}] {pos}/{len}, {elapsed} (eta {eta})",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        Bar(pb)
    }
    /// Removes the bar.
    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}

impl Progress for Bar {
    fn begin(&self, what: &str, total: usize) {
        self.0.reset();
        self.0.set_length(total as u64);
        self.0.set_message(what.to_string());
        if total >= 2 {
            self.0
                .set_draw_target(indicatif::ProgressDrawTarget::stderr());
        } else {
            self.0
                .set_draw_target(indicatif::ProgressDrawTarget::hidden());
        }
    }
    fn tick(&self) {
        self.0.inc(1);
    }
}

/// Prints the summary of a run and returns its exit code (the run's own
/// rule, [`RunReport::exit_code`]).
pub fn summarise(report: &RunReport) -> ExitCode {
    for p in &report.outputs {
        eprintln!("wrote {}", p.display());
    }
    for (f, why) in &report.unrouted {
        eprintln!("not taken by any stage: {f}: {why}");
    }
    for n in &report.notes {
        eprintln!("note: {n}");
    }
    print_warnings(report);
    for f in &report.failures {
        eprintln!(
            "FAILED {} ({}, {}): {}",
            f.source, f.stage, f.kind, f.message
        );
    }
    for w in &report.without_result {
        eprintln!(
            "{}: {} rows without a result (see their status column)",
            w.stage, w.rows
        );
    }
    if report.files > 0 {
        let mut line = format!(
            "{} of {} files processed, {} failed",
            report.succeeded,
            report.files,
            report.failed_files()
        );
        if !report.unrouted.is_empty() {
            line.push_str(&format!(", {} taken by no stage", report.unrouted.len()));
        }
        let companions = report
            .inputs
            .iter()
            .filter(|i| i.outcome == tribo::pipeline::inputs::Outcome::Companion)
            .count();
        if companions > 0 {
            line.push_str(&format!(", {companions} read with their data file"));
        }
        if !report.warnings.is_empty() {
            line.push_str(&format!(", {} rows with a warning", report.warnings.len()));
        }
        if report.files_reused > 0 {
            line.push_str(&format!(
                " ({} unchanged, from the cache)",
                report.files_reused
            ));
        }
        eprintln!("{line}");
    }
    if !report.stages_reused.is_empty() {
        eprintln!(
            "unchanged since the last run: {}",
            report.stages_reused.join(", ")
        );
    }
    ExitCode::from(report.exit_code())
}

/// Lines shown for rows with a warning before the rest are counted.
const WARNINGS_SHOWN: usize = 20;

/// One line per row whose status holds a warning (the first
/// [`WARNINGS_SHOWN`]), then how many more.
fn print_warnings(report: &RunReport) {
    for w in report.warnings.iter().take(WARNINGS_SHOWN) {
        // Model tables' rows have no source file: `table: status`.
        if w.source.is_empty() {
            eprintln!("warning: {}: {}", w.table, w.status);
        } else {
            eprintln!("warning: {}: {}: {}", w.table, w.source, w.status);
        }
    }
    if report.warnings.len() > WARNINGS_SHOWN {
        eprintln!(
            "warning: … and {} more rows with a warning (report.html, or the status columns)",
            report.warnings.len() - WARNINGS_SHOWN
        );
    }
}
