//! Numbers as the report shows them: one unit per column, taken from the
//! table's schema and given the SI prefix that suits the column's values
//! (Ra in µm, a wear volume in µm³ or mm³, a strength in MPa, a modulus in
//! GPa), each value to significant digits, and scientific notation for a
//! column whose values span decades. A cell is a plain number; its unit is
//! in the column's heading.

/// A column of numbers formatted for people.
#[derive(Debug, Clone, PartialEq)]
pub struct Numbers {
    /// The unit of every cell, as shown (`µm`, `mm³`, `MPa`; empty for a
    /// number without a unit).
    pub unit: String,
    /// One cell per value: a plain number, or `–` for none.
    pub cells: Vec<String>,
    /// A cell's number times `scale` is the value in the schema's unit.
    pub scale: f64,
}

/// The placeholder of a missing value.
pub const NONE: &str = "–";

/// Significant digits of the column's largest value.
const DIGITS: i32 = 4;
/// Significant digits at least of the column's smallest nonzero value.
const MIN_DIGITS: i32 = 2;
/// A column whose largest and smallest nonzero magnitudes differ by this
/// factor or more is written in scientific notation.
const DECADES: f64 = 1e3;

/// SI prefixes and their powers of ten.
const PREFIXES: &[(&str, i32)] = &[
    ("p", -12),
    ("n", -9),
    ("µ", -6),
    ("u", -6),
    ("m", -3),
    ("", 0),
    ("k", 3),
    ("M", 6),
    ("G", 9),
];

/// Units that take a prefix, with the range of prefixes a lab reads them
/// in (powers of ten): lengths from pm to km, pressures from Pa to GPa.
const BASES: &[(&str, i32, i32)] = &[
    ("m", -12, 3),
    ("Pa", 0, 9),
    ("N", -6, 3),
    ("s", -6, 0),
    ("J", -3, 6),
    ("Hz", 0, 9),
];

/// A prefixable unit: prefix power of ten, base, power (`mm^3` = (−3, m, 3)).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Prefixed {
    exp: i32,
    base: &'static str,
    power: i32,
    min: i32,
    max: i32,
}

fn parse_prefixed(unit: &str) -> Option<Prefixed> {
    let (body, power) = match unit.split_once('^') {
        Some((b, p)) => (b, p.parse::<i32>().ok().filter(|p| (1..=3).contains(p))?),
        None => (unit, 1),
    };
    // The base alone first: "m" is the metre, not a prefix.
    for &(base, min, max) in BASES {
        let exp = match body.strip_suffix(base) {
            Some("") => 0,
            Some(p) => PREFIXES.iter().find(|(s, _)| *s == p)?.1,
            None => continue,
        };
        return Some(Prefixed {
            exp,
            base,
            power,
            min,
            max,
        });
    }
    None
}

fn prefix_symbol(exp: i32) -> &'static str {
    PREFIXES
        .iter()
        .find(|(s, e)| *e == exp && *s != "u")
        .map_or("", |p| p.0)
}

/// A schema unit as people write it: `m^2` → `m²`, `um` → `µm`, `degC` →
/// `°C`, `1` → nothing.
pub fn pretty_unit(unit: &str) -> String {
    match unit {
        "1" | "" => return String::new(),
        "deg" => return "°".into(),
        "degC" => return "°C".into(),
        _ => {}
    }
    let mut out = String::with_capacity(unit.len() + 4);
    let mut chars = unit.chars().peekable();
    let mut prev_letter = false;
    while let Some(c) = chars.next() {
        match c {
            '^' => {}
            '2' | '3' if prev_letter || out.ends_with('^') => {
                out.push(if c == '2' { '²' } else { '³' })
            }
            '*' => out.push(' '),
            'u' if chars.peek().is_some_and(|n| *n == 'm') && !prev_letter => out.push('µ'),
            c => out.push(c),
        }
        prev_letter = c.is_ascii_alphabetic() || (c == '^' && prev_letter);
    }
    out
}

/// The column `values` (in the schema's `unit`) as the report shows it.
pub fn format_column(values: &[Option<f64>], unit: &str) -> Numbers {
    let finite = || values.iter().flatten().filter(|v| v.is_finite());
    let max = finite().fold(0.0_f64, |m, v| m.max(v.abs()));
    let min = finite()
        .map(|v| v.abs())
        .filter(|v| *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    // The prefix that puts the largest value in [1, 1000) of its unit.
    let (shown, scale) = match parse_prefixed(unit) {
        Some(p) if max > 0.0 => {
            let si = max * 10f64.powi(p.exp * p.power);
            let k = (si.log10() / (3 * p.power) as f64).floor() as i32 * 3;
            let k = k.clamp(p.min, p.max);
            let power = match p.power {
                1 => String::new(),
                n => pretty_unit(&format!("m^{n}"))[1..].to_string(),
            };
            let scale = 10f64.powi((k - p.exp) * p.power);
            (format!("{}{}{power}", prefix_symbol(k), p.base), scale)
        }
        _ => (pretty_unit(unit), 1.0),
    };
    let (max, min) = (max / scale, min / scale);
    let scientific = max > 0.0 && max / min >= DECADES;
    let decimals = if max > 0.0 {
        let for_max = DIGITS - 1 - max.log10().floor() as i32;
        let for_min = MIN_DIGITS - 1 - min.log10().floor() as i32;
        for_max.max(for_min).max(0) as usize
    } else {
        0
    };
    let cells = values
        .iter()
        .map(|v| match v.filter(|v| v.is_finite()) {
            None => NONE.to_string(),
            Some(v) if scientific => format!("{:.*e}", (DIGITS - 1) as usize, v / scale),
            Some(v) => format!("{:.*}", decimals, v / scale),
        })
        .collect();
    Numbers {
        unit: shown,
        cells,
        scale,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cells(values: &[f64], unit: &str) -> (String, Vec<String>) {
        let v: Vec<Option<f64>> = values.iter().copied().map(Some).collect();
        let n = format_column(&v, unit);
        (n.unit, n.cells)
    }

    /// Roughness in metres reads in µm or nm; areas and volumes take the
    /// prefix to their power; stresses stored in MPa may read in GPa.
    #[test]
    fn prefix_per_column() {
        assert_eq!(
            cells(&[1.234e-6, 0.52e-6], "m"),
            ("µm".into(), vec!["1.234".into(), "0.520".into()])
        );
        assert_eq!(cells(&[4.2e-9, 3.1e-9], "m").0, "nm");
        assert_eq!(
            cells(&[3.2e-11], "m^2"),
            ("µm²".into(), vec!["32.00".into()])
        );
        assert_eq!(cells(&[2.5e-13], "m^3").0, "µm³");
        assert_eq!(
            cells(&[2.5e-9], "m^3"),
            ("mm³".into(), vec!["2.500".into()])
        );
        assert_eq!(
            cells(&[2100.0, 1500.0], "MPa"),
            ("GPa".into(), vec!["2.100".into(), "1.500".into()])
        );
        assert_eq!(cells(&[0.5], "GPa"), ("MPa".into(), vec!["500.0".into()]));
        assert_eq!(cells(&[12.0], "mm"), ("mm".into(), vec!["12.00".into()]));
        // Pressures never below Pa; a dimensionless column has no unit.
        assert_eq!(cells(&[0.3], "Pa").0, "Pa");
        assert_eq!(
            cells(&[0.3, 0.31], "1"),
            (String::new(), vec!["0.3000".into(), "0.3100".into()])
        );
    }

    /// Decimals keep two significant digits of the smallest value; a column
    /// over three decades or more is scientific. No nonzero value is 0.
    #[test]
    fn digits_and_decades() {
        assert_eq!(
            cells(&[12.3, 0.05], "1").1,
            vec!["12.300".to_string(), "0.050".to_string()]
        );
        let (_, c) = cells(&[1.0, 1e-4, 0.0], "1");
        assert_eq!(c, vec!["1.000e0", "1.000e-4", "0.000e0"]);
        for (vals, unit) in [
            (vec![5e-7, 3e-12, 1e-3], "m"),
            (vec![999.0, 0.4], "N"),
            (vec![1e300, 1e-300], "1"),
        ] {
            let v: Vec<Option<f64>> = vals.iter().copied().map(Some).collect();
            let n = format_column(&v, unit);
            for (x, c) in vals.iter().zip(&n.cells) {
                let back: f64 = c.parse().unwrap();
                assert!(
                    (back * n.scale - x).abs() <= 5e-3 * x.abs(),
                    "{x} as {c} {}",
                    n.unit
                );
            }
        }
    }

    #[test]
    fn missing_values_and_units_as_written() {
        let n = format_column(&[None, Some(f64::NAN)], "m");
        assert_eq!(n.cells, vec![NONE, NONE]);
        assert_eq!(pretty_unit("mm^3/(N*m)"), "mm³/(N m)");
        assert_eq!(pretty_unit("MJ/m3"), "MJ/m³");
        assert_eq!(pretty_unit("g/cm3"), "g/cm³");
        assert_eq!(pretty_unit("um"), "µm");
        assert_eq!(pretty_unit("J/g"), "J/g");
        assert_eq!(pretty_unit("m/s"), "m/s");
    }
}
