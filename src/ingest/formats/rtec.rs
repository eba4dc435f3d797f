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
//! The recipe preamble comes in two forms: `key,value,` lines (one per
//! recipe step), or one line of keys and one of values (`Recipe,
//! UpperSample, …, Radius` then `name.Rx,,,,100,1000,Rotary,1,`, the first
//! ending in a bare CR in a real log, [`crate::ingest::text`]), paired here
//! into one entry per key.
//!
//! The table is split into one section per step (`Step 1`, `Step 2`, …),
//! each with its own time axis and its `Step` column, so the friction
//! stage reports the file's steps rather than re-detecting them from the
//! speed. Preamble values lose the trailing comma. `DAQ.COF` is the
//! instrument's own coefficient of friction (Fx/Fz, row by row).
//!
//! A rotary log that runs one track per step moves the stage between steps
//! (`XYZ.Y Position (mm)` −9.33, −12.33, … in a real log): the position of
//! the axis that moves is written into each step's metadata
//! ([`crate::ingest::radius::RADIAL_POSITION`], the step's median), from
//! which each step's track radius follows once the disc centre, or one
//! track's radius, is known ([`crate::ingest::radius`]).

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
        let (dialect, preamble, sections) = read_delimited(text, options)?;
        let mut preamble = pair_key_rows(text, preamble);
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
        mark_radial_positions(&mut out);
        Ok((dialect, preamble, out))
    }
}

/// The fields of a preamble line, without the trailing empty one.
fn fields(line: &str) -> Vec<&str> {
    let mut f: Vec<&str> = line.split(',').map(str::trim).collect();
    if f.last() == Some(&"") {
        f.pop();
    }
    f
}

/// A line of keys (three or more one-word names: `Recipe, UpperSample,
/// Averaging`) followed by a line of as many values or fewer, one of them
/// empty or a number, becomes one entry per key, on the values' line;
/// other entries stay (`Recipe Step 1,Rotary Speed 100 mm/s,…` lines).
fn pair_key_rows(text: &Text, preamble: Vec<MetaEntry>) -> Vec<MetaEntry> {
    let number = |f: &str| crate::ingest::dialect::parse_number(f, '.').is_some();
    let is_key = |f: &str| {
        !number(f)
            && f.chars()
                .all(|c| c.is_alphanumeric() || matches!(c, '.' | '_' | '-'))
    };
    let mut out = Vec::with_capacity(preamble.len());
    let mut i = 0;
    while i < preamble.len() {
        let m = &preamble[i];
        let keys = fields(text.line(m.line - 1));
        let next = preamble.get(i + 1).filter(|n| n.line == m.line + 1);
        let values = next.map(|n| fields(text.line(n.line - 1)));
        match values {
            Some(values)
                if keys.len() >= 3
                    && keys.iter().all(|k| is_key(k))
                    && values.len() <= keys.len()
                    && values.iter().any(|v| number(v)) =>
            {
                out.extend(keys.iter().enumerate().map(|(k, key)| MetaEntry {
                    key: key.to_string(),
                    value: values.get(k).unwrap_or(&"").to_string(),
                    line: m.line + 1,
                }));
                i += 2;
            }
            _ => {
                out.push(m.clone());
                i += 1;
            }
        }
    }
    out
}

/// The stage axes whose position a step may hold.
const STAGE_AXES: [&str; 2] = ["XYZ.Y Position", "XYZ.X Position"];

/// Writes, into each step's metadata, the median position of the stage
/// axis that moves from step to step (by more than 0.01 mm; the one that
/// moves most), when one does.
fn mark_radial_positions(steps: &mut [Section]) {
    let median = |v: &[f64]| {
        let mut v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
        crate::signal::stats::median_in_place(&mut v)
    };
    let spread = |axis: &str| -> Option<(f64, Vec<f64>, String)> {
        let unit = steps.first()?.channel(axis)?.raw_unit.clone();
        let medians: Option<Vec<f64>> = steps
            .iter()
            .map(|s| s.channel(axis).and_then(|c| median(&c.values)))
            .collect();
        let medians = medians?;
        let (lo, hi) = medians
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &m| {
                (a.min(m), b.max(m))
            });
        let mm = crate::units::parse_unit(&unit)?.to_si(hi - lo) * 1e3;
        (mm > 0.01).then_some((mm, medians, unit))
    };
    let moving = STAGE_AXES
        .iter()
        .filter_map(|a| spread(a).map(|s| (a, s)))
        .max_by(|x, y| x.1 .0.total_cmp(&y.1 .0));
    let Some((axis, (_, medians, unit))) = moving else {
        return;
    };
    for (s, m) in steps.iter_mut().zip(medians) {
        s.metadata.push(MetaEntry {
            key: crate::ingest::radius::RADIAL_POSITION.into(),
            value: format!("{m} {unit} (median of '{axis}' over the step)"),
            line: s.header_line.unwrap_or(s.first_data_line),
        });
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
