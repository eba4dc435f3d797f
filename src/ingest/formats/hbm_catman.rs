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
//! that was configured but not connected, is written as a no-value marker:
//! of the order of the largest double (`1,00000E+308`) in catman and
//! catmanAP, exactly `-1000000` in catmanEasy (the MX840B hot tensile test
//! of `gerlachjan/eval_TensileTest`, decimal points and CRLF). Such values
//! are never numbers: every value of magnitude at least [`NO_VALUE`], and
//! every value equal to [`EASY_NO_VALUE`], becomes missing (NaN, dropped
//! and counted by the friction stage), and a channel with nothing else is
//! dropped, with a `tribo.dropped_channel` entry in the preamble saying so.
//!
//! catman saves a job's metadata beside its data as a `.TSX` file
//! (`CATMAN TEST FILE`, `key=value` lines, `Messwertdatei=` naming the data
//! file). It is a companion of that data file, not an input of its own
//! (`ingest::companion`), whose lines every read of the data file puts in
//! its preamble after a `tribo.companion` entry naming it.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The catman reader.
pub struct HbmCatman;

/// Values at or beyond this magnitude are catman's no-value marker, not
/// measurements: no tribometer channel reads 1e300 in any unit.
pub const NO_VALUE: f64 = 1e300;

/// catmanEasy's marker of an unused channel, written in full on every row.
pub const EASY_NO_VALUE: f64 = -1_000_000.0;

/// Whether a value is one of catman's no-value markers (catmanEasy writes
/// its marker exactly, so an exact comparison is the test).
#[allow(clippy::float_cmp)]
fn is_marker(v: f64) -> bool {
    v.abs() >= NO_VALUE || v == EASY_NO_VALUE
}

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
                    if is_marker(*v) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_are_never_numbers() {
        assert!(is_marker(-1_000_000.0) && is_marker(1e308) && is_marker(-1e300));
        assert!(!is_marker(-999_999.0) && !is_marker(0.0));
    }
}
