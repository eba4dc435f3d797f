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
//! (`ingest::companion`): [`is_job_file`] recognises it, [`job_for`] finds
//! the one that belongs to a data file, and its lines are read into the
//! data file's preamble as `job: key` entries.

use std::path::{Path, PathBuf};

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
        preamble.extend(job_entries(&text.path));
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

/// The `key=value` lines of the job file beside a data file
/// ([`job_for`] among the `.tsx` files of its folder), as `job: key`
/// entries; none when there is no job file or it cannot be read (the data
/// file is read alone).
fn job_entries(data: &Path) -> Vec<MetaEntry> {
    let dir = match data.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let candidates: Vec<(PathBuf, String)> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("tsx")))
        .filter_map(|p| {
            let bytes = std::fs::read(&p).ok()?;
            let text = Text::decode(&p, &bytes)
                .ok()?
                .lines()
                .collect::<Vec<_>>()
                .join("\n");
            Some((p, text))
        })
        .collect();
    let Some(job) = job_for(data, &candidates) else {
        return Vec::new();
    };
    let Some((_, text)) = candidates.iter().find(|(p, _)| p == job) else {
        return Vec::new();
    };
    text.lines()
        .enumerate()
        .filter_map(|(i, l)| {
            let (k, v) = l.split_once('=')?;
            Some(MetaEntry {
                key: format!("job: {}", k.trim()),
                value: v.trim().to_string(),
                line: i + 1,
            })
        })
        .collect()
}

/// Whether a file is a catman job file (`.TSX`): by its extension, or by
/// its first line `CATMAN TEST FILE` (`head`: the start of its text).
pub fn is_job_file(path: &Path, head: &str) -> bool {
    let tsx = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("tsx"));
    tsx || head.trim_start().starts_with("CATMAN TEST FILE")
}

/// The data file a job file names (`Messwertdatei=`, else the file part of
/// `DATAFILE=`), as written.
pub fn job_data_file(job: &str) -> Option<String> {
    let value = |key: &str| {
        job.lines()
            .find_map(|l| l.trim().strip_prefix(key).map(|v| v.trim().to_string()))
            .filter(|v| !v.is_empty())
    };
    value("Messwertdatei=")
        .or_else(|| value("DATAFILE="))
        .map(|v| v.rsplit(['\\', '/']).next().unwrap_or(&v).to_string())
}

/// The job file that belongs to a data file, among `candidates` (the files
/// beside it, with their text): the one whose `Messwertdatei` names the data
/// file (case-insensitive), else one of the same stem that names no other
/// file. `None` when there is none: the data file is read alone.
pub fn job_for<'a>(data: &Path, candidates: &'a [(PathBuf, String)]) -> Option<&'a Path> {
    let name = data.file_name()?.to_string_lossy().to_lowercase();
    let stem = data.file_stem()?.to_string_lossy().to_lowercase();
    let jobs = candidates
        .iter()
        .filter(|(p, t)| is_job_file(p, t) && p.as_path() != data);
    let named = |t: &str| job_data_file(t).map(|n| n.to_lowercase());
    let by_name = jobs
        .clone()
        .find(|(_, t)| named(t).as_deref() == Some(&name));
    by_name
        .or_else(|| {
            jobs.clone().find(|(p, t)| {
                let same = p.file_stem().map(|s| s.to_string_lossy().to_lowercase());
                same.as_deref() == Some(&stem) && named(t).is_none()
            })
        })
        .map(|(p, _)| p.as_path())
}

#[cfg(test)]
mod tests {
    use super::*;

    const JOB: &str = "CATMAN TEST FILE\r\nJobname=Job1\r\nMesswertdatei=DD11_7_3.ASC\r\nDATAFILE=C:\\x\\DD11_7_3.ASC\r\n";

    #[test]
    fn a_job_file_belongs_to_the_data_file_it_names() {
        assert!(is_job_file(Path::new("a.TSX"), ""));
        assert!(is_job_file(Path::new("a.txt"), JOB));
        assert!(!is_job_file(
            Path::new("a.ASC"),
            "Zeit  1 - Standardmessrate [s]"
        ));
        assert_eq!(job_data_file(JOB).as_deref(), Some("DD11_7_3.ASC"));
        let c = vec![(PathBuf::from("d/DD11_7_3.TSX"), JOB.to_string())];
        assert_eq!(
            job_for(Path::new("d/DD11_7_3.asc"), &c),
            Some(Path::new("d/DD11_7_3.TSX"))
        );
        // the job names another measurement: not this file's
        assert_eq!(job_for(Path::new("d/DD11_7_1.ASC"), &c), None);
        let bare = vec![(PathBuf::from("d/run.tsx"), "CATMAN TEST FILE\n".to_string())];
        assert_eq!(
            job_for(Path::new("d/run.asc"), &bare),
            Some(Path::new("d/run.tsx"))
        );
    }

    #[test]
    fn markers_are_never_numbers() {
        assert!(is_marker(-1_000_000.0) && is_marker(1e308) && is_marker(-1e300));
        assert!(!is_marker(-999_999.0) && !is_marker(0.0));
    }
}
