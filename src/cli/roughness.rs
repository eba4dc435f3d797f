//! `tribo roughness FILE... --out DIR [--window 468um,733um] [--cutoff 0.25mm] ...`

use std::path::Path;

use serde::de::DeserializeOwned;
use tribo::extract::roughness::stage::RoughnessSpec;
use tribo::pipeline::exit::Tally;

use super::exec::execute;
use super::file_args::StageArgs;

/// Arguments of `tribo roughness`.
#[derive(clap::Args)]
pub struct RoughnessArgs {
    /// Profiles or maps (Dektak CSV, quoted "Distance","Profile" export,
    /// Nanovea x,y,z, generic x,z or x,y,z text, a z matrix: one row of
    /// heights per y, e.g. Gwyddion's text export, or a binary file of a
    /// surface instrument: X3P, SUR, ...; docs/formats.md), output folder
    /// (roughness, bearing_curve, psd,
    /// acf tables), samples (sample_id, pin), reader,
    /// settings (command-line options override them).
    #[command(flatten)]
    stage: StageArgs,
    /// The channel of a multi-channel binary file (its name in `tribo
    /// inspect`); the height channel when not given.
    #[arg(long)]
    channel: Option<String>,
    /// Evaluation window along x, START,END with units, e.g. 468um,733um.
    #[arg(long, value_delimiter = ',')]
    window: Option<Vec<String>>,
    /// Evaluation window along y for areal maps, START,END with units.
    #[arg(long, value_delimiter = ',')]
    window_y: Option<Vec<String>>,
    /// Sample spacing DX,DY of a z matrix (one row of heights per y) whose
    /// file does not state it, e.g. 0.5um,0.5um.
    #[arg(long, value_delimiter = ',')]
    spacing: Option<Vec<String>>,
    /// Form removal (F-operator); polynomial takes --form-degree, circle
    /// (cylinder for maps) --form-radius when known.
    #[arg(long, value_parser = ["none", "mean", "line", "polynomial", "circle"])]
    detrend: Option<String>,
    /// Degree of --detrend polynomial (default 2).
    #[arg(long)]
    form_degree: Option<usize>,
    /// Known radius of --detrend circle, e.g. 5mm; fitted when omitted.
    #[arg(long)]
    form_radius: Option<String>,
    /// Cut-off λs of the Gaussian S-filter applied first, e.g. 2.5um.
    #[arg(long)]
    short_cutoff: Option<String>,
    /// Cut-off λc of the L-filter, e.g. 0.25mm; no filter when omitted.
    #[arg(long)]
    cutoff: Option<String>,
    /// The L-filter: ISO 16610-21 Gaussian, ISO 16610-31 robust Gaussian
    /// regression, or ISO 13565-1 valley suppression.
    #[arg(long, value_parser = ["gaussian", "robust", "valley_suppression"])]
    filter: Option<String>,
    /// Stylus tip radius for the reliability cut-off, e.g. 2um (default:
    /// the file's, when it states one).
    #[arg(long)]
    tip_radius: Option<String>,
    /// The surface is periodic (synthetic): circular ACF, no window.
    #[arg(long)]
    periodic: bool,
    /// Skip the PSD and ACF tables.
    #[arg(long)]
    no_spectra: bool,
    /// Filter ends: drop λc/2 at each end, or keep them with the
    /// renormalised kernel.
    #[arg(long, value_parser = ["discard", "renormalize"])]
    filter_ends: Option<String>,
    /// Slope scheme for Rdq.
    #[arg(long, value_parser = ["forward", "central", "iso7_point"])]
    derivative: Option<String>,
    /// Fractal-dimension method.
    #[arg(long, value_parser = ["structure_function", "power_spectrum"])]
    fractal: Option<String>,
    /// Unit of x (and y) when the file has none, e.g. mm.
    #[arg(long)]
    x_unit: Option<String>,
    /// Unit of the heights when the file has none, e.g. um.
    #[arg(long)]
    z_unit: Option<String>,
    /// Nominal contact pressure with unit (e.g. 0.085MPa), for the contact
    /// length (Eq. 3.14–3.15); needs --hardness.
    #[arg(long)]
    pressure: Option<String>,
    /// Hardness of the softer body with unit (e.g. 25MPa).
    #[arg(long)]
    hardness: Option<String>,
}

fn choice<T: DeserializeOwned>(v: &Option<String>) -> tribo::Result<Option<T>> {
    v.as_ref()
        .map(|s| {
            serde_json::from_value(serde_json::Value::String(s.clone()))
                .map_err(|e| tribo::Error::Config(format!("'{s}': {e}")))
        })
        .transpose()
}

/// Two comma-separated values of a flag.
fn pair(v: &Option<Vec<String>>, flag: &str, expected: &str) -> tribo::Result<Option<[String; 2]>> {
    match v.as_deref() {
        None => Ok(None),
        Some([a, b]) => Ok(Some([a.clone(), b.clone()])),
        Some(w) => Err(tribo::Error::Config(format!(
            "{flag} takes {expected}, got {} values",
            w.len()
        ))),
    }
}

/// Runs `tribo roughness`.
pub fn run(args: &RoughnessArgs) -> tribo::Result<Tally> {
    let mut pipeline = args.stage.spec("roughness")?;
    let settings = pipeline.settings_mut("roughness");
    let mut spec: RoughnessSpec = std::mem::take(settings).try_into().map_err(|e| {
        let from = args.stage.params.as_ref();
        let from = from.map_or("roughness settings".into(), |p| p.display().to_string());
        tribo::Error::Config(format!("{from}: {e}"))
    })?;
    spec.window = pair(
        &args.window,
        "--window",
        "START,END (for example 468um,733um)",
    )?
    .or(spec.window);
    spec.window_y = pair(
        &args.window_y,
        "--window-y",
        "START,END (for example 0mm,1mm)",
    )?
    .or(spec.window_y);
    spec.spacing = pair(
        &args.spacing,
        "--spacing",
        "DX,DY (for example 0.5um,0.5um)",
    )?
    .or(spec.spacing);
    spec.detrend = choice(&args.detrend)?.or(spec.detrend);
    spec.cutoff = args.cutoff.clone().or(spec.cutoff);
    spec.form_degree = args.form_degree.or(spec.form_degree);
    spec.form_radius = args.form_radius.clone().or(spec.form_radius);
    spec.short_cutoff = args.short_cutoff.clone().or(spec.short_cutoff);
    spec.filter = choice(&args.filter)?.or(spec.filter);
    spec.tip_radius = args.tip_radius.clone().or(spec.tip_radius);
    if args.periodic {
        spec.periodic = Some(true);
    }
    if args.no_spectra {
        spec.spectra = Some(false);
    }
    spec.filter_ends = choice(&args.filter_ends)?.or(spec.filter_ends);
    spec.derivative = choice(&args.derivative)?.or(spec.derivative);
    spec.fractal_method = choice(&args.fractal)?.or(spec.fractal_method);
    spec.x_unit = args.x_unit.clone().or(spec.x_unit);
    spec.z_unit = args.z_unit.clone().or(spec.z_unit);
    spec.nominal_pressure = args.pressure.clone().or(spec.nominal_pressure);
    spec.hardness = args.hardness.clone().or(spec.hardness);
    pipeline.ingest.options.channel = args.channel.clone();
    *pipeline.settings_mut("roughness") = toml::Table::try_from(&spec)
        .map_err(|e| tribo::Error::Config(format!("roughness settings: {e}")))?;
    execute(&pipeline, Path::new(""), None)
}
