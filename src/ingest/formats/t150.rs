//! Agilent/Keysight T150 UTM nanotensile tester, NanoSuite text export.
//!
//! Layout: a title line (`EVOMECT150NanoTestDataFile`), `Key,value` lines,
//! a `Variables` block of `Name value unit` lines holding the instrument's
//! own results (SpecimenDiameter, StrainAtBreak, StressAtBreak, Toughness in
//! MPa = MJ/m³, Modulus, …), a `Segment Definition` block, then `Channel
//! Data` with three header rows (names, display names, units) over the
//! channels (EngineeringStrain mm/mm, EngineeringStress MPa, LoadOnSpecimen
//! mN, _Extension mm, _Time s). Strain is negative in the slack region
//! before the fibre is loaded; `_Extension` is the absolute crosshead
//! position.
//!
//! The preamble is kept verbatim, with each `Variables` line split into its
//! name and `value unit` (the generic metadata parser would split
//! `10:39:12 AM` at the colon).

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited_rekeyed;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The T150 NanoSuite reader.
pub struct T150;

impl Reader for T150 {
    fn name(&self) -> &'static str {
        "t150-nanosuite"
    }
    fn description(&self) -> &'static str {
        "Agilent/Keysight T150 UTM nanotensile NanoSuite export (results block, 3 header rows)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(3).iter().any(|l| {
            let l = l.trim();
            l.starts_with("EVOMECT150NanoTestDataFile") || l.starts_with("NanoSuiteFileName")
        })
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        read_delimited_rekeyed(text, options, |line, m| {
            let line = line.trim();
            if line.contains(',') {
                return Ok(()); // `Key,value` lines parse well already
            }
            if let Some((k, v)) = line.split_once(char::is_whitespace) {
                m.key = k.trim().to_string();
                m.value = v.trim().to_string();
            }
            Ok(())
        })
    }
}
