//! Running a pipeline from the binary: every subcommand builds a
//! [`PipelineSpec`] from its flags and comes here, so that there is one path
//! from inputs to tables and one summary; the run counts its own exit code
//! ([`RunReport::tally`]).

use std::path::Path;

use tribo::pipeline::exit::Tally;
use tribo::pipeline::spec::PipelineSpec;
use tribo::pipeline::{run_with, Mode, Plan, RunOptions, RunReport};

use super::progress::{summarise, Bar};

/// Validates `spec` (relative paths from `base`), runs it and prints the
/// summary. `threads` sets the worker threads (results do not depend on
/// it).
pub fn execute(spec: &PipelineSpec, base: &Path, threads: Option<usize>) -> tribo::Result<Tally> {
    let how = How {
        threads,
        ..Default::default()
    };
    execute_plan(&Plan::from_spec(spec, base)?, &how)
}

/// The command line as typed (after the program's name), every argument
/// with `--out` included, quoted for a POSIX shell where it needs it: the
/// provenance's `tribo.command`, enough to run the same command again.
pub fn invocation() -> String {
    let args: Vec<String> = std::env::args_os()
        .skip(1)
        .map(|a| a.to_string_lossy().into_owned())
        .collect();
    quoted(&args)
}

/// `args` joined for a POSIX shell: an argument with anything but
/// `[A-Za-z0-9_./:=,@+%-]` in it (or empty) is single-quoted.
fn quoted(args: &[String]) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_./:=,@+%-".contains(c);
    args.iter()
        .map(|a| {
            if !a.is_empty() && a.chars().all(plain) {
                a.clone()
            } else {
                format!("'{}'", a.replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// How the binary runs a plan.
#[derive(Default)]
pub struct How {
    /// Worker threads (results do not depend on it).
    pub threads: Option<usize>,
    /// Cache, dry run, lock waiting.
    pub options: RunOptions,
    /// A JSON summary on stdout.
    pub json: bool,
}

/// Runs a validated plan and prints the summary (or, in a dry run, what
/// would be redone).
pub fn execute_plan(plan: &Plan, how: &How) -> tribo::Result<Tally> {
    for w in &plan.warnings {
        eprintln!("warning: {w}");
    }
    let bar = Bar::new();
    let command = invocation();
    let go = || run_with(plan, &command, &bar, &how.options);
    let threads = how.threads;
    let report = match threads {
        Some(t) => rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| tribo::Error::Config(format!("--threads {t}: {e}")))?
            .install(go)?,
        None => go()?,
    };
    bar.finish();
    if how.options.mode == Mode::DryRun {
        print_dry_run(&report, how.json);
    } else {
        summarise(&report);
        if how.json {
            print_line(report.summary_json());
        }
    }
    Ok(report.tally())
}

/// Prints `text` and a newline with one write: `println!` goes through
/// standard output's line buffer, a write per kilobyte (5 000 for the
/// summary of 20 000 inputs).
fn print_line(mut text: String) {
    use std::io::Write;
    text.push('\n');
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

/// What a dry run would redo: one line per file or stage, or JSON.
fn print_dry_run(report: &RunReport, json: bool) {
    if json {
        println!(
            "{}",
            serde_json::json!({ "dry_run": true, "redo": report.redo })
        );
        return;
    }
    if report.redo.is_empty() {
        println!("nothing to redo: every table is current");
    }
    for r in &report.redo {
        println!("would redo {} {}: {}", r.what, r.name, r.reason);
    }
}

/// A stage's settings from a TOML file (`--params`), or empty.
pub fn params_file(path: Option<&Path>) -> tribo::Result<toml::Table> {
    let Some(p) = path else {
        return Ok(toml::Table::new());
    };
    let text = std::fs::read_to_string(p).map_err(|e| tribo::Error::io(p, e))?;
    toml::from_str(&text).map_err(|e| tribo::Error::Config(format!("{}: {e}", p.display())))
}

/// A one-stage pipeline with no input files (table and simulation
/// stages), writing to `out`.
pub fn table_stage(stage: &str, out: &Path) -> PipelineSpec {
    PipelineSpec::single_stage(stage, Vec::new(), None, out.display().to_string(), None)
}

/// Sets `key` in a stage's settings from a serialisable value.
pub fn set(table: &mut toml::Table, key: &str, value: impl serde::Serialize) -> tribo::Result<()> {
    let v =
        toml::Value::try_from(value).map_err(|e| tribo::Error::Config(format!("{key}: {e}")))?;
    table.insert(key.to_string(), v);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::quoted;

    /// The command reads back as the same arguments in a POSIX shell.
    #[test]
    fn arguments_are_quoted_only_where_a_shell_needs_it() {
        let args = ["friction", "a b.csv", "it's", "", "--out", "out/x-1"].map(String::from);
        assert_eq!(
            quoted(&args),
            "friction 'a b.csv' 'it'\\''s' '' --out out/x-1"
        );
    }
}
