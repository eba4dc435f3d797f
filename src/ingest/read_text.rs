//! A decoded text export read into a [`Dataset`]: the chosen reader's
//! sections, a check of quoted rows, tidying, companion metadata, and the
//! unit overrides of the options (checked against the file's own units).

use std::path::Path;

use super::{companion, text, tidy, Channel, Dataset, IngestOptions, Reader, Section, Text};
use crate::error::{Error, Location, Result};
use crate::units::parse_unit;

/// In a quoted export, a line with an odd number of quote marks cannot be
/// split into its fields; where it ends up just before a table's data (it
/// cut the table there, or took the header with it into the preamble), it
/// is an error naming it, rather than a table cut in two and a misleading
/// complaint about missing columns later.
fn check_quotes(path: &Path, text: &Text, sections: &[Section]) -> Result<()> {
    let odd = |n: usize| text.line(n - 1).bytes().filter(|b| *b == b'"').count() % 2 == 1;
    for s in sections {
        let before = s.first_data_line.saturating_sub(1);
        for n in [s.header_line, Some(before)].into_iter().flatten() {
            if n >= 1 && odd(n) {
                return Err(Error::input(
                    Location::line(path, n),
                    format!(
                        "an unterminated quote in {}: the row cannot be split into its fields",
                        text::quoted(text.line(n - 1))
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Reads decoded text with `reader`, then applies the unit overrides.
pub(super) fn read_text(
    path: &Path,
    text: &Text,
    reader: &'static dyn Reader,
    options: &IngestOptions,
) -> Result<Dataset> {
    let (dialect, mut preamble, mut sections) = reader.read(text, options)?;
    if dialect.quoted {
        check_quotes(path, text, &sections)?;
    }
    tidy::tidy(&mut sections, &mut preamble);
    preamble.extend(companion::metadata_for(path)?);
    apply_units(path, &mut sections, options)?;
    Ok(Dataset {
        source: path.to_path_buf(),
        sha256: String::new(), // set by `hashed`, beside which the read ran
        format: reader.name(),
        dialect: Some(dialect),
        preamble,
        sections,
        grids: Vec::new(),
    })
}

/// The units given in the options override the file's, by column name; an
/// override that contradicts the file's own unit fails the file
/// ([`check_unit_override`]).
pub(crate) fn apply_units(
    path: &Path,
    sections: &mut [Section],
    options: &IngestOptions,
) -> Result<()> {
    for section in sections {
        let line = section.header_line;
        for channel in &mut section.channels {
            if let Some(unit) = options.units.get(&channel.name) {
                check_unit_override(path, line, channel, unit, options.force)?;
                channel.raw_unit = unit.clone();
            }
        }
    }
    Ok(())
}

/// A unit override that contradicts the unit the file states for the
/// column fails the file, naming both (applied to every file, a wrong
/// override would put every value off by the units' ratio), unless
/// `force`. An override of a unit tribo does not know, or of none, is the
/// override's purpose.
fn check_unit_override(
    path: &Path,
    line: Option<usize>,
    channel: &Channel,
    unit: &str,
    force: bool,
) -> Result<()> {
    let (Some(stated), Some(given)) = (parse_unit(&channel.raw_unit), parse_unit(unit)) else {
        return Ok(());
    };
    if force || stated == given {
        return Ok(());
    }
    let location = Location {
        path: path.to_path_buf(),
        line,
        column: Some(channel.name.clone()),
    };
    Err(Error::input(
        location,
        format!(
            "the file states the unit '{}' and the pipeline's [ingest] units say '{unit}': \
             remove the override, or set force = true beside it to apply it anyway",
            channel.raw_unit
        ),
    ))
}
