//! The drive a file's header states: the CETR UMT linear wear module's
//! crank (`Radius = 3.9493`, mm, and `Velocity = 240`, rpm, in each step's
//! header). Its `V1` column is the carriage's small drift (µm/s), not the
//! sliding speed; the sliding speed is the crank's.
//!
//! A crank of radius r turning at f drives a stroke of 2r each half turn:
//! the mean sliding speed is 4·r·f and the peak (mid-stroke) speed 2π·r·f.
//! tribo reports the mean speed as the sliding speed (what a stroke's
//! length and duration give, and what ASTM G133 states for reciprocating
//! tests), and keeps the peak beside it.

use super::{Dataset, MetaEntry};
use crate::error::{Error, Location, Result};

/// A crank drive: its radius and rotational speed, as the header states
/// them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crank {
    /// Crank radius r, m (half the stroke length).
    pub radius_m: f64,
    /// Turns per second f, Hz (the header's rpm / 60).
    pub frequency_hz: f64,
    /// The header line of the speed, for messages.
    pub line: usize,
}

impl Crank {
    /// Mean sliding speed 4·r·f, m/s: two strokes of 2r per turn.
    pub fn mean_speed_m_per_s(&self) -> f64 {
        4.0 * self.radius_m * self.frequency_hz
    }
    /// Peak sliding speed 2π·r·f, m/s, at mid-stroke.
    pub fn peak_speed_m_per_s(&self) -> f64 {
        2.0 * std::f64::consts::PI * self.radius_m * self.frequency_hz
    }
    /// Stroke length 2r, m.
    pub fn stroke_length_m(&self) -> f64 {
        2.0 * self.radius_m
    }
    /// Duration of one stroke, half a turn: 1 / (2 f), s.
    pub fn stroke_duration_s(&self) -> f64 {
        0.5 / self.frequency_hz
    }
}

fn value_of<'a>(meta: &'a [MetaEntry], key: &str) -> Option<&'a MetaEntry> {
    meta.iter().find(|m| m.key.trim().eq_ignore_ascii_case(key))
}

/// The crank that section `index` of a CETR UMT file states (its step's
/// `Radius` in mm and `Velocity` in rpm). `None` for other formats and for
/// a step that states neither; an error naming the line for one that states
/// them as something other than positive numbers.
pub fn declared_crank(ds: &Dataset, index: usize) -> Result<Option<Crank>> {
    if ds.format != "cetr-umt" {
        return Ok(None);
    }
    let Some(section) = ds.sections.get(index) else {
        return Ok(None);
    };
    let meta = &section.metadata;
    let (Some(r), Some(v)) = (value_of(meta, "Radius"), value_of(meta, "Velocity")) else {
        return Ok(None);
    };
    let number = |m: &MetaEntry, what: &str| {
        super::dialect::parse_number(m.value.trim(), '.')
            .filter(|x| x.is_finite() && *x > 0.0)
            .ok_or_else(|| {
                Error::input(
                    Location::line(&ds.source, m.line),
                    format!(
                        "the step states '{} = {}', which is not a positive {what}",
                        m.key, m.value
                    ),
                )
            })
    };
    Ok(Some(Crank {
        radius_m: number(r, "crank radius in mm")? * 1e-3,
        frequency_hz: number(v, "speed in rpm")? / 60.0,
        line: v.line,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 240 rpm on a 3.9493 mm crank: 4 turns a second, strokes of
    /// 7.8986 mm in 0.125 s, mean 0.0631888 m/s, peak 0.0992607 m/s.
    #[test]
    fn crank_speeds_follow_from_radius_and_rpm() {
        let c = Crank {
            radius_m: 3.9493e-3,
            frequency_hz: 4.0,
            line: 1,
        };
        assert!((c.mean_speed_m_per_s() - 0.0631888).abs() < 1e-12);
        assert!(
            (c.peak_speed_m_per_s() - 2.0 * std::f64::consts::PI * 3.9493e-3 * 4.0).abs() < 1e-15
        );
        assert!(
            (c.peak_speed_m_per_s() / c.mean_speed_m_per_s() - std::f64::consts::PI / 2.0).abs()
                < 1e-12
        );
        // Mean speed = stroke length / stroke duration.
        assert!(
            (c.stroke_length_m() / c.stroke_duration_s() - c.mean_speed_m_per_s()).abs() < 1e-15
        );
    }
}
