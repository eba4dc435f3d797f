//! `tribo inspect FILE...`

use std::path::PathBuf;

use tribo::ingest::inspect::Inspection;
use tribo::ingest::IngestOptions;
use tribo::pipeline::examine::{examine, to_json};
use tribo::pipeline::exit::Tally;

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
    /// The channel of a multi-channel binary file to decode (default: the
    /// height channel); every channel is listed either way.
    #[arg(long)]
    channel: Option<String>,
}

fn print_text(i: &Inspection, kind: &str) {
    println!("{}", i.source);
    println!("  format      {}", i.format);
    println!("  kind        {kind}");
    match &i.dialect {
        Some(d) => println!(
            "  dialect     encoding {:?}, line ending {:?}, delimiter {:?}, decimal mark {:?}, quoted {}",
            d.encoding, d.line_ending, d.delimiter, d.decimal, d.quoted
        ),
        None => println!("  dialect     binary"),
    }
    println!("  sha256      {}", i.sha256);
    if !i.preamble.is_empty() {
        println!("  preamble    {} entries", i.preamble.len());
        for m in &i.preamble {
            match m.line {
                0 => println!("    {} = {}", m.key, m.value),
                n => println!("    line {n:>4}: {} = {}", m.key, m.value),
            }
        }
    }
    for g in &i.grids {
        let what = match (g.height, g.ny) {
            (true, 1) => "profile",
            (true, _) => "map",
            (false, _) => "channel",
        };
        let unit = if g.unit.is_empty() {
            "no unit"
        } else {
            &g.unit
        };
        let invalid = match g.n_invalid {
            Some(n) => format!(", {n} points not measured"),
            None => ", not decoded".into(),
        };
        println!(
            "  {what} '{}' [{unit}]: {} × {} points, spacing {:e} × {:e} m, origin ({:e}, {:e}) m{invalid}",
            g.name, g.nx, g.ny, g.dx_m, g.dy_m, g.x0_m, g.y0_m
        );
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

/// Runs `tribo inspect`.
pub fn run(args: &InspectArgs) -> tribo::Result<Tally> {
    let options = IngestOptions {
        format: args.format.clone(),
        channel: args.channel.clone(),
        ..Default::default()
    };
    let mut all = Vec::new();
    let mut failed = 0;
    for f in &args.files {
        match examine(f, &options) {
            Ok((i, kind)) => {
                if !args.json {
                    print_text(&i, &kind);
                }
                all.push(to_json(&i, &kind));
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
    Ok(Tally::without_result(failed))
}
