//! Length units as instrument files spell them: `nm`, `µm` in UTF-8 or
//! Latin-1, `~m` (Nanoscope's µ lost to an 8-bit code page), `um`, `Å`,
//! `mkm`, words (`micron`). Only lengths become metres here: a channel in
//! another unit keeps the unit the file gives it.

use crate::units::{parse_unit, Quantity};

/// Metres per `unit` when it is a length; `None` otherwise (`V`, `deg`,
/// `A` for ampere, an empty unit).
pub fn length_m(unit: &str) -> Option<f64> {
    let u = unit.trim();
    let u = u
        .strip_prefix('[')
        .and_then(|s| s.strip_suffix(']'))
        .unwrap_or(u)
        .trim();
    if matches!(u, "Å" | "\u{212b}" | "Ang" | "angstrom" | "Angstrom") {
        return Some(1e-10);
    }
    if let Some(prefix) = u.strip_suffix('m') {
        let f = match prefix {
            "" => 1.0,
            "k" => 1e3,
            "c" => 1e-2,
            "d" => 1e-1,
            "m" => 1e-3,
            "µ" | "μ" | "u" | "~" | "mk" | "Âµ" => 1e-6,
            "n" => 1e-9,
            "p" => 1e-12,
            "f" => 1e-15,
            _ => return None,
        };
        return Some(f);
    }
    parse_unit(u)
        .filter(|p| p.quantity == Quantity::Length)
        .map(|p| p.scale)
}

/// The factor of an SI prefix (`m`, `µ`, `n`, ... `k`, `M`), `""` → 1.
pub fn si_prefix(p: &str) -> Option<f64> {
    Some(match p {
        "" => 1.0,
        "G" => 1e9,
        "M" => 1e6,
        "k" => 1e3,
        "c" => 1e-2,
        "m" => 1e-3,
        "µ" | "μ" | "u" | "~" => 1e-6,
        "n" => 1e-9,
        "p" => 1e-12,
        "f" => 1e-15,
        _ => return None,
    })
}

/// How many `to` in one `from` when they are the same unit with SI
/// prefixes (`mV` → `V`: 1e-3); `None` for different units.
pub fn prefixed_ratio(from: &str, to: &str) -> Option<f64> {
    let (from, to) = (from.trim(), to.trim());
    if from == to {
        return Some(1.0);
    }
    if let (Some(a), Some(b)) = (length_m(from), length_m(to)) {
        return Some(a / b);
    }
    // The longest common ending is the base unit.
    (1..=from.len().min(to.len()))
        .rev()
        .filter(|&k| from.is_char_boundary(from.len() - k) && to.is_char_boundary(to.len() - k))
        .find(|&k| from[from.len() - k..] == to[to.len() - k..])
        .and_then(|k| {
            let (pf, pt) = (&from[..from.len() - k], &to[..to.len() - k]);
            Some(si_prefix(pf)? / si_prefix(pt)?)
        })
}

#[cfg(test)]
mod tests {
    use super::{length_m, prefixed_ratio};

    #[test]
    fn prefixed_ratios() {
        assert_eq!(prefixed_ratio("mV", "V"), Some(1e-3));
        assert_eq!(prefixed_ratio("V", "V"), Some(1.0));
        assert!((prefixed_ratio("nm", "um").unwrap() - 1e-3).abs() < 1e-18);
        assert_eq!(prefixed_ratio("kHz", "Hz"), Some(1e3));
        assert_eq!(prefixed_ratio("V", "A"), None);
        assert_eq!(prefixed_ratio("xV", "V"), None);
    }

    #[test]
    fn spellings_of_lengths() {
        for (u, f) in [
            ("m", 1.0),
            ("nm", 1e-9),
            (" µm ", 1e-6),
            ("μm", 1e-6),
            ("um", 1e-6),
            ("~m", 1e-6),
            ("mkm", 1e-6),
            ("Âµm", 1e-6),
            ("pm", 1e-12),
            ("mm", 1e-3),
            ("Å", 1e-10),
            ("[nm]", 1e-9),
            ("micron", 1e-6),
        ] {
            assert_eq!(length_m(u), Some(f), "{u}");
        }
        for u in ["", "V", "A", "deg", "º", "N", "mV", "Hz", "a.u."] {
            assert_eq!(length_m(u), None, "{u}");
        }
    }
}
