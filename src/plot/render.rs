//! Drawing a [`Chart`] with plotters' SVG backend. Log axes are drawn as
//! linear axes over log10 of the values, labelled with the values
//! themselves.

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::downsample::range;
use super::layout::{finite_runs, legend_place, ticks, Placement};
use super::legend;
use super::{Chart, Colour, Style};

type Failure = Box<dyn std::error::Error>;

pub(super) fn svg(c: &Chart) -> String {
    let mut out = String::new();
    let drawn = match c.is_empty() {
        true => Err("no data to draw".into()),
        false => draw(c, &mut out),
    };
    match drawn {
        Ok(Some(image)) => insert_image(out, &image),
        Ok(None) => out,
        Err(e) => notice(c, &e.to_string()),
    }
}

fn rgb(c: Colour) -> RGBColor {
    let (r, g, b) = c.rgb();
    RGBColor(r, g, b)
}

/// The value as drawn on a (possibly logarithmic) axis.
fn on_axis(v: f64, log: bool) -> f64 {
    match log {
        true if v > 0.0 => v.log10(),
        true => f64::NAN,
        false => v,
    }
}

/// The drawn range of one axis, padded by 4 % (a constant widened).
fn padded(values: Vec<f64>, fixed: Option<(f64, f64)>, log: bool) -> (f64, f64) {
    let (lo, hi) = match fixed {
        Some((a, b)) => (on_axis(a, log), on_axis(b, log)),
        None => range(&values).unwrap_or((0.0, 1.0)),
    };
    if hi > lo {
        let pad = 0.04 * (hi - lo);
        return (lo - pad, hi + pad);
    }
    let half = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
    (lo - half, hi + half)
}

/// A tick label; `scale` is the largest magnitude on the axis, so that
/// rounding residue at zero (−2e-16) reads as 0.
fn label(v: f64, log: bool, scale: f64) -> String {
    let v = if log { 10f64.powf(v) } else { v };
    let a = v.abs();
    if a == 0.0 || (!log && a < 1e-9 * scale) {
        "0".into()
    } else if !(1e-3..1e4).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// The ranges of both axes from everything drawn on them.
fn ranges(c: &Chart) -> ((f64, f64), (f64, f64)) {
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for s in &c.series {
        for &(x, y) in &s.points {
            xs.push(on_axis(x, c.x.log));
            ys.push(on_axis(y, c.y.log));
        }
    }
    for b in &c.bands {
        for &(x, lo, hi) in &b.points {
            xs.push(on_axis(x, c.x.log));
            ys.extend([on_axis(lo, c.y.log), on_axis(hi, c.y.log)]);
        }
    }
    if c.series.is_empty() && c.bands.is_empty() {
        xs.extend(c.spans.iter().flat_map(|s| [s.x.0, s.x.1]));
    }
    (
        padded(xs, c.x.range, c.x.log),
        padded(ys, c.y.range, c.y.log),
    )
}

/// Draws the chart into `out`; returns where a height image goes.
fn draw(c: &Chart, out: &mut String) -> Result<Option<(String, [i32; 4])>, Failure> {
    let ((x0, x1), (y0, y1)) = ranges(c);
    let entries = legend::entries(c);
    let labels: Vec<&str> = entries.iter().map(|e| e.label).collect();
    let size = legend::size(&labels);
    let place = (!entries.is_empty())
        .then(|| legend_place(c, |x, y| at(c, x, y), (x0, x1), (y0, y1), size));
    // A legend the data leave no corner for goes under the chart.
    let extra = match place {
        Some(Placement::Outside) => size.1 as u32 + 6,
        _ => 0,
    };
    let root = SVGBackend::with_string(out, (c.size.0, c.size.1 + extra)).into_drawing_area();
    root.fill(&WHITE)?;
    let (upper, _) = root.split_vertically(c.size.1);
    let mut chart = ChartBuilder::on(&upper)
        .caption(&c.title, ("sans-serif", 15))
        .margin(10)
        .x_label_area_size(42)
        .y_label_area_size(70)
        .build_cartesian_2d(Ticked::new(x0, x1, c.x.log), Ticked::new(y0, y1, c.y.log))?;
    let (sx, sy) = (x0.abs().max(x1.abs()), y0.abs().max(y1.abs()));
    let (fx, fy) = (
        |v: &f64| label(*v, c.x.log, sx),
        |v: &f64| label(*v, c.y.log, sy),
    );
    chart
        .configure_mesh()
        .x_desc(c.x.label.as_str())
        .y_desc(c.y.label.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .light_line_style(RGBColor(240, 240, 240))
        .draw()?;
    draw_spans(&mut chart, c, (y0, y1))?;
    draw_bands(&mut chart, c)?;
    draw_series(&mut chart, c)?;
    if let Some(place) = place {
        let plot = chart.plotting_area().get_pixel_range();
        let at = legend::origin(place, plot, (size.0 as i32, size.1 as i32), c.size.1 as i32);
        legend::draw(&root, at, &entries)?;
    }
    let image = c.image.as_ref().map(|img| {
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let (v, r, k) = super::png::shrink(&img.values, img.rows, img.cols, 200);
        let uri = super::png::data_uri(&v, r, k);
        (
            uri,
            [xr.start, yr.start, xr.end - xr.start, yr.end - yr.start],
        )
    });
    present(&root)?;
    Ok(image)
}

/// A linear axis (a log one is drawn over log10) marked at [`ticks`], its
/// labels from our formatter.
struct Ticked {
    inner: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Ticked {
    fn new(lo: f64, hi: f64, log: bool) -> Self {
        Ticked {
            inner: (lo..hi).into(),
            ticks: ticks(lo, hi, log),
        }
    }
}

impl Ranged for Ticked {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;
    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(v, limit)
    }
    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        match hint.weight().allow_light_points() {
            true => Vec::new(),
            false => self.ticks.clone(),
        }
    }
    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }
}

/// The chart being drawn.
type Ctx<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Ticked, Ticked>>;

/// A point as drawn on the chart's axes.
fn at(c: &Chart, x: f64, y: f64) -> (f64, f64) {
    (on_axis(x, c.x.log), on_axis(y, c.y.log))
}

/// Shaded windows and boundary lines, under everything else.
fn draw_spans(chart: &mut Ctx, c: &Chart, (y0, y1): (f64, f64)) -> Result<(), Failure> {
    for s in &c.spans {
        let (a, b) = (on_axis(s.x.0, c.x.log), on_axis(s.x.1, c.x.log));
        let colour = rgb(s.colour);
        match a.to_bits() == b.to_bits() {
            true => chart.draw_series(LineSeries::new([(a, y0), (a, y1)], colour.mix(0.6)))?,
            false => chart.draw_series([Rectangle::new(
                [(a, y0), (b, y1)],
                colour.mix(0.15).filled(),
            )])?,
        };
    }
    Ok(())
}

/// Bands as translucent polygons between their low and high curves, over
/// each run of two points or more whose values are all finite (on the
/// axes: a log axis has none at or below zero).
fn draw_bands(chart: &mut Ctx, c: &Chart) -> Result<(), Failure> {
    for b in &c.bands {
        let colour = rgb(b.colour);
        let drawn_points: Vec<(f64, f64, f64)> = b
            .points
            .iter()
            .map(|&(x, lo, hi)| (at(c, x, lo).0, at(c, x, lo).1, at(c, x, hi).1))
            .collect();
        let polys = finite_runs(&drawn_points).into_iter().map(|run| {
            let mut poly: Vec<(f64, f64)> = run.iter().map(|&(x, _, hi)| (x, hi)).collect();
            poly.extend(run.iter().rev().map(|&(x, lo, _)| (x, lo)));
            Polygon::new(poly, colour.mix(0.18).filled())
        });
        let polys: Vec<_> = polys.collect();
        if polys.is_empty() {
            continue;
        }
        chart.draw_series(polys)?;
    }
    Ok(())
}

/// Lines and markers, in order.
fn draw_series(chart: &mut Ctx, c: &Chart) -> Result<(), Failure> {
    for s in &c.series {
        let colour = rgb(s.colour);
        let pts = s
            .points
            .iter()
            .map(|&(x, y)| at(c, x, y))
            .filter(|(x, y)| x.is_finite() && y.is_finite());
        let line = colour.stroke_width(1);
        match s.style {
            Style::Line => chart.draw_series(LineSeries::new(pts, line))?,
            Style::Dashed => {
                chart.draw_series(DashedLineSeries::new(pts.collect::<Vec<_>>(), 6, 4, line))?
            }
            Style::Dots => chart.draw_series(pts.map(|q| Circle::new(q, 3, colour.filled())))?,
            Style::Crosses => {
                chart.draw_series(pts.map(|q| Cross::new(q, 5, colour.stroke_width(2))))?
            }
        };
    }
    Ok(())
}

fn present(root: &DrawingArea<SVGBackend, Shift>) -> Result<(), Failure> {
    root.present()?;
    Ok(())
}

/// Puts the image over the plotting area, before the closing tag.
fn insert_image(mut svg: String, (uri, [x, y, w, h]): &(String, [i32; 4])) -> String {
    let tag = format!(
        "<image x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" preserveAspectRatio=\"none\" href=\"{uri}\"/>\n"
    );
    match svg.rfind("</svg>") {
        Some(i) => svg.insert_str(i, &tag),
        None => svg.push_str(&tag),
    }
    svg
}

/// A figure that says why there is nothing to see.
fn notice(c: &Chart, why: &str) -> String {
    let (w, h) = (c.size.0, c.size.1 / 3);
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\
         <rect width=\"100%\" height=\"100%\" fill=\"#fafafa\" stroke=\"#ccc\"/>\
         <text x=\"12\" y=\"28\" font-family=\"sans-serif\" font-size=\"15\">{}</text>\
         <text x=\"12\" y=\"54\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#a33\">{}</text></svg>",
        super::escape(&c.title),
        super::escape(why)
    )
}

#[cfg(test)]
mod tests {
    use super::super::{Axis, Chart, Colour, Image, Style};

    fn chart() -> Chart {
        Chart::new("T(t)", Axis::linear("t [s]"), Axis::linear("T [N]"))
    }

    #[test]
    fn a_long_trace_gives_a_small_svg() {
        let n = 2_000_000;
        let xs: Vec<f64> = (0..n).map(|i| i as f64 * 1e-4).collect();
        let ys: Vec<f64> = xs.iter().map(|x| (x * 3.0).sin()).collect();
        let mut c = chart();
        c.line("trace", &xs, &ys, Colour::Black);
        c.span("window", (10.0, 20.0), Colour::Blue);
        c.span("", (50.0, 50.0), Colour::Grey);
        c.push("peak", vec![(5.2, 1.0)], Colour::Red, Style::Crosses);
        let svg = c.svg();
        assert!(svg.starts_with("<svg"), "{}", &svg[..100]);
        assert!(svg.contains("polyline"));
        assert!(svg.contains("T(t)") && svg.contains("window"));
        assert!(svg.len() < 200_000, "{} bytes", svg.len());
    }

    #[test]
    fn nothing_to_draw_says_so() {
        let svg = chart().svg();
        assert!(svg.contains("no data to draw"), "{svg}");
    }

    #[test]
    fn constant_and_non_finite_data_still_draw() {
        let mut c = chart();
        c.line(
            "flat",
            &[0.0, 1.0, 2.0],
            &[3.0, 3.0, f64::NAN],
            Colour::Black,
        );
        let mut l = Chart::new("log", Axis::log("v [m/s]"), Axis::linear("mu"));
        l.push(
            "mu",
            vec![(0.0, 1.0), (1e-3, 0.2), (1e-1, 0.1)],
            Colour::Blue,
            Style::Dots,
        );
        for svg in [c.svg(), l.svg()] {
            assert!(svg.starts_with("<svg") && !svg.contains("NaN"), "{svg}");
        }
    }

    #[test]
    fn a_height_map_is_embedded_as_png() {
        let mut c = Chart::new("map", Axis::linear("x [mm]"), Axis::linear("y [mm]"));
        c.push("", vec![(0.0, 0.0), (1.0, 1.0)], Colour::Black, Style::Dots);
        c.image = Some(Image {
            values: (0..400 * 300).map(|i| (i % 97) as f64).collect(),
            rows: 300,
            cols: 400,
        });
        let svg = c.svg();
        assert!(svg.contains("data:image/png;base64,"));
        assert!(svg.trim_end().ends_with("</svg>"));
    }
}
