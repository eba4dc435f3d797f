//! The tables of the roughness stage, from the typed reports: `roughness`
//! (one row per profile or map), `bearing_curve`, `psd` and `acf`. Each
//! has its schema in `schemas/`, with the columns in this order.

use serde::Serialize;

use super::analyze::{RoughnessReport, SurfaceKind};
use super::file::RoughnessFile;
use super::instrument::InstrumentRoughness;
use super::params::{Detrend, RoughnessParams};
use super::report::{AcfPoint, Functional};
use crate::error::Result;
use crate::table::{Table, TableBuilder};

/// The `roughness` table: one row per profile or map, with the manifest's
/// `sample_id` and `pin` and the settings. Profiles fill the R columns
/// (ISO 4287), maps the S columns (ISO 25178-2); the other family is null.
pub fn roughness_table(files: &[RoughnessFile], params: &RoughnessParams) -> Result<Table> {
    let rows: Vec<(&RoughnessFile, &RoughnessReport)> = files
        .iter()
        .flat_map(|f| f.reports.iter().map(move |r| (f, r)))
        .collect();
    let reports: Vec<&RoughnessReport> = rows.iter().map(|r| r.1).collect();
    let t = TableBuilder::new()
        .str("source", reports.iter().map(|r| Some(r.source.clone())))
        .str("sample_id", rows.iter().map(|r| r.0.sample_id.clone()))
        .str("pin", rows.iter().map(|r| r.0.pin.clone()))
        .str("kind", reports.iter().map(|r| Some(r.kind.as_str())))
        .i64("n_points", reports.iter().map(|r| Some(r.n_points as i64)))
        .f64("length_m", reports.iter().map(|r| Some(r.length)))
        .i64(
            "n_invalid",
            reports.iter().map(|r| Some(r.n_invalid as i64)),
        );
    let t = family_columns(t, &reports, SurfaceKind::Profile);
    let t = functional_columns(t, &reports, SurfaceKind::Profile);
    let t = family_columns(t, &reports, SurfaceKind::Areal);
    let t = functional_columns(t, &reports, SurfaceKind::Areal);
    let t = instrument_columns(t, &rows);
    let t = fractal_columns(t, &reports);
    let t = t
        .f64(
            "tip_radius_m",
            reports.iter().map(|r| r.reliability.map(|v| v.tip_radius)),
        )
        .f64(
            "reliability_cutoff_m",
            reports
                .iter()
                .map(|r| r.reliability.and_then(|v| v.cutoff.length())),
        )
        .f64("form_radius_m", reports.iter().map(|r| r.form_radius));
    let t = contact_columns(t, &reports).status(reports.iter().map(|r| &r.notes));
    settings_columns(t, &reports, params).build()
}

/// The fractal estimate and the wavelengths it was fitted between.
fn fractal_columns(t: TableBuilder, reports: &[&RoughnessReport]) -> TableBuilder {
    t.f64(
        "fractal_dimension",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().and_then(|e| e.dimension)),
    )
    .f64(
        "hurst_exponent",
        reports.iter().map(|r| r.fractal.as_ref().map(|e| e.hurst)),
    )
    .f64(
        "fractal_r_squared",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().map(|e| e.r_squared)),
    )
    .f64(
        "fractal_fit_min_m",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().map(|f| f.scales.0)),
    )
    .f64(
        "fractal_fit_max_m",
        reports
            .iter()
            .map(|r| r.fractal.as_ref().map(|f| f.scales.1)),
    )
}

/// The contact length of Eq. 3.14–3.15.
fn contact_columns(t: TableBuilder, reports: &[&RoughnessReport]) -> TableBuilder {
    t.f64(
        "area_ratio",
        reports.iter().map(|r| r.contact.map(|c| c.area_ratio)),
    )
    .f64(
        "contact_depth_m",
        reports.iter().map(|r| r.contact.map(|c| c.depth)),
    )
    .f64(
        "contact_length_m",
        reports.iter().map(|r| r.contact.map(|c| c.length)),
    )
}

/// The settings of the chain and the parameters, the same on every row
/// except the window (the instrument's when the file states one).
fn settings_columns(
    t: TableBuilder,
    reports: &[&RoughnessReport],
    params: &RoughnessParams,
) -> TableBuilder {
    let n = reports.len();
    let rep = |v: Option<f64>| std::iter::repeat_n(v, n);
    let reps = |v: Option<String>| std::iter::repeat_n(v, n);
    let f = params.filter;
    let polynomial = params.detrend == Detrend::Polynomial;
    t.f64(
        "window_start_m",
        reports.iter().map(|r| r.window.map(|w| w.0)),
    )
    .f64(
        "window_end_m",
        reports.iter().map(|r| r.window.map(|w| w.1)),
    )
    .f64("window_y_start_m", rep(params.window_y.map(|w| w.0)))
    .f64("window_y_end_m", rep(params.window_y.map(|w| w.1)))
    .f64("short_cutoff_m", rep(params.short_cutoff))
    .str("detrend", reps(Some(snake(&params.detrend))))
    .i64(
        "form_degree",
        std::iter::repeat_n(polynomial.then_some(params.form_degree as i64), n),
    )
    .str("filter", reps(f.map(|_| snake(&params.filter_kind))))
    .f64("filter_cutoff_m", rep(f.map(|f| f.cutoff)))
    .str("filter_ends", reps(f.map(|f| snake(&f.ends))))
    .str("derivative", reps(Some(snake(&params.derivative))))
    .str("fractal_method", reps(Some(snake(&params.fractal.method))))
    .str("rk_line", reps(Some(snake(&params.rk_line))))
    .f64("material_height_m", rep(Some(params.material_height)))
    .f64("material_ratio", rep(Some(params.material_ratio)))
    .f64("volume_p", rep(Some(params.volume_ratios.0)))
    .f64("volume_q", rep(Some(params.volume_ratios.1)))
    .f64("acf_threshold", rep(Some(params.acf_threshold)))
}

/// The Rk family, material ratio, volume, spatial and spacing columns of
/// one family (ISO 13565-2 and ISO 4287 names for profiles, ISO 25178-2
/// for maps); null on the rows of the other kind, and where the data
/// cannot support a parameter (the status says why).
fn functional_columns(
    t: TableBuilder,
    reports: &[&RoughnessReport],
    kind: SurfaceKind,
) -> TableBuilder {
    let col = |get: fn(&RoughnessReport) -> Option<f64>| {
        reports
            .iter()
            .map(move |r| if r.kind == kind { get(r) } else { None })
    };
    let f = |get: fn(&Functional) -> f64| {
        reports.iter().map(move |r| {
            (r.kind == kind)
                .then_some(r.functional.as_ref())
                .flatten()
                .map(get)
        })
    };
    match kind {
        SurfaceKind::Profile => t
            .f64("Rk_m", f(|f| f.rk.rk))
            .f64("Rpk_m", f(|f| f.rk.rpk))
            .f64("Rvk_m", f(|f| f.rk.rvk))
            .f64("Mr1", f(|f| f.rk.mr1))
            .f64("Mr2", f(|f| f.rk.mr2))
            .f64("A1_m", f(|f| f.rk.a1))
            .f64("A2_m", f(|f| f.rk.a2))
            .f64("Rmr", f(|f| f.smr))
            .f64("Rmc_m", f(|f| f.smc))
            .f64("RSm_m", col(|r| r.spatial.rsm)),
        SurfaceKind::Areal => t
            .f64("Sk_m", f(|f| f.rk.rk))
            .f64("Spk_m", f(|f| f.rk.rpk))
            .f64("Svk_m", f(|f| f.rk.rvk))
            .f64("Smr1", f(|f| f.rk.mr1))
            .f64("Smr2", f(|f| f.rk.mr2))
            .f64("Sxp_m", f(|f| f.sxp))
            .f64("Smr", f(|f| f.smr))
            .f64("Smc_m", f(|f| f.smc))
            .f64("Vmp_m3_per_m2", f(|f| f.volume.vmp))
            .f64("Vmc_m3_per_m2", f(|f| f.volume.vmc))
            .f64("Vvc_m3_per_m2", f(|f| f.volume.vvc))
            .f64("Vvv_m3_per_m2", f(|f| f.volume.vvv))
            .f64("Sdr", col(|r| r.spatial.sdr))
            .f64("Sal_m", col(|r| r.spatial.sal))
            .f64("Str", col(|r| r.spatial.str_ratio))
            .f64("Std_deg", col(|r| r.spatial.std_deg)),
    }
}

/// The amplitude, slope and height columns of one family: R-names for
/// profiles, S-names for maps; null on the rows of the other kind.
fn family_columns(
    t: TableBuilder,
    reports: &[&RoughnessReport],
    kind: SurfaceKind,
) -> TableBuilder {
    let p = if kind == SurfaceKind::Profile {
        "R"
    } else {
        "S"
    };
    let col = |get: fn(&RoughnessReport) -> Option<f64>| {
        reports
            .iter()
            .map(move |r| if r.kind == kind { get(r) } else { None })
    };
    let t = t
        .f64(&format!("{p}a_m"), col(|r| Some(r.ra)))
        .f64(&format!("{p}q_m"), col(|r| Some(r.rq)))
        .f64(&format!("{p}dq_deg"), col(|r| r.rdq_deg))
        .f64(&format!("{p}sk"), col(|r| r.rsk))
        .f64(&format!("{p}ku"), col(|r| r.rku))
        .f64(&format!("{p}p_m"), col(|r| Some(r.heights.peak)))
        .f64(&format!("{p}v_m"), col(|r| Some(r.heights.valley)));
    match kind {
        SurfaceKind::Profile => t
            .f64("Rt_m", col(|r| Some(r.heights.total)))
            .f64("Rz_m", col(|r| r.heights.rz_iso))
            .i64(
                "Rz_sampling_lengths",
                reports.iter().map(|r| {
                    (r.kind == kind && r.heights.rz_iso.is_some())
                        .then_some(r.heights.rz_sampling_lengths as i64)
                }),
            )
            .f64("Rz_DIN_m", col(|r| r.heights.rz_din)),
        SurfaceKind::Areal => t.f64("Sz_m", col(|r| Some(r.heights.total))),
    }
}

/// The instrument's printed results (null when the file prints none).
fn instrument_columns(
    t: TableBuilder,
    rows: &[(&RoughnessFile, &RoughnessReport)],
) -> TableBuilder {
    let col = |get: fn(&InstrumentRoughness) -> Option<f64>| {
        rows.iter().map(move |(f, _)| get(&f.instrument))
    };
    t.f64("instrument_Ra_m", col(|i| i.ra.map(|p| p.value)))
        .f64("instrument_Rq_m", col(|i| i.rq.map(|p| p.value)))
        .f64("instrument_Rsk", col(|i| i.rsk.map(|p| p.value)))
        .f64("instrument_Rz_DIN_m", col(|i| i.rz_din.map(|p| p.value)))
        .f64("instrument_window_start_m", col(|i| i.window.map(|w| w.0)))
        .f64("instrument_window_end_m", col(|i| i.window.map(|w| w.1)))
}

/// The `bearing_curve` table: material ratio and height for every report.
pub fn bearing_table(reports: &[&RoughnessReport]) -> Result<Table> {
    let rows: Vec<(&str, f64, f64)> = reports
        .iter()
        .flat_map(|r| r.bearing.iter().map(|&(m, h)| (r.source.as_str(), m, h)))
        .collect();
    TableBuilder::new()
        .str("source", rows.iter().map(|r| Some(r.0)))
        .f64("material_ratio", rows.iter().map(|r| Some(r.1)))
        .f64("height_m", rows.iter().map(|r| Some(r.2)))
        .build()
}

/// The `psd` table: the binned PSD of every report; `psd_m3` for profiles
/// (C1D), `psd_m4` for maps (C2D); `reliable` says whether the wavelength
/// is at or above the tip's reliability cut-off (null without a tip
/// radius).
pub fn psd_table(reports: &[&RoughnessReport]) -> Result<Table> {
    let rows: Vec<(&RoughnessReport, f64, f64)> = reports
        .iter()
        .flat_map(|r| r.psd.q.iter().zip(&r.psd.c).map(move |(&q, &c)| (*r, q, c)))
        .collect();
    let by_kind = |kind: SurfaceKind| {
        rows.iter()
            .map(move |(r, _, c)| (r.kind == kind).then_some(*c))
    };
    TableBuilder::new()
        .str("source", rows.iter().map(|r| Some(r.0.source.as_str())))
        .str("kind", rows.iter().map(|r| Some(r.0.kind.as_str())))
        .f64("q_rad_per_m", rows.iter().map(|r| Some(r.1)))
        .f64(
            "wavelength_m",
            rows.iter().map(|r| Some(2.0 * std::f64::consts::PI / r.1)),
        )
        .f64("psd_m3", by_kind(SurfaceKind::Profile))
        .f64("psd_m4", by_kind(SurfaceKind::Areal))
        .bool(
            "reliable",
            rows.iter().map(|(r, q, _)| {
                r.reliability.map(|v| {
                    v.cutoff
                        .length()
                        .is_none_or(|l| 2.0 * std::f64::consts::PI / q >= l)
                })
            }),
        )
        .str(
            "window",
            rows.iter()
                .map(|r| Some(if r.0.psd.windowed { "hann" } else { "none" })),
        )
        .build()
}

/// The `acf` table: the ACF of every report along x, along y and radially
/// averaged (profiles: along x).
pub fn acf_table(reports: &[&RoughnessReport]) -> Result<Table> {
    let rows: Vec<(&RoughnessReport, &AcfPoint)> = reports
        .iter()
        .flat_map(|r| r.acf.iter().map(move |p| (*r, p)))
        .collect();
    TableBuilder::new()
        .str("source", rows.iter().map(|r| Some(r.0.source.as_str())))
        .str("kind", rows.iter().map(|r| Some(r.0.kind.as_str())))
        .str("direction", rows.iter().map(|r| Some(r.1.direction)))
        .f64("lag_m", rows.iter().map(|r| Some(r.1.lag)))
        .f64("acf", rows.iter().map(|r| Some(r.1.value)))
        .build()
}

/// The serde (snake-case) name of a settings enum, for the table.
fn snake<T: Serialize>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(v) => v.to_string(),
        Err(_) => String::new(),
    }
}
