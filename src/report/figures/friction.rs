//! Friction figures (MODELS.md §1): per section, the force with what was
//! decided on it — stroke boundaries, the static peak, the dynamic window,
//! each stick-slip event — then μ(t) with the instrument's μ over the same
//! windows, and μ(v) of velocity steps.

use super::{num, Figure};
use crate::extract::friction::{FrictionRow, StepRow, StickSlipRow, TraceFeatures};
use crate::ingest::trace::Trace;
use crate::plot::{Axis, Chart, Colour, Style};

/// One section's rows, as the stage extracted them.
struct Section<'a> {
    /// Its segments (one per stroke).
    rows: Vec<&'a FrictionRow>,
    /// Its stick-slip events.
    events: Vec<&'a StickSlipRow>,
    /// Its velocity steps.
    steps: Vec<&'a StepRow>,
}

impl<'a> Section<'a> {
    /// The rows of the file's `features` whose section is `name`.
    fn of(features: &'a [TraceFeatures], name: &str) -> Self {
        let all = || features.iter();
        Section {
            rows: all()
                .flat_map(|f| &f.segments)
                .filter(|r| r.section == name)
                .collect(),
            events: all()
                .flat_map(|f| &f.events)
                .filter(|e| e.section == name)
                .collect(),
            steps: all()
                .flat_map(|f| &f.steps)
                .filter(|(s, _)| s == name)
                .map(|(_, s)| s)
                .collect(),
        }
    }

    /// A value of every segment (NaN where it has none).
    fn col(&self, get: impl Fn(&FrictionRow) -> Option<f64>) -> Vec<f64> {
        self.rows.iter().map(|r| num(get(r))).collect()
    }
}

/// Every figure of one file: force and μ per section, μ(v) where there
/// are velocity steps. `features` are the file's, one per trace.
pub fn figures(source: &str, traces: &[Trace], features: &[TraceFeatures]) -> Vec<Figure> {
    let mut out = Vec::new();
    for trace in traces {
        let sec = Section::of(features, &trace.section);
        let label = title(source, &trace.section, traces.len());
        // The two charts of a long trace each thin it: both at once.
        let (force, mu) = rayon::join(
            || {
                let chart = force_chart(&label, trace, &sec);
                Figure::draw(source, &trace.section, "force", &chart)
            },
            || {
                let chart = mu_chart(&label, trace, &sec);
                Figure::draw(source, &trace.section, "mu", &chart)
            },
        );
        out.extend([force, mu]);
        if sec.steps.len() > 1 {
            out.push(Figure::draw(
                source,
                &trace.section,
                "steps",
                &steps_chart(&label, &sec.steps),
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

/// The force against time with the decisions drawn on it.
fn force_chart(label: &str, trace: &Trace, sec: &Section) -> Chart {
    let mut c = Chart::new(
        format!("{label}: friction force"),
        Axis::linear("time [s]"),
        Axis::linear("friction force T [N]"),
    );
    let sign = sec.col(|r| r.direction_sign);
    let start = sec.col(|r| r.start_s);
    let (w0, w1) = (
        sec.col(|r| r.dynamic_window_start_s),
        sec.col(|r| r.dynamic_window_end_s),
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
    let peaks: Vec<(f64, f64)> = sec
        .col(|r| r.static_time_s)
        .into_iter()
        .zip(sec.col(|r| r.static_force_n))
        .zip(&sign)
        .map(|((x, y), s)| (x, y * s))
        .collect();
    c.push("static peak", peaks, Colour::Red, Style::Crosses);
    let stroke_rows = sec.col(|r| r.stroke.map(|s| s as f64));
    let ev_sign = |e: &StickSlipRow| {
        let stroke = e.stroke as f64;
        let k = stroke_rows
            .iter()
            .position(|s| s.to_bits() == stroke.to_bits());
        k.map_or(1.0, |k| sign[k])
    };
    let ev: Vec<(f64, f64)> = sec
        .events
        .iter()
        .map(|e| {
            let (t, f) = (e.event.peak_time_s, e.event.peak_force_n);
            (num(Some(t)), num(Some(f)) * ev_sign(e))
        })
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
fn mu_chart(label: &str, trace: &Trace, sec: &Section) -> Chart {
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
    let (w0, w1, md, mi) = (
        sec.col(|r| r.dynamic_window_start_s),
        sec.col(|r| r.dynamic_window_end_s),
        sec.col(|r| r.mu_dynamic),
        sec.col(|r| r.mu_instrument),
    );
    for k in 0..sec.rows.len() {
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
    let statics: Vec<(f64, f64)> = sec
        .col(|r| r.static_time_s)
        .into_iter()
        .zip(sec.col(|r| r.mu_static))
        .collect();
    c.push("μ static", statics, Colour::Red, Style::Crosses);
    c
}

/// μ against sliding velocity for velocity steps.
fn steps_chart(label: &str, steps: &[&StepRow]) -> Chart {
    let v: Vec<f64> = steps
        .iter()
        .map(|s| num(Some(s.velocity_m_per_s)))
        .collect();
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
    let (mu, sd): (Vec<f64>, Vec<f64>) =
        steps.iter().map(|s| (num(s.mu_mean), num(s.mu_sd))).unzip();
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
