//! Surface patterns on the block lattice (Table 4.1, MODELS.md §2 and §7).
//!
//! A pattern marks some blocks as holes: a hole block is not in contact, so
//! its friction coefficients are zero (and, by default, its adhesion too).
//! Circular holes of diameter Φ at pitch p (samples A, B, C) are drawn as
//! squares of side Φ (thesis §4.3), so the lattice contact fraction is
//! 1 − Φ²/p², below the circular AF = 1 − πΦ²/(4p²). The S sample is a
//! staggered array of rectangles.
//!
//! Sizes are given in metres and must be whole multiples of the lattice
//! spacing l (to 1e-6 of a block): a hole cannot cover part of a block.
//! Each hole sits centred in its pitch cell; with `stagger` s, every other
//! row of holes is shifted by s·p_x along x.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// A pattern of holes; a scene file's `[pattern]` table, selected by `kind`,
/// with lengths in `*_m` keys and a mask as strings of `#`/`1` (hole) and
/// `.`/`0` (contact), one per row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Pattern {
    /// No holes.
    #[default]
    Flat,
    /// Square holes of side Φ on a square grid of pitch p (A, B, C of Table
    /// 4.1 with their circles drawn as squares).
    Holes {
        /// Φ, hole side (the circle's diameter) \[m\].
        #[serde(rename = "diameter_m")]
        diameter: f64,
        /// p, centre-to-centre pitch \[m\].
        #[serde(rename = "pitch_m")]
        pitch: f64,
    },
    /// Rectangular holes a_x × a_y at pitch p_x × p_y, every other row
    /// shifted by `stagger`·p_x along x (sample S).
    Rectangles {
        /// (a_x, a_y), hole size \[m\].
        #[serde(rename = "size_m")]
        size: [f64; 2],
        /// (p_x, p_y), pitch \[m\].
        #[serde(rename = "pitch_m")]
        pitch: [f64; 2],
        /// Shift of odd rows as a fraction of p_x, in [0, 1). Default 0.
        #[serde(default)]
        stagger: f64,
    },
    /// An explicit mask, `true` = hole, indexed `[iy][ix]`.
    Mask {
        /// The rows, iy = 0, 1, …
        #[serde(with = "mask_text")]
        rows: Vec<Vec<bool>>,
    },
}

/// A mask as text, one string per row: `#` or `1` is a hole, `.` or `0`
/// contact.
mod mask_text {
    use serde::{de::Error as _, Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(rows: &[Vec<bool>], s: S) -> Result<S::Ok, S::Error> {
        let text = rows
            .iter()
            .map(|r| -> String { r.iter().map(|&h| if h { '#' } else { '.' }).collect() });
        s.collect_seq(text)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vec<bool>>, D::Error> {
        let rows = Vec::<String>::deserialize(d)?;
        rows.iter()
            .enumerate()
            .map(|(iy, r)| {
                r.chars()
                    .enumerate()
                    .map(|(ix, c)| match c {
                        '#' | '1' => Ok(true),
                        '.' | '0' => Ok(false),
                        _ => Err(D::Error::custom(format!(
                            "pattern mask row {iy}, column {ix} is '{c}'; expected '#' or '1' \
                             (hole) or '.' or '0' (contact)"
                        ))),
                    })
                    .collect()
            })
            .collect()
    }
}

/// Whole number of blocks in a length, or an error naming the quantity.
fn blocks(what: &str, length: f64, spacing: f64) -> Result<usize> {
    let n = length / spacing;
    let r = n.round();
    if !(length.is_finite() && length > 0.0) || r < 1.0 || (n - r).abs() > 1e-6 {
        return Err(Error::Config(format!(
            "spring-block pattern: {what} is {length} m = {n} blocks of l = {spacing} m; \
             expected a positive whole number of blocks"
        )));
    }
    Ok(r as usize)
}

fn fits(what: &str, n: usize, lattice: usize, axis: &str) -> Result<()> {
    if n > lattice {
        return Err(Error::Config(format!(
            "spring-block pattern: {what} is {n} blocks along {axis}, larger than the \
             lattice's {lattice} blocks; expected at most {lattice}"
        )));
    }
    Ok(())
}

/// Hole mask of a rectangular array, row-major `iy * nx + ix`.
fn rectangles(
    (ax, ay): (usize, usize),
    (px, py): (usize, usize),
    shift: usize,
    (nx, ny): (usize, usize),
) -> Vec<bool> {
    let (ox, oy) = ((px - ax) / 2, (py - ay) / 2);
    let mut mask = vec![false; nx * ny];
    for iy in 0..ny {
        let row = iy / py;
        let yy = iy % py;
        if yy < oy || yy >= oy + ay {
            continue;
        }
        let sx = if row % 2 == 1 { shift } else { 0 };
        for ix in 0..nx {
            let xx = (ix + px - sx % px) % px;
            if xx >= ox && xx < ox + ax {
                mask[iy * nx + ix] = true;
            }
        }
    }
    mask
}

impl Pattern {
    /// The hole mask on an `nx × ny` lattice of spacing `spacing`, row-major
    /// (`iy * nx + ix`), `true` = hole. Errors when a size is not a whole
    /// number of blocks, when the hole or its pitch is larger than the
    /// lattice, when holes would touch their neighbours completely (a hole
    /// as large as its pitch in both directions), or when no block is left
    /// in contact.
    pub fn mask(&self, nx: usize, ny: usize, spacing: f64) -> Result<Vec<bool>> {
        let mask = match self {
            Pattern::Flat => vec![false; nx * ny],
            Pattern::Holes { diameter, pitch } => {
                let a = blocks("hole diameter", *diameter, spacing)?;
                let p = blocks("pitch", *pitch, spacing)?;
                for (n, what) in [(a, "hole diameter"), (p, "pitch")] {
                    fits(what, n, nx, "x")?;
                    fits(what, n, ny, "y")?;
                }
                if a >= p {
                    return Err(Error::Config(format!(
                        "spring-block pattern: hole diameter {diameter} m is not smaller than \
                         the pitch {pitch} m; expected Φ < p"
                    )));
                }
                rectangles((a, a), (p, p), 0, (nx, ny))
            }
            Pattern::Rectangles {
                size,
                pitch,
                stagger,
            } => {
                let ax = blocks("hole size along x", size[0], spacing)?;
                let ay = blocks("hole size along y", size[1], spacing)?;
                let px = blocks("pitch along x", pitch[0], spacing)?;
                let py = blocks("pitch along y", pitch[1], spacing)?;
                fits("hole size", ax, nx, "x")?;
                fits("hole size", ay, ny, "y")?;
                fits("pitch", px, nx, "x")?;
                fits("pitch", py, ny, "y")?;
                if ax > px || ay > py || (ax == px && ay == py) {
                    return Err(Error::Config(format!(
                        "spring-block pattern: hole {size:?} m does not fit its pitch \
                         {pitch:?} m; expected a hole no larger than the pitch, smaller in \
                         at least one direction"
                    )));
                }
                if !(0.0..1.0).contains(stagger) {
                    return Err(Error::Config(format!(
                        "spring-block pattern: stagger is {stagger}; expected a fraction of \
                         the pitch in [0, 1)"
                    )));
                }
                let shift = (stagger * px as f64).round() as usize;
                rectangles((ax, ay), (px, py), shift, (nx, ny))
            }
            Pattern::Mask { rows } => {
                if rows.len() != ny || rows.iter().any(|r| r.len() != nx) {
                    let widths: Vec<usize> = rows.iter().map(Vec::len).collect();
                    return Err(Error::Config(format!(
                        "spring-block pattern: mask has {} rows of widths {:?}; expected \
                         {ny} rows of {nx} (N_y × N_x)",
                        rows.len(),
                        widths
                    )));
                }
                rows.iter().flatten().copied().collect()
            }
        };
        if mask.iter().all(|&h| h) {
            return Err(Error::Config(
                "spring-block pattern: every block is a hole; expected some contact".into(),
            ));
        }
        Ok(mask)
    }

    /// The area fraction of the real pattern, AF = 1 − A_holes/A_th
    /// (MODELS.md §2): 1 − πΦ²/(4p²) for circular holes, 1 − a_x a_y/(p_x p_y)
    /// for rectangles; `None` for a mask (use [`contact_fraction`]).
    pub fn area_fraction(&self) -> Option<f64> {
        match self {
            Pattern::Flat => Some(1.0),
            Pattern::Holes { diameter, pitch } => {
                Some(1.0 - std::f64::consts::PI * diameter * diameter / (4.0 * pitch * pitch))
            }
            Pattern::Rectangles { size, pitch, .. } => {
                Some(1.0 - size[0] * size[1] / (pitch[0] * pitch[1]))
            }
            Pattern::Mask { .. } => None,
        }
    }
}

/// Fraction of blocks in contact (not holes).
pub fn contact_fraction(mask: &[bool]) -> f64 {
    let contact = mask.iter().filter(|&&h| !h).count();
    contact as f64 / mask.len() as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: f64 = 5e-6;

    #[test]
    fn table_4_1_patterns_on_the_lattice() {
        // B: Φ = 10 µm (2 blocks), p = 15 µm (3 blocks): 4 hole blocks in 9,
        // exact on a 9 × 9 lattice (3 whole cells per side).
        let b = Pattern::Holes {
            diameter: 10e-6,
            pitch: 15e-6,
        };
        let m = b.mask(9, 9, L).unwrap();
        assert!((contact_fraction(&m) - 5.0 / 9.0).abs() < 1e-15);
        // AF of the circular pattern (Table 4.1 gives 0.65).
        assert!((b.area_fraction().unwrap() - 0.651).abs() < 1e-3);
        // A: Φ 5, p 20 → AF 0.95 (Table 4.1: 0.95); C: Φ 15, p 20 → 0.56.
        let a = Pattern::Holes {
            diameter: 5e-6,
            pitch: 20e-6,
        };
        assert!((a.area_fraction().unwrap() - 0.951).abs() < 1e-3);
        let c = Pattern::Holes {
            diameter: 15e-6,
            pitch: 20e-6,
        };
        assert!((c.area_fraction().unwrap() - 0.558).abs() < 1e-3);
        // S: 200 × 40 µm at 200 × 120 µm → AF 2/3 (Table 4.1: 0.67).
        let s = Pattern::Rectangles {
            size: [200e-6, 40e-6],
            pitch: [200e-6, 120e-6],
            stagger: 0.5,
        };
        assert!((s.area_fraction().unwrap() - 2.0 / 3.0).abs() < 1e-12);
        let m = s.mask(80, 48, L).unwrap();
        assert!((contact_fraction(&m) - 2.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn hole_is_centred_in_its_cell_and_rows_are_staggered() {
        let p = Pattern::Rectangles {
            size: [10e-6, 5e-6],
            pitch: [20e-6, 15e-6],
            stagger: 0.5,
        };
        let m = p.mask(8, 6, L).unwrap();
        let row = |iy: usize| -> String {
            (0..8)
                .map(|ix| if m[iy * 8 + ix] { '#' } else { '.' })
                .collect()
        };
        assert_eq!(row(0), "........");
        assert_eq!(row(1), ".##..##.");
        // Second row of holes shifted by 0.5 · 4 = 2 blocks.
        assert_eq!(row(4), "#..##..#");
    }

    #[test]
    fn pattern_larger_than_lattice_is_an_error() {
        let p = Pattern::Holes {
            diameter: 50e-6,
            pitch: 60e-6,
        };
        let e = p.mask(8, 8, L).unwrap_err().to_string();
        assert!(e.contains("larger than the lattice"), "{e}");
        let e = Pattern::Holes {
            diameter: 7e-6,
            pitch: 20e-6,
        }
        .mask(8, 8, L)
        .unwrap_err()
        .to_string();
        assert!(e.contains("whole number of blocks"), "{e}");
        let e = Pattern::Mask {
            rows: vec![vec![false; 3]; 2],
        }
        .mask(3, 3, L)
        .unwrap_err()
        .to_string();
        assert!(e.contains("expected 3 rows"), "{e}");
    }
}
