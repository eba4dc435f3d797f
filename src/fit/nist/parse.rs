//! Parser of the NIST StRD nonlinear-regression `.dat` format: the dataset
//! name and difficulty, the parameter lines `bK = start1 start2 certified
//! sd`, the certified residual sum of squares, and the data block whose line
//! range the header states (`Data (lines 61 to 74)`).

use std::path::Path;

use crate::error::{Error, Location, Result};

/// One NIST StRD nonlinear problem as read from its file.
#[derive(Debug, Clone)]
pub struct NistData {
    /// Dataset name (`BoxBOD`).
    pub name: String,
    /// `Lower`, `Average` or `Higher`.
    pub difficulty: String,
    /// Starting values 1 and 2.
    pub starts: [Vec<f64>; 2],
    /// Certified parameter values.
    pub certified: Vec<f64>,
    /// Certified standard deviations of the parameters.
    pub certified_sd: Vec<f64>,
    /// Certified residual sum of squares.
    pub certified_rss: f64,
    /// Response values.
    pub y: Vec<f64>,
    /// Predictor rows (1 or 2 predictors).
    pub x: Vec<Vec<f64>>,
}

fn num(s: &str) -> Option<f64> {
    s.trim().parse::<f64>().ok()
}

/// Parses a `.dat` file's text; `path` is used in error messages.
pub fn parse_nist(path: &Path, text: &str) -> Result<NistData> {
    let lines: Vec<&str> = text.lines().collect();
    let err = |line: usize, msg: String| Error::input(Location::line(path, line), msg);
    let name = lines
        .iter()
        .find_map(|l| l.trim().strip_prefix("Dataset Name:"))
        .and_then(|r| r.split_whitespace().next())
        .ok_or_else(|| {
            err(
                1,
                "no 'Dataset Name:' line; expected a NIST StRD .dat file".into(),
            )
        })?
        .to_string();
    let difficulty = lines
        .iter()
        .find_map(|l| l.trim().strip_suffix("Level of Difficulty"))
        .map(|d| d.trim().to_string())
        .unwrap_or_default();
    let (d0, d1) = data_lines(path, &lines)?;
    let (starts, certified, certified_sd, certified_rss) = parameters(path, &lines[..d0 - 1])?;
    let (mut y, mut x) = (vec![], vec![]);
    for (i, l) in lines[d0 - 1..d1].iter().enumerate() {
        let v: Option<Vec<f64>> = l.split_whitespace().map(num).collect();
        match v {
            Some(v) if v.len() >= 2 => {
                y.push(v[0]);
                x.push(v[1..].to_vec());
            }
            _ => {
                return Err(err(
                    d0 + i,
                    format!("data line '{}': expected 'y x [x2]' numbers", l.trim()),
                ))
            }
        }
    }
    Ok(NistData {
        name,
        difficulty,
        starts,
        certified,
        certified_sd,
        certified_rss,
        y,
        x,
    })
}

/// The first and last data lines, from "Data  (lines 61 to 74)" in the File
/// Format header, checked against the file's length.
fn data_lines(path: &Path, lines: &[&str]) -> Result<(usize, usize)> {
    let err = |msg: String| Error::input(Location::line(path, 1), msg);
    let (d0, d1) = lines
        .iter()
        .find_map(|l| {
            let l = l.trim();
            let rest = l
                .strip_prefix("Data")?
                .trim_start()
                .strip_prefix("(lines")?;
            let mut it = rest.trim_end_matches(')').split("to");
            let a = it.next()?.trim().parse::<usize>().ok()?;
            let b = it.next()?.trim().parse::<usize>().ok()?;
            Some((a, b))
        })
        .ok_or_else(|| err("no 'Data (lines A to B)' header line".into()))?;
    if d0 == 0 || d1 < d0 || d1 > lines.len() {
        return Err(err(format!(
            "data lines {d0} to {d1} outside the file's {} lines",
            lines.len()
        )));
    }
    Ok((d0, d1))
}

/// Both starts, the certified values and their sds, and the certified
/// residual sum of squares.
type Parameters = ([Vec<f64>; 2], Vec<f64>, Vec<f64>, f64);

/// The header's parameter lines `bK = start1 start2 certified sd` (in order)
/// and the certified residual sum of squares.
fn parameters(path: &Path, header: &[&str]) -> Result<Parameters> {
    let err = |line: usize, msg: String| Error::input(Location::line(path, line), msg);
    let (mut s1, mut s2, mut cert, mut sd) = (vec![], vec![], vec![], vec![]);
    let mut certified_rss = None;
    for (i, l) in header.iter().enumerate() {
        let t = l.trim();
        if let Some(rest) = t.strip_prefix("Residual Sum of Squares:") {
            certified_rss = num(rest);
        }
        let Some((lhs, rhs)) = t.split_once('=') else {
            continue;
        };
        let lhs = lhs.trim();
        let Some(k) = lhs.strip_prefix('b').and_then(|k| k.parse::<usize>().ok()) else {
            continue;
        };
        let v: Vec<f64> = rhs.split_whitespace().filter_map(num).collect();
        if v.len() != 4 || k != s1.len() + 1 {
            return Err(err(
                i + 1,
                format!(
                    "parameter line '{t}': expected 'b{} = start1 start2 certified sd'",
                    s1.len() + 1
                ),
            ));
        }
        s1.push(v[0]);
        s2.push(v[1]);
        cert.push(v[2]);
        sd.push(v[3]);
    }
    if s1.is_empty() {
        return Err(err(1, "no parameter lines 'b1 = ...'".into()));
    }
    let certified_rss =
        certified_rss.ok_or_else(|| err(1, "no 'Residual Sum of Squares:' line".into()))?;
    Ok(([s1, s2], cert, sd, certified_rss))
}
