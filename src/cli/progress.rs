//! Progress bars (binary only) and the run summary.

use std::process::ExitCode;

use indicatif::{ProgressBar, ProgressStyle};
use tribo::pipeline::RunReport;

/// A bar for `n` files; hidden for a single file or when stderr is not a
/// terminal (indicatif hides itself then).
pub fn bar(n: usize, what: &str) -> ProgressBar {
    if n < 2 {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(n as u64);
    pb.set_style(
        ProgressStyle::with_template(
            "{spinner} {msg} [{bar:30}] {pos}/{len} files, {elapsed} (eta {eta})",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// Prints the summary of a run and returns its exit code: 0 when every file
/// succeeded, 1 when some failed.
pub fn summarise(report: &RunReport) -> ExitCode {
    for p in &report.outputs {
        eprintln!("wrote {}", p.display());
    }
    for f in &report.failures {
        eprintln!(
            "FAILED {} ({}, {}): {}",
            f.source, f.stage, f.kind, f.message
        );
    }
    eprintln!(
        "{} of {} files processed, {} failed",
        report.succeeded,
        report.files,
        report.failed_files()
    );
    if report.failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
