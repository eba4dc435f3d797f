//! Ours against the instrument's printed result (the modulus, strength or
//! strain at break that the vendor software wrote into the export).

use super::{note, percent, Shown, Tolerance};
use crate::status::{Code, Note};

/// `None` when our value agrees with the printed one within `tol`; else an
/// [`Code::InstrumentMismatch`] note naming both values, their difference
/// and the tolerance (`modulus: ours 0.741 GPa, the file prints 1.127 GPa
/// (−34.25 %; tolerance ±5 %)`). `why`, when not empty, is appended: what
/// is known about the cause (`the file does not state its window`).
pub fn against_printed(
    q: Shown,
    ours: f64,
    printed: f64,
    tol: Tolerance,
    why: &str,
) -> Option<Note> {
    if tol.admits(ours, printed) {
        return None;
    }
    let why = match why.is_empty() {
        true => String::new(),
        false => format!(": {why}"),
    };
    note(
        Code::InstrumentMismatch,
        format!(
            "{}: ours {}, the file prints {} ({}, tolerance {}){why}",
            q.name,
            q.value(ours),
            q.value(printed),
            percent(ours, printed),
            tol.describe(q.scale, q.unit),
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const MODULUS: Shown = Shown {
        name: "modulus",
        unit: "GPa",
        scale: 1e-9,
    };

    #[test]
    fn a_disagreement_names_both_values() {
        assert_eq!(
            against_printed(MODULUS, 1.10e9, 1.12712e9, Tolerance::rel(0.05), ""),
            None
        );
        let n = against_printed(MODULUS, 0.741e9, 1.12712e9, Tolerance::rel(0.05), "").unwrap();
        assert_eq!(n.code, Code::InstrumentMismatch);
        assert_eq!(
            n.detail,
            "modulus: ours 0.741 GPa, the file prints 1.1271 GPa (−34.257 %, tolerance ±5 %)"
        );
        // a NaN never agrees
        assert!(against_printed(MODULUS, f64::NAN, 1e9, Tolerance::rel(1.0), "").is_some());
    }
}
