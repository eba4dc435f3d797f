//! `tribo inspect FILE...`

use std::path::PathBuf;
use std::process::ExitCode;

use tribo::ingest::inspect::{inspect, Inspection};
use tribo::ingest::source::Source;
use tribo::ingest::{read_data, IngestOptions, Reading};
use tribo::pipeline::route::kind_of;

/// Arguments of `tribo inspect`.
#[derive(clap::Args)]
pub struct InspectArgs {
    /// Files to inspect.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Print JSON (one array of objects) instead of text.
    #[arg(long)]
    json: bool,
    /// Force a reader instead of sniffing (cetr-umt, csm-pin-on-disc, delimited, ...).
    #[arg(long)]
    format: Option<String>,
}

fn print_text(i: &Inspection, kind: &str) {
    println!("{}", i.source);
    println!("  format      {}", i.format);
    println!("  kind        {kind}");
    let d = &i.dialect;
    println!(
        "  dialect     encoding {:?}, line ending {:?}, delimiter {:?}, decimal mark {:?}, quoted {}",
        d.encoding, d.line_ending, d.delimiter, d.decimal, d.quoted
    );
    println!("  sha256      {}", i.sha256);
    if !i.preamble.is_empty() {
        println!("  preamble    {} entries", i.preamble.len());
        for m in &i.preamble {
            println!("    line {:>4}: {} = {}", m.line, m.key, m.value);
        }
    }
    for s in &i.sections {
        let rate = s
            .sample_rate_hz
            .map(|r| format!(", {r:.4} Hz"))
            .unwrap_or_default();
        println!(
            "  section '{}': {} rows from line {} (header line {}){rate}",
            s.name,
            s.rows,
            s.first_data_line,
            s.header_line.map_or("none".into(), |l| l.to_string())
        );
        for m in &s.metadata {
            println!("    line {:>4}: {} = {}", m.line, m.key, m.value);
        }
        for c in &s.columns {
            let unit = if c.unit.is_empty() {
                "(no unit)".to_string()
            } else {
                format!("[{}] -> {}", c.unit, c.si_unit)
            };
            let role = c.role.map(|r| format!("  <- {r}")).unwrap_or_default();
            println!("    {:<24} {unit}{role}", c.name);
        }
    }
}

/// What `tribo inspect` makes of one file: its description and its kind
/// (or why it has none, as a run would list it); an error when it cannot be
/// read or is not a data file.
fn inspect_file(
    path: &std::path::Path,
    options: &IngestOptions,
) -> tribo::Result<(Inspection, String)> {
    let source = Source::open(path)?;
    let ds = match read_data(path, &source, None, options).1? {
        Reading::Data(ds) => ds,
        Reading::NotData(why) => {
            return Err(tribo::Error::NotApplicable(format!(
                "{}: not a data file: {why}",
                path.display()
            )))
        }
    };
    let kind = match kind_of(&ds, &Default::default()) {
        (Some(k), _) => k.to_string(),
        (None, why) => format!("none: {why}"),
    };
    Ok((inspect(&ds, &Default::default()), kind))
}

/// Runs `tribo inspect`.
pub fn run(args: &InspectArgs) -> tribo::Result<ExitCode> {
    let options = IngestOptions {
        format: args.format.clone(),
        ..Default::default()
    };
    let mut all = Vec::new();
    let mut failed = 0;
    for f in &args.files {
        match inspect_file(f, &options) {
            Ok((i, kind)) => {
                if !args.json {
                    print_text(&i, &kind);
                }
                let mut v = serde_json::to_value(&i).unwrap_or_default();
                if let Some(o) = v.as_object_mut() {
                    o.insert("kind".into(), kind.into());
                }
                all.push(v);
            }
            Err(e) => {
                failed += 1;
                eprintln!("error: {e}");
                all.push(serde_json::json!({ "source": f.display().to_string(), "error": e.to_string() }));
            }
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&all).unwrap_or_default());
    }
    Ok(if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
