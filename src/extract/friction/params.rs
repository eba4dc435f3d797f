//! Parameters of the friction features, with their defaults and valid
//! ranges. Every value is recorded in the output's metadata.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Whether to split a trace into strokes by the sign of the friction force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum StrokeMode {
    /// Split when the force changes sign for long enough (reciprocating and
    /// bidirectional tests); a unidirectional trace is one stroke.
    #[default]
    Auto,
    /// Never split: the whole section is one segment, using |T|.
    Off,
}

/// Parameters of static-peak, plateau, stick-slip, stroke and step
/// detection (MODELS.md §1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionParams {
    /// Width of the running median applied before peak detection, samples
    /// (odd; 1 disables). Default 3: removes single-sample spikes and keeps
    /// a detachment peak two samples wide, as at 50 Hz on the CETR UMT.
    pub median_window: usize,
    /// Static peak: minimum prominence in units of the noise σ of the raw
    /// signal (the prominence is measured on the running median, whose noise
    /// is about half as large). Default 3.
    pub peak_noise_factor: f64,
    /// Static peak: minimum prominence as a fraction of the segment's median
    /// |T|. Default 0.02.
    pub peak_min_relative: f64,
    /// Dynamic window: band around the plateau level, as a fraction of it.
    /// Default 0.03.
    pub plateau_tolerance: f64,
    /// Dynamic window: width of the running mean, as a fraction of the
    /// segment length. Default 0.05.
    pub plateau_window_fraction: f64,
    /// Fraction of each segment trimmed at its end (the approach of the next
    /// reversal). Default 0.05.
    pub end_trim_fraction: f64,
    /// Stick-slip: minimum drop in units of the noise σ. Default 6.
    pub stickslip_noise_factor: f64,
    /// Stick-slip: minimum drop as a fraction of the plateau level. Default 0.03.
    pub stickslip_min_relative: f64,
    /// Stroke segmentation mode. Default `auto`.
    pub strokes: StrokeMode,
    /// Strokes shorter than this fraction of the longest are reversal
    /// transients and are dropped. Default 0.2.
    pub min_stroke_fraction: f64,
    /// Velocity steps: relative band of one step. Default 0.1.
    pub step_tolerance: f64,
    /// Velocity steps: fraction at the start of each step left out as
    /// running-in before the mean. Default 0.2.
    pub step_settle_fraction: f64,
    /// Velocity steps: minimum step length, samples. Default 20.
    pub step_min_samples: usize,
    /// Minimum samples of a segment. Default 10.
    pub min_samples: usize,
    /// Velocity steps: a step whose normal force changes by more than this
    /// fraction of its mean across the step (on a fitted line) is a load
    /// ramp, not a plateau. Default 0.1.
    pub load_ramp_fraction: f64,
    /// Running-in: the steady state is μ within this fraction of its
    /// plateau (MODELS.md §11). Default 0.02.
    pub running_in_band: f64,
    /// Running-in: the final fraction of the cycles whose trend decides
    /// whether the test settled. Default 0.25.
    pub steady_tail_fraction: f64,
    /// Running-in: fewest whole cycles to judge a steady state. Default 10.
    pub steady_min_cycles: usize,
    /// A stroke at the record's edge reaching less than this fraction of
    /// the test's median stroke was cut off. Default 0.9.
    pub partial_stroke_fraction: f64,
}

impl FrictionParams {
    /// The running-in parameters.
    pub fn steady(&self) -> super::running_in::SteadyParams {
        super::running_in::SteadyParams {
            band: self.running_in_band,
            tail_fraction: self.steady_tail_fraction,
            min_cycles: self.steady_min_cycles,
        }
    }
}

impl Default for FrictionParams {
    fn default() -> Self {
        FrictionParams {
            median_window: 3,
            peak_noise_factor: 3.0,
            peak_min_relative: 0.02,
            plateau_tolerance: 0.03,
            plateau_window_fraction: 0.05,
            end_trim_fraction: 0.05,
            stickslip_noise_factor: 6.0,
            stickslip_min_relative: 0.03,
            strokes: StrokeMode::Auto,
            min_stroke_fraction: 0.2,
            step_tolerance: 0.1,
            step_settle_fraction: 0.2,
            step_min_samples: 20,
            min_samples: 10,
            load_ramp_fraction: 0.1,
            running_in_band: 0.02,
            steady_tail_fraction: 0.25,
            steady_min_cycles: 10,
            partial_stroke_fraction: 0.9,
        }
    }
}

impl FrictionParams {
    /// Checks every range; the message names the parameter.
    pub fn validate(&self) -> Result<()> {
        let frac = |name: &str, v: f64, hi: f64| {
            if v.is_finite() && (0.0..hi).contains(&v) {
                Ok(())
            } else {
                Err(Error::Config(format!(
                    "friction.{name} = {v} is outside [0, {hi})"
                )))
            }
        };
        frac("peak_min_relative", self.peak_min_relative, 1.0)?;
        frac("plateau_tolerance", self.plateau_tolerance, 1.0)?;
        frac("plateau_window_fraction", self.plateau_window_fraction, 0.5)?;
        frac("end_trim_fraction", self.end_trim_fraction, 0.5)?;
        frac("stickslip_min_relative", self.stickslip_min_relative, 1.0)?;
        frac("min_stroke_fraction", self.min_stroke_fraction, 1.0)?;
        frac("step_tolerance", self.step_tolerance, 1.0)?;
        frac("step_settle_fraction", self.step_settle_fraction, 0.9)?;
        frac("load_ramp_fraction", self.load_ramp_fraction, 10.0)?;
        frac("running_in_band", self.running_in_band, 1.0)?;
        frac("steady_tail_fraction", self.steady_tail_fraction, 1.0)?;
        frac("partial_stroke_fraction", self.partial_stroke_fraction, 1.0)?;
        if self.running_in_band <= 0.0 || self.steady_tail_fraction <= 0.0 {
            return Err(Error::Config(
                "friction.running_in_band and friction.steady_tail_fraction must be > 0".into(),
            ));
        }
        for (name, v) in [
            ("peak_noise_factor", self.peak_noise_factor),
            ("stickslip_noise_factor", self.stickslip_noise_factor),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::Config(format!("friction.{name} = {v} must be > 0")));
            }
        }
        if self.min_samples < 3 || self.step_min_samples < 2 {
            return Err(Error::Config(
                "friction.min_samples must be >= 3 and step_min_samples >= 2".into(),
            ));
        }
        Ok(())
    }
}
