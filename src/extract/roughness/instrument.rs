//! What the instrument itself states in its export: its evaluation window
//! (the Dektak's cursors), its printed results, and its stylus. The
//! window is the default evaluation window when the settings give none; a
//! result on another window says so (`window_differs`); on the same
//! window, a printed result that differs from ours by more than one unit
//! of its last printed digit plus 1 % of it is a status
//! (`instrument_mismatch`). One unit of the last digit is the printing's
//! own rounding (half a unit) plus as much again for the vendor's
//! positions and sums; 1 % holds the Rz cut into five parts, which moves
//! with the boundary points (the Dektak's RzDin is 0.77 % from ours,
//! docs/roughness.md).

use super::report::{RoughnessReport, SurfaceKind};
use crate::ingest::formats::dektak::analytical_results;
use crate::ingest::{Dataset, MetaEntry};
use crate::status::{Code, Status};
use crate::units::parse_quantity;
use crate::units::Quantity;

/// One printed result: its value (SI) and one unit of its last printed
/// digit (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Printed {
    /// The value.
    pub value: f64,
    /// One unit of the last digit printed.
    pub step: f64,
}

/// Roughness results an instrument printed in its export, in SI, with the
/// cursor window they were computed on and its stylus tip radius.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct InstrumentRoughness {
    /// Ra (m).
    pub ra: Option<Printed>,
    /// Rq (m).
    pub rq: Option<Printed>,
    /// Skewness.
    pub rsk: Option<Printed>,
    /// Rz by DIN 4768 (m).
    pub rz_din: Option<Printed>,
    /// Cursor window (m): the R and M cursor positions, ordered.
    pub window: Option<(f64, f64)>,
    /// Stylus tip radius (m), when the file states it.
    pub tip_radius: Option<f64>,
}

/// One unit of the last digit of the number that starts `text`, relative
/// to the number (so that the SI value times it is the SI step).
fn last_digit(text: &str) -> Option<f64> {
    let num: String = text
        .trim()
        .chars()
        .take_while(|c| c.is_ascii_digit() || matches!(c, '.' | '-' | '+'))
        .collect();
    let v: f64 = num.parse().ok()?;
    let decimals = num.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    (v != 0.0).then(|| 10f64.powi(-decimals) / v.abs())
}

/// The stylus radius of a Dektak preamble line `Stylus,Radius: 2.5 µm`.
fn stylus_radius(preamble: &[MetaEntry]) -> Option<f64> {
    let m = preamble
        .iter()
        .find(|m| m.key.eq_ignore_ascii_case("Stylus"))?;
    let (_, r) = m.value.split_once(':')?;
    // Latin-1 files may carry µ as a replacement character: read it as µm.
    let r = r.trim().replace('\u{fffd}', "µ");
    parse_quantity(&r, Quantity::Length, "stylus radius").ok()
}

impl InstrumentRoughness {
    /// The printed results of a Dektak export; empty for other formats.
    pub fn from_dataset(ds: &Dataset) -> Self {
        if ds.format != "dektak" {
            return Self::default();
        }
        let results = analytical_results(&ds.preamble);
        let get = |f: &str| {
            let r = results
                .iter()
                .find(|r| r.function.eq_ignore_ascii_case(f))?;
            let text = ds.preamble.iter().find(|m| m.key == r.function)?;
            let printed = text.value.rsplit(',').next()?;
            Some(Printed {
                value: r.value,
                step: last_digit(printed)? * r.value.abs(),
            })
        };
        let window = results
            .first()
            .map(|r| (r.r_cursor.min(r.m_cursor), r.r_cursor.max(r.m_cursor)));
        InstrumentRoughness {
            ra: get("Ra"),
            rq: get("Rq"),
            rsk: get("Skew"),
            rz_din: get("RzDin"),
            window,
            tip_radius: stylus_radius(&ds.preamble),
        }
    }

    /// Whether our `window` is the instrument's (to a thousandth of a
    /// micrometre: the cursors are printed to 0.1 µm).
    fn same_window(&self, window: Option<(f64, f64)>) -> bool {
        match (self.window, window) {
            (Some(a), Some(b)) => (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
            _ => false,
        }
    }

    /// The notes of a profile's report against the printed results:
    /// `window_differs` on another window, else `instrument_mismatch`
    /// beyond the tolerance (module documentation).
    pub fn compare(&self, r: &RoughnessReport) -> Status {
        let mut notes = Status::ok();
        let Some(w) = self.window.filter(|_| r.kind == SurfaceKind::Profile) else {
            return notes;
        };
        if !self.same_window(r.window) {
            let ours = r.window.map_or("the whole profile".to_string(), |(a, b)| {
                format!("{:.1}–{:.1} µm", a * 1e6, b * 1e6)
            });
            notes.push(
                Code::WindowDiffers,
                format!(
                    "the instrument's results are for {:.1}–{:.1} µm; this result is for {ours}",
                    w.0 * 1e6,
                    w.1 * 1e6
                ),
            );
            return notes;
        }
        let pairs = [
            ("Ra", self.ra, Some(r.ra)),
            ("Rq", self.rq, Some(r.rq)),
            ("Rsk", self.rsk, r.rsk),
            ("Rz DIN", self.rz_din, r.heights.rz_din),
        ];
        let off: Vec<String> = pairs
            .iter()
            .filter_map(|&(name, printed, ours)| {
                let (p, v) = (printed?, ours?);
                let tol = p.step + 0.01 * p.value.abs();
                ((v - p.value).abs() > tol)
                    .then(|| format!("{name} {v:.6e} against the printed {:.6e}", p.value))
            })
            .collect();
        if !off.is_empty() {
            notes.push(Code::InstrumentMismatch, off.join(", "));
        }
        notes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn last_printed_digit_and_stylus() {
        assert!((last_digit("0.00525 um").unwrap() * 0.00525 - 1e-5).abs() < 1e-18);
        assert!((last_digit("6.96").unwrap() * 6.96 - 0.01).abs() < 1e-15);
        assert!((last_digit("12").unwrap() * 12.0 - 1.0).abs() < 1e-15);
        assert!(last_digit("abc").is_none());
        let pre = vec![MetaEntry {
            key: "Stylus".into(),
            value: "Radius: 2.5 \u{fffd}m".into(),
            line: 4,
        }];
        assert!((stylus_radius(&pre).unwrap() - 2.5e-6).abs() < 1e-18);
    }
}
