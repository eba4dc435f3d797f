//! Ingestion: instrument exports as they come off the instruments, read into
//! sections of named channels with their units and the file's metadata kept.
//!
//! A [`Reader`] is chosen from [`READERS`]: the one named in the options,
//! else the first binary reader whose `sniff_bytes` recognises the file's
//! bytes (magic numbers, container structure), else — the file decoded
//! ([`text`]) and its dialect sniffed ([`dialect`]) — the first whose
//! `sniff` recognises the text. Each reader declares its name and how it
//! recognises its files; adding a format means one file in [`formats`] and
//! one line in [`READERS`]. Binary readers share [`binary`]'s helpers.
//!
//! Values of text exports stay as written (raw units) in a [`Dataset`]'s
//! sections; conversion to SI happens once, when a stage takes the channels
//! it needs (for friction, [`trace::Trace`]), because the meaning of a unit
//! can depend on the channel's role (`g` on a force column is gram-force).
//! Maps and profiles of binary formats are [`grid::Grid`]s, decoded once
//! into one buffer with heights in metres.

pub mod binary;
pub mod blocks;
#[cfg(test)]
mod blocks_oracle;
#[cfg(test)]
mod blocks_props;
pub mod columns;
pub mod companion;
pub mod csv_table;
pub mod dialect;
pub mod drive;
pub mod fastrows;
pub mod formats;
pub mod grid;
pub mod header;
pub mod inspect;
pub mod kind;
pub mod manifest;
pub mod memory;
pub mod probe;
pub mod radius;
#[cfg(test)]
mod radius_tests;
mod read_text;
mod role_names;
pub mod roles;
pub mod source;
pub mod started;
pub mod text;
pub mod tidy;
pub mod trace;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, Location, Result};
use crate::units::{parse_unit, Unit};
pub use binary::Decoded;
pub use dialect::Dialect;
pub(crate) use read_text::apply_units;
use read_text::read_text;
pub use text::Text;

/// The key of a preamble entry a reader adds for a column the file gives
/// no unit for, read in the unit its format's layout uses: the value is
/// `<column> as <unit>`, and the analyses say so in their status
/// (`assumed_unit`) unless the user gave the unit.
pub const ASSUMED_UNIT: &str = "assumed unit";

/// One `key = value` entry of a preamble or section header, with its line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MetaEntry {
    /// The key (or the whole line when it has no value).
    pub key: String,
    /// The value, possibly empty.
    pub value: String,
    /// 1-based line number.
    pub line: usize,
}

impl MetaEntry {
    /// Parses a metadata line: `key = value`, `key<delimiter>value`,
    /// `key: value` (a key of at most four words), or `Key 1.23 unit` (a
    /// one-word key followed by a number). Anything else is kept whole as
    /// the key with an empty value. Blank lines give `None`.
    pub fn parse(line: &str, number: usize, delimiter: char) -> Option<MetaEntry> {
        let l = line.trim();
        if l.is_empty() {
            return None;
        }
        let split = |sep: char| l.split_once(sep).map(|(k, v)| (k.trim(), v.trim()));
        let short_key = |(k, v): &(&str, &str)| {
            k.len() > 1 && k.split_whitespace().count() <= 4 && !v.is_empty()
        };
        let numeric_value = |(k, v): &(&str, &str)| {
            !k.is_empty()
                && v.trim_start_matches(['-', '+'])
                    .starts_with(|c: char| c.is_ascii_digit())
        };
        let (key, value) = split('=')
            .or_else(|| (delimiter != ' ').then(|| split(delimiter)).flatten())
            .or_else(|| split(':').filter(short_key))
            .or_else(|| split(' ').filter(numeric_value))
            .unwrap_or((l, ""));
        let unquote = |s: &str| s.trim_matches('"').trim().to_string();
        Some(MetaEntry {
            key: unquote(key),
            value: unquote(value),
            line: number,
        })
    }
}

/// One named column of numbers, as written in the file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Channel {
    /// Name from the header (without its unit).
    pub name: String,
    /// Unit as written (empty when the file gives none).
    pub raw_unit: String,
    /// Values in the file's unit; NaN marks an empty or `NaN` cell.
    #[serde(skip)]
    pub values: Vec<f64>,
}

impl Channel {
    /// The channel's unit, or `None` when the file gives none. An unknown
    /// unit is an error naming the file and column.
    pub fn unit(&self, path: &Path) -> Result<Option<Unit>> {
        if self.raw_unit.is_empty() {
            return Ok(None);
        }
        parse_unit(&self.raw_unit).map(Some).ok_or_else(|| Error::Unit {
            location: Location::file(path).with_column(&self.name),
            unit: self.raw_unit.clone(),
            expected: "a unit tribo knows (N, mN, gf, g, s, ms, m, mm, um, m/s, mm/s, Pa, MPa, %, degC, ...)"
                .into(),
        })
    }
}

/// A table in a file: a step of a multi-step test, or the whole file.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Section {
    /// Name: `1`, `2`, … or the instrument's own (for example `Step 1`).
    pub name: String,
    /// Metadata lines that belong to this section (empty for the first
    /// section when they are the file's preamble).
    pub metadata: Vec<MetaEntry>,
    /// 1-based line of the first header row, if any.
    pub header_line: Option<usize>,
    /// 1-based line of the first data row.
    pub first_data_line: usize,
    /// The columns.
    pub channels: Vec<Channel>,
}

impl Section {
    /// Number of data rows.
    pub fn rows(&self) -> usize {
        self.channels.first().map_or(0, |c| c.values.len())
    }
    /// A channel by exact name.
    pub fn channel(&self, name: &str) -> Option<&Channel> {
        self.channels.iter().find(|c| c.name == name)
    }
}

/// Everything read from one file.
#[derive(Debug, Clone, Serialize)]
pub struct Dataset {
    /// The file.
    pub source: PathBuf,
    /// SHA-256 of its bytes.
    pub sha256: String,
    /// The reader that understood it.
    pub format: &'static str,
    /// How a text export is written; `None` for a binary file.
    pub dialect: Option<Dialect>,
    /// File-level metadata (preamble, instrument results), kept verbatim;
    /// binary readers add the common keys of [`binary::keys`].
    pub preamble: Vec<MetaEntry>,
    /// The tables.
    pub sections: Vec<Section>,
    /// Channels on a regular grid (maps, profiles) of binary and structured
    /// formats, in the file's order; empty for text exports.
    pub grids: Vec<grid::Grid>,
}

/// Options that a user or pipeline file gives for odd exports: the keys of
/// a pipeline file's `[ingest]` table besides its own (`files`, `columns`,
/// `override`), which it reads into this type directly.
#[derive(Debug, Clone, Default, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IngestOptions {
    /// Force a reader by name instead of sniffing.
    #[serde(default)]
    pub format: Option<String>,
    /// Units per column name, overriding or completing the file's.
    #[serde(default)]
    pub units: BTreeMap<String, String>,
    /// Field delimiter (`","`, `";"`, `"\t"`, `" "`) instead of sniffing.
    #[serde(default)]
    pub delimiter: Option<char>,
    /// Decimal mark (`"."` or `","`) instead of sniffing.
    #[serde(default)]
    pub decimal: Option<char>,
    /// Apply a unit of `units` even where the file states another.
    #[serde(default)]
    pub force: bool,
    /// The channel of a multi-channel binary file to decode (its name in
    /// `tribo inspect`); the height channel when not given.
    #[serde(default)]
    pub channel: Option<String>,
}

impl IngestOptions {
    /// Lays `over` on these options, as a later `[[ingest.override]]`
    /// lays itself on the defaults: what it states replaces, its units
    /// add to (and replace) these, and `force` once set stays set.
    pub fn overlay(&mut self, over: &IngestOptions) {
        if over.format.is_some() {
            self.format = over.format.clone();
        }
        self.units.extend(over.units.clone());
        self.delimiter = over.delimiter.or(self.delimiter);
        self.decimal = over.decimal.or(self.decimal);
        self.force |= over.force;
        if over.channel.is_some() {
            self.channel = over.channel.clone();
        }
    }
}

/// A file format tribo can read.
pub trait Reader: Sync {
    /// Short name, used in `tribo inspect` and in pipeline files.
    fn name(&self) -> &'static str;
    /// One line: which instrument and export this is.
    fn description(&self) -> &'static str;
    /// Whether this reader recognises a text file, from its first lines.
    /// Binary readers keep the default (no).
    fn sniff(&self, _text: &Text) -> bool {
        false
    }
    /// What its files hold, when the format says (an instrument that only
    /// writes friction traces); `None` for generic formats, whose kind
    /// follows from their columns ([`kind::classify`]).
    fn kind(&self) -> Option<kind::DataKind> {
        None
    }
    /// Reads a text file. Binary readers keep the default, never called:
    /// their files are read by [`Reader::read_bytes`].
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        Err(text::binary_error(&text.path))
    }
    /// Whether this binary reader recognises the file from its bytes
    /// (magic numbers, container structure), before any text decoding.
    /// Text readers keep the default (no).
    fn sniff_bytes(&self, _bytes: &[u8]) -> bool {
        false
    }
    /// Reads a binary (or structured) file from its bytes: `Some` for a
    /// binary reader, `None` (the default) for a text reader.
    fn read_bytes(
        &self,
        _bytes: &binary::Bytes,
        _options: &IngestOptions,
    ) -> Option<Result<Decoded>> {
        None
    }
}

/// Every reader, most specific first; the generic delimited reader is last
/// and accepts anything with a numeric table. Binary readers recognise a
/// file by its bytes before any text reader sees it (their place in the
/// list orders them among themselves only).
pub static READERS: &[&dyn Reader] = &[
    &formats::companion_file::CompanionFile,
    &formats::x3p::X3p,
    &formats::sur::Sur,
    &formats::metropro::MetroPro,
    &formats::datx::Datx,
    &formats::gwy::Gwy,
    &formats::nanoscope::Nanoscope,
    &formats::plu::Plu,
    &formats::opd::Opd,
    &formats::opdx::Opdx,
    &formats::netcdf::NetCdf,
    &formats::npy::Npy,
    &formats::sdf::Sdf,
    &formats::tmd::Tmd,
    &formats::al3d::Al3d,
    &formats::ibw::Ibw,
    &formats::nid::Nid,
    &formats::mi::Mi,
    &formats::bcr::Bcr,
    &formats::wsxm::Wsxm,
    &formats::frt::Frt,
    &formats::zon::Zon,
    &formats::vk::Vk,
    &formats::plux::Plux,
    &formats::cetr_umt::CetrUmt,
    &formats::csm_pin_on_disc::CsmPinOnDisc,
    &formats::rtec::Rtec,
    &formats::pcs_mtm::PcsMtm,
    &formats::hbm_catman::HbmCatman,
    &formats::t150::T150,
    &formats::instron_blocks::InstronBlocks,
    &formats::bluehill::Bluehill,
    &formats::zwick_testxpert::ZwickTestXpert,
    &formats::mts793::Mts793,
    &formats::instron_parameters::InstronParameters,
    &formats::dektak::Dektak,
    &formats::profile_csv::ProfileCsv,
    &formats::surfcom_tx::SurfcomTx,
    &formats::stylus_heights::StylusHeights,
    &formats::surface_text::SurfaceText,
    &formats::fixed_width_xyz::FixedWidthXyz,
    &formats::nanovea::Nanovea,
    &formats::xz_line_scan::XzLineScan,
    &formats::results_table::ResultsTable,
    &formats::delimited::Delimited,
];

/// Reads a file with the reader named in `options` or the first that
/// recognises it, then applies the unit overrides; the SHA-256 is computed
/// beside the read ([`hashed`]).
pub fn read_path(path: &Path, options: &IngestOptions) -> Result<Dataset> {
    let source = source::Source::open(path)?;
    let read = || {
        let bytes = binary::Bytes::from_source(path, &source);
        if let Some(ds) = binary::read(&bytes, options)? {
            return Ok(ds);
        }
        let text = Text::decode_source(path, &source)?;
        read_text(path, &text, choose_reader(&text, options)?, options)
    };
    hashed(|| source.sha256(), read).1
}

/// As [`read_path`], from bytes already in memory.
pub fn read_bytes(path: &Path, bytes: &[u8], options: &IngestOptions) -> Result<Dataset> {
    let read = || {
        if let Some(ds) = binary::read(&binary::Bytes::new(path, bytes), options)? {
            return Ok(ds);
        }
        let text = Text::decode(path, bytes)?;
        read_text(path, &text, choose_reader(&text, options)?, options)
    };
    hashed(|| crate::hash::sha256_hex(bytes), read).1
}

/// What holds a dataset's SHA-256 once it is known.
trait Hashed {
    fn set_sha256(&mut self, sha256: &str);
}

impl Hashed for Dataset {
    /// The one place a dataset gets its hash: a read leaves it empty.
    fn set_sha256(&mut self, sha256: &str) {
        self.sha256 = sha256.to_string();
    }
}

impl Hashed for Reading {
    fn set_sha256(&mut self, sha256: &str) {
        if let Reading::Data(ds) = self {
            ds.set_sha256(sha256);
        }
    }
}

/// Runs `read` and `sha256` side by side (`rayon::join`), and gives the
/// hash to what was read. SHA-256 is a sequential pass over the whole file
/// (about a tenth of a large file's read, `docs/speed.md`); beside the read
/// it takes a second core instead of wall time.
fn hashed<T: Hashed + Send>(
    sha256: impl FnOnce() -> String + Send,
    read: impl FnOnce() -> Result<T> + Send,
) -> (String, Result<T>) {
    let (sha256, mut read) = rayon::join(sha256, read);
    if let Ok(r) = &mut read {
        r.set_sha256(&sha256);
    }
    (sha256, read)
}

/// What a file turned out to be, for a pipeline that routes files by kind.
#[derive(Debug)]
pub enum Reading {
    /// A data file, read.
    Data(Dataset),
    /// Not a data file (an image, a notes file), and why: nothing to route.
    NotData(String),
}

/// As [`read_bytes`], but a file that is plainly not data — binary, or
/// text without a single numeric row that only the generic reader would
/// have tried — is [`Reading::NotData`] rather than an error. A file that a
/// specific reader recognises, or that has numeric rows, and still fails to
/// read is an error.
/// `sha256` is the file's when the caller knows it (a cached route's
/// entry); else it is computed beside the read ([`hashed`]). The hash is
/// returned with the reading, whatever became of the file.
pub fn read_data(
    path: &Path,
    source: &source::Source,
    sha256: Option<String>,
    options: &IngestOptions,
) -> (String, Result<Reading>) {
    hashed(
        || sha256.unwrap_or_else(|| source.sha256()),
        || read_unhashed(path, source, options),
    )
}

/// [`read_data`] less the hash.
fn read_unhashed(path: &Path, source: &source::Source, options: &IngestOptions) -> Result<Reading> {
    if let Some(ds) = binary::read(&binary::Bytes::from_source(path, source), options)? {
        return Ok(Reading::Data(ds));
    }
    // The decoding pass finds NUL bytes: no pass of its own here.
    let Some(text) = Text::decode_source_or_binary(path, source)? else {
        let bytes = source.bytes();
        let utf16 = bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]);
        return match options.format.is_none() && !utf16 {
            true => Ok(Reading::NotData("a binary file, not a text export".into())),
            false => Err(text::binary_error(path)),
        };
    };
    let reader = choose_reader(&text, options)?;
    match read_text(path, &text, reader, options) {
        Ok(ds) => Ok(Reading::Data(ds)),
        Err(e)
            if options.format.is_none() && reader.kind().is_none() && !has_numeric_rows(&text) =>
        {
            Ok(Reading::NotData(format!("no numeric table ({e})")))
        }
        Err(e) => Err(e),
    }
}

/// Whether any line reads as a row of at least two numbers under the
/// file's sniffed dialect.
fn has_numeric_rows(text: &Text) -> bool {
    let (delimiter, decimal, _) = dialect::sniff(text.lines());
    text.lines()
        .any(|l| matches!(dialect::parse_line(l, delimiter, decimal), (Some(r), _) if r.len() >= 2))
}

/// The reader named in the options, if any; an unknown name is an error
/// listing the known ones.
pub(crate) fn named_reader(options: &IngestOptions) -> Result<Option<&'static dyn Reader>> {
    let Some(name) = &options.format else {
        return Ok(None);
    };
    READERS
        .iter()
        .copied()
        .find(|r| r.name() == name)
        .map(Some)
        .ok_or_else(|| {
            let names: Vec<_> = READERS.iter().map(|r| r.name()).collect();
            Error::Config(format!(
                "unknown format '{name}'; known formats: {}",
                names.join(", ")
            ))
        })
}

/// The reader named in the options, or the first that recognises the text.
fn choose_reader(text: &Text, options: &IngestOptions) -> Result<&'static dyn Reader> {
    match named_reader(options)? {
        Some(r) => Ok(r),
        None => Ok(READERS
            .iter()
            .copied()
            .find(|r| r.sniff(text))
            .expect("the last reader accepts any file")),
    }
}
