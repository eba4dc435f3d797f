//! x y z scanner export in fixed-width columns: each row holds three
//! right-aligned numbers padded with spaces to a fixed width, with no
//! delimiter character, so a wide value (`-123.45678` in a 10-character
//! field) touches its neighbour and splitting at blanks would lose a
//! column. An optional header row names the columns in the same widths
//! (`    X [mm]    Y [mm]    Z [um]`, units in brackets or parentheses).
//!
//! The field boundaries are the end columns of the three numbers, taken from
//! the rows where the numbers are apart (the most common set of end
//! columns); every row is then cut at those columns. A row that does not
//! fit (a field that is not a number, text beyond the last field) is an
//! error naming the line and field; a header unit tribo does not know is an
//! error naming the line and column. Without a header the channels are
//! `x`, `y`, `z` with no unit, and the roughness stage asks for them
//! (`--x-unit`, `--z-unit`) rather than guessing.

use std::collections::BTreeMap;

use crate::error::{Error, Result};
use crate::ingest::dialect::parse_number;
use crate::ingest::header::split_name_unit;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::parse_unit;

/// The fixed-width x y z reader.
pub struct FixedWidthXyz;

/// End columns (exclusive, in bytes) of the whitespace-separated tokens.
fn token_ends(line: &str) -> Vec<usize> {
    let b = line.as_bytes();
    (0..b.len())
        .filter(|&i| b[i] != b' ' && (i + 1 == b.len() || b[i + 1] == b' '))
        .map(|i| i + 1)
        .collect()
}

/// A row of three numbers apart from each other, right-aligned. Its tokens
/// are split at spaces only, as [`token_ends`] splits them: another blank
/// (a form feed, a bare CR) inside a row makes it no spaced row.
fn is_spaced_row(line: &str) -> bool {
    let t: Vec<&str> = line.split(' ').filter(|f| !f.is_empty()).collect();
    line.is_ascii()
        && line.starts_with(' ')
        && !line.contains([',', ';', '\t'])
        && t.len() == 3
        && t.iter().all(|f| parse_number(f, '.').is_some())
}

/// The most common end columns among the first spaced rows, and how many
/// rows had them.
fn field_ends(text: &Text) -> Option<([usize; 3], usize)> {
    let mut counts: BTreeMap<[usize; 3], usize> = BTreeMap::new();
    for line in text.lines().take(400).map(str::trim_end) {
        if is_spaced_row(line) {
            let e = token_ends(line);
            *counts.entry([e[0], e[1], e[2]]).or_default() += 1;
        }
    }
    counts.into_iter().max_by_key(|(_, n)| *n)
}

/// Cuts a row at the field ends.
fn cut(line: &str, ends: &[usize; 3]) -> [String; 3] {
    let mut start = 0;
    ends.map(|e| {
        let cell = line
            .get(start.min(line.len())..e.min(line.len()))
            .unwrap_or("");
        start = e;
        cell.trim().to_string()
    })
}

/// A data row: three numbers cut at the field ends, or an error naming the
/// line and field.
fn data_row(text: &Text, n: usize, line: &str, ends: &[usize; 3]) -> Result<[f64; 3]> {
    let fail = |what: String| Error::input(text.at(n), what);
    if !line.is_ascii() || line.len() > ends[2] {
        return Err(fail(format!(
            "'{}' does not fit the fixed-width columns ending at {:?}",
            line.trim(),
            ends
        )));
    }
    let cells = cut(line, ends);
    let mut row = [0.0; 3];
    for (k, c) in cells.iter().enumerate() {
        row[k] = parse_number(c, '.').ok_or_else(|| {
            fail(format!(
                "field {} (columns {}–{}) is '{c}', not a number",
                k + 1,
                if k == 0 { 1 } else { ends[k - 1] + 1 },
                ends[k]
            ))
        })?;
    }
    Ok(row)
}

/// Names and units from the header row, cut at the same columns.
fn header_channels(text: &Text, n: usize, line: &str, ends: &[usize; 3]) -> Result<Vec<Channel>> {
    cut(line, ends)
        .iter()
        .map(|cell| {
            let (name, unit) = split_name_unit(cell);
            if !unit.is_empty() && parse_unit(&unit).is_none() {
                return Err(Error::Unit {
                    location: text.at(n).with_column(&name),
                    unit,
                    expected: "a length unit (m, mm, um, nm, angstrom, in)".into(),
                });
            }
            Ok(Channel {
                name,
                raw_unit: unit,
                values: Vec::new(),
            })
        })
        .collect()
}

impl Reader for FixedWidthXyz {
    fn name(&self) -> &'static str {
        "fixed-width-xyz"
    }
    fn description(&self) -> &'static str {
        "x y z scanner points in fixed-width, space-padded columns without a delimiter (optional header with units)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::ArealMap)
    }
    fn sniff(&self, text: &Text) -> bool {
        #![allow(clippy::float_cmp)] // equal coordinates as written
        let Some((ends, rows)) = field_ends(text) else {
            return false;
        };
        // A grid's scan line: the first rows share y (or x) while the other
        // coordinate increases; a three-column trace (t, Fx, Fz) does not.
        let first: Vec<[f64; 3]> = text
            .lines()
            .map(str::trim_end)
            .filter(|l| is_spaced_row(l))
            .take(3)
            .filter_map(|l| data_row(text, 1, l, &ends).ok())
            .collect();
        let runs = |a: usize, b: usize| {
            first.len() == 3
                && first
                    .windows(2)
                    .all(|w| w[0][a] == w[1][a] && w[1][b] > w[0][b])
        };
        rows >= 3
            && (runs(1, 0) || runs(0, 1))
            && ends[0] >= 3
            && text
                .lines()
                .map(str::trim_end)
                .filter(|l| is_spaced_row(l))
                .take(20)
                .all(|l| token_ends(l) == ends)
    }
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (ends, _) = field_ends(text)
            .ok_or_else(|| Error::input(text.at(1), "no row of three right-aligned numbers"))?;
        let lines: Vec<&str> = text.lines().map(str::trim_end).collect();
        let first = lines
            .iter()
            .position(|l| !l.trim().is_empty() && data_row(text, 1, l, &ends).is_ok())
            .unwrap_or(lines.len());
        let mut preamble = Vec::new();
        let mut channels = ["x", "y", "z"].map(|n| Channel {
            name: n.into(),
            raw_unit: String::new(),
            values: Vec::new(),
        });
        let mut header_line = None;
        for (i, l) in lines[..first].iter().enumerate() {
            if l.trim().is_empty() {
                continue;
            }
            if i + 1 == first || (i + 2 == first && lines[i + 1].trim().is_empty()) {
                let named = header_channels(text, i + 1, l, &ends)?;
                channels = [named[0].clone(), named[1].clone(), named[2].clone()];
                header_line = Some(i + 1);
            } else if let Some(m) = MetaEntry::parse(l, i + 1, ' ') {
                preamble.push(m);
            }
        }
        for (i, l) in lines.iter().enumerate().skip(first) {
            if l.trim().is_empty() {
                continue;
            }
            let row = data_row(text, i + 1, l, &ends)?;
            for (c, v) in channels.iter_mut().zip(row) {
                c.values.push(v);
            }
        }
        let section = Section {
            name: "1".into(),
            metadata: Vec::new(),
            header_line,
            first_data_line: first + 1,
            channels: channels.into(),
        };
        Ok((Dialect::whitespace(text), preamble, vec![section]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn touching_fields_are_cut_at_the_columns() {
        let ends = [10, 20, 30];
        assert_eq!(
            token_ends("    0.0100    0.0200  12.34567"),
            vec![10, 20, 30]
        );
        assert_eq!(
            cut("    0.0100    0.0200-123.45678", &ends),
            ["0.0100".to_string(), "0.0200".into(), "-123.45678".into()]
        );
        assert_eq!(
            cut("    X [mm]    Y [mm]    Z [um]", &ends),
            ["X [mm]".to_string(), "Y [mm]".into(), "Z [um]".into()]
        );
    }
}
