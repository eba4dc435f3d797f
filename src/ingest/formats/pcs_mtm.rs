//! PCS Instruments MTM (mini traction machine) and EHD text export,
//! tab-separated.
//!
//! Layout: a test header (`PCS Instruments …`, test name, profile, ball,
//! disc, lubricant), then the profile's steps in order. Each step opens
//! with `Step N<TAB>type` (Timed, Traction, Stribeck, Mapper, …) and its
//! parameters as `key<TAB>value` lines; a step that logs data follows with
//! a table — a header row with units in parentheses (`Time (s)`, `Mean
//! Speed (mm/s)`, `SRR (%)`, `Load (N)`, `Traction Coeff`, `Lube Temp
//! (°C)`, …) and one row per record, the time restarting at each step.
//! Steps without data (a 3D mapper step, whose images live in the binary
//! file; a suspend) have no table.
//!
//! Each table is one section named after its step (`Step 3`), with that
//! step's parameter lines as its metadata and a `Step` channel holding the
//! file's step number, so the friction stage reports the file's steps. A
//! step without a table is kept in the preamble: a
//! `tribo.step_without_table` entry naming it, then its parameter lines.
//! `Traction Coeff` is the instrument's coefficient; there is no friction
//! force column, so T = μ·N from the `Load` column. The step's speed is
//! the mean (entrainment) speed, the one the profile sets and a Stribeck
//! curve is drawn against.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The PCS Instruments MTM/EHD reader.
pub struct PcsMtm;

/// A `Step N<TAB>type` line: 1-based line, N, type.
struct StepLine {
    line: usize,
    number: u32,
    kind: String,
}

fn step_line(line: &str, number: usize) -> Option<StepLine> {
    let mut fields = line.split('\t').map(str::trim);
    let n = fields.next()?.strip_prefix("Step ")?.trim().parse().ok()?;
    Some(StepLine {
        line: number,
        number: n,
        kind: fields.next().unwrap_or("").to_string(),
    })
}

impl Reader for PcsMtm {
    fn name(&self) -> &'static str {
        "pcs-mtm"
    }
    fn description(&self) -> &'static str {
        "PCS Instruments MTM/EHD text export (tab-separated, Step N sections, some steps without tables)"
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(3)
            .iter()
            .any(|l| l.trim_start().starts_with("PCS Instruments"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, preamble, mut sections) = read_delimited(text, options)?;
        let steps: Vec<StepLine> = text
            .lines()
            .enumerate()
            .filter_map(|(i, l)| step_line(l, i + 1))
            .collect();
        let mut pool: Vec<MetaEntry> = preamble;
        for s in &mut sections {
            pool.append(&mut s.metadata);
        }
        let first_step = steps.first().map_or(usize::MAX, |s| s.line);
        let mut out_preamble: Vec<MetaEntry> = pool
            .iter()
            .filter(|m| m.line < first_step)
            .cloned()
            .collect();
        let mut used = vec![false; steps.len()];
        for s in &mut sections {
            let header = s.header_line.unwrap_or(s.first_data_line);
            let Some(k) = steps.iter().rposition(|st| st.line < header) else {
                continue;
            };
            used[k] = true;
            let st = &steps[k];
            s.name = format!("Step {}", st.number);
            s.metadata = pool
                .iter()
                .filter(|m| m.line >= st.line && m.line < header)
                .cloned()
                .collect();
            if s.channel("Step").is_none() {
                s.channels.insert(
                    0,
                    Channel {
                        name: "Step".into(),
                        raw_unit: "1".into(),
                        values: vec![f64::from(st.number); s.rows()],
                    },
                );
            }
        }
        for (k, st) in steps.iter().enumerate().filter(|(k, _)| !used[*k]) {
            out_preamble.push(MetaEntry {
                key: "tribo.step_without_table".into(),
                value: format!("Step {} ({})", st.number, st.kind),
                line: st.line,
            });
            out_preamble.extend(step_parameters(text, &steps, k));
        }
        Ok((dialect, out_preamble, sections))
    }
}

/// The parameter lines of step `k`: from its `Step N` line to the next
/// step's, or to the first blank line.
fn step_parameters(text: &Text, steps: &[StepLine], k: usize) -> Vec<MetaEntry> {
    let end = steps.get(k + 1).map_or(text.line_count(), |s| s.line - 1);
    (steps[k].line..end)
        .map(|j| (j, text.line(j)))
        .take_while(|(_, l)| !l.trim().is_empty())
        .filter_map(|(j, l)| MetaEntry::parse(l, j + 1, '\t'))
        .collect()
}
