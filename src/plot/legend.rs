//! The legend, drawn by us rather than by plotters: plotters keeps its
//! legend inside the plotting area (it squeezes one placed beside it to
//! zero width), and draws every entry even where several series share a
//! name and a look. Here an entry is a label and a swatch drawn as its
//! series is; entries that repeat are shown once; the box goes in a free
//! corner or, when the data leave none, under the chart.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::layout::{Corner, Placement};
use super::{Chart, Colour, Style};

type Failure = Box<dyn std::error::Error>;

/// How an entry is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Swatch {
    /// A shaded window or band: a translucent patch.
    Patch(Colour),
    /// A boundary (a span of zero width): a thin line.
    Rule(Colour),
    /// A series, in its style.
    Series(Colour, Style),
}

/// One line of the legend.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Entry<'c> {
    pub label: &'c str,
    pub swatch: Swatch,
}

/// The legend's lines in drawing order (spans, bands, series), each label
/// and look once.
pub(super) fn entries(c: &Chart) -> Vec<Entry<'_>> {
    let spans = c.spans.iter().map(|s| Entry {
        label: &s.name,
        swatch: match s.x.0.to_bits() == s.x.1.to_bits() {
            true => Swatch::Rule(s.colour),
            false => Swatch::Patch(s.colour),
        },
    });
    let bands = c.bands.iter().map(|b| Entry {
        label: &b.name,
        swatch: Swatch::Patch(b.colour),
    });
    let series = c.series.iter().map(|s| Entry {
        label: &s.name,
        swatch: Swatch::Series(s.colour, s.style),
    });
    let mut out: Vec<Entry> = Vec::new();
    for e in spans.chain(bands).chain(series) {
        if !e.label.is_empty() && !out.contains(&e) {
            out.push(e);
        }
    }
    out
}

/// Line height, inner margin and the swatch's width, in pixels.
const LINE: i32 = 18;
const PAD: i32 = 6;
const SWATCH: i32 = 16;

/// The legend's size in pixels: a line per entry, the swatch and the
/// longest label (12 px sans-serif, at most about 7 px a character).
pub(super) fn size(labels: &[&str]) -> (f64, f64) {
    let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    (
        chars as f64 * 7.0 + f64::from(SWATCH + 3 * PAD),
        labels.len() as f64 * f64::from(LINE) + f64::from(2 * PAD),
    )
}

/// The legend's upper left corner: inset 5 px in its corner of the
/// plotting area `plot` (pixel ranges), or at the left of the plot just
/// under the chart of height `below`.
pub(super) fn origin(
    place: Placement,
    plot: (std::ops::Range<i32>, std::ops::Range<i32>),
    (w, h): (i32, i32),
    below: i32,
) -> (i32, i32) {
    let (x, y) = plot;
    let left = x.start + 5;
    let right = x.end - w - 5;
    let top = y.start + 5;
    let bottom = y.end - h - 5;
    match place {
        Placement::Inside(Corner::UpperRight) => (right, top),
        Placement::Inside(Corner::UpperLeft) => (left, top),
        Placement::Inside(Corner::LowerRight) => (right, bottom),
        Placement::Inside(Corner::LowerLeft) => (left, bottom),
        Placement::Outside => (x.start, below + 2),
    }
}

/// Draws the box and its entries with its upper left corner at `(x, y)`.
pub(super) fn draw(
    root: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    entries: &[Entry],
) -> Result<(), Failure> {
    let labels: Vec<&str> = entries.iter().map(|e| e.label).collect();
    let (w, h) = size(&labels);
    let corner = [(x, y), (x + w as i32, y + h as i32)];
    root.draw(&Rectangle::new(corner, WHITE.mix(0.85).filled()))?;
    root.draw(&Rectangle::new(corner, RGBColor(200, 200, 200)))?;
    let font = ("sans-serif", 12)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (i, e) in entries.iter().enumerate() {
        let mid = y + PAD + LINE * i as i32 + LINE / 2;
        swatch(root, (x + PAD, mid), e.swatch)?;
        root.draw(&Text::new(e.label, (x + 2 * PAD + SWATCH, mid), &font))?;
    }
    Ok(())
}

/// A swatch [`SWATCH`] px wide whose left end is at `(x, y)`, drawn as its
/// series is: a dashed line dashed, dots as a dot, crosses as a cross.
fn swatch(
    root: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    swatch: Swatch,
) -> Result<(), Failure> {
    let rgb = |c: Colour| {
        let (r, g, b) = c.rgb();
        RGBColor(r, g, b)
    };
    let mid = (x + SWATCH / 2, y);
    match swatch {
        Swatch::Patch(c) => root.draw(&Rectangle::new(
            [(x, y - 4), (x + SWATCH, y + 4)],
            rgb(c).mix(0.3).filled(),
        ))?,
        Swatch::Rule(c) => root.draw(&PathElement::new(
            vec![(mid.0, y + 7), (mid.0, y - 7)],
            rgb(c).mix(0.6),
        ))?,
        Swatch::Series(c, style) => {
            let line = rgb(c).stroke_width(2);
            match style {
                Style::Line => root.draw(&PathElement::new(vec![(x, y), (x + SWATCH, y)], line))?,
                Style::Dashed => {
                    root.draw(&PathElement::new(vec![(x, y), (x + 6, y)], line))?;
                    root.draw(&PathElement::new(vec![(x + 10, y), (x + SWATCH, y)], line))?
                }
                Style::Dots => root.draw(&Circle::new(mid, 3, rgb(c).filled()))?,
                Style::Crosses => root.draw(&Cross::new(mid, 4, line))?,
            }
        }
    }
    Ok(())
}
