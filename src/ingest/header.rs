//! Column headers: names with units inline (`Fx [mN]`, `Friction force (N)`,
//! `Time/s`), or a separate unit row (`g,g,mm,…`, `(s),(mm),…`).

use crate::units::parse_unit;

/// Splits a header cell into (name, unit). The unit is the text in trailing
/// brackets or parentheses, or after a last ` / ` or `/` or ` in ` (`x in
/// µm`, SurfaceTopography's CSV) when that part is a known unit. Returns an
/// empty unit when there is none.
pub fn split_name_unit(cell: &str) -> (String, String) {
    let cell = cell.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let Some(stripped) = cell.strip_suffix(close) {
            if let Some(i) = stripped.rfind(open) {
                let name = stripped[..i].trim();
                if !name.is_empty() {
                    return (name.to_string(), stripped[i + 1..].trim().to_string());
                }
            }
        }
    }
    if let Some((name, unit)) = cell.rsplit_once(" in ") {
        if !name.trim().is_empty() && parse_unit(unit).is_some() {
            return (name.trim().to_string(), unit.trim().to_string());
        }
    }
    if let Some(i) = cell.rfind('/') {
        let (name, unit) = (cell[..i].trim(), cell[i + 1..].trim());
        // "m/s" alone must stay a name-less unit; require a name and a known unit.
        if !name.is_empty() && parse_unit(unit).is_some() && !name.ends_with(['m', 'c']) {
            return (name.to_string(), unit.to_string());
        }
    }
    (cell.to_string(), String::new())
}

/// Whether a header row is a unit row: every non-empty cell is a known unit
/// (possibly in parentheses or brackets), and at least one cell is non-empty.
pub fn is_unit_row(cells: &[String]) -> bool {
    let non_empty: Vec<&String> = cells.iter().filter(|c| !c.trim().is_empty()).collect();
    !non_empty.is_empty() && non_empty.iter().all(|c| parse_unit(c).is_some())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inline_units() {
        assert_eq!(split_name_unit("Fx [mN]"), ("Fx".into(), "mN".into()));
        assert_eq!(
            split_name_unit("Friction force (N)"),
            ("Friction force".into(), "N".into())
        );
        assert_eq!(split_name_unit(" t (s) "), ("t".into(), "s".into()));
        assert_eq!(split_name_unit("Time/s"), ("Time".into(), "s".into()));
        assert_eq!(split_name_unit("COF"), ("COF".into(), "".into()));
        assert_eq!(split_name_unit("x in µm"), ("x".into(), "µm".into()));
        assert_eq!(
            split_name_unit("Temperature in reservoir"),
            ("Temperature in reservoir".into(), "".into())
        );
        assert_eq!(
            split_name_unit("Tensile strain (Strain 1)"),
            ("Tensile strain".into(), "Strain 1".into())
        );
    }

    #[test]
    fn unit_rows() {
        let row = |s: &str| s.split(',').map(str::to_string).collect::<Vec<_>>();
        assert!(is_unit_row(&row("g,g,mm,mm/sec,sec,g,")));
        assert!(is_unit_row(&row("(s),(mm),(N),(%),(MPa)")));
        assert!(!is_unit_row(&row("Fx,Fz,T")));
        assert!(!is_unit_row(&row(",,")));
    }
}
