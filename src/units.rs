//! Units and their conversion to SI, done once at the ingestion boundary.
//!
//! The table is deliberately explicit: a unit that is not listed here is an
//! error naming the column ([`crate::Error::Unit`]), never a guess. Symbols
//! are matched after trimming and with `µ`, `μ` and `u` treated alike.
//!
//! Gram-force: tribometers (the CETR UMT among them) label forces in `g`,
//! meaning gram-force. A mass unit on a force column is read as the
//! corresponding force with standard gravity g = 9.80665 m/s² (exact, CGPM
//! 1901); see [`Unit::as_force`].

/// Standard gravity, m/s² (exact by definition).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The physical quantity a unit measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Quantity {
    /// Newton.
    Force,
    /// Metre.
    Length,
    /// Second.
    Time,
    /// Metre per second.
    Velocity,
    /// Kelvin (Celsius and Fahrenheit are converted with their offsets).
    Temperature,
    /// Pascal.
    Stress,
    /// Kilogram.
    Mass,
    /// Square metre.
    Area,
    /// Radian.
    Angle,
    /// Radian per second (rotational speed: rpm on a pin-on-disc spindle).
    AngularVelocity,
    /// A ratio: strain, coefficient of friction, percent, count.
    Dimensionless,
}

impl Quantity {
    /// The quantity's name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Force => "force",
            Quantity::Length => "length",
            Quantity::Time => "time",
            Quantity::Velocity => "velocity",
            Quantity::Temperature => "temperature",
            Quantity::Stress => "stress",
            Quantity::Mass => "mass",
            Quantity::Area => "area",
            Quantity::Angle => "angle",
            Quantity::AngularVelocity => "rotational speed",
            Quantity::Dimensionless => "dimensionless",
        }
    }

    /// The SI unit symbol of the quantity.
    pub fn si_symbol(self) -> &'static str {
        match self {
            Quantity::Force => "N",
            Quantity::Length => "m",
            Quantity::Time => "s",
            Quantity::Velocity => "m/s",
            Quantity::Temperature => "K",
            Quantity::Stress => "Pa",
            Quantity::Mass => "kg",
            Quantity::Area => "m^2",
            Quantity::Angle => "rad",
            Quantity::AngularVelocity => "rad/s",
            Quantity::Dimensionless => "1",
        }
    }
}

/// A unit: SI value = `scale` × value + `offset`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Unit {
    /// The symbol as tribo knows it (normalised).
    pub symbol: &'static str,
    /// What it measures.
    pub quantity: Quantity,
    /// Multiplier to SI.
    pub scale: f64,
    /// Offset to SI, after scaling (temperatures only).
    pub offset: f64,
}

impl Unit {
    /// Converts a value in this unit to SI.
    pub fn to_si(&self, value: f64) -> f64 {
        value * self.scale + self.offset
    }

    /// Reads a mass unit as the force of that mass under standard gravity
    /// (gram-force, kilogram-force); other units are returned unchanged.
    pub fn as_force(&self) -> Unit {
        if self.quantity == Quantity::Mass {
            Unit {
                symbol: self.symbol,
                quantity: Quantity::Force,
                scale: self.scale * STANDARD_GRAVITY,
                offset: 0.0,
            }
        } else {
            self.clone()
        }
    }
}

macro_rules! units {
    ($( [$($sym:literal),+] => $canon:literal, $q:ident, $scale:expr, $offset:expr; )*) => {
        /// Every unit tribo accepts: (accepted spellings, canonical symbol, quantity, scale, offset).
        const UNITS: &[(&[&str], &str, Quantity, f64, f64)] = &[
            $( (&[$($sym),+], $canon, Quantity::$q, $scale, $offset), )*
        ];
    };
}

units! {
    ["n", "newton", "newtons"] => "N", Force, 1.0, 0.0;
    ["mn", "millinewton"] => "mN", Force, 1e-3, 0.0;
    ["un", "micronewton"] => "uN", Force, 1e-6, 0.0;
    ["kn", "kilonewton"] => "kN", Force, 1e3, 0.0;
    ["gf", "gram-force", "gram force", "grams-force", "g-force", "pond"] => "gf", Force, 1e-3 * STANDARD_GRAVITY, 0.0;
    ["kgf", "kg-f", "kilogram-force", "kilogram force", "kp", "kilopond"] => "kgf", Force, STANDARD_GRAVITY, 0.0;
    ["lbf"] => "lbf", Force, 4.448_221_615_260_5, 0.0;
    ["g", "gram", "grams"] => "g", Mass, 1e-3, 0.0;
    ["mg"] => "mg", Mass, 1e-6, 0.0;
    ["kg"] => "kg", Mass, 1.0, 0.0;
    ["m", "meter", "metre", "meters", "metres"] => "m", Length, 1.0, 0.0;
    ["cm"] => "cm", Length, 1e-2, 0.0;
    ["mm", "millimeter", "millimetre"] => "mm", Length, 1e-3, 0.0;
    ["um", "micron", "microns", "micrometer", "micrometre", "micrometers"] => "um", Length, 1e-6, 0.0;
    ["nm", "nanometer", "nanometre"] => "nm", Length, 1e-9, 0.0;
    ["angstrom"] => "angstrom", Length, 1e-10, 0.0;
    ["in", "inch"] => "in", Length, 0.0254, 0.0;
    ["s", "sec", "secs", "second", "seconds"] => "s", Time, 1.0, 0.0;
    ["ms", "msec"] => "ms", Time, 1e-3, 0.0;
    ["us"] => "us", Time, 1e-6, 0.0;
    ["min", "minute", "minutes"] => "min", Time, 60.0, 0.0;
    ["h", "hr", "hour", "hours"] => "h", Time, 3600.0, 0.0;
    ["m/s", "m s-1", "m*s^-1"] => "m/s", Velocity, 1.0, 0.0;
    ["cm/s"] => "cm/s", Velocity, 1e-2, 0.0;
    ["mm/s", "mm/sec", "mm s-1"] => "mm/s", Velocity, 1e-3, 0.0;
    ["um/s", "um/sec"] => "um/s", Velocity, 1e-6, 0.0;
    ["mm/min"] => "mm/min", Velocity, 1e-3 / 60.0, 0.0;
    ["m/min"] => "m/min", Velocity, 1.0 / 60.0, 0.0;
    ["k", "kelvin"] => "K", Temperature, 1.0, 0.0;
    ["°c", "degc", "deg c", "c", "celsius", "ºc"] => "degC", Temperature, 1.0, 273.15;
    ["°f", "degf", "fahrenheit"] => "degF", Temperature, 5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0;
    ["pa"] => "Pa", Stress, 1.0, 0.0;
    ["kpa"] => "kPa", Stress, 1e3, 0.0;
    ["mpa", "n/mm2", "n/mm^2", "n/mm²"] => "MPa", Stress, 1e6, 0.0;
    ["gpa"] => "GPa", Stress, 1e9, 0.0;
    ["m2", "m^2", "m²"] => "m^2", Area, 1.0, 0.0;
    ["cm2", "cm^2", "cm²"] => "cm^2", Area, 1e-4, 0.0;
    ["mm2", "mm^2", "mm²"] => "mm^2", Area, 1e-6, 0.0;
    ["um2", "um^2", "um²"] => "um^2", Area, 1e-12, 0.0;
    ["rad"] => "rad", Angle, 1.0, 0.0;
    ["rpm", "r/min", "rev/min", "u/min", "1/min", "min-1", "min^-1"] => "rpm", AngularVelocity, 2.0 * std::f64::consts::PI / 60.0, 0.0;
    ["rad/s", "rad s-1"] => "rad/s", AngularVelocity, 1.0, 0.0;
    ["rps", "rev/s"] => "rev/s", AngularVelocity, 2.0 * std::f64::consts::PI, 0.0;
    ["deg", "°", "degree", "degrees"] => "deg", Angle, std::f64::consts::PI / 180.0, 0.0;
    ["1", "-", "mm/mm", "m/m", "ratio"] => "1", Dimensionless, 1.0, 0.0;
    ["%", "percent"] => "%", Dimensionless, 1e-2, 0.0;
}

/// Normalises a unit spelling: trims, drops surrounding brackets, lower-cases,
/// and maps the micro signs to `u`.
fn normalise(symbol: &str) -> String {
    let s = symbol.trim();
    let s = s
        .strip_prefix('[')
        .and_then(|s| s.strip_suffix(']'))
        .or_else(|| s.strip_prefix('(').and_then(|s| s.strip_suffix(')')))
        .unwrap_or(s);
    s.trim().replace(['µ', 'μ'], "u").to_lowercase()
}

/// Looks a unit up. Returns `None` for an unknown unit, and for an empty one.
pub fn parse_unit(symbol: &str) -> Option<Unit> {
    let key = normalise(symbol);
    if key.is_empty() {
        return None;
    }
    UNITS
        .iter()
        .find(|(spellings, ..)| spellings.contains(&key.as_str()))
        .map(|&(_, canon, quantity, scale, offset)| Unit {
            symbol: canon,
            quantity,
            scale,
            offset,
        })
}

/// A short list of accepted units for a quantity, for error messages.
pub fn accepted(quantity: Quantity) -> String {
    UNITS
        .iter()
        .filter(|u| u.2 == quantity || (quantity == Quantity::Force && u.2 == Quantity::Mass))
        .map(|u| u.1)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Parses `"<number> <unit>"` (space optional: `0.8mm`) into SI, checking
/// the quantity.
pub fn parse_quantity(text: &str, quantity: Quantity, what: &str) -> crate::error::Result<f64> {
    let t = text.trim();
    let split = t
        .char_indices()
        .find(|(_, c)| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))
        .map_or(t.len(), |(i, _)| i);
    let (num, unit) = t.split_at(split);
    let value: f64 = num.trim().parse().map_err(|_| {
        crate::error::Error::Config(format!(
            "{what} = '{text}'; expected a number with a unit, e.g. '0.8 mm'"
        ))
    })?;
    let unit = unit.trim();
    let u = parse_unit(unit).ok_or_else(|| {
        crate::error::Error::Config(format!(
            "{what} = '{text}': unknown or missing unit '{unit}'; expected {} units",
            quantity.si_symbol()
        ))
    })?;
    if u.quantity != quantity {
        return Err(crate::error::Error::Config(format!(
            "{what} = '{text}': '{unit}' is not a unit of {:?}",
            quantity
        )));
    }
    let v = u.to_si(value);
    if !v.is_finite() {
        return Err(crate::error::Error::Config(format!(
            "{what} = '{text}' is not finite"
        )));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Conversions are exact multiplications; compare to 1 ulp-ish relative.
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn common_spellings_convert_to_si() {
        assert!(close(parse_unit("mN").unwrap().to_si(250.0), 0.25));
        assert!(close(parse_unit("[µm]").unwrap().to_si(3.0), 3e-6));
        assert!(close(parse_unit("(mm/sec)").unwrap().to_si(2.0), 2e-3));
        assert!(close(parse_unit("°C").unwrap().to_si(-10.0), 263.15));
        assert!(close(parse_unit("%").unwrap().to_si(8.0), 0.08));
        assert!(close(parse_unit("GPa").unwrap().to_si(9.581), 9.581e9));
        // Instron exports areas in cm²
        assert!(close(parse_unit("cm²").unwrap().to_si(0.2), 2e-5));
    }

    /// CETR files give forces in `g`: gram-force with standard gravity.
    #[test]
    fn gram_on_a_force_column_is_gram_force() {
        let g = parse_unit("g").unwrap();
        assert_eq!(g.quantity, Quantity::Mass);
        let f = g.as_force();
        assert_eq!(f.quantity, Quantity::Force);
        assert!(close(f.to_si(200.0), 0.2 * 9.80665));
    }

    /// Every spelling of gram-force and kilogram-force is a force already;
    /// a bare `g`/`kg` becomes one on a force column (`as_force`).
    #[test]
    fn gram_force_spellings() {
        for (sym, v, n) in [
            ("gf", 1000.0, 9.80665),
            ("kgf", 1.0, 9.80665),
            ("kp", 2.0, 19.6133),
            ("[kg]", 1.0, 9.80665),
        ] {
            let u = parse_unit(sym).unwrap().as_force();
            assert_eq!(u.quantity, Quantity::Force, "{sym}");
            assert!(close(u.to_si(v), n), "{sym}: {}", u.to_si(v));
        }
    }

    /// 60 rpm is one turn per second: 2π rad/s.
    #[test]
    fn rpm_is_an_angular_velocity() {
        let u = parse_unit("rpm").unwrap();
        assert_eq!(u.quantity, Quantity::AngularVelocity);
        assert!(close(u.to_si(60.0), 2.0 * std::f64::consts::PI));
    }

    #[test]
    fn unknown_and_empty_units_are_none() {
        assert!(parse_unit("furlong").is_none());
        assert!(parse_unit("").is_none());
        assert!(parse_unit("  ").is_none());
    }
}
