//! Pin-on-disc export with CSM/Anton Paar column names: tab-separated,
//! decimal comma, header `Time, Distance, Laps, mu, FrictionForce` without
//! units (the `mu` column may arrive as `µ` or `?`). Other exports of the
//! family are read too: the columns in any order, among others (`Normal
//! load`, `Temperature`), with or without units (`Time [s]`,
//! `Friction force [N]`), comma- or semicolon-separated, decimal point or
//! comma. The units the header leaves out are those of the instrument software: time in s,
//! sliding distance in m (1592 laps over 30.2 m is a 3.0 mm track radius; in
//! mm it would be 3 µm), laps as a count, μ dimensionless, friction force in
//! N. `mu` is the instrument's own coefficient of friction.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The CSM-style pin-on-disc reader.
pub struct CsmPinOnDisc;

/// How the μ column's name arrives: some exports lose the µ sign to the
/// encoding and write `?`.
const MU_SPELLINGS: [&str; 4] = ["mu", "µ", "μ", "?"];

const COLUMNS: [(&str, &str); 5] = [
    ("Time", "s"),
    ("Distance", "m"),
    ("Laps", "1"),
    ("mu", "1"),
    ("FrictionForce", "N"),
];

/// The family's name of a column (`Friction force` → `FrictionForce`,
/// `µ` → `mu`); other names unchanged.
fn canonical(name: &str) -> String {
    let squashed: String = name
        .chars()
        .filter(|c| !matches!(c, ' ' | '_' | '-'))
        .collect::<String>()
        .to_lowercase();
    let spellings: [(&str, &[&str]); 4] = [
        ("Time", &["time", "zeit", "tiempo", "tempo"]),
        ("Distance", &["distance", "weg", "distancia", "distância"]),
        ("Laps", &["laps", "runden", "vueltas", "voltas"]),
        (
            "FrictionForce",
            &[
                "frictionforce",
                "reibkraft",
                "fuerzadefricción",
                "forçadeatrito",
            ],
        ),
    ];
    if MU_SPELLINGS.contains(&squashed.as_str()) && squashed != "?" {
        return "mu".into();
    }
    spellings
        .iter()
        .find(|(_, s)| s.contains(&squashed.as_str()))
        .map_or(name.to_string(), |(c, _)| c.to_string())
}

impl Reader for CsmPinOnDisc {
    fn name(&self) -> &'static str {
        "csm-pin-on-disc"
    }
    fn description(&self) -> &'static str {
        "pin-on-disc TSV with CSM/Anton Paar column names (Time, Distance, Laps, mu, FrictionForce), decimal comma"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::FrictionTrace)
    }
    fn sniff(&self, text: &Text) -> bool {
        let Some(first) = text.lines().find(|l| !l.trim().is_empty()) else {
            return false;
        };
        let Some(delimiter) = ['\t', ';', ','].into_iter().find(|d| first.contains(*d)) else {
            return false;
        };
        let names: Vec<String> = first
            .split(delimiter)
            .map(|c| canonical(&crate::ingest::header::split_name_unit(c.trim_matches('"')).0))
            .collect();
        let has = |c: &str| names.iter().any(|n| n == c);
        // `?`: the µ sign lost to the encoding, beside the family's columns.
        let mu = has("mu") || has("?");
        has("Time") && mu && has("FrictionForce") && (has("Distance") || has("Laps"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, mut sections) = read_delimited(text, options)?;
        for s in &mut sections {
            for c in &mut s.channels {
                let name = canonical(&c.name);
                if c.name != name && name != "mu" {
                    c.name = name;
                }
                if c.name != "mu" && MU_SPELLINGS.contains(&c.name.as_str()) {
                    preamble.push(MetaEntry {
                        key: "tribo.renamed_column".into(),
                        value: format!(
                            "'{}' -> 'mu' (the µ sign of the instrument's coefficient column)",
                            c.name
                        ),
                        line: s.header_line.unwrap_or(1),
                    });
                    c.name = "mu".into();
                }
                if let Some((_, unit)) = COLUMNS.iter().find(|(n, _)| *n == c.name) {
                    if c.raw_unit.is_empty() {
                        c.raw_unit = unit.to_string();
                    }
                }
            }
        }
        Ok((dialect, preamble, sections))
    }
}
