//! The friction stage's tables: `friction`, `friction_steps`, `stickslip`,
//! `traces` and `friction_figures`, declared here with the code that turns
//! the stage's typed rows into their columns (schemas in `schemas/`).

use super::analysis::FrictionFile;
use crate::error::Result;
use crate::extract::friction::FrictionRow;
use crate::ingest::trace::Trace;
use crate::report::figures::file_figures_table;
use crate::schema::{Show, TableDef};
use crate::table::{Table, TableBuilder};

/// One row per stroke (segment) of every trace.
pub static FRICTION: TableDef = TableDef::new(
    "friction",
    include_str!("../../../schemas/friction.toml"),
    Show::PerFile(&[
        ("section", "section"),
        ("stroke", "stroke"),
        ("mu_static", "μ static"),
        ("mu_dynamic", "μ dynamic"),
        ("mu_instrument", "μ instrument"),
        ("stickslip_events", "stick-slip"),
        ("status", "status"),
    ]),
);

/// One row per velocity step.
pub static FRICTION_STEPS: TableDef = TableDef::new(
    "friction_steps",
    include_str!("../../../schemas/friction_steps.toml"),
    Show::Hidden,
);

/// One row per stick-slip event.
pub static STICKSLIP: TableDef = TableDef::new(
    "stickslip",
    include_str!("../../../schemas/stickslip.toml"),
    Show::Hidden,
);

/// Every sample of every trace, in SI: a dataset, one file per input.
pub static TRACES: TableDef = TableDef::dataset(
    "traces",
    include_str!("../../../schemas/traces.toml"),
    Show::Hidden,
);

/// Force and μ per section, μ(v) of velocity steps.
pub static FRICTION_FIGURES: TableDef = file_figures_table("friction_figures");

fn usize_col(v: impl IntoIterator<Item = usize>) -> impl Iterator<Item = Option<i64>> {
    v.into_iter().map(|x| Some(x as i64))
}

/// `friction.parquet`: one row per segment.
pub fn friction_table(files: &[FrictionFile]) -> Result<Table> {
    let rows: Vec<(&FrictionFile, &FrictionRow)> = files
        .iter()
        .flat_map(|f| {
            f.features
                .iter()
                .flat_map(move |t| t.segments.iter().map(move |r| (f, r)))
        })
        .collect();
    let s = |g: fn(&FrictionFile) -> Option<String>| {
        rows.iter().map(move |(f, _)| g(f)).collect::<Vec<_>>()
    };
    let sf = |g: fn(&FrictionFile) -> Option<f64>| {
        rows.iter().map(move |(f, _)| g(f)).collect::<Vec<_>>()
    };
    let r = |g: fn(&FrictionRow) -> Option<f64>| {
        rows.iter().map(move |(_, r)| g(r)).collect::<Vec<_>>()
    };
    TableBuilder::new()
        .str("source", rows.iter().map(|(f, _)| Some(&f.source)))
        .str("section", rows.iter().map(|(_, r)| Some(&r.section)))
        .i64(
            "stroke",
            rows.iter().map(|(_, r)| r.stroke.map(|s| s as i64)),
        )
        .str("sample_id", s(|f| f.sample.sample_id.clone()))
        .str("test_started_at", s(|f| f.started_at.clone()))
        .str("pattern", s(|f| f.sample.pattern.clone()))
        .f64("area_fraction", sf(|f| f.sample.area_fraction))
        .f64("apparent_area_m2", sf(|f| f.sample.apparent_area_m2))
        .str("material", s(|f| f.sample.material.clone()))
        .str("pin", s(|f| f.sample.pin.clone()))
        .str("direction", s(|f| f.sample.direction.clone()))
        .f64("temperature_C", sf(|f| f.sample.temperature_c))
        .f64("direction_sign", r(|r| r.direction_sign))
        .f64("segment_start_s", r(|r| r.start_s))
        .f64("segment_end_s", r(|r| r.end_s))
        .i64(
            "n_samples",
            usize_col(rows.iter().map(|(_, r)| r.n_samples)),
        )
        .i64(
            "n_nan_dropped",
            usize_col(rows.iter().map(|(_, r)| r.n_nan_dropped)),
        )
        .f64("noise_N", r(|r| r.noise_n))
        .f64("normal_force_N", r(|r| r.normal_force_n))
        .str(
            "normal_force_source",
            rows.iter().map(|(_, r)| r.normal_force_source),
        )
        .str(
            "friction_force_source",
            rows.iter().map(|(_, r)| r.friction_force_source),
        )
        .f64("static_force_N", r(|r| r.static_force_n))
        .f64("static_time_s", r(|r| r.static_time_s))
        .f64("static_prominence_N", r(|r| r.static_prominence_n))
        .f64("mu_static", r(|r| r.mu_static))
        .f64("dynamic_force_N", r(|r| r.dynamic_force_n))
        .f64("dynamic_force_sd_N", r(|r| r.dynamic_force_sd_n))
        .f64("mu_dynamic", r(|r| r.mu_dynamic))
        .f64("mu_dynamic_sd", r(|r| r.mu_dynamic_sd))
        .f64("dynamic_window_start_s", r(|r| r.dynamic_window_start_s))
        .f64("dynamic_window_end_s", r(|r| r.dynamic_window_end_s))
        .i64(
            "dynamic_n",
            rows.iter().map(|(_, r)| r.dynamic_n.map(|n| n as i64)),
        )
        .f64("mu_instrument", r(|r| r.mu_instrument))
        .i64(
            "stickslip_events",
            usize_col(rows.iter().map(|(_, r)| r.stickslip_events)),
        )
        .f64("stickslip_mean_drop_N", r(|r| r.stickslip_mean_drop_n))
        .f64("stickslip_frequency_Hz", r(|r| r.stickslip_frequency_hz))
        .status(rows.iter().map(|(_, r)| &r.status))
        .build()
}

/// The track radius that gave a section's sliding speed from its rpm.
fn radius_of(f: &FrictionFile, section: &str) -> Option<crate::ingest::radius::TrackRadius> {
    f.traces
        .iter()
        .find(|t| t.section == section)
        .and_then(|t| t.track_radius)
}

/// `friction_steps.parquet`: one row per velocity step.
pub fn steps_table(files: &[FrictionFile]) -> Result<Table> {
    let rows: Vec<_> = files
        .iter()
        .flat_map(|f| {
            f.features
                .iter()
                .flat_map(move |t| t.steps.iter().map(move |(sec, s)| (f, sec, s)))
        })
        .collect();
    TableBuilder::new()
        .str("source", rows.iter().map(|(f, _, _)| Some(&f.source)))
        .str("section", rows.iter().map(|(_, sec, _)| Some(sec)))
        .i64("step", usize_col(rows.iter().map(|(_, _, s)| s.step)))
        .str(
            "step_source",
            rows.iter().map(|(_, _, s)| Some(s.source.as_str())),
        )
        .str(
            "sample_id",
            rows.iter().map(|(f, _, _)| f.sample.sample_id.as_ref()),
        )
        .str(
            "test_started_at",
            rows.iter().map(|(f, _, _)| f.started_at.as_ref()),
        )
        .str("pin", rows.iter().map(|(f, _, _)| f.sample.pin.as_ref()))
        .f64(
            "temperature_C",
            rows.iter().map(|(f, _, _)| f.sample.temperature_c),
        )
        .f64_values(
            "velocity_m_per_s",
            rows.iter().map(|(_, _, s)| s.velocity_m_per_s),
        )
        .f64(
            "track_radius_m",
            rows.iter()
                .map(|(f, sec, _)| radius_of(f, sec).map(|r| r.radius_m)),
        )
        .str(
            "track_radius_source",
            rows.iter()
                .map(|(f, sec, _)| radius_of(f, sec).map(|r| r.source.as_str())),
        )
        .f64("mu_mean", rows.iter().map(|(_, _, s)| s.mu_mean))
        .f64("mu_sd", rows.iter().map(|(_, _, s)| s.mu_sd))
        .i64("n", usize_col(rows.iter().map(|(_, _, s)| s.n)))
        .f64_values("start_s", rows.iter().map(|(_, _, s)| s.start_s))
        .f64_values("end_s", rows.iter().map(|(_, _, s)| s.end_s))
        .f64(
            "normal_force_N",
            rows.iter().map(|(_, _, s)| s.normal_force_n),
        )
        .f64(
            "normal_start_N",
            rows.iter().map(|(_, _, s)| s.ramp_n.map(|r| r.0)),
        )
        .f64(
            "normal_end_N",
            rows.iter().map(|(_, _, s)| s.ramp_n.map(|r| r.1)),
        )
        .f64(
            "contact_pressure_Pa",
            rows.iter()
                .map(|(_, _, s)| s.stribeck.pressure.map(|p| p.0)),
        )
        .str(
            "pressure_kind",
            rows.iter()
                .map(|(_, _, s)| s.stribeck.pressure.map(|p| p.1.as_str())),
        )
        .f64(
            "stribeck_m",
            rows.iter().map(|(_, _, s)| s.stribeck.parameter_m),
        )
        .f64("film_min_m", rows.iter().map(|(_, _, s)| s.stribeck.film_m))
        .f64(
            "film_parameter",
            rows.iter().map(|(_, _, s)| s.stribeck.lambda),
        )
        .f64(
            "hersey_number",
            rows.iter().map(|(_, _, s)| s.stribeck.hersey),
        )
        .status(rows.iter().map(|(_, _, s)| &s.status))
        .build()
}

/// `stickslip.parquet`: one row per event.
pub fn stickslip_table(files: &[FrictionFile]) -> Result<Table> {
    let rows: Vec<_> = files
        .iter()
        .flat_map(|f| {
            f.features
                .iter()
                .flat_map(move |t| t.events.iter().map(move |e| (f, e)))
        })
        .collect();
    TableBuilder::new()
        .str("source", rows.iter().map(|(f, _)| Some(&f.source)))
        .str("section", rows.iter().map(|(_, e)| Some(&e.section)))
        .str(
            "test_started_at",
            rows.iter().map(|(f, _)| f.started_at.as_ref()),
        )
        .i64("stroke", usize_col(rows.iter().map(|(_, e)| e.stroke)))
        .f64_values("peak_time_s", rows.iter().map(|(_, e)| e.event.peak_time_s))
        .f64_values(
            "peak_force_N",
            rows.iter().map(|(_, e)| e.event.peak_force_n),
        )
        .f64_values("drop_N", rows.iter().map(|(_, e)| e.event.drop_n))
        .f64_values("rise_time_s", rows.iter().map(|(_, e)| e.event.rise_time_s))
        .f64_values("drop_time_s", rows.iter().map(|(_, e)| e.event.drop_time_s))
        .f64("period_s", rows.iter().map(|(_, e)| e.event.period_s))
        .build()
}

/// `traces.parquet`: every sample in SI, with the stroke it belongs to.
/// Built from the columns, which it takes: the file and section names are
/// dictionary columns built from runs (each name stored once, a code per
/// row, and written to Parquet without hashing a string per row), the values of a single
/// trace become the table's buffers without a copy (several are joined),
/// and a channel no trace has is a null column, not a column of NaN.
pub fn traces_table(files: Vec<FrictionFile>) -> Result<Table> {
    let lens: Vec<usize> = files
        .iter()
        .flat_map(|f| f.traces.iter().map(Trace::len))
        .collect();
    let strokes: Vec<(Option<i64>, usize)> = files
        .iter()
        .flat_map(|f| {
            f.traces.iter().enumerate().flat_map(|(i, t)| {
                let segments = f.features.get(i).map_or(&[][..], |x| &x.segments[..]);
                stroke_runs(&t.time_s, segments)
            })
        })
        .collect();
    let source_runs: Vec<(Option<String>, usize)> = files
        .iter()
        .flat_map(|f| f.traces.iter().map(|t| (Some(f.source.clone()), t.len())))
        .collect();
    let section_runs: Vec<(Option<String>, usize)> = files
        .iter()
        .flat_map(|f| f.traces.iter().map(|t| (Some(t.section.clone()), t.len())))
        .collect();
    let mut traces: Vec<Trace> = files.into_iter().flat_map(|f| f.traces).collect();
    let mut b = TableBuilder::new()
        .cat_runs("source", source_runs)
        .cat_runs("section", section_runs)
        .i64_runs("stroke", strokes);
    type Take = fn(&mut Trace) -> Option<Vec<f64>>;
    let columns: [(&str, Take); 7] = [
        ("time_s", |t| Some(std::mem::take(&mut t.time_s))),
        ("friction_force_N", |t| {
            Some(std::mem::take(&mut t.friction_n))
        }),
        ("normal_force_N", |t| t.normal_n.take()),
        ("velocity_m_per_s", |t| t.velocity_m_per_s.take()),
        ("position_m", |t| t.position_m.take()),
        ("temperature_K", |t| t.temperature_k.take()),
        ("mu_instrument", |t| t.instrument_cof.take()),
    ];
    let total = lens.iter().sum();
    for (name, take) in columns {
        let parts: Vec<Option<Vec<f64>>> = traces.iter_mut().map(take).collect();
        b = match joined(parts, &lens, total) {
            Some(v) => b.f64_vec(name, v),
            None => b.f64_null(name, total),
        };
    }
    b.build()
}

/// One column of several traces joined (a single trace's taken whole; a
/// trace without the channel gives NaN, null in the table); `None` when no
/// trace has it.
fn joined(mut parts: Vec<Option<Vec<f64>>>, lens: &[usize], total: usize) -> Option<Vec<f64>> {
    if parts.iter().all(Option::is_none) {
        return None;
    }
    if let [Some(v)] = parts.as_mut_slice() {
        return Some(std::mem::take(v));
    }
    let mut out = Vec::with_capacity(total);
    for (p, &n) in parts.into_iter().zip(lens) {
        match p {
            Some(v) => out.extend_from_slice(&v),
            None => out.extend(std::iter::repeat_n(f64::NAN, n)),
        }
    }
    Some(out)
}

/// The stroke of every sample as runs: the `stroke` of the friction row
/// whose segment (`segment_start_s` to `segment_end_s`) holds the sample's
/// time, null outside every segment (between strokes, a trace that could
/// not be segmented, a sample without time).
fn stroke_runs(time_s: &[f64], segments: &[FrictionRow]) -> Vec<(Option<i64>, usize)> {
    let mut spans: Vec<(f64, f64, i64)> = segments
        .iter()
        .filter_map(|r| Some((r.start_s?, r.end_s?, r.stroke? as i64)))
        .collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut runs: Vec<(Option<i64>, usize)> = Vec::new();
    for &t in time_s {
        // The last segment starting at or before t, if t is within it.
        let k = spans.partition_point(|s| s.0 <= t);
        let stroke = k
            .checked_sub(1)
            .map(|k| spans[k])
            .filter(|s| t <= s.1)
            .map(|s| s.2);
        match runs.last_mut() {
            Some((s, n)) if *s == stroke => *n += 1,
            _ => runs.push((stroke, 1)),
        }
    }
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_take_the_stroke_whose_span_holds_their_time() {
        let row = |k: usize, a: f64, b: f64| FrictionRow {
            stroke: Some(k),
            start_s: Some(a),
            end_s: Some(b),
            ..Default::default()
        };
        // Given out of order, as a table might hold them.
        let segments = [row(2, 2.0, 3.0), row(1, 0.0, 1.0)];
        let t = [0.0, 0.5, 1.0, 1.5, 2.0, 3.0, f64::NAN, 4.0];
        assert_eq!(
            stroke_runs(&t, &segments),
            vec![(Some(1), 3), (None, 1), (Some(2), 2), (None, 2)]
        );
        let invalid = FrictionRow::default();
        assert_eq!(stroke_runs(&t[..2], &[invalid]), vec![(None, 2)]);
    }
}
