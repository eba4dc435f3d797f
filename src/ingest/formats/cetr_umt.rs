//! CETR UMT "CETR Data Viewer" CSV export (Bruker's predecessor of the UMT
//! tribometers): a preamble, then one section per test step ("Step No. N",
//! step parameters, a header row and a unit row). Forces are in gram-force
//! (`g`), distance in mm, time in s; `COF` and `Ff` are the instrument's own
//! results.
//!
//! Recognised by the banner of any version of the viewer or the
//! instrument software (`Created by CETR Data Viewer ver.2.19.106`,
//! `Created by CETR UMT ver.1.136.257`, `Created by UMT …`, `Created by
//! Bruker …`) in the first lines, or, without one, by the structure: a
//! `Step No.` line followed by a header with `Fx` and `Fz`. The unit row
//! gives each column's unit whatever the column order.

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
        let head = text.head(40);
        let banner = head.iter().take(5).any(|l| {
            l.trim_start()
                .strip_prefix("Created by")
                .is_some_and(|rest| {
                    ["CETR", "UMT", "Bruker"]
                        .iter()
                        .any(|w| rest.trim_start().starts_with(w))
                })
        });
        let step = head
            .iter()
            .position(|l| l.trim_start().starts_with("Step No."));
        let forces = |l: &&str| {
            let names: Vec<&str> = l.split([',', ';', '\t']).map(str::trim).collect();
            names.contains(&"Fx") && names.contains(&"Fz")
        };
        banner || step.is_some_and(|i| head[i..].iter().any(forces))
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
