//! A companion file met on its own (a stylus export's `.tx3` conditions, a
//! catman job file): recognised by its content
//! ([`crate::ingest::companion`]) and said to be one, naming the data file
//! it belongs to. Reading it alone is an error that says so, which a
//! pipeline reports as a file that is not data; its entries are read with
//! its data file, into that dataset's preamble.

use crate::error::{Error, Result};
use crate::ingest::companion::{companion_of, is_companion_text};
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The companion-file recogniser.
pub struct CompanionFile;

impl Reader for CompanionFile {
    fn name(&self) -> &'static str {
        "companion"
    }
    fn description(&self) -> &'static str {
        "a companion of a data file (stylus .tx3 measuring conditions, HBM catman job file): read with its data file, not on its own"
    }
    fn sniff(&self, text: &Text) -> bool {
        is_companion_text(text)
    }
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let what = match companion_of(&text.path) {
            Some(c) => {
                let names: Vec<String> = c
                    .data_files
                    .iter()
                    .map(|p| {
                        let present = if p.is_file() { "" } else { " (absent)" };
                        format!("{}{present}", p.display())
                    })
                    .collect();
                format!("{} of {}", c.family.what(), names.join(" and "))
            }
            None => "a companion file whose data file is not beside it".to_string(),
        };
        Err(Error::input(
            text.at(1),
            format!("{what}: a companion, read with its data file rather than on its own"),
        ))
    }
}
