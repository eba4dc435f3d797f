//! The library's error type.
//!
//! Two families are kept apart, as users act on them differently:
//! - **bad input** ([`Error::Input`], [`Error::Unit`], [`Error::Config`]): the
//!   file, table or configuration is not what was expected. The message names
//!   the file, line and column and says what was expected. Fix the input.
//! - **not applicable** ([`Error::NotApplicable`], [`Error::Numerical`]): the
//!   input was read, but the model or method cannot give a trustworthy number
//!   (outside the model's domain, no sliding phase, a fit that did not
//!   converge, a simulation that diverged).
//!
//! [`Error::Io`] and [`Error::Table`] wrap failures of the file system and of
//! the table layer.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::status::{Code, Status};

/// Result with the library's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Where in an input something went wrong: a file, and optionally a 1-based
/// line and a column name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The input file.
    pub path: PathBuf,
    /// 1-based line number in the file, when known.
    pub line: Option<usize>,
    /// Column name (or 1-based index as text), when known.
    pub column: Option<String>,
}

impl Location {
    /// A whole file.
    pub fn file(path: impl AsRef<Path>) -> Self {
        Location {
            path: path.as_ref().to_path_buf(),
            line: None,
            column: None,
        }
    }
    /// A line of a file.
    pub fn line(path: impl AsRef<Path>, line: usize) -> Self {
        Location {
            line: Some(line),
            ..Location::file(path)
        }
    }
    /// Adds a column name.
    pub fn with_column(mut self, column: impl Into<String>) -> Self {
        self.column = Some(column.into());
        self
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, ", line {line}")?;
        }
        if let Some(col) = &self.column {
            write!(f, ", column '{col}'")?;
        }
        Ok(())
    }
}

/// Everything that can go wrong in tribo.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input: a file whose content is not what its format requires.
    #[error("{location}: {message}")]
    Input {
        /// Where.
        location: Location,
        /// What was found and what was expected.
        message: String,
    },
    /// Bad input: a unit that tribo does not know, or one that does not fit
    /// the quantity of its column. Never guessed.
    #[error("{location}: unknown unit '{unit}'; expected {expected}")]
    Unit {
        /// Where (the column is always named).
        location: Location,
        /// The unit as written in the file.
        unit: String,
        /// What would have been accepted.
        expected: String,
    },
    /// Bad input: a binary or structured file (a container, a header, a
    /// data block) that does not hold together at a byte offset: truncated,
    /// corrupted, or a version the reader does not know.
    #[error("{}: byte {offset}: {structure}: {message}", path.display())]
    Structure {
        /// The file.
        path: PathBuf,
        /// The structure that failed (`SUR header`, `zip central directory`).
        structure: String,
        /// Byte offset in the file (or in the decompressed entry it names).
        offset: u64,
        /// What was found and what was expected.
        message: String,
    },
    /// Bad configuration: a command-line argument, pipeline file, scene file
    /// or parameter out of its valid range.
    #[error("{0}")]
    Config(String),
    /// Not applicable: the data was read, but the method or model does not
    /// apply (no sliding phase, outside the model's domain, singular design).
    #[error("not applicable: {0}")]
    NotApplicable(String),
    /// Not applicable, for a reason a status code names (surfaces that
    /// lock, no contact, a singular design): a row that could not be
    /// computed carries that code, matched on the code, not the message.
    #[error("not applicable: {message}")]
    Coded {
        /// What the row's status says.
        code: Code,
        /// What was found.
        message: String,
    },
    /// Not applicable: a numerical procedure failed (no convergence,
    /// divergence, a non-finite value at a named step).
    #[error("numerical failure: {0}")]
    Numerical(String),
    /// The file system refused a read or a write.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or folder involved.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The table layer (polars / Parquet) failed.
    #[error("table: {0}")]
    Table(String),
}

impl Error {
    /// Bad input at a location.
    pub fn input(location: Location, message: impl Into<String>) -> Self {
        Error::Input {
            location,
            message: message.into(),
        }
    }
    /// An I/O error on a path.
    pub fn io(path: impl AsRef<Path>, source: std::io::Error) -> Self {
        Error::Io {
            path: path.as_ref().to_path_buf(),
            source,
        }
    }
    /// A not-applicable error for the reason `code` names.
    pub fn coded(code: Code, message: impl Into<String>) -> Self {
        Error::Coded {
            code,
            message: message.into(),
        }
    }

    /// The status code of a row this error left without a result, from
    /// the error's kind (never its message): the code it carries, a model
    /// that does not apply, a numerical failure, or bad input.
    pub fn status_code(&self) -> Code {
        match self {
            Error::Coded { code, .. } => *code,
            Error::NotApplicable(_) => Code::OutOfValidity,
            Error::Numerical(_) => Code::NumericalFailure,
            _ => Code::BadInput,
        }
    }

    /// The status of a row this error left without a result: its code
    /// ([`Error::status_code`]) with the message as the detail.
    pub fn status(&self) -> Status {
        Status::of(self.status_code(), self.to_string())
    }

    /// What kind of problem this is, for callers that act on it (the exit
    /// code, the `kind` column of `errors.parquet`).
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::Input { .. }
            | Error::Unit { .. }
            | Error::Structure { .. }
            | Error::Io { .. } => ErrorKind::BadInput,
            Error::Config(_) => ErrorKind::Configuration,
            Error::NotApplicable(_) | Error::Coded { .. } => ErrorKind::NotApplicable,
            Error::Numerical(_) => ErrorKind::Numerical,
            Error::Table(_) => ErrorKind::Table,
        }
    }
}

/// The family of an [`Error`], matchable across layers. Its text form (the
/// `kind` column of `errors.parquet`) is stable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum ErrorKind {
    /// The input is not what its format requires (or cannot be read).
    BadInput,
    /// The data was read, but the method or model does not apply.
    NotApplicable,
    /// A numerical procedure failed.
    Numerical,
    /// A command-line argument, pipeline, scene or parameter is invalid.
    Configuration,
    /// The table layer failed (a schema mismatch is a defect of tribo).
    Table,
}

impl ErrorKind {
    /// Stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            ErrorKind::BadInput => "bad_input",
            ErrorKind::NotApplicable => "not_applicable",
            ErrorKind::Numerical => "numerical",
            ErrorKind::Configuration => "configuration",
            ErrorKind::Table => "table",
        }
    }
}

impl fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}
