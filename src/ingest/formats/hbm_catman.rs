//! HBM catman ASCII export (catman, catmanEasy, catmanAP), German.
//!
//! Layout: tab-separated, decimal commas, one header row of channel names
//! with units in brackets, the time channel first and named for its
//! sample rate (`Zeit  1 - Standardmessrate [s]`, in English exports
//! `Time  1 - default sample rate [s]`), German channel names (`Reibkraft
//! [N]`, `Normalkraft [N]`, `Weg [mm]`, `Temperatur [°C]`, `Reibwert []`),
//! often a tab at the end of every line, optionally a few `key<TAB>value`
//! lines above the header.
//!
//! A sample the amplifier did not deliver, and every sample of a channel
//! that was configured but not connected, is written as a no-value marker
//! of the order of the largest double (`1,00000E+308`). Such values are
//! never numbers: every value of magnitude at least [`NO_VALUE`] becomes
//! missing (NaN, dropped and counted by the friction stage), and a channel
//! with nothing else is dropped, with a `tribo.dropped_channel` entry in
//! the preamble saying so.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The catman reader.
pub struct HbmCatman;

/// Values at or beyond this magnitude are catman's no-value marker, not
/// measurements: no tribometer channel reads 1e300 in any unit.
pub const NO_VALUE: f64 = 1e300;

/// Whether a header row starts with catman's time channel.
fn is_header(line: &str) -> bool {
    let first = line.split('\t').next().unwrap_or("").trim().to_lowercase();
    (first.starts_with("zeit ") && first.contains("messrate"))
        || (first.starts_with("time ") && first.contains("sample rate"))
}

impl Reader for HbmCatman {
    fn name(&self) -> &'static str {
        "hbm-catman"
    }
    fn description(&self) -> &'static str {
        "HBM catman ASCII export (tab-separated, German channel names, decimal commas, no-value markers for unused channels)"
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(30).iter().any(|l| is_header(l))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, mut sections) = read_delimited(text, options)?;
        for s in &mut sections {
            let line = s.header_line.unwrap_or(s.first_data_line);
            s.channels.retain_mut(|c| {
                let mut marked = 0;
                for v in &mut c.values {
                    if v.abs() >= NO_VALUE {
                        *v = f64::NAN;
                        marked += 1;
                    }
                }
                let unused = marked > 0 && c.values.iter().all(|v| v.is_nan());
                if unused {
                    preamble.push(MetaEntry {
                        key: "tribo.dropped_channel".into(),
                        value: format!(
                            "'{}': every value is catman's no-value marker (a channel not connected)",
                            c.name
                        ),
                        line,
                    });
                } else if marked > 0 {
                    preamble.push(MetaEntry {
                        key: "tribo.missing_values".into(),
                        value: format!("'{}': {marked} no-value markers read as missing", c.name),
                        line,
                    });
                }
                !unused
            });
        }
        Ok((dialect, preamble, sections))
    }
}
