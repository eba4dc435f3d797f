//! PCS Instruments MTM (mini traction machine), EHD and ETM text exports,
//! tab-separated.
//!
//! Two layouts of the family are read:
//! - the results export: a banner `PCS Instruments …`, the test header
//!   (test name, profile, ball, disc, lubricant), then each step as `Step
//!   N<TAB>type` with its parameters as `key<TAB>value` lines and, for a
//!   step that logs data, a table (`Time (s)`, `Mean Speed (mm/s)`, `SRR
//!   (%)`, `Load (N)`, `Traction Coeff`, …);
//! - the test data file of the instrument software (`MTM311 Test Data
//!   File`, and the same banner for other models: `MTM2`, `EHD2`, `ETM`):
//!   each step opens with `Step N started at <date>`, then `Step
//!   type<TAB>BOD_TIMED<TAB>Step description<TAB>…` (pairs on one line),
//!   the step's preamble (`Zero traction force (N)`, `Disc track radius used
//!   for this step (mm)`) and, for a timed or traction step, a table that
//!   starts with a two-column summary (`Step Time (s)`, `Traction Coeff
//!   (-)`) and then the full column set, so that column names repeat (the
//!   repeats hold the same values and are dropped, [`crate::ingest::tidy`]).
//!   A `MAPPER` step (3D-SLIM film thickness images, which live in the
//!   binary file) writes `key = value` lines and no table.
//!
//! Each table is one section named after its step (`Step 3`), with that
//! step's parameter lines as its metadata and a `Step` channel holding the
//! file's step number, so the friction stage reports the file's steps; the
//! time restarts at each step. A step without a table is kept in the
//! preamble: a `tribo.step_without_table` entry naming it, then its
//! parameter lines. The traction coefficient is the instrument's μ. The
//! step's speed is the mean (entrainment, "rolling") speed, the one the
//! profile sets and a Stribeck curve is drawn against: where the table also
//! has a sliding speed the reader says so ([`Role::hint_key`]). The ball
//! load is the normal force and the traction force, where logged, the
//! friction force; without it T = μ·N from the load.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::roles::Role;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The PCS Instruments MTM/EHD reader.
pub struct PcsMtm;

/// Instrument models whose software writes `<model> Test Data File`.
const MODELS: [&str; 6] = ["MTM", "EHD", "ETM", "HFRR", "MPR", "SLIM"];

/// A step's first line: 1-based line, N, type.
struct StepLine {
    line: usize,
    number: u32,
    kind: String,
}

/// `Step N<TAB>type` or `Step N started at …` (the type then on the next
/// line, `Step type<TAB>…`).
fn step_line(text: &Text, i: usize) -> Option<StepLine> {
    let line = text.line(i);
    let rest = line.strip_prefix("Step ")?;
    let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
    let number = rest[..digits].parse().ok()?;
    let after = rest[digits..].trim_start_matches([' ', '\t']);
    let kind = if after.starts_with("started at") {
        let next = (i + 1 < text.line_count()).then(|| text.line(i + 1));
        let fields = next.and_then(|l| l.strip_prefix("Step type\t"));
        fields.and_then(|f| f.split('\t').next()).unwrap_or("")
    } else if rest[digits..].starts_with('\t') {
        after.split('\t').next().unwrap_or("")
    } else {
        return None;
    };
    Some(StepLine {
        line: i + 1,
        number,
        kind: kind.trim().to_string(),
    })
}

/// Whether a line is the family's banner: `PCS Instruments …` or `<model>
/// Test Data File` (`MTM311 Test Data File`, `EHD2 Test Data File`).
fn is_banner(line: &str) -> bool {
    let l = line.trim();
    if l.starts_with("PCS Instruments") {
        return true;
    }
    let Some(model) = l.strip_suffix("Test Data File") else {
        return false;
    };
    let model = model.trim();
    MODELS.iter().any(|m| {
        model
            .strip_prefix(m)
            .is_some_and(|rest| rest.chars().all(|c| c.is_ascii_alphanumeric()))
    })
}

impl Reader for PcsMtm {
    fn name(&self) -> &'static str {
        "pcs-mtm"
    }
    fn description(&self) -> &'static str {
        "PCS Instruments MTM/EHD text export (\"PCS Instruments\" or \"MTM311 Test Data File\" banner, tab-separated, Step N blocks, tables only for steps that log data)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::FrictionTrace)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.lines()
            .filter(|l| !l.trim().is_empty())
            .take(3)
            .any(is_banner)
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, preamble, mut sections) = read_delimited(text, options)?;
        let steps: Vec<StepLine> = (0..text.line_count())
            .filter_map(|i| step_line(text, i))
            .collect();
        let mut pool: Vec<MetaEntry> = preamble;
        for s in &mut sections {
            pool.append(&mut s.metadata);
        }
        let pool = split_pairs(text, pool);
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
            s.metadata.extend(role_hints(s, header));
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

/// The format's meaning of its columns where names alone would choose
/// otherwise: the mean ("rolling") speed is the step's speed though the
/// table also has a sliding speed.
fn role_hints(s: &Section, line: usize) -> Vec<MetaEntry> {
    let hint = |role: Role, names: &[&str]| {
        let c = names.iter().find(|n| s.channel(n).is_some())?;
        Some(MetaEntry {
            key: role.hint_key(),
            value: c.to_string(),
            line,
        })
    };
    [
        hint(Role::Velocity, &["Rolling Speed", "Mean Speed"]),
        hint(Role::Time, &["Step Time", "Time"]),
        hint(Role::NormalForce, &["Ball Load", "Load"]),
        hint(Role::FrictionForce, &["Traction Force"]),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// Metadata lines that hold several `key<TAB>value` pairs (`Step
/// type<TAB>BOD_TIMED<TAB>Step description<TAB>…`) as one entry per pair;
/// a value followed by a remark in parentheses (`Zero traction force
/// (N)<TAB>-0.5444<TAB>(measured at the start of this step)`) keeps it
/// after a space.
fn split_pairs(text: &Text, pool: Vec<MetaEntry>) -> Vec<MetaEntry> {
    let mut out = Vec::with_capacity(pool.len());
    for mut m in pool {
        let fields: Vec<&str> = text.line(m.line - 1).split('\t').map(str::trim).collect();
        if let [_, value, remark] = fields[..] {
            if remark.starts_with('(') && !value.is_empty() {
                m.value = format!("{value} {remark}");
            }
        }
        if fields.len() < 4 || fields.len() % 2 == 1 || fields.iter().any(|f| f.is_empty()) {
            out.push(m);
            continue;
        }
        out.extend(fields.chunks(2).map(|kv| MetaEntry {
            key: kv[0].to_string(),
            value: kv[1].to_string(),
            line: m.line,
        }));
    }
    out
}

/// The parameter lines of step `k`: from its `Step N` line to the next
/// step's, or to the first blank line.
fn step_parameters(text: &Text, steps: &[StepLine], k: usize) -> Vec<MetaEntry> {
    let end = steps.get(k + 1).map_or(text.line_count(), |s| s.line - 1);
    let lines = (steps[k].line..end)
        .map(|j| (j, text.line(j)))
        .take_while(|(_, l)| !l.trim().is_empty())
        .filter_map(|(j, l)| MetaEntry::parse(l, j + 1, '\t'))
        .collect();
    split_pairs(text, lines)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn banners_of_the_family() {
        for b in [
            "PCS Instruments MTM Test Results",
            "MTM311 Test Data File",
            "MTM2 Test Data File",
            "EHD2 Test Data File",
            "ETM Test Data File",
        ] {
            assert!(is_banner(b), "{b}");
        }
        for b in [
            "Rtec Test Data File",
            "MTM 3 Test Data File x",
            "Test Data File",
        ] {
            assert!(!is_banner(b), "{b}");
        }
    }
}
