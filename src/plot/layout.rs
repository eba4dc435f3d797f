//! Where things go on a chart: tick marks at values people read (decades
//! on a log axis, 1-2-5 steps on a linear one), the legend in a corner
//! free of data (or beside the plot), and bands split where they have no
//! value.

use super::{Chart, Style};

/// A 1, 2 or 5 times a power of ten, at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let p = 10f64.powf(raw.log10().floor());
    let m = raw / p;
    let k = match m {
        m if m <= 1.0 => 1.0,
        m if m <= 2.0 => 2.0,
        m if m <= 5.0 => 5.0,
        _ => 10.0,
    };
    k * p
}

/// About six ticks over [lo, hi] at multiples of a 1-2-5 step.
fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let step = nice_step((hi - lo) / 6.0);
    let (a, b) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    (a..=b).map(|k| k as f64 * step).collect()
}

/// Ticks of an axis drawn from `lo` to `hi`. A log axis is drawn over
/// log10 of the values: its ticks are the decades (every k-th over more
/// than eight), the 1-2-5 values of the decades when it spans less than
/// two, and 1-2-5 steps of the values when even those are fewer than two.
pub(super) fn ticks(lo: f64, hi: f64, log: bool) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    if !log {
        return linear_ticks(lo, hi);
    }
    let (a, b) = (lo.ceil() as i32, hi.floor() as i32);
    if b > a {
        let every = ((b - a) / 8 + 1) as usize;
        return (a..=b).step_by(every).map(f64::from).collect();
    }
    let decades = (lo.floor() as i32)..=(hi.ceil() as i32);
    let v: Vec<f64> = decades
        .flat_map(|d| [1.0, 2.0, 5.0].map(|m| (m * 10f64.powi(d)).log10()))
        .filter(|x| (lo..=hi).contains(x))
        .collect();
    if v.len() >= 2 {
        return v;
    }
    linear_ticks(10f64.powf(lo), 10f64.powf(hi))
        .into_iter()
        .filter(|v| *v > 0.0)
        .map(f64::log10)
        .collect()
}

/// A corner of the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Corner {
    UpperRight,
    UpperLeft,
    LowerRight,
    LowerLeft,
}

/// Where the legend goes: in a corner of the plotting area that no data
/// passes through, or, when every corner has some, outside it on the right
/// (a legend is never drawn over data).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Placement {
    Inside(Corner),
    Outside,
}

/// The plotting area's size in pixels for a chart of `size` (the margins,
/// caption and label areas of [`super::render`]).
pub(super) fn plot_size(size: (u32, u32)) -> (f64, f64) {
    (
        (size.0 as f64 - 90.0).max(60.0),
        (size.1 as f64 - 90.0).max(60.0),
    )
}

/// The corner whose legend-sized box no drawn data passes through (lines
/// are followed between their points, bands along both edges, boundaries
/// from bottom to top), the upper
/// right first; [`Placement::Outside`] when there is none. `at` maps a
/// point to the drawn axes; `x`, `y` are the drawn ranges; `legend` the
/// legend's size in pixels.
pub(super) fn legend_place(
    c: &Chart,
    at: impl Fn(f64, f64) -> (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    legend: (f64, f64),
) -> Placement {
    let (pw, ph) = plot_size(c.size);
    // The box as a fraction of the plotting area, with a few pixels of air.
    let (w, h) = (
        ((legend.0 + 10.0) / pw).min(0.95),
        ((legend.1 + 10.0) / ph).min(0.95),
    );
    let frac = |(x, y): (f64, f64)| {
        let (x, y) = at(x, y);
        ((x - x0) / (x1 - x0), (y - y0) / (y1 - y0))
    };
    let mut hit = [false; 4];
    let mut mark = |(fx, fy): (f64, f64)| {
        if !(fx.is_finite() && fy.is_finite()) {
            return;
        }
        let (right, left) = (fx >= 1.0 - w, fx <= w);
        let (top, bottom) = (fy >= 1.0 - h, fy <= h);
        for (k, inside) in [right && top, left && top, right && bottom, left && bottom]
            .into_iter()
            .enumerate()
        {
            hit[k] |= inside;
        }
    };
    for s in &c.series {
        let joined = matches!(s.style, Style::Line | Style::Dashed);
        trace(s.points.iter().map(|&p| frac(p)), joined, &mut mark);
    }
    // A boundary (a span of zero width) is a vertical line over the plot.
    for s in c
        .spans
        .iter()
        .filter(|s| s.x.0.to_bits() == s.x.1.to_bits())
    {
        let x = frac((s.x.0, f64::NAN)).0;
        trace([(x, 0.0), (x, 1.0)].into_iter(), true, &mut mark);
    }
    for b in &c.bands {
        trace(
            b.points.iter().map(|&(x, lo, _)| frac((x, lo))),
            true,
            &mut mark,
        );
        trace(
            b.points.iter().map(|&(x, _, hi)| frac((x, hi))),
            true,
            &mut mark,
        );
    }
    let corners = [
        Corner::UpperRight,
        Corner::UpperLeft,
        Corner::LowerRight,
        Corner::LowerLeft,
    ];
    match (0..4).find(|&k| !hit[k]) {
        Some(k) => Placement::Inside(corners[k]),
        None => Placement::Outside,
    }
}

/// Calls `mark` with each point and, when `joined`, with points every 1 %
/// of the plotting area along the segments between finite neighbours.
fn trace(
    points: impl Iterator<Item = (f64, f64)>,
    joined: bool,
    mark: &mut impl FnMut((f64, f64)),
) {
    let mut last: Option<(f64, f64)> = None;
    for p in points {
        let finite = p.0.is_finite() && p.1.is_finite();
        if let (Some(a), true, true) = (last, joined, finite) {
            let n = ((p.0 - a.0).abs().max((p.1 - a.1).abs()) / 0.01)
                .ceil()
                .min(1e4) as usize;
            for i in 1..n {
                let t = i as f64 / n as f64;
                mark((a.0 + t * (p.0 - a.0), a.1 + t * (p.1 - a.1)));
            }
        }
        mark(p);
        last = finite.then_some(p);
    }
}

/// The runs of consecutive points whose every value is finite, of two
/// points or more: a band is drawn over these only (a run of one point,
/// or a gap, would make a polygon across it).
pub(super) fn finite_runs(points: &[(f64, f64, f64)]) -> Vec<&[(f64, f64, f64)]> {
    points
        .split(|&(x, lo, hi)| !(x.is_finite() && lo.is_finite() && hi.is_finite()))
        .filter(|r| r.len() >= 2)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::{Axis, Chart, Colour, Style};
    use super::*;

    fn near(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    /// Velocities from 0.02 to 3 m/s: ticks at 0.1 and 1 (log10 −1, 0),
    /// never at 0.0251 or 0.0398.
    #[test]
    fn log_axes_are_marked_at_decades() {
        let t = ticks(0.02f64.log10(), 3f64.log10(), true);
        assert!(near(&t, &[-1.0, 0.0]), "{t:?}");
        let t = ticks(-12.0, 3.0, true);
        assert!(t.iter().all(|v| v.fract() == 0.0) && t.len() <= 9, "{t:?}");
        // Less than two decades: 1-2-5.
        let t = ticks(0.15f64.log10(), 3f64.log10(), true);
        let want: Vec<f64> = [0.2, 0.5, 1.0, 2.0]
            .iter()
            .map(|v: &f64| v.log10())
            .collect();
        assert!(near(&t, &want), "{t:?}");
        // Within a factor of two: steps of the values.
        let t = ticks(0.31f64.log10(), 0.39f64.log10(), true);
        assert!(t.len() >= 2, "{t:?}");
        for v in t {
            let x = 10f64.powf(v) * 100.0;
            assert!((x - x.round()).abs() < 1e-6, "{x}");
        }
    }

    #[test]
    fn linear_axes_are_marked_in_1_2_5_steps() {
        assert!(near(
            &ticks(0.0, 1.0, false),
            &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
        ));
        assert!(near(
            &ticks(-3.0, 27.0, false),
            &[0.0, 5.0, 10.0, 15.0, 20.0, 25.0]
        ));
        assert!(ticks(1.0, 1.0, false).is_empty());
        assert!(ticks(f64::NAN, 1.0, true).is_empty());
    }

    /// A curve rising to the upper right puts the legend upper left; a
    /// falling one puts it upper right.
    #[test]
    fn the_legend_goes_where_there_is_no_data() {
        let xs: Vec<f64> = (0..100).map(f64::from).collect();
        let rising: Vec<f64> = xs.iter().map(|x| x * x).collect();
        let mut c = Chart::new("", Axis::linear("x"), Axis::linear("y"));
        c.push(
            "curve",
            xs.iter().copied().zip(rising).collect(),
            Colour::Blue,
            Style::Line,
        );
        c.push("max", vec![(99.0, 9801.0)], Colour::Red, Style::Crosses);
        let id = |x, y| (x, y);
        let r = ((0.0, 99.0), (0.0, 9801.0));
        let small = super::super::legend::size(&["curve", "max"]);
        assert_eq!(
            legend_place(&c, id, r.0, r.1, small),
            Placement::Inside(Corner::UpperLeft)
        );
        let mut c = Chart::new("", Axis::linear("x"), Axis::linear("y"));
        let falling: Vec<(f64, f64)> = xs.iter().map(|x| (*x, 1.0 / (1.0 + x))).collect();
        c.push("decay", falling, Colour::Blue, Style::Line);
        assert_eq!(
            legend_place(
                &c,
                id,
                (0.0, 99.0),
                (0.0, 1.0),
                super::super::legend::size(&["decay"])
            ),
            Placement::Inside(Corner::UpperRight)
        );
    }

    /// Two points beside the upper right corner: as dots they leave it
    /// free; joined by a line, the segment between them crosses it. Lines
    /// through all four corners send the legend outside.
    #[test]
    fn lines_between_points_count_and_a_full_plot_puts_the_legend_outside() {
        let id = |x, y| (x, y);
        let r = ((0.0, 1.0), (0.0, 1.0));
        let size = super::super::legend::size(&["edge"]);
        let mut c = Chart::new("", Axis::linear("x"), Axis::linear("y"));
        c.push(
            "edge",
            vec![(0.8, 1.0), (1.0, 0.8)],
            Colour::Blue,
            Style::Dots,
        );
        let inside = |k| Placement::Inside(k);
        assert_eq!(
            legend_place(&c, id, r.0, r.1, size),
            inside(Corner::UpperRight)
        );
        // A boundary near the right edge runs through both right corners.
        c.span("cut-off", (0.97, 0.97), Colour::Red);
        assert_eq!(
            legend_place(&c, id, r.0, r.1, size),
            inside(Corner::UpperLeft)
        );
        c.spans.clear();
        c.series[0].style = Style::Line;
        assert_eq!(
            legend_place(&c, id, r.0, r.1, size),
            inside(Corner::UpperLeft)
        );
        let mut c = Chart::new("", Axis::linear("x"), Axis::linear("y"));
        c.push(
            "up",
            vec![(0.0, 0.0), (1.0, 1.0)],
            Colour::Blue,
            Style::Line,
        );
        c.push(
            "down",
            vec![(0.0, 1.0), (1.0, 0.0)],
            Colour::Red,
            Style::Dashed,
        );
        assert_eq!(legend_place(&c, id, r.0, r.1, size), Placement::Outside);
    }

    #[test]
    fn bands_are_drawn_over_runs_of_two_finite_points_or_more() {
        let nan = f64::NAN;
        let p = [
            (1.0, 0.1, 0.2),
            (2.0, nan, nan),
            (3.0, 0.1, 0.3),
            (4.0, 0.2, 0.4),
            (5.0, 0.2, nan),
        ];
        let runs = finite_runs(&p);
        assert_eq!(runs, vec![&p[2..4]]);
        assert!(finite_runs(&p[..1]).is_empty());
    }
}
