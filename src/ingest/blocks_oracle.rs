//! The block reader as it was before rows were parsed straight into
//! columns: every line classified into a `Vec<f64>` first, then rows copied
//! into columns. Kept, for tests only, as the oracle the fast reader must
//! match on every dialect ([`super::blocks`] property test).

#![allow(dead_code)]

use super::dialect::{parse_line, parse_number, split_fields};
use super::header::{is_unit_row, split_name_unit};
use super::text::Text;
use super::{Channel, MetaEntry, Section};
use crate::error::{Error, Result};

/// A block without any header row above must have at least this many rows to
/// be taken as data rather than stray numeric metadata.
const MIN_HEADERLESS_ROWS: usize = 3;

enum Line {
    Blank,
    Numeric(Vec<f64>),
    Text { raw_fields: usize },
}

/// Each line as blank (a spacer: nothing but delimiters and quotes, as in
/// the engine), numeric (its values) or text (its field count).
fn classify(text: &Text, delimiter: char, decimal: char) -> Vec<Line> {
    text.lines()
        .map(|l| {
            if l.chars()
                .all(|c| c.is_whitespace() || c == delimiter || c == '"')
            {
                return Line::Blank;
            }
            match parse_line(l, delimiter, decimal) {
                (Some(row), _) if row.len() >= 2 || delimiter_free_number(l) => Line::Numeric(row),
                (_, raw_fields) => Line::Text { raw_fields },
            }
        })
        .collect()
}

/// Splits `text` into the preamble and its sections.
pub fn read_blocks_oracle(
    text: &Text,
    delimiter: char,
    decimal: char,
) -> Result<(Vec<MetaEntry>, Vec<Section>)> {
    let mut classified = classify(text, delimiter, decimal);
    let mut sections = Vec::new();
    let mut preamble = Vec::new();
    let mut meta_start = 0; // first line (0-based) not yet used
    let mut i = 0;
    while i < classified.len() {
        let Line::Numeric(first) = &classified[i] else {
            i += 1;
            continue;
        };
        let width = first.len();
        let header = header_rows(text, &classified, i, width, delimiter);
        let start = i;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        while i < classified.len() {
            match &mut classified[i] {
                Line::Numeric(row) if row.len() == width => rows.push(std::mem::take(row)),
                Line::Numeric(row) if !header.is_empty() || rows.len() >= MIN_HEADERLESS_ROWS => {
                    return Err(Error::input(
                        text.at(i + 1),
                        format!(
                            "expected {width} numeric fields as in the rows above, found {}",
                            row.len()
                        ),
                    ));
                }
                Line::Text { raw_fields }
                    if *raw_fields >= width
                        && (!header.is_empty() || rows.len() >= MIN_HEADERLESS_ROWS) =>
                {
                    return Err(bad_cell(text, i, width, delimiter, decimal, &header));
                }
                _ => break,
            }
            i += 1;
        }
        if header.is_empty() && rows.len() < MIN_HEADERLESS_ROWS {
            continue; // stray numbers: left as metadata
        }
        let header_start = header.first().map_or(start, |h| h.0);
        let meta: Vec<MetaEntry> = (meta_start..header_start)
            .filter_map(|j| MetaEntry::parse(text.line(j), j + 1, delimiter))
            .collect();
        if sections.is_empty() {
            preamble = meta.clone();
        }
        let channels = make_channels(&header, width, &rows);
        sections.push(Section {
            name: (sections.len() + 1).to_string(),
            metadata: if sections.is_empty() {
                Vec::new()
            } else {
                meta
            },
            header_line: header.first().map(|h| h.0 + 1),
            first_data_line: start + 1,
            channels,
        });
        meta_start = i;
    }
    if sections.is_empty() {
        return Err(no_data(text));
    }
    Ok((preamble, sections))
}

/// Where data was expected and not found: the line after the first
/// non-empty one (the header), quoted; or the header itself when nothing
/// follows it.
fn no_data(text: &Text) -> Error {
    let mut filled = (1..=text.line_count()).filter(|&i| !text.line(i - 1).trim().is_empty());
    let (Some(header), second) = (filled.next(), filled.next()) else {
        return Error::input(text.at(1), "no data found: the file is empty");
    };
    match second {
        Some(l) => Error::input(
            text.at(l),
            format!(
                "no data found: expected numeric rows after the header on line {header}, found {}",
                super::text::quoted(text.line(l - 1).trim())
            ),
        ),
        None => Error::input(
            text.at(header),
            "no data found: a header row with no numeric rows after it",
        ),
    }
}

/// A single number on a line with no delimiter (one-column data).
fn delimiter_free_number(line: &str) -> bool {
    parse_number(line, '.').is_some_and(|v| !v.is_nan())
}

/// The header rows directly above the block starting at `start`: up to three
/// text rows whose field count matches the block's width, blank lines allowed
/// only between the block and the nearest header row. Returns (0-based line,
/// cells), top first.
fn header_rows(
    text: &Text,
    classified: &[Line],
    start: usize,
    width: usize,
    delimiter: char,
) -> Vec<(usize, Vec<String>)> {
    let mut rows = Vec::new();
    let mut j = start;
    let mut skipped_blank = false;
    while j > 0 && rows.len() < 3 {
        j -= 1;
        match &classified[j] {
            Line::Blank if rows.is_empty() && !skipped_blank => skipped_blank = true,
            Line::Blank if rows.is_empty() => continue,
            Line::Text { raw_fields } if *raw_fields >= width => {
                let cells = split_fields(text.line(j), delimiter);
                let named = cells.iter().filter(|c| !c.trim().is_empty()).count();
                if named > width {
                    break;
                }
                rows.push((j, cells));
            }
            _ => break,
        }
    }
    rows.reverse();
    rows
}

fn make_channels(header: &[(usize, Vec<String>)], width: usize, rows: &[Vec<f64>]) -> Vec<Channel> {
    let cell =
        |r: &Vec<String>, k: usize| r.get(k).map(|s| s.trim().to_string()).unwrap_or_default();
    let unit_row = header.iter().skip(1).rev().find(|(_, r)| is_unit_row(r));
    (0..width)
        .map(|k| {
            let raw_name = header.first().map(|(_, r)| cell(r, k)).unwrap_or_default();
            let (name, unit) = match unit_row {
                Some((_, units)) => (raw_name.clone(), cell(units, k)),
                None => split_name_unit(&raw_name),
            };
            let name = if name.is_empty() {
                format!("column_{}", k + 1)
            } else {
                name
            };
            Channel {
                name,
                raw_unit: unit.trim_matches(['(', ')', '[', ']']).trim().to_string(),
                values: rows.iter().map(|r| r[k]).collect(),
            }
        })
        .collect()
}

fn bad_cell(
    text: &Text,
    line: usize,
    width: usize,
    delimiter: char,
    decimal: char,
    header: &[(usize, Vec<String>)],
) -> Error {
    let fields = split_fields(text.line(line), delimiter);
    let bad = fields
        .iter()
        .position(|f| parse_number(f, decimal).is_none())
        .unwrap_or(0);
    let column = header
        .first()
        .and_then(|(_, r)| r.get(bad))
        .map(|c| c.trim().to_string())
        .unwrap_or_else(|| format!("{}", bad + 1));
    Error::input(
        text.at(line + 1).with_column(column),
        format!(
            "expected a number (decimal mark '{decimal}', {width} fields), found {}",
            super::text::quoted(fields.get(bad).map(|s| s.trim()).unwrap_or(""))
        ),
    )
}
