//! Thinning long series for drawing: within each run of points that fall
//! in one pixel column, only the lowest and the highest are kept, in their
//! order. The drawn line covers exactly the pixels the full line would
//! (every extreme is kept), at about two points per column whatever the
//! length of the record.
//!
//! Heights are stored ([`min_max`]) or computed from the index
//! ([`min_max_by`]: μ = |T| / N of a long trace is thinned without ever
//! being held whole).

use crate::signal::scan::{extremes, first_pair};
use rayon::prelude::*;
use std::ops::Range;

/// The heights of a series, read one at a time or by stretch.
trait Heights: Sync {
    /// The height at `i`.
    fn at(&self, i: usize) -> f64;
    /// The heights of `r`: borrowed when stored, else computed into `buf`.
    fn stretch<'a>(&'a self, r: Range<usize>, buf: &'a mut Vec<f64>) -> &'a [f64];
}

impl Heights for [f64] {
    fn at(&self, i: usize) -> f64 {
        self[i]
    }
    fn stretch<'a>(&'a self, r: Range<usize>, _: &'a mut Vec<f64>) -> &'a [f64] {
        &self[r]
    }
}

/// Heights computed from the index.
struct Computed<F>(F);

impl<F: Fn(usize) -> f64 + Sync> Heights for Computed<F> {
    fn at(&self, i: usize) -> f64 {
        (self.0)(i)
    }
    fn stretch<'a>(&'a self, r: Range<usize>, buf: &'a mut Vec<f64>) -> &'a [f64] {
        buf.clear();
        buf.extend(r.map(&self.0));
        buf
    }
}

/// The points of `(xs, ys)` to draw on a chart `columns` pixels wide.
/// Non-finite points are dropped. Points are kept in input order; where x
/// goes back and forth so often that runs stay short, every k-th run is
/// kept instead, so the result never exceeds about four points per column.
pub fn min_max(xs: &[f64], ys: &[f64], columns: usize) -> Vec<(f64, f64)> {
    let n = xs.len().min(ys.len());
    thin(&xs[..n], ys, columns)
}

/// [`min_max`] of the heights `y(i)` at `xs[i]`, each computed when read.
pub fn min_max_by(xs: &[f64], y: impl Fn(usize) -> f64 + Sync, columns: usize) -> Vec<(f64, f64)> {
    thin(xs, &Computed(y), columns)
}

fn thin<H: Heights + ?Sized>(xs: &[f64], ys: &H, columns: usize) -> Vec<(f64, f64)> {
    let n = xs.len();
    let columns = columns.max(1);
    if n <= 2 * columns {
        return (0..n)
            .map(|i| (xs[i], ys.at(i)))
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
    }
    // A time base's range is its ends: the ordered check first saves a
    // pass over x.
    let sorted = is_ordered(xs);
    let Some((lo, hi)) = (if sorted {
        Some((xs[0], xs[n - 1]))
    } else {
        range(xs)
    }) else {
        return Vec::new();
    };
    let width = (hi - lo).max(f64::MIN_POSITIVE);
    let column = |x: f64| (((x - lo) / width) * columns as f64).min(columns as f64 - 1.0) as usize;
    let joined = match sorted {
        true => sorted_runs(xs, ys, columns, &column),
        false => chunked_runs(xs, ys, &column),
    };
    let mut out = Vec::with_capacity(2 * joined.len());
    for r in joined {
        emit(&mut out, xs, ys, r.min, r.max);
    }
    if out.len() > 4 * columns {
        let k = out.len().div_ceil(4 * columns);
        out = out.into_iter().step_by(k).collect();
    }
    out
}

/// Whether x is finite and never decreases (a time base, a scan).
fn is_ordered(xs: &[f64]) -> bool {
    xs.first().is_some_and(|x| x.is_finite())
        && first_pair(xs, |a, b| !(a <= b && b.is_finite())).is_none()
}

/// Points per parallel chunk (fixed, so the split never depends on the
/// thread count).
const CHUNK: usize = 1 << 18;

/// Consecutive finite points in one pixel column: the indices of the first
/// lowest and the first highest.
#[derive(Clone, Copy)]
struct Run {
    column: usize,
    min: usize,
    max: usize,
}

impl Run {
    /// This run followed by `next` in the same column.
    fn join<H: Heights + ?Sized>(self, next: Run, ys: &H) -> Run {
        Run {
            column: self.column,
            min: if ys.at(next.min) < ys.at(self.min) {
                next.min
            } else {
                self.min
            },
            max: if ys.at(next.max) > ys.at(self.max) {
                next.max
            } else {
                self.max
            },
        }
    }
}

/// The runs of any record: each chunk's in parallel, and a run that a chunk
/// boundary cuts joined again, so the runs are those of one pass in order.
fn chunked_runs<H: Heights + ?Sized>(
    xs: &[f64],
    ys: &H,
    column: &(impl Fn(f64) -> usize + Sync),
) -> Vec<Run> {
    let n = xs.len();
    let parts: Vec<Vec<Run>> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| runs(xs, ys, c * CHUNK..((c + 1) * CHUNK).min(n), column))
        .collect();
    let mut joined: Vec<Run> = Vec::new();
    for r in parts.into_iter().flatten() {
        match joined.last_mut() {
            Some(last) if last.column == r.column => *last = last.join(r, ys),
            _ => joined.push(r),
        }
    }
    joined
}

/// The runs of an ordered record ([`is_ordered`]): each column's points
/// are one stretch, found by bisection, so only the heights are read.
fn sorted_runs<H: Heights + ?Sized>(
    xs: &[f64],
    ys: &H,
    columns: usize,
    column: &(impl Fn(f64) -> usize + Sync),
) -> Vec<Run> {
    let starts: Vec<usize> = (0..=columns)
        .map(|c| xs.partition_point(|&x| column(x) < c))
        .collect();
    // A column's first lowest and first highest finite point: its extremes
    // without a branch per point, then where each first occurs.
    let run = |buf: &mut Vec<f64>, c: usize| {
        let col = ys.stretch(starts[c]..starts[c + 1], buf);
        let (lo, hi) = extremes(col, f64::is_finite);
        if lo > hi {
            return None;
        }
        #[allow(clippy::float_cmp)] // the extreme itself, found again
        let at = |v: f64| col.iter().position(|&y| y == v).map(|i| starts[c] + i);
        Some(Run {
            column: c,
            min: at(lo)?,
            max: at(hi)?,
        })
    };
    (0..columns)
        .into_par_iter()
        .map_init(Vec::new, run)
        .flatten()
        .collect()
}

/// The runs of the points in `range`, in order.
fn runs<H: Heights + ?Sized>(
    xs: &[f64],
    ys: &H,
    range: Range<usize>,
    column: &impl Fn(f64) -> usize,
) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for i in range.filter(|&i| xs[i].is_finite() && ys.at(i).is_finite()) {
        let here = Run {
            column: column(xs[i]),
            min: i,
            max: i,
        };
        match out.last_mut() {
            Some(last) if last.column == here.column => *last = last.join(here, ys),
            _ => out.push(here),
        }
    }
    out
}

fn emit<H: Heights + ?Sized>(out: &mut Vec<(f64, f64)>, xs: &[f64], ys: &H, a: usize, b: usize) {
    let (first, second) = if a <= b { (a, b) } else { (b, a) };
    out.push((xs[first], ys.at(first)));
    if second != first {
        out.push((xs[second], ys.at(second)));
    }
}

/// The smallest and largest finite value.
pub fn range(v: &[f64]) -> Option<(f64, f64)> {
    crate::signal::scan::finite_range(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chunked runs equal those of one sequential pass (the former
    /// code, kept here as the oracle) on a long noisy record whose runs
    /// straddle chunk boundaries, with NaN and ties.
    #[test]
    fn chunked_runs_equal_one_pass() {
        fn one_pass(xs: &[f64], ys: &[f64], columns: usize) -> Vec<(f64, f64)> {
            let (lo, hi) = range(xs).unwrap();
            let width = (hi - lo).max(f64::MIN_POSITIVE);
            let column =
                |x: f64| (((x - lo) / width) * columns as f64).min(columns as f64 - 1.0) as usize;
            let mut out = Vec::new();
            let mut run: Option<(usize, usize, usize)> = None;
            for i in (0..xs.len()).filter(|&i| xs[i].is_finite() && ys[i].is_finite()) {
                let c = column(xs[i]);
                run = match run {
                    Some((rc, a, b)) if rc == c => Some((
                        c,
                        if ys[i] < ys[a] { i } else { a },
                        if ys[i] > ys[b] { i } else { b },
                    )),
                    Some((_, a, b)) => {
                        emit(&mut out, xs, ys, a, b);
                        Some((c, i, i))
                    }
                    None => Some((c, i, i)),
                };
            }
            if let Some((_, a, b)) = run {
                emit(&mut out, xs, ys, a, b);
            }
            out
        }
        let n = 5 * CHUNK + 123;
        let noise = crate::signal::testing::gaussian_noise(n, 1.0, 11);
        let xs: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let mut ys: Vec<f64> = noise.iter().map(|e| (e * 3.0).round()).collect();
        ys[CHUNK] = f64::NAN;
        // Columns narrow enough that the whole record stays under the
        // thinning limit, so the runs are compared one for one.
        let columns = n / 4;
        assert_eq!(min_max(&xs, &ys, columns), one_pass(&xs, &ys, columns));
        // A record whose x goes back once takes the chunked path.
        let mut back = xs.clone();
        back[3 * CHUNK + 5] = 0.5;
        assert_eq!(min_max(&back, &ys, columns), one_pass(&back, &ys, columns));
        let columns = 700;
        let got = min_max(&xs, &ys, columns);
        assert!(got.len() <= 2 * columns + 2, "{}", got.len());
        let want = one_pass(&xs, &ys, columns);
        assert_eq!(got, want);
    }

    /// Heights computed as they are read give the points of the same
    /// heights stored, on the ordered path and the chunked one, short and
    /// long, with non-finite heights.
    #[test]
    fn computed_heights_thin_as_stored() {
        let n = 3 * CHUNK + 77;
        let noise = crate::signal::testing::gaussian_noise(n, 1.0, 5);
        let y = |i: usize| match i % 1000 {
            0 => f64::NAN,
            _ => noise[i].abs() / (1.0 + (i % 7) as f64),
        };
        let stored: Vec<f64> = (0..n).map(y).collect();
        let xs: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
        let mut back = xs.clone();
        back[2 * CHUNK + 3] = 0.0;
        for x in [&xs, &back] {
            for columns in [700, n] {
                let want = min_max(x, &stored, columns);
                assert_eq!(min_max_by(x, y, columns), want, "{columns} columns");
            }
        }
    }

    #[test]
    fn short_series_are_kept_whole() {
        let xs = [0.0, 1.0, f64::NAN, 3.0];
        let ys = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(
            min_max(&xs, &ys, 10),
            vec![(0.0, 1.0), (1.0, 2.0), (3.0, 4.0)]
        );
    }

    #[test]
    fn long_series_keep_every_columns_extremes() {
        let n = 1_000_000;
        let xs: Vec<f64> = (0..n).map(|i| i as f64 * 1e-3).collect();
        let ys: Vec<f64> = xs
            .iter()
            .map(|x| (x * 7.3).sin() + 0.01 * (x * 911.0).sin())
            .collect();
        let out = min_max(&xs, &ys, 700);
        assert!(out.len() <= 2 * 700, "{} points", out.len());
        // The global extremes survive, and so does each column's.
        let (ymin, ymax) = range(&ys).unwrap();
        let (omin, omax) = range(&out.iter().map(|p| p.1).collect::<Vec<_>>()).unwrap();
        assert_eq!((omin, omax), (ymin, ymax));
        let width = xs[n - 1] / 700.0;
        for c in [0usize, 123, 699] {
            let in_col = |x: f64| ((x / width) as usize).min(699) == c;
            let full = xs
                .iter()
                .zip(&ys)
                .filter(|(x, _)| in_col(**x))
                .map(|(_, y)| *y);
            let kept = out.iter().filter(|(x, _)| in_col(*x)).map(|(_, y)| *y);
            let (a, b) = (
                range(&full.collect::<Vec<_>>()),
                range(&kept.collect::<Vec<_>>()),
            );
            assert_eq!(a, b, "column {c}");
        }
        // In order along x.
        assert!(out.windows(2).all(|w| w[0].0 <= w[1].0));
    }

    #[test]
    fn back_and_forth_stays_bounded() {
        let n = 100_000;
        let xs: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 0.0 } else { 1.0 }).collect();
        let ys: Vec<f64> = (0..n).map(|i| i as f64).collect();
        assert!(min_max(&xs, &ys, 100).len() <= 400);
    }
}
