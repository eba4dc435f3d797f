//! Friction figures (MODELS.md §1): per section, the force with what was
//! decided on it — stroke boundaries, the static peak, the dynamic window,
//! each stick-slip event — then μ(t) with the instrument's μ over the same
//! windows, and μ(v) of velocity steps.

use super::{numbers, rows_where, Figure};
use crate::ingest::trace::Trace;
use crate::plot::{Axis, Chart, Colour, Style};
use crate::table::Table;

/// The tables the friction stage made for one file.
pub struct FrictionTables<'a> {
    /// `friction` rows (one per stroke).
    pub rows: &'a Table,
    /// `stickslip` events.
    pub events: &'a Table,
    /// `friction_steps` rows.
    pub steps: &'a Table,
}

/// Every figure of one file: force and μ per section, μ(v) where there
/// are velocity steps.
pub fn figures(source: &str, traces: &[Trace], t: &FrictionTables) -> Vec<Figure> {
    let mut out = Vec::new();
    for trace in traces {
        let rows = rows_where(t.rows, "section", &trace.section);
        let events = rows_where(t.events, "section", &trace.section);
        let label = title(source, &trace.section, traces.len());
        // The two charts of a long trace each thin it: both at once.
        let (force, mu) = rayon::join(
            || {
                let chart = force_chart(&label, trace, t, &rows, &events);
                Figure::draw(source, &trace.section, "force", &chart)
            },
            || {
                let chart = mu_chart(&label, trace, t.rows, &rows);
                Figure::draw(source, &trace.section, "mu", &chart)
            },
        );
        out.extend([force, mu]);
        let steps = rows_where(t.steps, "section", &trace.section);
        if steps.len() > 1 {
            out.push(Figure::draw(
                source,
                &trace.section,
                "steps",
                &steps_chart(&label, t.steps, &steps),
            ));
        }
    }
    out
}

fn title(source: &str, section: &str, sections: usize) -> String {
    let name = super::file_name(source);
    match sections > 1 {
        true => format!("{name} — {section}"),
        false => name,
    }
}

fn pick(v: &[f64], rows: &[usize]) -> Vec<f64> {
    rows.iter().map(|&i| v[i]).collect()
}

/// The force against time with the decisions drawn on it.
fn force_chart(
    label: &str,
    trace: &Trace,
    t: &FrictionTables,
    rows: &[usize],
    events: &[usize],
) -> Chart {
    let mut c = Chart::new(
        format!("{label}: friction force"),
        Axis::linear("time [s]"),
        Axis::linear("friction force T [N]"),
    );
    let sign = pick(&numbers(t.rows, "direction_sign"), rows);
    let start = pick(&numbers(t.rows, "segment_start_s"), rows);
    let (w0, w1) = (
        pick(&numbers(t.rows, "dynamic_window_start_s"), rows),
        pick(&numbers(t.rows, "dynamic_window_end_s"), rows),
    );
    for (k, (a, b)) in w0.iter().zip(&w1).enumerate() {
        let name = if k == 0 { "dynamic window" } else { "" };
        c.span(name, (*a, *b), Colour::Blue);
        if k > 0 && start[k].is_finite() {
            let name = if k == 1 { "stroke boundary" } else { "" };
            c.span(name, (start[k], start[k]), Colour::Grey);
        }
    }
    c.line("T", &trace.time_s, &trace.friction_n, Colour::Black);
    let peaks: Vec<(f64, f64)> = pick(&numbers(t.rows, "static_time_s"), rows)
        .into_iter()
        .zip(pick(&numbers(t.rows, "static_force_N"), rows))
        .zip(&sign)
        .map(|((x, y), s)| (x, y * s))
        .collect();
    c.push("static peak", peaks, Colour::Red, Style::Crosses);
    let strokes = numbers(t.events, "stroke");
    let stroke_rows = pick(&numbers(t.rows, "stroke"), rows);
    let ev_sign = |i: usize| {
        let k = stroke_rows
            .iter()
            .position(|s| s.to_bits() == strokes[i].to_bits());
        k.map_or(1.0, |k| sign[k])
    };
    let (et, ef) = (
        numbers(t.events, "peak_time_s"),
        numbers(t.events, "peak_force_N"),
    );
    let ev: Vec<(f64, f64)> = events
        .iter()
        .map(|&i| (et[i], ef[i] * ev_sign(i)))
        .collect();
    if !ev.is_empty() {
        c.push(
            format!("stick-slip ({})", ev.len()),
            ev,
            Colour::Orange,
            Style::Dots,
        );
    }
    c
}

/// μ = |T| / N against time, the instrument's μ, and per stroke the
/// dynamic μ with the instrument's mean over the same window.
fn mu_chart(label: &str, trace: &Trace, table: &Table, rows: &[usize]) -> Chart {
    let mut c = Chart::new(
        format!("{label}: coefficient of friction"),
        Axis::linear("time [s]"),
        Axis::linear("μ"),
    );
    // Computed as thinned: never a second copy of the trace. A sample a
    // column lacks is not drawn (NaN).
    let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(f64::NAN);
    if let Some(n) = &trace.normal_n {
        let f = &trace.friction_n;
        let mu = |i| match at(n, i) {
            n if n > 0.0 => at(f, i).abs() / n,
            _ => f64::NAN,
        };
        c.line_by("|T| / N", &trace.time_s, mu, Colour::Black);
    }
    if let Some(m) = &trace.instrument_cof {
        let abs = |i| at(m, i).abs();
        c.line_by("instrument μ", &trace.time_s, abs, Colour::Orange);
    }
    let col = |name: &str| pick(&numbers(table, name), rows);
    let (w0, w1, md, mi) = (
        col("dynamic_window_start_s"),
        col("dynamic_window_end_s"),
        col("mu_dynamic"),
        col("mu_instrument"),
    );
    for k in 0..rows.len() {
        let first = k == 0;
        let seg = |v: f64| vec![(w0[k], v), (w1[k], v)];
        c.push(
            if first { "μ dynamic" } else { "" },
            seg(md[k]),
            Colour::Blue,
            Style::Line,
        );
        if mi[k].is_finite() {
            let name = if first {
                "instrument μ, same window"
            } else {
                ""
            };
            c.push(name, seg(mi[k]), Colour::Orange, Style::Dashed);
        }
    }
    let statics: Vec<(f64, f64)> = col("static_time_s")
        .into_iter()
        .zip(col("mu_static"))
        .collect();
    c.push("μ static", statics, Colour::Red, Style::Crosses);
    c
}

/// μ against sliding velocity for velocity steps.
fn steps_chart(label: &str, steps: &Table, rows: &[usize]) -> Chart {
    let v = pick(&numbers(steps, "velocity_m_per_s"), rows);
    let log = v.iter().all(|x| *x > 0.0) && {
        let (lo, hi) = crate::plot::downsample::range(&v).unwrap_or((1.0, 1.0));
        hi > 20.0 * lo
    };
    let x = match log {
        true => Axis::log("sliding velocity [m/s]"),
        false => Axis::linear("sliding velocity [m/s]"),
    };
    let mut c = Chart::new(
        format!("{label}: μ of each velocity step"),
        x,
        Axis::linear("μ"),
    );
    let (mu, sd) = (
        pick(&numbers(steps, "mu_mean"), rows),
        pick(&numbers(steps, "mu_sd"), rows),
    );
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    c.bands.push(crate::plot::Band {
        name: "± sd".into(),
        points: order
            .iter()
            .map(|&i| (v[i], mu[i] - sd[i], mu[i] + sd[i]))
            .collect(),
        colour: Colour::Blue,
    });
    c.push(
        "μ mean",
        v.into_iter().zip(mu).collect(),
        Colour::Blue,
        Style::Dots,
    );
    c
}
