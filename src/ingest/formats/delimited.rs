//! Generic delimited text (CSV, TSV, semicolon, whitespace), with units in
//! the header (`Fx [mN]`, `Friction force (N)`, `t (s)`) or in a unit row,
//! a preamble, and one or more tables.

use crate::error::Result;
use crate::ingest::{blocks, dialect, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The fallback reader: any text file with a numeric table.
pub struct Delimited;

/// Reads the blocks as [`read_delimited`] does, then lets a format re-key
/// each preamble entry from its own line (results blocks whose lines the
/// generic `key: value` parser splits wrongly).
pub fn read_delimited_rekeyed(
    text: &Text,
    options: &IngestOptions,
    mut rekey: impl FnMut(&str, &mut MetaEntry) -> Result<()>,
) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
    let (dialect, mut preamble, sections) = read_delimited(text, options)?;
    for m in &mut preamble {
        rekey(text.line(m.line - 1), m)?;
    }
    Ok((dialect, preamble, sections))
}

/// Sniffs the dialect (unless the options fix it) and reads the blocks.
pub fn read_delimited(
    text: &Text,
    options: &IngestOptions,
) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
    let (delimiter, decimal, quoted) = dialect::sniff(text.lines());
    let delimiter = options.delimiter.unwrap_or(delimiter);
    let decimal = options.decimal.unwrap_or(decimal);
    let (preamble, sections) = blocks::read_blocks(text, delimiter, decimal)?;
    let dialect = Dialect {
        encoding: text.encoding,
        line_ending: text.line_ending,
        delimiter,
        decimal,
        quoted,
    };
    Ok((dialect, preamble, sections))
}

impl Reader for Delimited {
    fn name(&self) -> &'static str {
        "delimited"
    }
    fn description(&self) -> &'static str {
        "generic CSV/TSV/semicolon text with units in the header or a unit row"
    }
    fn sniff(&self, _text: &Text) -> bool {
        true
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        read_delimited(text, options)
    }
}
