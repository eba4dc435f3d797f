//! Quoted decimal-comma profile export: a header `"Distance","Profile"` and
//! rows such as `"0,00050","0,03"`. The file states no units: the roughness
//! stage asks for them (`--x-unit`, `--z-unit`, or `units` in a pipeline
//! file) rather than guessing.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The quoted `"Distance","Profile"` reader.
pub struct ProfileCsv;

impl Reader for ProfileCsv {
    fn name(&self) -> &'static str {
        "profile-csv"
    }
    fn description(&self) -> &'static str {
        "quoted decimal-comma stylus profile (\"Distance\",\"Profile\"), no units in the file"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(1).first().is_some_and(|l| {
            let l = l.trim().replace(' ', "");
            l == "\"Distance\",\"Profile\"" || l == "\"Distance\";\"Profile\""
        })
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        read_delimited(text, options)
    }
}
