//! The sliding path of a trace (MODELS.md §11): how far the contact slides
//! from one sample to the next, and where each lap of a rotary test
//! begins and ends.
//!
//! The sliding distance comes from the most direct channel there is: a
//! position or sliding-distance column (Σ|Δx|, which for a cumulative
//! distance is its increase), else the sliding speed (∫|v| dt by the
//! trapezoid rule), else a speed the header states (v̄ Δt). Laps come from
//! the file's lap counter, else its angle, else the sliding distance over
//! the track length 2π r.

use std::ops::Range;

/// Where a trace's sliding distance comes from (the `distance_source`
/// column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DistanceSource {
    /// A position or sliding-distance column: Σ|Δx|.
    Position,
    /// A sliding-speed column: ∫|v| dt.
    Velocity,
    /// The speed the header states (a CETR crank's mean speed): v̄ Δt.
    DeclaredSpeed,
}

impl DistanceSource {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            DistanceSource::Position => "position",
            DistanceSource::Velocity => "velocity",
            DistanceSource::DeclaredSpeed => "declared_speed",
        }
    }
}

/// The sliding path sample to sample.
#[derive(Debug, Clone, Copy)]
pub enum Path<'a> {
    /// A position (back and forth) or a cumulative sliding distance, m.
    Position(&'a [f64]),
    /// Time, s, and the sliding speed, m/s.
    Velocity(&'a [f64], &'a [f64]),
    /// Time, s, and a constant speed, m/s.
    DeclaredSpeed(&'a [f64], f64),
}

impl<'a> Path<'a> {
    /// The path of a trace: its position when that moves at all, else its
    /// speed, else the declared speed; `None` when none is known.
    pub fn of(
        time_s: &'a [f64],
        position: Option<&'a [f64]>,
        velocity: Option<&'a [f64]>,
        declared_speed: Option<f64>,
    ) -> Option<Path<'a>> {
        let moves =
            |x: &[f64]| crate::signal::scan::finite_range(x).is_some_and(|(lo, hi)| hi > lo);
        match (position, declared_speed, velocity) {
            (Some(x), _, _) if moves(x) => Some(Path::Position(x)),
            (_, Some(v), _) if v.is_finite() && v > 0.0 => Some(Path::DeclaredSpeed(time_s, v)),
            (_, _, Some(v)) => Some(Path::Velocity(time_s, v)),
            _ => None,
        }
    }

    /// Where the distance comes from.
    pub fn source(&self) -> DistanceSource {
        match self {
            Path::Position(_) => DistanceSource::Position,
            Path::Velocity(..) => DistanceSource::Velocity,
            Path::DeclaredSpeed(..) => DistanceSource::DeclaredSpeed,
        }
    }

    /// |Δs| from sample `i` to `i + 1`, m (0 across a non-finite value: a
    /// gap slides no measured distance).
    #[inline]
    pub fn step(&self, i: usize) -> f64 {
        let d = match *self {
            Path::Position(x) => (x[i + 1] - x[i]).abs(),
            Path::Velocity(t, v) => 0.5 * (v[i].abs() + v[i + 1].abs()) * (t[i + 1] - t[i]),
            Path::DeclaredSpeed(t, v) => v * (t[i + 1] - t[i]),
        };
        if d.is_finite() {
            d
        } else {
            0.0
        }
    }

    /// The signed Δx from `i` to `i + 1` of a position (the friction loop
    /// ∮ F dx needs the direction); `None` for a path without one.
    #[inline]
    pub fn signed_step(&self, i: usize) -> Option<f64> {
        match *self {
            Path::Position(x) => Some(x[i + 1] - x[i]).filter(|d| d.is_finite()),
            _ => None,
        }
    }
}

/// One lap of a rotary test: the samples whose lap coordinate ℓ (laps
/// since the origin) has the same whole part.
#[derive(Debug, Clone, PartialEq)]
pub struct LapSpan {
    /// The whole part of ℓ: the file's lap number (0 for the first turn of
    /// a counter that starts at 0).
    pub lap: i64,
    /// Its samples.
    pub range: Range<usize>,
    /// Whether the record holds the whole lap: its first sample within one
    /// sample's advance of the lap's start, and its last within one of the
    /// next lap's start.
    pub complete: bool,
}

/// Where laps come from (the `cycle_source` column).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LapSource {
    /// The file's lap counter.
    Counter,
    /// The file's angle channel, unwrapped.
    Angle,
    /// The sliding distance over the track length 2π r.
    Distance,
}

impl LapSource {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            LapSource::Counter => "lap_counter",
            LapSource::Angle => "angle",
            LapSource::Distance => "distance",
        }
    }
}

/// Laps from a lap coordinate ℓ(i) (laps, increasing or decreasing): runs
/// of one whole part. A non-finite ℓ extends the run it is in. A lap is
/// complete when ℓ at its first sample is within the lap's mean advance
/// per sample of its start (k, or k + 1 going backwards), and at its last
/// sample within as much of the next lap's: no sample of it is missing.
pub fn laps_of(n: usize, coord: impl Fn(usize) -> f64) -> Vec<LapSpan> {
    let mut runs: Vec<(i64, Range<usize>)> = Vec::new();
    for i in 0..n {
        let l = coord(i);
        match runs.last_mut() {
            Some((k, r)) if !l.is_finite() || l.floor() as i64 == *k => r.end = i + 1,
            _ if l.is_finite() => runs.push((l.floor() as i64, i..i + 1)),
            _ => {}
        }
    }
    let last = runs.len().saturating_sub(1);
    runs.into_iter()
        .enumerate()
        .map(|(j, (k, range))| {
            let (a, b) = (coord(range.start), coord(range.end - 1));
            let samples = range.len() as f64;
            let advance = (b - a).abs() / (samples - 1.0).max(1.0);
            let tol = advance * (1.0 + 1e-9);
            let forward = b >= a;
            // The lap's start and end in ℓ, in the direction of travel.
            let (from, to) = match forward {
                true => (k as f64, (k + 1) as f64),
                false => ((k + 1) as f64, k as f64),
            };
            let whole_start = j > 0 || (a - from).abs() <= tol;
            let whole_end = j < last || (to - b).abs() <= tol;
            let complete = range.len() >= 2 && advance > 0.0 && whole_start && whole_end;
            LapSpan {
                lap: k,
                range,
                complete,
            }
        })
        .collect()
}

/// Laps of a lap-counter column (`Laps`, `Cycles`: ℓ is the counter).
pub fn laps_from_counter(counter: &[f64]) -> Vec<LapSpan> {
    laps_of(counter.len(), |i| counter[i])
}

/// Laps of an angle channel, rad, wrapped (0..2π, −π..π) or not: the angle
/// is unwrapped (a jump of more than π between samples is a wrap), and ℓ
/// is the unwrapped angle over 2π, so laps begin where the disc's angle is
/// a whole turn.
pub fn laps_from_angle(angle_rad: &[f64]) -> Vec<LapSpan> {
    let tau = std::f64::consts::TAU;
    let mut unwrapped = Vec::with_capacity(angle_rad.len());
    let (mut turns, mut prev) = (0.0, f64::NAN);
    for &a in angle_rad {
        if a.is_finite() && prev.is_finite() {
            let d = a - prev;
            if d > std::f64::consts::PI {
                turns -= tau;
            } else if d < -std::f64::consts::PI {
                turns += tau;
            }
        }
        if a.is_finite() {
            prev = a;
        }
        unwrapped.push((a + turns) / tau);
    }
    laps_of(unwrapped.len(), |i| unwrapped[i])
}

/// Laps of a track of length `track_m` from the sliding path: ℓ is the
/// sliding distance since the first sample over the track length (the
/// first lap begins at the first sample).
pub fn laps_from_path(path: &Path, n: usize, track_m: f64) -> Vec<LapSpan> {
    if n == 0 || !(track_m.is_finite() && track_m > 0.0) {
        return Vec::new();
    }
    let mut s = Vec::with_capacity(n);
    let mut acc = 0.0;
    s.push(0.0);
    for i in 0..n - 1 {
        acc += path.step(i);
        s.push(acc / track_m);
    }
    laps_of(n, |i| s[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A counter stepping 1/7 of a lap per sample from 0 to 3.43: laps 0,
    /// 1, 2 complete and lap 3 cut off at 0.43.
    #[test]
    fn a_counter_gives_its_laps_and_the_cut_last_one() {
        let c: Vec<f64> = (0..25)
            .map(|i| (i as f64 / 7.0 * 1e5).round() / 1e5)
            .collect();
        let laps = laps_from_counter(&c);
        assert_eq!(laps.len(), 4);
        assert_eq!(
            laps.iter()
                .map(|l| (l.lap, l.range.clone(), l.complete))
                .collect::<Vec<_>>(),
            vec![
                (0, 0..7, true),
                (1, 7..14, true),
                (2, 14..21, true),
                (3, 21..25, false)
            ]
        );
        // Starting mid-lap: the first lap is cut.
        let laps = laps_from_counter(&c[3..]);
        assert!(!laps[0].complete && laps[1].complete);
    }

    /// A wrapped angle (0..360° as rad) turning 40° per sample from 50°:
    /// the first lap is cut (its 0° and 10°–40° samples are missing), the
    /// next ones whole; from 10° nothing is missing; the same backwards.
    #[test]
    fn a_wrapped_angle_is_unwrapped_into_laps() {
        let deg = |d: f64| (d.rem_euclid(360.0)).to_radians();
        let a: Vec<f64> = (0..40).map(|i| deg(50.0 + 40.0 * i as f64)).collect();
        let laps = laps_from_angle(&a);
        assert!(
            !laps[0].complete && laps[0].range == (0..8),
            "{:?}",
            laps[0]
        );
        assert!(
            laps[1].complete && laps[1].range == (8..17),
            "{:?}",
            laps[1]
        );
        let a: Vec<f64> = (0..40).map(|i| deg(10.0 + 40.0 * i as f64)).collect();
        assert!(laps_from_angle(&a)[0].complete);
        let back: Vec<f64> = (0..40).map(|i| deg(310.0 - 40.0 * i as f64)).collect();
        let laps = laps_from_angle(&back);
        assert!(!laps[0].complete && laps[1].complete, "{laps:?}");
        assert_eq!(
            (laps[0].range.len(), laps[1].range.len(), laps[1].lap),
            (8, 9, -1)
        );
    }

    /// The path's steps: a position back and forth gives Σ|Δx|; a speed
    /// the trapezoid; a declared speed v Δt; a position that never moves
    /// gives way to the speed.
    #[test]
    fn path_steps_are_the_distance_slid() {
        let t = [0.0, 1.0, 2.0, 3.0];
        let x = [0.0, 2.0, 1.0, 3.0];
        let p = Path::of(&t, Some(&x), None, None).unwrap();
        assert!(((0..3).map(|i| p.step(i)).sum::<f64>() - 5.0).abs() < 1e-15);
        assert_eq!(p.signed_step(1), Some(-1.0));
        let v = [1.0, 3.0, -3.0, 1.0];
        let still = [4.0; 4];
        let p = Path::of(&t, Some(&still), Some(&v), None).unwrap();
        assert_eq!(p.source(), DistanceSource::Velocity);
        assert!(((0..3).map(|i| p.step(i)).sum::<f64>() - 7.0).abs() < 1e-15);
        let p = Path::of(&t, Some(&still), Some(&v), Some(0.5)).unwrap();
        assert_eq!(p.source(), DistanceSource::DeclaredSpeed);
        assert!((p.step(2) - 0.5).abs() < 1e-15);
        assert!(Path::of(&t, Some(&still), None, None).is_none());
        // 10 laps of a 2 m track at 1 m/s sampled at 0.5 s.
        let t: Vec<f64> = (0..41).map(|i| i as f64 * 0.5).collect();
        let laps = laps_from_path(&Path::DeclaredSpeed(&t, 1.0), t.len(), 2.0);
        assert_eq!(laps.len(), 11);
        assert!(laps[..10].iter().all(|l| l.complete && l.range.len() == 4));
        // The last sample alone (ℓ = 10.0 exactly) is lap 10, cut.
        assert!(!laps[10].complete && laps[10].range == (40..41));
    }
}
