//! Two channels of one file that must agree: row by row (the instrument's
//! COF against Fx / Fz), or through one constant (stress = force / A,
//! strain = extension / L0, a section stated twice).

use super::{note, percent, sig, Shown, Tolerance};
use crate::status::{Code, Note};

/// A least-squares line y = intercept + slope · x over the finite pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// dy/dx.
    pub slope: f64,
    /// y at x = 0 (0 for a line through the origin).
    pub intercept: f64,
    /// Root-mean-square residual over the root-mean-square of y: how far the
    /// two channels are from the line, as a fraction.
    pub scatter: f64,
    /// Pairs used.
    pub n: usize,
}

/// The least-squares line of y on x (through the origin when `origin`).
/// `None` with fewer than 3 finite pairs, or x constant.
pub fn line(x: &[f64], y: &[f64], origin: bool) -> Option<Line> {
    let pts: Vec<(f64, f64)> = x
        .iter()
        .zip(y)
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .map(|(a, b)| (*a, *b))
        .collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let nf = n as f64;
    let (mx, my) = match origin {
        true => (0.0, 0.0),
        false => (
            pts.iter().map(|p| p.0).sum::<f64>() / nf,
            pts.iter().map(|p| p.1).sum::<f64>() / nf,
        ),
    };
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx.is_nan() || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let rss: f64 = pts
        .iter()
        .map(|p| (p.1 - intercept - slope * p.0).powi(2))
        .sum();
    let syy: f64 = pts.iter().map(|p| p.1 * p.1).sum();
    let scatter = match syy > 0.0 {
        true => (rss / syy).sqrt(),
        false => 0.0,
    };
    Some(Line {
        slope,
        intercept,
        scatter,
        n,
    })
}

/// Two channels that must hold the same value row by row (`computed` from
/// other channels, `recorded` by the instrument). `None` when every row
/// agrees within `tol`; else a [`Code::ChannelMismatch`] note with the
/// number of rows that do not and the worst of them (1-based data row).
pub fn rowwise(what: &str, computed: &[f64], recorded: &[f64], tol: Tolerance) -> Option<Note> {
    let mut bad = 0;
    let mut worst: Option<(usize, f64)> = None;
    let mut n = 0;
    for (i, (c, r)) in computed.iter().zip(recorded).enumerate() {
        if !(c.is_finite() && r.is_finite()) {
            continue;
        }
        n += 1;
        if !tol.admits(*c, *r) {
            bad += 1;
            let d = (c - r).abs();
            if worst.is_none_or(|(_, w)| d > w) {
                worst = Some((i, d));
            }
        }
    }
    let (i, _) = worst?;
    note(
        Code::ChannelMismatch,
        format!(
            "{what}: {bad} of {n} rows disagree beyond {}, worst data row {}: {} against {}",
            tol.describe(1.0, ""),
            i + 1,
            sig(computed[i]),
            sig(recorded[i])
        ),
    )
}

/// A law that ties two channels through one constant, for
/// [`constant`]: `'Stress' = 'Load' / A`.
#[derive(Debug, Clone, Copy)]
pub struct Relation<'a> {
    /// The law in words, with the channels' names as the file gives them.
    pub law: &'a str,
    /// The constant (`A`, `mm^2`, 1e6): how it is shown.
    pub constant: Shown<'a>,
    /// The range of the constant that is physically plausible, SI.
    pub plausible: (f64, f64),
    /// Tolerance of the constant against its expected value; its relative
    /// part also bounds the scatter of the rows about the law.
    pub tol: Tolerance,
}

/// The constant a file's two channels imply (`implied`, SI, with the
/// `scatter` of the rows about the law, [`Line::scatter`]) against what is
/// expected of it: a stated value with where it comes from (`expected`),
/// and the plausible range. `None` when all holds; else one
/// [`Code::ChannelMismatch`] note listing what does not.
pub fn constant(
    r: &Relation,
    implied: f64,
    scatter: f64,
    expected: Option<(f64, &str)>,
) -> Option<Note> {
    let c = r.constant;
    let mut problems = Vec::new();
    if scatter.is_nan() || scatter > r.tol.rel {
        problems.push(format!(
            "the rows are not on the law: they scatter by {} % (rms) about it, beyond {}",
            sig(scatter * 100.0),
            r.tol.describe(1.0, "")
        ));
    }
    let (lo, hi) = r.plausible;
    if !(implied >= lo && implied <= hi) {
        problems.push(format!(
            "it implies {} = {}, outside the plausible {}–{}",
            c.name,
            c.value(implied),
            sig(lo * c.scale),
            c.value(hi)
        ));
    } else if let Some((e, source)) = expected {
        if !r.tol.admits(implied, e) {
            problems.push(format!(
                "it implies {} = {}, {source} gives {} ({}, tolerance {})",
                c.name,
                c.value(implied),
                c.value(e),
                percent(implied, e),
                r.tol.describe(c.scale, c.unit)
            ));
        }
    }
    match problems.is_empty() {
        true => None,
        false => note(
            Code::ChannelMismatch,
            format!("{}: {}", r.law, problems.join(" and ")),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const AREA: Relation = Relation {
        law: "'Stress' = 'Load' / A",
        constant: Shown {
            name: "A",
            unit: "mm^2",
            scale: 1e6,
        },
        plausible: (1e-12, 1.0),
        tol: Tolerance::rel(0.01),
    };

    #[test]
    fn a_line_and_its_scatter() {
        let x: Vec<f64> = (0..10).map(f64::from).collect();
        let y: Vec<f64> = x.iter().map(|v| 2.0 * v + 1.0).collect();
        let l = line(&x, &y, false).unwrap();
        assert!((l.slope - 2.0).abs() < 1e-12 && (l.intercept - 1.0).abs() < 1e-12);
        assert!(l.scatter < 1e-12 && l.n == 10);
        let o = line(&x, &y, true).unwrap();
        assert!(o.intercept == 0.0 && o.scatter > 0.01);
        assert_eq!(line(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0], false), None);
        assert_eq!(line(&[1.0, f64::NAN], &[1.0, 2.0], false), None);
    }

    #[test]
    fn rows_that_disagree_are_counted() {
        let cof = [0.1, 0.2, 0.3];
        assert_eq!(
            rowwise("COF", &cof, &[0.1, 0.2, 0.3], Tolerance::rel(1e-3)),
            None
        );
        let n = rowwise("COF", &cof, &[0.1, 0.25, 0.3], Tolerance::rel(1e-3)).unwrap();
        assert_eq!(n.code, Code::ChannelMismatch);
        assert!(n.detail.contains("1 of 3 rows") && n.detail.contains("row 2: 0.2 against 0.25"));
    }

    #[test]
    fn a_constant_against_its_expected_value_and_range() {
        assert_eq!(
            constant(&AREA, 120.9e-6, 0.001, Some((120.0e-6, "the manifest"))),
            None
        );
        let n = constant(&AREA, 120.9e-6, 0.001, Some((100e-6, "the manifest"))).unwrap();
        assert_eq!(
            n.detail,
            "'Stress' = 'Load' / A: it implies A = 120.9 mm^2, the manifest gives 100 mm^2 (+20.9 %, tolerance ±1 %)"
        );
        let n = constant(&AREA, 120.9e-6, 0.2, None).unwrap();
        assert!(n.detail.contains("scatter by 20 %"), "{}", n.detail);
        let n = constant(&AREA, 2.0, 0.0, None).unwrap();
        assert!(n.detail.contains("outside the plausible"), "{}", n.detail);
    }
}
