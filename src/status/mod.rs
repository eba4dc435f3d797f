//! Statuses of result rows: `ok`, or one or more codes ([`Code`], one
//! vocabulary for every table), each with a detail for people that carries
//! the numbers behind it. Each code has a stable text form, a
//! [`Severity`], and says whether the row keeps its result.
//!
//! A table holds a row's status as three columns, written by
//! `TableBuilder::status` from a schema's `type = "status"` entry:
//! `status` (a dictionary column: the most severe code, or `ok`),
//! `status_codes` (a list of every code, in the order found) and
//! `status_detail` (`code: detail; code: detail`, null when `ok`). A row
//! with any code never says `ok`.

use std::fmt;

mod codes;

pub use codes::Code;

/// How much a code weighs on its row; ordered from the least severe.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Said for the record: how the result was obtained (a load ramp, an
    /// averaged window). The result stands.
    Info,
    /// The result is given but partial, doubtful, or rests on a default or
    /// an assumption.
    Warning,
    /// No result, or values that must not be used as one.
    Error,
}

impl Code {
    /// The code of a text form.
    pub fn parse(s: &str) -> Option<Code> {
        Code::ALL.iter().copied().find(|c| c.as_str() == s)
    }

    /// Whether a result computed from a row with this code inherits it as
    /// a doubt: a warning (an info code says how, an error leaves no
    /// value to compute from).
    pub fn is_doubt(self) -> bool {
        self.severity() == Severity::Warning
    }

    /// Whether the code doubts a friction row's static peak and nothing
    /// else: a result from the sliding part (a dynamic fit, a cycle's μ)
    /// does not inherit it.
    pub fn doubts_static_peak_only(self) -> bool {
        matches!(
            self,
            Code::NoStaticPeak | Code::StaticBelowDynamic | Code::PeakAtStart
        )
    }

    /// How codes rank for a row's `status`: by severity, then a code
    /// without a result above one with.
    fn rank(self) -> (Severity, bool) {
        (self.severity(), !self.has_result())
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The text of the `status` column for a row without codes.
pub const OK: &str = "ok";

/// One code with its detail.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// What.
    pub code: Code,
    /// For people: the values behind it.
    pub detail: String,
}

/// A row a result is computed from (a fit's point, a group's member),
/// with those of its warnings that concern the result ([`Status::inherit`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InputRow {
    /// Names the row for people: its file, and what within it.
    pub label: String,
    /// Its warnings that concern the result.
    pub codes: Vec<Code>,
}

/// A row's status: `ok` when it has no notes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Status {
    notes: Vec<Note>,
}

impl Status {
    /// `ok`.
    pub fn ok() -> Self {
        Status::default()
    }
    /// A status with one note.
    pub fn of(code: Code, detail: impl Into<String>) -> Self {
        let mut s = Status::ok();
        s.push(code, detail);
        s
    }
    /// Adds a note. A `; ` in the detail becomes `, `: it separates the
    /// notes of a `status_detail` cell.
    pub fn push(&mut self, code: Code, detail: impl Into<String>) {
        let detail: String = detail.into();
        let detail = match detail.contains("; ") {
            true => detail.replace("; ", ", "),
            false => detail,
        };
        self.notes.push(Note { code, detail });
    }
    /// Adds every note of `other`.
    pub fn extend(&mut self, other: Status) {
        self.notes.extend(other.notes);
    }
    /// Whether there is nothing to say.
    pub fn is_ok(&self) -> bool {
        self.notes.is_empty()
    }
    /// Whether it has `code`.
    pub fn has(&self, code: Code) -> bool {
        self.notes.iter().any(|n| n.code == code)
    }
    /// Whether every code is one of `allowed` (`ok` is).
    pub fn only(&self, allowed: &[Code]) -> bool {
        self.notes.iter().all(|n| allowed.contains(&n.code))
    }
    /// The notes, in the order found.
    pub fn notes(&self) -> &[Note] {
        &self.notes
    }
    /// The distinct codes, in the order found.
    pub fn codes(&self) -> Vec<Code> {
        let mut out: Vec<Code> = Vec::with_capacity(self.notes.len());
        for n in &self.notes {
            if !out.contains(&n.code) {
                out.push(n.code);
            }
        }
        out
    }
    /// The distinct codes of severity warning, in the order found: what a
    /// result computed from this one inherits ([`Status::inherit`]).
    pub fn warnings(&self) -> Vec<Code> {
        let mut w = self.codes();
        w.retain(|c| c.is_doubt());
        w
    }
    /// The most severe code (the first found among equals); `None` when ok.
    pub fn worst(&self) -> Option<Code> {
        let mut worst: Option<Code> = None;
        for n in &self.notes {
            if worst.is_none_or(|w| n.code.rank() > w.rank()) {
                worst = Some(n.code);
            }
        }
        worst
    }
    /// The `status` cell: the most severe code, or `ok`.
    pub fn cell(&self) -> &'static str {
        self.worst().map_or(OK, Code::as_str)
    }
    /// The severity of the most severe code; `None` when ok.
    pub fn severity(&self) -> Option<Severity> {
        self.worst().map(Code::severity)
    }
    /// Whether the row keeps its result: every code says so.
    pub fn has_result(&self) -> bool {
        self.notes.iter().all(|n| n.code.has_result())
    }
    /// The `status_detail` cell: every note as `code: detail`, joined by
    /// `; `; `None` when ok.
    pub fn detail(&self) -> Option<String> {
        (!self.is_ok()).then(|| self.to_string())
    }

    /// Adds `doubtful_points` when some of the `used` rows a result rests
    /// on (a fit's points, a group's members; each with the warnings that
    /// concern the result, often none) carry warnings of their own: a
    /// result over doubtful rows is not `ok`. The detail names the first
    /// three, in input order, with their codes.
    pub fn inherit<'a>(&mut self, used: impl IntoIterator<Item = &'a InputRow>) {
        let mut n = 0;
        let doubtful: Vec<&InputRow> = used
            .into_iter()
            .inspect(|_| n += 1)
            .filter(|r| !r.codes.is_empty())
            .collect();
        if doubtful.is_empty() {
            return;
        }
        let named: Vec<String> = doubtful
            .iter()
            .take(3)
            .map(|r| {
                let codes: Vec<&str> = r.codes.iter().map(|c| c.as_str()).collect();
                format!("{} ({})", r.label, codes.join(", "))
            })
            .collect();
        let more = match doubtful.len() {
            k if k > 3 => format!(" and {} more", k - 3),
            _ => String::new(),
        };
        self.push(
            Code::DoubtfulPoints,
            format!(
                "{} of the {n} rows used carry warnings: {}{more}",
                doubtful.len(),
                named.join(", ")
            ),
        );
    }

    /// The status a table's row holds, from its `status_codes` and
    /// `status_detail` cells (the inverse of [`Status::codes`] and
    /// [`Status::detail`]). The detail is split where a part begins with
    /// one of the row's codes; a code without a part has an empty detail.
    pub fn from_cells(codes: &[Code], detail: Option<&str>) -> Status {
        let mut s = Status::ok();
        let starts = |part: &str| {
            codes.iter().copied().find(|c| {
                part.strip_prefix(c.as_str())
                    .is_some_and(|rest| rest.is_empty() || rest.starts_with(": "))
            })
        };
        for part in detail.into_iter().flat_map(|d| d.split("; ")) {
            match (starts(part), s.notes.last_mut()) {
                (Some(c), _) => {
                    let rest = &part[c.as_str().len()..];
                    s.push(c, rest.strip_prefix(": ").unwrap_or(rest));
                }
                (None, Some(last)) => {
                    last.detail.push_str("; ");
                    last.detail.push_str(part);
                }
                (None, None) => {}
            }
        }
        for &c in codes {
            if !s.has(c) {
                s.push(c, "");
            }
        }
        s
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.notes.is_empty() {
            return f.write_str(OK);
        }
        for (i, n) in self.notes.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            match n.detail.is_empty() {
                true => write!(f, "{}", n.code)?,
                false => write!(f, "{}: {}", n.code, n.detail)?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_form_round_trips() {
        for &c in Code::ALL {
            assert_eq!(Code::parse(c.as_str()), Some(c));
            assert!(!c.meaning().trim().is_empty(), "{c}");
        }
        let mut s = Status::of(Code::NoStaticPeak, "no maximum stands out of the noise");
        s.push(Code::NoNormalForce, "no column");
        let text = s.to_string();
        assert_eq!(
            text,
            "no_static_peak: no maximum stands out of the noise; no_normal_force: no column"
        );
        assert_eq!(Status::ok().to_string(), "ok");
        assert_eq!(Status::ok().detail(), None);
        assert_eq!(
            Status::of(Code::SeUndefined, "").to_string(),
            "se_undefined"
        );
    }

    /// The most severe code is the row's `status`: an error above a
    /// warning above a note, the first found among equals; a row keeps
    /// its result only when every code says so.
    #[test]
    fn worst_code_and_result() {
        let mut s = Status::of(Code::LoadRamp, "5 → 10 N");
        assert_eq!(s.cell(), "load_ramp");
        assert!(s.has_result());
        s.push(Code::PeakAtStart, "t = 0.01 s");
        s.push(Code::StaticBelowDynamic, "0.2 < 0.3");
        assert_eq!(s.worst(), Some(Code::PeakAtStart));
        s.push(Code::NoNormalForce, "");
        assert_eq!(s.cell(), "no_normal_force");
        assert_eq!(s.severity(), Some(Severity::Error));
        assert!(!s.has_result());
        assert_eq!(Status::ok().cell(), OK);
        assert!(Status::ok().has_result());
        // Among errors without a result, the first found.
        let mut t = Status::of(Code::ImpossibleValue, "-8.2 MPa");
        t.push(Code::NoLoad, "");
        assert_eq!(t.worst(), Some(Code::ImpossibleValue));
    }

    /// Codes and detail cells give the status back, details holding `; `
    /// and `:` included; repeated codes are listed once.
    #[test]
    fn cells_round_trip() {
        let mut s = Status::of(Code::BeyondValidity, "film 1e-10 m; thin: yes");
        s.push(Code::SeUndefined, "");
        s.push(Code::BeyondValidity, "μ = 4.1 above 1");
        s.push(Code::Misfit, "rel_rmse = 0.3 > 0.1");
        let codes = s.codes();
        assert_eq!(
            codes,
            [Code::BeyondValidity, Code::SeUndefined, Code::Misfit]
        );
        assert_eq!(Status::from_cells(&codes, s.detail().as_deref()), s);
        assert_eq!(Status::from_cells(&[], None), Status::ok());
    }
}
