//! Values physics rules out, and units their values contradict.

use super::{note, sig, Shown};
use crate::status::{Code, Note};

/// [`Code::ImpossibleValue`] when `value` is below `min` (a negative
/// strength or yield stress: `min` = 0), naming the value and the bound.
pub fn at_least(q: Shown, value: f64, min: f64, why: &str) -> Option<Note> {
    (value < min).then_some(()).and_then(|_| {
        note(
            Code::ImpossibleValue,
            format!(
                "{} {} is below {} ({why})",
                q.name,
                q.value(value),
                q.value(min)
            ),
        )
    })
}

/// [`Code::ImpossibleValue`] when `value` exceeds `max` (a strain beyond
/// the bound of its material class), naming the value, the bound and why.
pub fn at_most(q: Shown, value: f64, max: f64, why: &str) -> Option<Note> {
    (value > max).then_some(()).and_then(|_| {
        note(
            Code::ImpossibleValue,
            format!(
                "{} {} exceeds {} ({why})",
                q.name,
                q.value(value),
                q.value(max)
            ),
        )
    })
}

/// [`Code::SuspectUnit`] when a time column spans more than `max_s`
/// seconds for one test of a kind whose duration is bounded (`what`): the
/// unit it states is doubtful. When the span read in milliseconds falls in
/// bounds, the detail says so (a column headed `(s)` that counts ms).
pub fn duration(column: &str, unit: &str, span_s: f64, max_s: f64, what: &str) -> Option<Note> {
    if span_s.is_nan() || span_s <= max_s {
        return None;
    }
    let ms = match span_s * 1e-3 <= max_s {
        true => format!(
            ", and read as milliseconds it would span {} s",
            sig(span_s * 1e-3)
        ),
        false => String::new(),
    };
    note(
        Code::SuspectUnit,
        format!(
            "time column '{column}' in {unit} spans {} s ({} h), more than {} h for {what}{ms}",
            sig(span_s),
            sig(span_s / 3600.0),
            sig(max_s / 3600.0),
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const STRESS: Shown = Shown {
        name: "yield stress",
        unit: "MPa",
        scale: 1e-6,
    };

    #[test]
    fn bounds_name_the_value() {
        assert_eq!(at_least(STRESS, 5e6, 0.0, "tension"), None);
        let n = at_least(STRESS, -8.2e6, 0.0, "a stress in tension is positive").unwrap();
        assert_eq!(n.code, Code::ImpossibleValue);
        assert_eq!(
            n.detail,
            "yield stress -8.2 MPa is below 0 MPa (a stress in tension is positive)"
        );
        assert!(at_most(STRESS, 2e6, 1e6, "x").is_some());
        assert!(at_most(STRESS, f64::NAN, 1e6, "x").is_none());
        let t = duration("Time", "s", 437_500.0, 86_400.0, "one tensile test").unwrap();
        assert_eq!(t.code, Code::SuspectUnit);
        assert!(
            t.detail.contains("437500 s") && t.detail.contains("437.5 s"),
            "{}",
            t.detail
        );
        assert_eq!(duration("Time", "s", 600.0, 86_400.0, "x"), None);
    }
}
