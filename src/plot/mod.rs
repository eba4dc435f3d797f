//! Figures as SVG text: what the report and `tribo plot` draw.
//!
//! A [`Chart`] is plain data — series, shaded windows, marks — that
//! [`Chart::svg`] draws with `plotters`' SVG backend (no fonts or native
//! libraries: the browser lays out the text). Long series are thinned to
//! the minimum and maximum of each pixel column ([`downsample`]) so a
//! 10 M-row trace draws as about two thousand points and looks the same.
//! Height maps are embedded as a PNG image ([`png`]).

pub mod downsample;
mod layout;
mod legend;
pub mod png;
mod render;

/// One of a few distinguishable colours (Okabe–Ito, readable by people
/// with colour-vision deficiencies).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Colour {
    /// Data.
    Black,
    /// First model or overlay.
    Blue,
    /// Second.
    Orange,
    /// Third.
    Green,
    /// Doubtful or rejected.
    Red,
    /// Fourth.
    Purple,
    /// Context (windows, boundaries).
    Grey,
}

impl Colour {
    /// The colour's red, green and blue.
    pub fn rgb(self) -> (u8, u8, u8) {
        match self {
            Colour::Black => (0, 0, 0),
            Colour::Blue => (0, 114, 178),
            Colour::Orange => (230, 159, 0),
            Colour::Green => (0, 158, 115),
            Colour::Red => (213, 94, 0),
            Colour::Purple => (204, 121, 167),
            Colour::Grey => (150, 150, 150),
        }
    }

    /// The `i`-th colour for a series of groups.
    pub fn cycle(i: usize) -> Colour {
        const ALL: [Colour; 5] = [
            Colour::Blue,
            Colour::Orange,
            Colour::Green,
            Colour::Purple,
            Colour::Black,
        ];
        ALL[i % ALL.len()]
    }
}

/// How points of a series are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// Joined by a line.
    Line,
    /// Dashed line.
    Dashed,
    /// Filled circles.
    Dots,
    /// Crosses (marked points: misfits, rejected values).
    Crosses,
}

/// A named series of points.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text; empty for none.
    pub name: String,
    /// The points (non-finite ones are skipped).
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: Colour,
    /// Line or markers.
    pub style: Style,
}

/// A band between two curves (a confidence band).
#[derive(Debug, Clone)]
pub struct Band {
    /// Legend text.
    pub name: String,
    /// `(x, low, high)`.
    pub points: Vec<(f64, f64, f64)>,
    /// Colour (drawn translucent).
    pub colour: Colour,
}

/// A shaded x interval (an evaluation window) or, with equal ends, a
/// vertical line (a boundary).
#[derive(Debug, Clone)]
pub struct Span {
    /// Legend text; empty for none.
    pub name: String,
    /// Start and end along x.
    pub x: (f64, f64),
    /// Colour (drawn translucent).
    pub colour: Colour,
}

/// A height image drawn under the axes.
#[derive(Debug, Clone)]
pub struct Image {
    /// Row-major values, `rows × cols`, row 0 at the top.
    pub values: Vec<f64>,
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
}

/// An axis: its label with unit, and whether it is logarithmic.
#[derive(Debug, Clone, Default)]
pub struct Axis {
    /// Label, with the unit in brackets.
    pub label: String,
    /// Log scale (non-positive values are skipped).
    pub log: bool,
    /// A fixed range instead of the data's.
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// A linear axis.
    pub fn linear(label: impl Into<String>) -> Self {
        Axis {
            label: label.into(),
            ..Default::default()
        }
    }
    /// A logarithmic axis.
    pub fn log(label: impl Into<String>) -> Self {
        Axis {
            label: label.into(),
            log: true,
            range: None,
        }
    }
}

/// A figure: title, axes and what is drawn on them.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Title.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Series, drawn in order.
    pub series: Vec<Series>,
    /// Bands, drawn under the series.
    pub bands: Vec<Band>,
    /// Shaded windows and boundaries, drawn first.
    pub spans: Vec<Span>,
    /// A height image filling the plotting area.
    pub image: Option<Image>,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

/// Default figure size in pixels.
pub const SIZE: (u32, u32) = (720, 360);

impl Chart {
    /// An empty chart with a title and two linear axes.
    pub fn new(title: impl Into<String>, x: Axis, y: Axis) -> Self {
        Chart {
            title: title.into(),
            x,
            y,
            size: SIZE,
            ..Default::default()
        }
    }

    /// Adds a line, thinned to at most two points per pixel column.
    pub fn line(&mut self, name: impl Into<String>, xs: &[f64], ys: &[f64], colour: Colour) {
        let columns = self.size.0 as usize;
        let points = downsample::min_max(xs, ys, columns);
        self.push(name, points, colour, Style::Line);
    }

    /// [`Chart::line`] of heights `y(i)` at `xs[i]`, computed as they are
    /// thinned (a derived series of a long record is never held whole).
    pub fn line_by(
        &mut self,
        name: impl Into<String>,
        xs: &[f64],
        y: impl Fn(usize) -> f64 + Sync,
        colour: Colour,
    ) {
        let columns = self.size.0 as usize;
        let points = downsample::min_max_by(xs, y, columns);
        self.push(name, points, colour, Style::Line);
    }

    /// Adds a series as given (few points: markers, fitted lines).
    pub fn push(
        &mut self,
        name: impl Into<String>,
        points: Vec<(f64, f64)>,
        colour: Colour,
        style: Style,
    ) {
        self.series.push(Series {
            name: name.into(),
            points,
            colour,
            style,
        });
    }

    /// Adds a shaded window (or a line where `x.0 == x.1`).
    pub fn span(&mut self, name: impl Into<String>, x: (f64, f64), colour: Colour) {
        self.spans.push(Span {
            name: name.into(),
            x,
            colour,
        });
    }

    /// Whether anything would be drawn.
    pub fn is_empty(&self) -> bool {
        self.image.is_none()
            && self.series.iter().all(|s| s.points.is_empty())
            && self.bands.iter().all(|b| b.points.is_empty())
    }

    /// The figure as a standalone SVG document. A chart with nothing to
    /// draw gives a figure that says so.
    pub fn svg(&self) -> String {
        render::svg(self)
    }
}

/// Escapes text for HTML and SVG.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}
