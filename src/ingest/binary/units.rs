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

#[cfg(test)]
mod tests {
    use super::length_m;

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
