//! Roughness figures (MODELS.md §4): a profile as measured with its
//! evaluation window and least-squares reference line; the bearing
//! (Abbott–Firestone) curve with the contact depth; a map as a height
//! image.

use super::{num, Figure};
use crate::extract::roughness::input::Surface;
use crate::extract::roughness::material::RkFamily;
use crate::extract::roughness::stage::RoughnessFile;
use crate::extract::roughness::RoughnessParams;
use crate::extract::roughness::RoughnessReport;
use crate::extract::roughness::{AreaMap, Profile};
use crate::plot::{Axis, Chart, Colour, Image, Style};
use rayon::prelude::*;

/// A profile's measured line as its figure draws it (mm, µm), thinned to
/// the figure's pixel columns, for each surface (`None` for a map). It
/// needs no result, so it can be drawn while the analysis runs.
pub struct Thinned(Vec<Option<Vec<(f64, f64)>>>);

/// The measured lines of `surfaces`, thinned ([`Thinned`]).
pub fn thin(surfaces: &[Surface]) -> Thinned {
    let line = |p: &Profile| {
        // Scaled for the axes on all threads: a profile can hold 1e7 points.
        let x: Vec<f64> = (0..p.z.len()).into_par_iter().map(|i| mm(p, i)).collect();
        let z: Vec<f64> = p.z.par_iter().map(|v| v * 1e6).collect();
        crate::plot::downsample::min_max(&x, &z, crate::plot::SIZE.0 as usize)
    };
    Thinned(
        surfaces
            .iter()
            .map(|s| match s {
                Surface::Profile(p) => Some(line(p)),
                Surface::Map(_) => None,
            })
            .collect(),
    )
}

/// Position `i` of a profile in mm: as written when known.
fn mm(p: &Profile, i: usize) -> f64 {
    match &p.positions {
        Some(x) => x[i] * 1e3,
        None => (p.x0 + i as f64 * p.dx) * 1e3,
    }
}

/// Figures of one file's surfaces; `file` holds their reports (one per
/// surface), `params` the evaluation window, `thinned` their measured
/// lines.
pub fn figures(
    source: &str,
    surfaces: &[Surface],
    thinned: Thinned,
    file: &RoughnessFile,
    params: &RoughnessParams,
) -> Vec<Figure> {
    let name = super::file_name(source);
    let mut out = Vec::new();
    for (k, (s, line)) in surfaces.iter().zip(thinned.0).enumerate() {
        let part = if surfaces.len() > 1 {
            format!("{}", k + 1)
        } else {
            String::new()
        };
        // The window of the surface's report (the instrument's when the
        // settings give none); none without a report.
        let window = file.reports.get(k).and_then(|r| r.window).or(params.window);
        let chart = match s {
            Surface::Profile(p) => profile_chart(&name, p, line.unwrap_or_default(), window),
            Surface::Map(m) => map_chart(&name, m),
        };
        out.push(Figure::draw(source, &part, "surface", &chart));
    }
    for (k, r) in file.reports.iter().enumerate() {
        let part = if file.reports.len() > 1 {
            format!("{}", k + 1)
        } else {
            String::new()
        };
        if !r.bearing.is_empty() {
            out.push(Figure::draw(
                source,
                &part,
                "bearing",
                &bearing_chart(&name, r),
            ));
        }
        if !r.psd.q.is_empty() {
            out.push(Figure::draw(source, &part, "psd", &psd_chart(&name, r)));
        }
    }
    out
}

fn profile_chart(
    name: &str,
    p: &Profile,
    line: Vec<(f64, f64)>,
    window: Option<(f64, f64)>,
) -> Chart {
    let mut c = Chart::new(
        format!("{name}: profile"),
        Axis::linear("x [mm]"),
        Axis::linear("height [µm]"),
    );
    let (w0, w1) = (
        num(window.map(|w| w.0)) * 1e3,
        num(window.map(|w| w.1)) * 1e3,
    );
    let (w0, w1) = match w0.is_finite() && w1.is_finite() {
        true => (w0, w1),
        false => (mm(p, 0), mm(p, p.z.len() - 1)),
    };
    c.span("evaluation window", (w0, w1), Colour::Blue);
    c.push("as measured", line, Colour::Black, Style::Line);
    if let Some((a, b)) = line_fit(p, (w0, w1)) {
        let line = vec![(w0, a + b * w0), (w1, a + b * w1)];
        c.push("least-squares line", line, Colour::Orange, Style::Dashed);
    }
    c
}

/// Least-squares line `z = a + b x` (µm against mm) over the window. The
/// window's points are read again for each sum rather than copied (a
/// profile can hold 1e7), the independent sums side by side, each in order.
fn line_fit(p: &Profile, (lo, hi): (f64, f64)) -> Option<(f64, f64)> {
    let pts = || {
        (0..p.z.len())
            .map(|i| (mm(p, i), p.z[i] * 1e6))
            .filter(move |(x, _)| *x >= lo && *x <= hi)
    };
    let n = pts().count() as f64;
    if n < 2.0 {
        return None;
    }
    let (mx, mz) = rayon::join(
        || pts().map(|p| p.0).sum::<f64>() / n,
        || pts().map(|p| p.1).sum::<f64>() / n,
    );
    let (sxx, sxz): (f64, f64) = rayon::join(
        || pts().map(|p| (p.0 - mx).powi(2)).sum(),
        || pts().map(|p| (p.0 - mx) * (p.1 - mz)).sum(),
    );
    (sxx > 0.0).then(|| (mz - sxz / sxx * mx, sxz / sxx))
}

fn map_chart(name: &str, m: &AreaMap) -> Chart {
    let mut x = Axis::linear("x [mm]");
    let mut y = Axis::linear("y [mm]");
    x.range = Some((m.x0 * 1e3, (m.x0 + (m.nx - 1) as f64 * m.dx) * 1e3));
    y.range = Some((m.y0 * 1e3, (m.y0 + (m.ny - 1) as f64 * m.dy) * 1e3));
    let (lo, hi) = crate::plot::downsample::range(&m.z).unwrap_or((0.0, 0.0));
    let mut c = Chart::new(
        format!(
            "{name}: heights, {:.3} µm (dark) to {:.3} µm (light)",
            lo * 1e6,
            hi * 1e6
        ),
        x,
        y,
    );
    // Row 0 is y0, drawn at the bottom: the image's rows run top down.
    let mut values = Vec::with_capacity(m.z.len());
    for r in (0..m.ny).rev() {
        values.extend_from_slice(&m.z[r * m.nx..(r + 1) * m.nx]);
    }
    c.image = Some(Image {
        values,
        rows: m.ny,
        cols: m.nx,
    });
    c
}

/// The bearing (Abbott–Firestone) curve of a report with the Rk
/// construction (ISO 13565-2): the equivalent line through the central
/// 40 %, its heights c1 and c2 at 0 and 100 %, the ratios Mr1 and Mr2 where
/// the curve meets them, and the Rpk and Rvk triangles of the same areas as
/// the peak and valley zones; and the contact depth when computed.
fn bearing_chart(name: &str, r: &RoughnessReport) -> Chart {
    let mut c = Chart::new(
        format!("{name}: bearing curve"),
        Axis::linear("material ratio"),
        Axis::linear("height [µm]"),
    );
    let um = |h: f64| h * 1e6;
    let pts: Vec<(f64, f64)> = r.bearing.iter().map(|&(m, h)| (m, um(h))).collect();
    let top = pts.first().map_or(f64::NAN, |p| p.1);
    c.push("bearing curve", pts, Colour::Black, Style::Line);
    if let Some(f) = &r.functional {
        rk_construction(&mut c, &f.rk);
    }
    let contact = r.contact;
    let depth = num(contact.map(|c| c.depth));
    let ratio = num(contact.map(|c| c.area_ratio));
    if depth.is_finite() && top.is_finite() {
        let level = top - depth * 1e6;
        c.push(
            "contact depth",
            vec![(0.0, level), (1.0, level)],
            Colour::Red,
            Style::Dashed,
        );
        if ratio.is_finite() {
            c.push(
                "contact area ratio",
                vec![(ratio, level)],
                Colour::Red,
                Style::Crosses,
            );
        }
    }
    c
}

/// The Rk construction on a bearing chart: the equivalent line, c1/Mr1,
/// c2/Mr2 and the Rpk and Rvk triangles.
fn rk_construction(c: &mut Chart, k: &RkFamily) {
    let um = |h: f64| h * 1e6;
    let m = k.central_start;
    let line = |x: f64| um(k.c1 + (k.c2 - k.c1) * x);
    c.push(
        "equivalent line (central 40 %)",
        vec![(0.0, line(0.0)), (1.0, line(1.0))],
        Colour::Blue,
        Style::Dashed,
    );
    c.push(
        "",
        vec![(m, line(m)), (m + 0.4, line(m + 0.4))],
        Colour::Blue,
        Style::Line,
    );
    // The two construction lines look alike: one legend line for both.
    c.push(
        "c1 at Mr1, c2 at Mr2",
        vec![(0.0, um(k.c1)), (k.mr1, um(k.c1)), (k.mr1, um(k.c2))],
        Colour::Grey,
        Style::Dashed,
    );
    c.push(
        "",
        vec![(k.mr2, um(k.c1)), (k.mr2, um(k.c2)), (1.0, um(k.c2))],
        Colour::Grey,
        Style::Dashed,
    );
    c.push(
        "Rpk triangle",
        vec![
            (0.0, um(k.c1)),
            (0.0, um(k.c1 + k.rpk)),
            (k.mr1, um(k.c1)),
            (0.0, um(k.c1)),
        ],
        Colour::Orange,
        Style::Line,
    );
    c.push(
        "Rvk triangle",
        vec![
            (1.0, um(k.c2)),
            (1.0, um(k.c2 - k.rvk)),
            (k.mr2, um(k.c2)),
            (1.0, um(k.c2)),
        ],
        Colour::Green,
        Style::Line,
    );
}

/// The PSD of a report on log-log axes, with the fractal fit's range of
/// wavevectors shaded and the tip's reliability cut-off marked.
fn psd_chart(name: &str, r: &RoughnessReport) -> Chart {
    let areal = r.kind == crate::extract::roughness::SurfaceKind::Areal;
    let unit = if areal { "C2D [m⁴]" } else { "C1D [m³]" };
    let mut x = Axis::log("wavevector q [rad/m]");
    let (q0, q1) = (r.psd.q[0], r.psd.q[r.psd.q.len() - 1]);
    x.range = Some((q0, q1));
    let mut c = Chart::new(
        format!("{name}: power spectral density"),
        x,
        Axis::log(unit),
    );
    let tau = 2.0 * std::f64::consts::PI;
    if let Some(f) = &r.fractal {
        let (lo, hi) = f.scales;
        c.span(
            "fractal fit",
            ((tau / hi).max(q0), (tau / lo).min(q1)),
            Colour::Blue,
        );
    }
    if let Some(l) = r.reliability.and_then(|v| v.cutoff.length()) {
        let q = (tau / l).clamp(q0, q1);
        c.span("tip reliability cut-off", (q, q), Colour::Red);
    }
    let pts: Vec<(f64, f64)> = r
        .psd
        .q
        .iter()
        .copied()
        .zip(r.psd.c.iter().copied())
        .collect();
    c.push("PSD", pts, Colour::Black, Style::Line);
    c
}
