//! Statuses of result rows: `ok`, or one or more codes, each with a detail
//! for people. Codes are matchable across layers ([`Code`]) and have a
//! stable text form; in a table's `status` column a status reads
//! `code: detail; code: detail`, so `status.split("; ")` and the text before
//! each `:` give the codes back ([`codes_of`]). A row with any code never
//! says `ok`.

use std::fmt;

/// Why a row's result is missing, partial or doubtful. The text form
/// ([`Code::as_str`]) is stable: it is what tables hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[non_exhaustive]
pub enum Code {
    // Friction traces (MODELS.md §1).
    /// Fewer valid samples than the analysis needs.
    TooFewSamples,
    /// Time does not increase.
    NonMonotonicTime,
    /// No sliding phase (or no steady window after the peak).
    NoSlidingPhase,
    /// No static peak stands out of the noise.
    NoStaticPeak,
    /// No normal force: μ cannot be computed.
    NoNormalForce,
    /// A normal force of zero or less: μ undefined.
    NonpositiveNormalForce,
    /// μ_s below μ_d: the static peak is doubtful.
    StaticBelowDynamic,
    /// The static peak lies in the first samples of its segment.
    PeakAtStart,
    /// A value far outside any physical range (μ = 1e300 from a normal
    /// force of 1e-300 N): not reported as a number.
    AbsurdMagnitude,
    /// A step whose normal force changes steadily across it (a load ramp):
    /// reported with its start and end load, not as a plateau mean.
    LoadRamp,
    /// A step the file declares whose sliding speed is not steady within
    /// `step_tolerance`: its median speed does not stand for the step.
    UnsteadySpeed,
    /// A cycle cut off by the start or end of the record: reported, not
    /// averaged into the test's steady state.
    PartialCycle,
    /// μ does not settle: the cycles' final part still drifts.
    NoSteadyState,
    /// A stepped-velocity test: μ depends on the step, so a whole-trace
    /// value would be that of an arbitrary step.
    SteppedTest,
    /// The speed the header states disagrees with the record's own timing.
    SpeedMismatch,
    // Tensile curves (MODELS.md §6).
    /// The record ends during the final drop.
    FractureTruncated,
    /// Lengths that an equation needs are missing.
    MissingLengths,
    /// The manifest has no row for the file: defaults were used.
    NoManifestRow,
    /// A manifest value could not be read.
    BadManifest,
    /// The control named for Eq. 5.4 is not in the run.
    ControlNotFound,
    /// The control has no toughness, or the ratio is undefined.
    ControlUnusable,
    /// The analysis parameters are invalid.
    InvalidParameters,
    /// The curve has no samples.
    EmptyCurve,
    /// Samples with NaN or infinite values.
    NonFinite,
    /// No sample with strain ≥ 0.
    NoLoading,
    /// The stress is never positive.
    NoLoad,
    /// The record ends before the fracture.
    NoFracture,
    /// The strain decreases through the record (reversed or sign-flipped).
    ReversedStrain,
    /// No density was given: the toughness per mass uses a default density.
    DefaultedDensity,
    /// The density is not a positive number.
    BadDensity,
    /// The diameter is not a positive number.
    BadDiameter,
    /// The file's values cannot be used (a unit or column problem).
    BadInput,
    // Roughness (MODELS.md §4).
    /// A flat surface (Rq = 0): shape parameters undefined.
    Flat,
    /// The fractal dimension could not be estimated.
    FractalUndefined,
    /// The RMS slope could not be computed.
    SlopeUndefined,
    /// The contact length could not be computed.
    ContactUndefined,
    // Wear (MODELS.md §9).
    /// The specific wear rate needs the normal load and the sliding distance.
    WearRateUndefined,
    // Fits and models.
    /// A fit with as many points as parameters: no standard errors.
    SeUndefined,
    /// Too few points for a fit.
    TooFewPoints,
    /// A fit with fewer points than its parameters + 2: not judged.
    FewPoints,
    /// A fitted value with a sign the physics rules out.
    UnphysicalSign,
    /// All points at one abscissa: the fit's parameters cannot be separated.
    SingularDesign,
    /// The model does not apply here (outside its stated validity).
    OutOfValidity,
    /// A numerical procedure failed.
    NumericalFailure,
}

impl Code {
    /// Every code, for documentation and parsing.
    pub const ALL: &'static [Code] = &[
        Code::TooFewSamples,
        Code::NonMonotonicTime,
        Code::NoSlidingPhase,
        Code::NoStaticPeak,
        Code::NoNormalForce,
        Code::NonpositiveNormalForce,
        Code::StaticBelowDynamic,
        Code::PeakAtStart,
        Code::AbsurdMagnitude,
        Code::LoadRamp,
        Code::UnsteadySpeed,
        Code::PartialCycle,
        Code::NoSteadyState,
        Code::SteppedTest,
        Code::SpeedMismatch,
        Code::FractureTruncated,
        Code::MissingLengths,
        Code::NoManifestRow,
        Code::BadManifest,
        Code::ControlNotFound,
        Code::ControlUnusable,
        Code::InvalidParameters,
        Code::EmptyCurve,
        Code::NonFinite,
        Code::NoLoading,
        Code::NoLoad,
        Code::NoFracture,
        Code::ReversedStrain,
        Code::DefaultedDensity,
        Code::BadDensity,
        Code::BadDiameter,
        Code::BadInput,
        Code::Flat,
        Code::FractalUndefined,
        Code::SlopeUndefined,
        Code::ContactUndefined,
        Code::WearRateUndefined,
        Code::SeUndefined,
        Code::TooFewPoints,
        Code::FewPoints,
        Code::UnphysicalSign,
        Code::SingularDesign,
        Code::OutOfValidity,
        Code::NumericalFailure,
    ];

    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            Code::TooFewSamples => "too_few_samples",
            Code::NonMonotonicTime => "non_monotonic_time",
            Code::NoSlidingPhase => "no_sliding_phase",
            Code::NoStaticPeak => "no_static_peak",
            Code::NoNormalForce => "no_normal_force",
            Code::NonpositiveNormalForce => "nonpositive_normal_force",
            Code::StaticBelowDynamic => "static_below_dynamic",
            Code::PeakAtStart => "peak_at_start",
            Code::AbsurdMagnitude => "absurd_magnitude",
            Code::LoadRamp => "load_ramp",
            Code::UnsteadySpeed => "unsteady_speed",
            Code::PartialCycle => "partial_cycle",
            Code::NoSteadyState => "no_steady_state",
            Code::SteppedTest => "stepped_test",
            Code::SpeedMismatch => "speed_mismatch",
            Code::FractureTruncated => "fracture_truncated",
            Code::MissingLengths => "missing_lengths",
            Code::NoManifestRow => "no_manifest_row",
            Code::BadManifest => "bad_manifest",
            Code::ControlNotFound => "control_not_found",
            Code::ControlUnusable => "control_unusable",
            Code::InvalidParameters => "invalid_parameters",
            Code::EmptyCurve => "empty_curve",
            Code::NonFinite => "non_finite",
            Code::NoLoading => "no_loading",
            Code::NoLoad => "no_load",
            Code::NoFracture => "no_fracture",
            Code::ReversedStrain => "reversed_strain",
            Code::DefaultedDensity => "defaulted_density",
            Code::BadDensity => "bad_density",
            Code::BadDiameter => "bad_diameter",
            Code::BadInput => "bad_input",
            Code::Flat => "flat",
            Code::FractalUndefined => "fractal_undefined",
            Code::SlopeUndefined => "slope_undefined",
            Code::ContactUndefined => "contact_undefined",
            Code::WearRateUndefined => "wear_rate_undefined",
            Code::SeUndefined => "se_undefined",
            Code::TooFewPoints => "too_few_points",
            Code::FewPoints => "few_points",
            Code::UnphysicalSign => "unphysical_sign",
            Code::SingularDesign => "singular_design",
            Code::OutOfValidity => "out_of_validity",
            Code::NumericalFailure => "numerical_failure",
        }
    }

    /// The code of a text form.
    pub fn parse(s: &str) -> Option<Code> {
        Code::ALL.iter().copied().find(|c| c.as_str() == s)
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl Status {
    /// The status of a result that could not be computed, from its error:
    /// a model that does not apply, a numerical failure, or bad input.
    pub fn of_error(e: &crate::error::Error) -> Self {
        use crate::error::ErrorKind;
        let code = match e.kind() {
            ErrorKind::NotApplicable => Code::OutOfValidity,
            ErrorKind::Numerical => Code::NumericalFailure,
            _ => Code::BadInput,
        };
        Status::of(code, e.to_string())
    }
}

/// One code with its detail.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// What.
    pub code: Code,
    /// For people: the values behind it.
    pub detail: String,
}

/// A row's status: `ok` when it has no notes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Status {
    notes: Vec<Note>,
}

impl Status {
    /// `ok`.
    pub fn ok() -> Self {
        Status::default()
    }
    /// A status with one note.
    pub fn of(code: Code, detail: impl Into<String>) -> Self {
        let mut s = Status::ok();
        s.push(code, detail);
        s
    }
    /// Adds a note.
    pub fn push(&mut self, code: Code, detail: impl Into<String>) {
        self.notes.push(Note {
            code,
            detail: detail.into(),
        });
    }
    /// Adds every note of `other`.
    pub fn extend(&mut self, other: Status) {
        self.notes.extend(other.notes);
    }
    /// Whether there is nothing to say.
    pub fn is_ok(&self) -> bool {
        self.notes.is_empty()
    }
    /// Whether it has `code`.
    pub fn has(&self, code: Code) -> bool {
        self.notes.iter().any(|n| n.code == code)
    }
    /// The notes.
    pub fn notes(&self) -> &[Note] {
        &self.notes
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.notes.is_empty() {
            return f.write_str("ok");
        }
        for (i, n) in self.notes.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            match n.detail.is_empty() {
                true => write!(f, "{}", n.code)?,
                false => write!(f, "{}: {}", n.code, n.detail)?,
            }
        }
        Ok(())
    }
}

/// The codes in a `status` cell as tables hold it (`ok` has none). Text
/// before a `:` that is not a known code is left out.
pub fn codes_of(cell: &str) -> Vec<Code> {
    cell.split("; ")
        .filter_map(|part| Code::parse(part.split(':').next().unwrap_or("").trim()))
        .collect()
}

/// Whether a `status` cell is `ok` or holds only codes from `allowed`
/// (text that is not a known code makes it false).
pub fn only(cell: &str, allowed: &[Code]) -> bool {
    cell == "ok"
        || cell.split("; ").all(|part| {
            Code::parse(part.split(':').next().unwrap_or("").trim())
                .is_some_and(|c| allowed.contains(&c))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_form_round_trips() {
        for &c in Code::ALL {
            assert_eq!(Code::parse(c.as_str()), Some(c));
        }
        let mut s = Status::of(Code::NoStaticPeak, "no maximum stands out of the noise");
        s.push(Code::NoNormalForce, "no column");
        let text = s.to_string();
        assert_eq!(
            text,
            "no_static_peak: no maximum stands out of the noise; no_normal_force: no column"
        );
        assert_eq!(
            codes_of(&text),
            vec![Code::NoStaticPeak, Code::NoNormalForce]
        );
        assert_eq!(Status::ok().to_string(), "ok");
        assert!(codes_of("ok").is_empty());
        assert!(only("ok", &[]) && only("se_undefined", &[Code::SeUndefined]));
        assert!(!only("too_few_points", &[Code::SeUndefined]) && !only("whatever", &[]));
        assert_eq!(
            Status::of(Code::SeUndefined, "").to_string(),
            "se_undefined"
        );
    }
}
