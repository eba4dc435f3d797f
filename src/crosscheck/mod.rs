//! Cross-checks: one quantity known two ways must agree.
//!
//! Instrument exports are redundant: a file carries stress beside force,
//! strain beside extension, the instrument's own printed results (modulus,
//! strength, strain at break, Ra, COF) beside the raw channels. Each
//! redundancy is a free test of the file and of tribo. The functions here
//! are pure and take plain numbers and slices, so that every stage uses the
//! same checks with the same wording; each returns `None` when the two
//! agree and otherwise a [`Note`] with a status code per kind of
//! disagreement and a detail naming both values:
//!
//! | kind | code | function |
//! |---|---|---|
//! | ours against the file's printed result | [`Code::InstrumentMismatch`] | [`printed::against_printed`] |
//! | two channels (or metadata values) of one file | [`Code::ChannelMismatch`] | [`channels::rowwise`], [`channels::constant`] |
//! | a value physics rules out | [`Code::ImpossibleValue`] | [`bounds::at_least`], [`bounds::at_most`] |
//! | a stated unit its values contradict | [`Code::SuspectUnit`] | [`bounds::duration`] |
//!
//! Tolerances are stated by the caller ([`Tolerance`]) and documented with
//! the stage (`docs/tensile.md`, "Cross-checks"): a check whose tolerance is
//! not written down cannot be judged.

pub mod bounds;
pub mod channels;
pub mod printed;

use crate::status::Note;

/// How far two values may differ and still agree: |a − b| ≤ `abs` +
/// `rel` · |b|, with b the reference (the file's value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Relative part, a fraction (0.05 = 5 %).
    pub rel: f64,
    /// Absolute part, in the values' unit (for rounding of printed digits).
    pub abs: f64,
}

impl Tolerance {
    /// A relative tolerance only.
    pub const fn rel(rel: f64) -> Self {
        Tolerance { rel, abs: 0.0 }
    }
    /// A relative tolerance and an absolute floor.
    pub const fn new(rel: f64, abs: f64) -> Self {
        Tolerance { rel, abs }
    }
    /// Whether `value` agrees with `reference`. Non-finite values never
    /// agree.
    pub fn admits(&self, value: f64, reference: f64) -> bool {
        value.is_finite()
            && reference.is_finite()
            && (value - reference).abs() <= self.abs + self.rel * reference.abs()
    }
    /// The tolerance as people read it: `±5 %`, `±5 % + 0.001`.
    pub fn describe(&self, scale: f64, unit: &str) -> String {
        let rel = format!("±{} %", sig(self.rel * 100.0));
        match self.abs > 0.0 {
            true => format!("{rel} + {} {unit}", sig(self.abs * scale))
                .trim_end()
                .to_string(),
            false => rel,
        }
    }
}

/// A quantity as it is shown in a detail: its name, unit and the factor from
/// SI to that unit (`modulus`, `GPa`, 1e-9).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shown<'a> {
    /// What it is, in words (`modulus`, `strain at break`).
    pub name: &'a str,
    /// The unit the detail uses (empty for a fraction).
    pub unit: &'a str,
    /// SI value × `scale` = the value in `unit`.
    pub scale: f64,
}

impl Shown<'_> {
    /// `1.127 GPa`, with five significant digits.
    pub fn value(&self, si: f64) -> String {
        format!("{} {}", sig(si * self.scale), self.unit)
            .trim_end()
            .to_string()
    }
}

/// A number with five significant digits and no trailing zeros.
pub fn sig(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    if x.abs() < 1e-4 || x.abs() >= 1e9 {
        return format!("{x:.4e}");
    }
    let digits = (4 - x.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let s = format!("{x:.digits$}");
    match s.contains('.') {
        true => s.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => s,
    }
}

/// The signed relative difference of `value` from `reference`, in percent,
/// as text (`−34.2 %`); empty when the reference is zero.
pub fn percent(value: f64, reference: f64) -> String {
    if reference == 0.0 || !reference.is_finite() {
        return String::new();
    }
    let d = (value / reference - 1.0) * 100.0;
    format!("{}{} %", if d < 0.0 { "−" } else { "+" }, sig(d.abs()))
}

/// A note, for the submodules.
fn note(code: crate::status::Code, detail: String) -> Option<Note> {
    Some(Note { code, detail })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tolerances_and_numbers_read_as_people_write_them() {
        let t = Tolerance::new(0.05, 0.001);
        assert!(t.admits(1.05, 1.0) && t.admits(1.0509, 1.0));
        assert!(!t.admits(1.052, 1.0) && !t.admits(f64::NAN, 1.0));
        assert!(Tolerance::rel(0.0).admits(2.0, 2.0));
        assert_eq!(sig(1127.12), "1127.1");
        assert_eq!(sig(0.000123456), "0.00012346");
        assert_eq!(sig(7.713e-7), "7.7130e-7");
        assert_eq!(sig(37.9483), "37.948");
        assert_eq!(sig(-2.0), "-2");
        assert_eq!(percent(0.741, 1.127), "−34.25 %");
        assert_eq!(percent(1.0, 0.0), "");
        assert_eq!(Tolerance::rel(0.05).describe(1.0, ""), "±5 %");
    }
}
