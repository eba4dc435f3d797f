//! Companion files: files that describe a measurement whose data are in
//! another file, and that are read with that data file rather than as
//! inputs of their own.
//!
//! | family | companion | its data file |
//! |---|---|---|
//! | stylus 3-file text export (Surfcom style) | `NAME.tx3`: measuring conditions, tab `key<TAB>value` lines | `NAME.tx1` (primary profile), `NAME.tx2` (roughness profile) |
//! | HBM catman | a job file whose first line is `CATMAN TEST FILE` (`.TSX`) | the file its `Messwertdatei=` (or `DATAFILE=`) names, in the same folder, else `NAME.ASC` |
//!
//! A companion is recognised by its content (the catman banner; the
//! conditions file's key/value lines) beside its naming convention, never
//! by its extension alone.
//!
//! For a pipeline, [`companion_of`] says whether an input is a companion,
//! and of which data file (which may be absent: a job file whose export
//! was not kept); [`data_file_of`] gives the data file among a run's inputs.
//! Reading a data file appends its companions' entries to the dataset's
//! preamble ([`metadata_for`], called by every read), after a
//! `tribo.companion` entry naming the companion.

use std::path::{Path, PathBuf};

mod inputs;

use inputs::same_file;
pub use inputs::Inputs;

use super::text::Text;
use super::MetaEntry;
use crate::error::Result;

/// How many bytes of a file are read to tell whether it is a companion.
const PEEK: usize = 4096;

/// The families of companion files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Stylus 3-file text export: `.tx3` conditions of `.tx1`/`.tx2`.
    SurfcomConditions,
    /// HBM catman job file (`CATMAN TEST FILE`).
    CatmanJob,
}

impl Family {
    /// What the companion holds, for people.
    pub fn what(self) -> &'static str {
        match self {
            Family::SurfcomConditions => "measuring conditions of a stylus profile (.tx3)",
            Family::CatmanJob => "HBM catman job data (CATMAN TEST FILE)",
        }
    }
}

/// A companion file and the data file(s) it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct Companion {
    /// Its family.
    pub family: Family,
    /// The data files it describes, in the same folder, whether or not
    /// they exist (see [`Companion::existing`]).
    pub data_files: Vec<PathBuf>,
}

impl Companion {
    /// The data files that exist.
    pub fn existing(&self) -> Vec<&Path> {
        self.data_files
            .iter()
            .filter(|p| p.is_file())
            .map(PathBuf::as_path)
            .collect()
    }
}

/// The first bytes of a file, decoded; `None` when it cannot be read or is
/// binary.
fn peek(path: &Path) -> Option<Text<'static>> {
    use std::io::Read;
    let mut bytes = Vec::with_capacity(PEEK);
    let file = std::fs::File::open(path).ok()?;
    file.take(PEEK as u64).read_to_end(&mut bytes).ok()?;
    Text::decode_owned(path, bytes).ok()
}

/// The file's extension, lower case.
fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// Whether the file's extension is `ext` (lower case), in any case. Asked
/// of every input of a run: no lower-case copy of each name.
fn extension_is(path: &Path, ext: &str) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// `path` with its extension replaced by `ext`, in the case of an existing
/// file when one exists (`3.TX1` beside `3.TX3`), else as given.
fn sibling(path: &Path, ext: &str) -> PathBuf {
    let upper = path.with_extension(ext.to_ascii_uppercase());
    match upper.is_file() {
        true => upper,
        false => path.with_extension(ext),
    }
}

/// Whether a decoded text is a companion by its content, as far as the
/// text alone tells (a `.tx3`'s data files are then looked for beside it).
pub fn is_companion_text(text: &Text) -> bool {
    let first = text.lines().find(|l| !l.trim().is_empty());
    first.is_some_and(|l| l.trim() == "CATMAN TEST FILE")
        || (extension(&text.path) == "tx3" && is_conditions(text))
}

/// Whether a text is a stylus conditions file: most of its non-blank lines
/// are `key<TAB>value` with a key that is not a number, and no line is a
/// row of numbers.
fn is_conditions(text: &Text) -> bool {
    let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    let keyed = lines
        .iter()
        .filter(|l| {
            l.split_once('\t').is_some_and(|(k, _)| {
                !k.trim().is_empty() && super::dialect::parse_number(k, '.').is_none()
            })
        })
        .count();
    let numeric = lines.iter().any(|l| {
        let f: Vec<&str> = l.split('\t').filter(|f| !f.trim().is_empty()).collect();
        !f.is_empty()
            && f.iter()
                .all(|f| super::dialect::parse_number(f, '.').is_some())
    });
    lines.len() >= 5 && keyed * 10 >= lines.len() * 8 && !numeric
}

/// The data file a catman job file names (`Messwertdatei=DD11_7_3.ASC`,
/// `DATAFILE=C:\…\DD11_7_3.ASC`), in the job file's folder.
fn catman_data_file(path: &Path, text: &Text) -> PathBuf {
    let named = text.lines().find_map(|l| {
        let (k, v) = l.split_once('=')?;
        matches!(
            k.trim(),
            "Messwertdatei" | "DATAFILE" | "Data file" | "Datafile"
        )
        .then(|| {
            v.trim()
                .rsplit(['\\', '/'])
                .next()
                .unwrap_or("")
                .to_string()
        })
        .filter(|n| !n.is_empty())
    });
    match named {
        Some(name) => path.with_file_name(name),
        None => sibling(path, "asc"),
    }
}

/// Whether `path` is a companion file, and of which data files.
pub fn companion_of(path: &Path) -> Option<Companion> {
    let ext = extension(path);
    let text = peek(path)?;
    let first = text.lines().find(|l| !l.trim().is_empty())?;
    if first.trim() == "CATMAN TEST FILE" {
        return Some(Companion {
            family: Family::CatmanJob,
            data_files: vec![catman_data_file(path, &text)],
        });
    }
    if ext == "tx3" && is_conditions(&text) {
        return Some(Companion {
            family: Family::SurfcomConditions,
            data_files: vec![sibling(path, "tx1"), sibling(path, "tx2")],
        });
    }
    None
}

/// Extensions of the companion families' files as their software writes
/// them (lower case). The pipeline peeks only at inputs with one of these
/// before asking their content ([`data_file_of`]): planning a run of many
/// files must not open each of them. A companion met under another name is
/// still recognised by its content when read (the `companion` reader).
const COMPANION_EXTENSIONS: [&str; 2] = ["tx3", "tsx"];

/// The data file among `inputs` that `path` is read with, when `path` is a
/// companion (by its name, then its content) of one of them (a `.tx3`'s
/// `.tx1`, else its `.tx2`). An input for which this is `Some(data)` is
/// read with `data` (its entries are in that dataset's preamble) and is
/// not an input of its own: outcome `companion`. When it is `None` but
/// [`companion_of`] is `Some`, the input is a companion whose data file is
/// not among the inputs: read on its own, it is said to be one.
pub fn data_file_of<'a>(path: &Path, inputs: &Inputs<'a>) -> Option<&'a Path> {
    if !COMPANION_EXTENSIONS.iter().any(|c| extension_is(path, c)) {
        return None;
    }
    let c = companion_of(path)?;
    c.data_files.iter().find_map(|d| inputs.find(d))
}

/// The companion files read with `data_file` ([`metadata_for`]): what a
/// cache must watch besides the data file itself.
pub fn files_of(data_file: &Path) -> Vec<PathBuf> {
    companions(data_file).into_iter().map(|(_, p)| p).collect()
}

/// Per data file extension, the extension of its companion and the
/// companion's family: the one list of files that look beside them.
const WATCHED: &[(&str, &str, Family)] = &[
    ("tx1", "tx3", Family::SurfcomConditions),
    ("tx2", "tx3", Family::SurfcomConditions),
    ("asc", "tsx", Family::CatmanJob),
];

/// Whether a file of this name can have companions (a Surfcom `.tx1` or
/// `.tx2`, a catman `.asc`): only those look beside them for one.
pub fn may_have_companions(data_file: &Path) -> bool {
    WATCHED.iter().any(|(e, _, _)| extension_is(data_file, e))
}

/// The paths whose presence and content decide which companions
/// `data_file` has ([`files_of`]): each watched sibling in upper and in
/// lower case, whether or not it exists. A rerun that finds each as the
/// last run saw it (absent, or with the same stat) knows the companions
/// are unchanged without reading them. Empty (no allocation) for a file
/// that cannot have companions.
pub fn beside(data_file: &Path) -> Vec<PathBuf> {
    if !may_have_companions(data_file) {
        return Vec::new();
    }
    WATCHED
        .iter()
        .filter(|(e, _, _)| extension_is(data_file, e))
        .flat_map(|(_, c, _)| {
            [
                data_file.with_extension(c.to_ascii_uppercase()),
                data_file.with_extension(c),
            ]
        })
        .collect()
}

/// The companions of a data file that exist beside it.
fn companions(data_file: &Path) -> Vec<(Family, PathBuf)> {
    let ext = extension(data_file);
    let mut out: Vec<(Family, PathBuf)> = WATCHED
        .iter()
        .filter(|(e, _, _)| *e == ext)
        .map(|(_, c, family)| (*family, sibling(data_file, c)))
        .filter(|(_, c)| c.is_file())
        .collect();
    // Each must confirm by its content that it belongs to this file.
    out.retain(|(_, c)| {
        companion_of(c).is_some_and(|k| k.data_files.iter().any(|d| same_file(d, data_file)))
    });
    out
}

/// The entries of every companion of `data_file`: a `tribo.companion`
/// entry naming it and what it holds, then its lines as `key = value`
/// (their line numbers the companion's), then the `tribo.*` entries its
/// family's reader derives ([`conditions`] for a stylus conditions file).
/// An unreadable companion is an error naming it.
pub fn metadata_for(data_file: &Path) -> Result<Vec<MetaEntry>> {
    let mut out = Vec::new();
    for (family, path) in companions(data_file) {
        let bytes = std::fs::read(&path).map_err(|e| crate::error::Error::io(&path, e))?;
        let text = Text::decode(&path, &bytes)?;
        out.push(MetaEntry {
            key: "tribo.companion".into(),
            value: format!("{} ({})", path.display(), family.what()),
            line: 1,
        });
        let delimiter = match family {
            Family::SurfcomConditions => '\t',
            Family::CatmanJob => '=',
        };
        let entries: Vec<MetaEntry> = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
            .map(|(i, l)| {
                let (key, value) = l.split_once(delimiter).unwrap_or((l, ""));
                MetaEntry {
                    key: key.trim().to_string(),
                    value: value.trim().to_string(),
                    line: i + 1,
                }
            })
            .collect();
        if family == Family::SurfcomConditions {
            out.extend(conditions(&entries));
        }
        out.extend(entries);
    }
    Ok(out)
}

/// Keys of a stylus conditions file in the languages its software writes
/// (Spanish, English, German, Portuguese), lower case, and the `tribo.*`
/// key each becomes.
const CONDITION_KEYS: [(&str, &[&str]); 7] = [
    (
        "tribo.evaluation_length",
        &[
            "longitud evaluación",
            "evaluation length",
            "auswertelänge",
            "comprimento de avaliação",
        ],
    ),
    (
        "tribo.measuring_length",
        &[
            "longitud medición",
            "measuring length",
            "messstrecke",
            "comprimento de medição",
        ],
    ),
    (
        "tribo.cutoff_lambda_c",
        &[
            "onda de corte",
            "cutoff",
            "cut-off",
            "cutoff wavelength",
            "grenzwellenlänge",
            "comprimento de onda de corte",
        ],
    ),
    (
        "tribo.cutoff_lambda_s",
        &[
            "longitud onda corte ls",
            "ls cutoff",
            "cutoff ls",
            "lambda s",
            "ls-grenzwellenlänge",
            "comprimento de onda de corte ls",
        ],
    ),
    (
        "tribo.filter",
        &[
            "tipo corte",
            "filter type",
            "cutoff type",
            "filtertyp",
            "tipo de filtro",
        ],
    ),
    ("tribo.standard", &["estándar", "standard", "norm", "norma"]),
    (
        "tribo.output_units",
        &[
            "unidad salida",
            "output unit",
            "output units",
            "ausgabeeinheit",
            "unidade de saída",
        ],
    ),
];

/// The measuring conditions a stylus conditions file states, under
/// language-free keys (`tribo.cutoff_lambda_c = 2.5mm`): the first entry
/// of each.
pub fn conditions(entries: &[MetaEntry]) -> Vec<MetaEntry> {
    CONDITION_KEYS
        .iter()
        .filter_map(|(key, spellings)| {
            let m = entries
                .iter()
                .find(|m| spellings.contains(&m.key.trim().to_lowercase().as_str()))?;
            Some(MetaEntry {
                key: key.to_string(),
                value: m.value.split('\t').next().unwrap_or("").trim().to_string(),
                line: m.line,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const TX3: &str = "Fecha\t08.04.2025\nUnidad salida\tmm,um\nLongitud evaluaci\u{f3}n\t10.0mm\n\
        Onda de corte\t2.5mm\nLongitud onda corte Ls\t25.0um\nTipo corte\tGausiano\nRa\t*.*******um\t*.*******um\n";

    /// A `.tx3` beside its `.tx1` and `.tx2` is their companion (ISO-8859-1,
    /// Spanish keys); the data files get its entries and its conditions in
    /// language-free keys; a `.tx3` of another content, and the data files
    /// themselves, are no companions.
    #[test]
    fn stylus_conditions_go_with_their_profiles() {
        let dir = tempfile::tempdir().unwrap();
        let latin1: Vec<u8> = TX3.chars().map(|c| c as u32 as u8).collect();
        std::fs::write(dir.path().join("3.tx3"), latin1).unwrap();
        std::fs::write(dir.path().join("3.tx1"), "10.0\n3\n1\n2\n3\n").unwrap();
        let tx3 = dir.path().join("3.tx3");
        let c = companion_of(&tx3).unwrap();
        assert_eq!(c.family, Family::SurfcomConditions);
        assert_eq!(c.existing(), [dir.path().join("3.tx1")]);
        let (tx1, tx2) = (dir.path().join("3.tx1"), dir.path().join("3.TX2"));
        assert_eq!(
            data_file_of(&tx3, &Inputs::new(&[&tx2, &tx1])),
            Some(tx1.as_path())
        );
        assert_eq!(
            data_file_of(&tx3, &Inputs::new(&[&tx3])),
            None,
            "its data file is no input"
        );
        assert_eq!(data_file_of(&tx1, &Inputs::new(&[&tx1, &tx3])), None);
        assert_eq!(companion_of(&dir.path().join("3.tx1")), None);
        let m = metadata_for(&dir.path().join("3.tx1")).unwrap();
        let get = |k: &str| m.iter().find(|e| e.key == k).map(|e| e.value.as_str());
        assert!(get("tribo.companion").unwrap().contains("3.tx3"));
        assert_eq!(get("tribo.cutoff_lambda_c"), Some("2.5mm"));
        assert_eq!(get("tribo.cutoff_lambda_s"), Some("25.0um"));
        assert_eq!(get("tribo.evaluation_length"), Some("10.0mm"));
        assert_eq!(get("tribo.output_units"), Some("mm,um"));
        assert_eq!(get("Longitud evaluación"), Some("10.0mm"));
        // A profile without conditions beside it has none.
        assert!(metadata_for(&dir.path().join("5.tx2")).unwrap().is_empty());
        std::fs::write(
            dir.path().join("4.tx3"),
            "0.5\t1.5\n1\t2\n2\t3\n3\t4\n4\t5\n",
        )
        .unwrap();
        assert_eq!(companion_of(&dir.path().join("4.tx3")), None);
    }

    /// Extensions are told in any case, as instruments write them.
    #[test]
    fn extensions_are_told_in_any_case() {
        for (name, watched) in [
            ("DD11_7_1.ASC", true),
            ("3.Tx1", true),
            ("3.tx2", true),
            ("3.tx3", false),
            ("trace.csv", false),
            ("TX1", false),
        ] {
            assert_eq!(may_have_companions(Path::new(name)), watched, "{name}");
        }
        let job = Path::new("DD11_7_3.TSX");
        assert!(COMPANION_EXTENSIONS.iter().any(|c| extension_is(job, c)));
        assert!(!extension_is(Path::new("tsx"), "tsx"));
    }

    /// A catman job file names its data file: a companion of it, present
    /// or not, whatever its own name.
    #[test]
    fn catman_job_names_its_data_file() {
        let dir = tempfile::tempdir().unwrap();
        let job = dir.path().join("DD11_7_3.TSX");
        std::fs::write(
            &job,
            "CATMAN TEST FILE\r\nJobname=Job1\r\nMesswertdatei=DD11_7_3.ASC\r\nStandardmessrate=50 Hz\r\n",
        )
        .unwrap();
        let c = companion_of(&job).unwrap();
        assert_eq!(c.family, Family::CatmanJob);
        assert_eq!(c.data_files, [dir.path().join("DD11_7_3.ASC")]);
        let asc = dir.path().join("DD11_7_3.ASC");
        assert_eq!(
            data_file_of(&job, &Inputs::new(&[&job])),
            None,
            "its data file is absent"
        );
        std::fs::write(&asc, "t\tF\n0\t1\n").unwrap();
        assert_eq!(
            data_file_of(&job, &Inputs::new(&[&asc, &job])),
            Some(asc.as_path())
        );
        let m = metadata_for(&dir.path().join("DD11_7_3.ASC")).unwrap();
        assert!(m
            .iter()
            .any(|e| e.key == "Standardmessrate" && e.value == "50 Hz"));
        // A job file of another export is not this one's.
        std::fs::write(dir.path().join("DD11_7_1.ASC"), "t\tF\n0\t1\n").unwrap();
        std::fs::copy(&job, dir.path().join("DD11_7_1.TSX")).unwrap();
        assert!(metadata_for(&dir.path().join("DD11_7_1.ASC"))
            .unwrap()
            .is_empty());
    }
}
