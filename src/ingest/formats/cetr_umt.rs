//! CETR UMT "CETR Data Viewer" CSV export (Bruker's predecessor of the UMT
//! tribometers): a preamble, then one section per test step ("Step No. N",
//! step parameters, a header row and a unit row). Forces are in gram-force
//! (`g`), distance in mm, time in s; `COF` and `Ff` are the instrument's own
//! results.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The CETR UMT reader.
pub struct CetrUmt;

impl Reader for CetrUmt {
    fn name(&self) -> &'static str {
        "cetr-umt"
    }
    fn description(&self) -> &'static str {
        "CETR UMT tribometer, CETR Data Viewer CSV (preamble, Step sections, gram-force)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::FrictionTrace)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(3)
            .iter()
            .any(|l| l.starts_with("Created by CETR"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, mut sections) = read_delimited(text, options)?;
        // The generic engine puts everything above the first table into the
        // preamble; the step's own parameters start at "Step No.".
        if let Some(i) = preamble.iter().position(|m| m.key.starts_with("Step No")) {
            let step = preamble.split_off(i);
            if let Some(first) = sections.first_mut() {
                first.metadata = step;
            }
        }
        for s in &mut sections {
            if let Some(n) = s.metadata.iter().find(|m| m.key.starts_with("Step No")) {
                let number = n.key.trim_start_matches("Step No.").trim();
                let number = if number.is_empty() {
                    n.value.as_str()
                } else {
                    number
                };
                s.name = format!("Step {}", number.trim_start_matches('.').trim());
            }
        }
        Ok((dialect, preamble, sections))
    }
}
