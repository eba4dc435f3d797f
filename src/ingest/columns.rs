//! A numeric block parsed straight into column buffers: lines split among
//! threads at line boundaries, each writing its rows into its own stretch of
//! the columns, with no allocation per line or per row. The result is the
//! same whatever the number of threads: chunks are taken in file order and
//! the block ends at the first line, in file order, that is not a row.

use std::mem::MaybeUninit;

use rayon::prelude::*;

use super::dialect::parse_line;
use super::fastrows::{self, Row};
use super::text::Text;

/// Lines per parallel task.
const CHUNK: usize = 1 << 15;

/// How the rows of a block are written.
#[derive(Debug, Clone, Copy)]
pub struct RowShape {
    /// Field delimiter (`' '`: runs of whitespace).
    pub delimiter: char,
    /// Decimal mark.
    pub decimal: char,
    /// Numbers per row.
    pub width: usize,
}

/// Parses lines `start..` of `text` as rows of `shape.width` numbers until
/// the first line that is not one. Returns the columns and the 0-based
/// index of that line (the line count when the block runs to the end).
pub fn parse_block(text: &Text, start: usize, shape: RowShape) -> (Vec<Vec<f64>>, usize) {
    let n = text.line_count();
    // Room for every remaining line at once: growing wave by wave copied
    // the columns at each doubling (and faulted their pages in twice). The
    // room is virtual until written; a block that stops early gives back
    // the rest.
    let mut columns: Vec<Vec<f64>> = (0..shape.width)
        .map(|_| Vec::with_capacity(n.saturating_sub(start)))
        .collect();
    let most = rayon::current_num_threads().max(1) * 4;
    let (mut next, mut chunks) = (start, 1);
    while next < n {
        // Small blocks stay on one thread; waves grow for long ones, so a
        // short block followed by others wastes little.
        let end = n.min(next + CHUNK * chunks);
        let stops: Vec<Option<usize>> = split(&mut columns, next, end)
            .into_par_iter()
            .map(|(first, mut slices)| fill(text, first, &mut slices, shape))
            .collect();
        // Parsed lines are not read again: a mapped file's pages go back.
        text.release_lines(next..end);
        let stop = stops.into_iter().flatten().next();
        let rows = stop.unwrap_or(end) - next;
        for c in &mut columns {
            // SAFETY: `fill` writes every column of each row it accepts, in
            // order, up to the line where its chunk stops; the chunks before
            // the first stop ran to their end, so the wave's first `rows`
            // rows are all written (the capacity was reserved by `split`).
            unsafe { c.set_len(c.len() + rows) };
        }
        if let Some(stop) = stop {
            columns.iter_mut().for_each(Vec::shrink_to_fit);
            return (columns, stop);
        }
        next = end;
        chunks = (chunks * 2).min(most);
    }
    (columns, n)
}

/// Room for lines `first..end` after the columns' rows, cut into chunks of
/// at most [`CHUNK`] lines: (first line, one slice per column). The room is
/// reserved, not zeroed: its pages are first touched by the threads that
/// fill them, in parallel, rather than zeroed on this one wave by wave.
fn split(
    columns: &mut [Vec<f64>],
    first: usize,
    end: usize,
) -> Vec<(usize, Vec<&mut [MaybeUninit<f64>]>)> {
    let starts: Vec<usize> = (first..end).step_by(CHUNK).collect();
    let mut chunks: Vec<(usize, Vec<&mut [MaybeUninit<f64>]>)> =
        starts.iter().map(|&s| (s, Vec::new())).collect();
    for column in columns.iter_mut() {
        column.reserve(end - first);
        let mut rest = &mut column.spare_capacity_mut()[..end - first];
        for (s, slices) in &mut chunks {
            let len = CHUNK.min(end - *s);
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
            slices.push(head);
            rest = tail;
        }
    }
    chunks
}

/// Fills `slices` from the lines starting at `first`; returns the first
/// line that is not a row of the block, if any. Every row before it is
/// written in every column (a row has exactly one number per column).
fn fill(
    text: &Text,
    first: usize,
    slices: &mut [&mut [MaybeUninit<f64>]],
    shape: RowShape,
) -> Option<usize> {
    let len = slices.first().map_or(0, |s| s.len());
    let mut scratch = Vec::with_capacity(shape.width);
    for r in 0..len {
        let line = text.line(first + r);
        if !is_row(line, shape, &mut scratch) {
            return Some(first + r);
        }
        for (column, &v) in slices.iter_mut().zip(&scratch) {
            column[r].write(v);
        }
    }
    None
}

/// Whether `line` is a row of the block (what the block reader classifies
/// as numeric, with the block's width), its numbers left in `scratch`.
pub fn is_row(line: &str, shape: RowShape, scratch: &mut Vec<f64>) -> bool {
    match fastrows::row(line, shape.delimiter, shape.decimal, scratch) {
        Row::Numbers { .. } => {}
        Row::NotNumeric { .. } => return false,
        Row::Slow => match parse_line(line, shape.delimiter, shape.decimal).0 {
            Some(row) => *scratch = row,
            None => return false,
        },
    }
    scratch.len() == shape.width && (shape.width >= 2 || delimiter_free_number(line))
}

/// A single number on a line with no delimiter (one-column data), read
/// with a decimal point.
pub fn delimiter_free_number(line: &str) -> bool {
    match fastrows::number(line.as_bytes(), b'.') {
        fastrows::Parsed::Value(v) => !v.is_nan(),
        fastrows::Parsed::Empty => false,
        fastrows::Parsed::Slow => {
            super::dialect::parse_number(line, '.').is_some_and(|v| !v.is_nan())
        }
    }
}
