//! Rtec Instruments tribometer data log (MFT series), comma-separated.
//!
//! Layout: a preamble of `key,value,` lines with the recipe (one line per
//! recipe step), then one table whose header names the instrument's
//! modules: `Step, Timestamp, RecipeStep, DAQ.Fz (N),DAQ.Fx (N),DAQ.COF
//! (),Rotary.Velocity (rpm),XYZ.Z Depth (mm),XYZ.Z Position (mm),
//! Rotary.Angle (deg),` — units in parentheses, every line ending in a
//! comma, CRLF and LF mixed. `Step` numbers the recipe step of each sample
//! and `Timestamp` (seconds, no unit written) may restart at each step.
//!
//! The table is split into one section per step (`Step 1`, `Step 2`, …),
//! each with its own time axis and its `Step` column, so the friction
//! stage reports the file's steps rather than re-detecting them from the
//! speed. Preamble values lose the trailing comma. `DAQ.COF` is the
//! instrument's own coefficient of friction.

use crate::error::{Error, Result};
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The Rtec reader.
pub struct Rtec;

/// Units the header leaves out: the step numbers are counts, the
/// timestamp is in seconds.
const IMPLIED_UNITS: [(&str, &str); 3] = [("Step", "1"), ("RecipeStep", "1"), ("Timestamp", "s")];

/// Lines searched for the table header: a recipe can be long.
const SNIFF_LINES: usize = 200;

/// Whether a line is the header of an Rtec table.
fn is_header(line: &str) -> bool {
    let names: Vec<&str> = line.split(',').map(str::trim).collect();
    names.first() == Some(&"Step")
        && names.contains(&"Timestamp")
        && names.iter().any(|n| n.starts_with("DAQ."))
}

impl Reader for Rtec {
    fn name(&self) -> &'static str {
        "rtec"
    }
    fn description(&self) -> &'static str {
        "Rtec tribometer data log (recipe preamble, Step/Timestamp/DAQ.* columns, trailing commas), one section per step"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::FrictionTrace)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(SNIFF_LINES).iter().any(|l| is_header(l))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, sections) = read_delimited(text, options)?;
        for m in &mut preamble {
            m.value = m.value.trim_end_matches(',').trim().to_string();
        }
        let mut out = Vec::new();
        for mut s in sections {
            for c in &mut s.channels {
                if let Some((_, u)) = IMPLIED_UNITS.iter().find(|(n, _)| *n == c.name) {
                    if c.raw_unit.is_empty() {
                        c.raw_unit = u.to_string();
                    }
                }
            }
            out.extend(split_steps(text, s)?);
        }
        Ok((dialect, preamble, out))
    }
}

/// Splits a section into one section per run of its `Step` column, named
/// `Step N`. A step number that is not a whole number is an error naming
/// its line.
fn split_steps(text: &Text, s: Section) -> Result<Vec<Section>> {
    let Some(step) = s.channel("Step").map(|c| c.values.clone()) else {
        return Ok(vec![s]);
    };
    let mut runs: Vec<(usize, usize)> = Vec::new(); // (start, end) rows
    for (i, &v) in step.iter().enumerate() {
        if !(v.is_finite() && v >= 0.0 && v.fract() == 0.0) {
            return Err(Error::input(
                text.at(s.first_data_line + i).with_column("Step"),
                format!("expected a whole step number, found {v}"),
            ));
        }
        match runs.last_mut() {
            // Step numbers are labels (checked whole above): compared exactly.
            Some((start, end)) if step[*start].to_bits() == v.to_bits() => *end = i + 1,
            _ => runs.push((i, i + 1)),
        }
    }
    Ok(runs
        .into_iter()
        .enumerate()
        .map(|(k, (a, b))| Section {
            name: format!("Step {}", step[a]),
            metadata: if k == 0 {
                s.metadata.clone()
            } else {
                Vec::new()
            },
            header_line: s.header_line,
            first_data_line: s.first_data_line + a,
            channels: s
                .channels
                .iter()
                .map(|c| crate::ingest::Channel {
                    name: c.name.clone(),
                    raw_unit: c.raw_unit.clone(),
                    values: c.values[a..b].to_vec(),
                })
                .collect(),
        })
        .collect())
}
