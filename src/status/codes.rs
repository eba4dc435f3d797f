//! The status codes, one table: each code's stable text form, how severe
//! it is, whether the row keeps a result, and (its doc comment) what it
//! means. `docs/statuses.md` is checked against this table.

use super::Severity::{self, Error, Info, Warning};

/// The code table: `/// meaning` `Name = "text", severity, has_result;`.
macro_rules! codes {
    ($( $(#[doc = $doc:literal])+ $name:ident = $text:literal, $sev:ident, $result:literal; )+) => {
        /// Why a row's result is missing, partial, doubtful or how it was
        /// obtained. The text form ([`Code::as_str`]) is stable: it is
        /// what tables hold.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        #[non_exhaustive]
        pub enum Code {
            $( $(#[doc = $doc])+ $name, )+
        }

        impl Code {
            /// Every code, in the order of `docs/statuses.md`.
            pub const ALL: &'static [Code] = &[$(Code::$name),+];

            /// The stable text form.
            pub fn as_str(self) -> &'static str {
                match self { $(Code::$name => $text,)+ }
            }

            /// How severe the code is; a row's `status` is its most
            /// severe code.
            pub fn severity(self) -> Severity {
                match self { $(Code::$name => $sev,)+ }
            }

            /// Whether a row with this code keeps its result (its values
            /// are given); `false`: the values it is about are null, or
            /// must not be used as results.
            pub fn has_result(self) -> bool {
                match self { $(Code::$name => $result,)+ }
            }

            /// What the code means (for people and `docs/statuses.md`).
            pub fn meaning(self) -> &'static str {
                match self { $(Code::$name => concat!($($doc),+),)+ }
            }
        }
    };
}

codes! {
    // Friction traces (MODELS.md §1).
    /// Fewer valid samples than the analysis needs.
    TooFewSamples = "too_few_samples", Error, false;
    /// Time does not increase.
    NonMonotonicTime = "non_monotonic_time", Error, false;
    /// No sliding phase (or no steady window after the peak): no μ_d.
    NoSlidingPhase = "no_sliding_phase", Error, false;
    /// No static peak stands out of the noise: no μ_s (μ_d is given).
    NoStaticPeak = "no_static_peak", Warning, true;
    /// No normal force: μ cannot be computed.
    NoNormalForce = "no_normal_force", Error, false;
    /// A normal force of zero or less: μ undefined.
    NonpositiveNormalForce = "nonpositive_normal_force", Error, false;
    /// μ_s below μ_d: the static peak is doubtful.
    StaticBelowDynamic = "static_below_dynamic", Warning, true;
    /// The static peak lies in the first samples of its segment.
    PeakAtStart = "peak_at_start", Warning, true;
    /// A value far outside any physical range (μ = 1e300 from a normal
    /// force of 1e-300 N): not reported as a number.
    AbsurdMagnitude = "absurd_magnitude", Error, false;
    /// A step whose normal force changes steadily across it (a load ramp):
    /// reported with its start and end load, not as a plateau mean.
    LoadRamp = "load_ramp", Info, true;
    /// A step the file declares whose sliding speed is not steady within
    /// `step_tolerance`: its median speed does not stand for the step.
    UnsteadySpeed = "unsteady_speed", Warning, true;
    /// The track radius that turns a rotational speed into the sliding
    /// speed comes from the file's name (`6-15mm-radius`), not from the file
    /// or the manifest: give `track_radius_mm`, `track_centre_mm` or
    /// `step_track_radius_mm`.
    RadiusFromFileName = "radius_from_file_name", Warning, true;
    /// A cycle cut off by the start or end of the record: reported, not
    /// averaged into the test's steady state.
    PartialCycle = "partial_cycle", Info, true;
    /// μ does not settle: the cycles' final part still drifts, so there is
    /// no steady-state μ (friction_tests, and the whole-trace μ_d).
    NoSteadyState = "no_steady_state", Warning, true;
    /// A test exported as several files whose numbered exports skip some
    /// (001, 002, 010): the series counts only the files present.
    SeriesGap = "series_gap", Warning, true;
    /// The film parameter's composite roughness has only one body's
    /// roughness (the other was not measured in the run): λ is an upper
    /// bound.
    PartialRoughness = "partial_roughness", Warning, true;
    /// A stepped-velocity test: μ depends on the step, so the whole-trace
    /// row has no μ_d (it would be that of an arbitrary step); the steps'
    /// rows have theirs.
    SteppedTest = "stepped_test", Info, true;
    /// The speed the header states disagrees with the record's own timing.
    SpeedMismatch = "speed_mismatch", Warning, true;
    // Tensile curves (MODELS.md §6).
    /// The record ends during the final drop.
    FractureTruncated = "fracture_truncated", Warning, true;
    /// Lengths that an equation needs are missing (wear: the track length,
    /// so no volume).
    MissingLengths = "missing_lengths", Warning, true;
    /// The manifest has no row for the file: defaults were used.
    NoManifestRow = "no_manifest_row", Warning, true;
    /// A manifest value could not be read.
    BadManifest = "bad_manifest", Warning, true;
    /// The control named for Eq. 5.4 is not in the run.
    ControlNotFound = "control_not_found", Warning, true;
    /// The control has no toughness, or the ratio is undefined.
    ControlUnusable = "control_unusable", Warning, true;
    /// The analysis parameters are invalid.
    InvalidParameters = "invalid_parameters", Error, false;
    /// The curve has no samples.
    EmptyCurve = "empty_curve", Error, false;
    /// Samples with NaN or infinite values.
    NonFinite = "non_finite", Error, false;
    /// No sample with strain ≥ 0.
    NoLoading = "no_loading", Error, false;
    /// The stress is never positive.
    NoLoad = "no_load", Error, false;
    /// The record ends before the fracture (the maximum stress, modulus and
    /// yield are still reported).
    NoFracture = "no_fracture", Warning, true;
    /// The strain decreases through the record (reversed or sign-flipped):
    /// no modulus, yield or toughness.
    ReversedStrain = "reversed_strain", Error, false;
    /// No density was given: the toughness per mass uses the default
    /// 1.4 g/cm³ (silk).
    DefaultedDensity = "defaulted_density", Warning, true;
    /// The density is not a positive number.
    BadDensity = "bad_density", Warning, true;
    /// The diameter is not a positive number.
    BadDiameter = "bad_diameter", Error, false;
    /// The file's values cannot be used (a unit or column problem).
    BadInput = "bad_input", Error, false;
    /// No material class (manifest `material_class`): the modulus uses
    /// tribo's stated default window (docs/tensile.md); the value is given.
    DefaultModulusWindow = "default_modulus_window", Info, true;
    /// A value without a unit read in the unit its format uses (MTS 793
    /// `Durchmesser : 100,1`; a `"Distance","Profile"` profile's columns);
    /// the detail names it.
    AssumedUnit = "assumed_unit", Warning, true;
    /// A displacement channel zeroed again during the record (a tare at
    /// the preload): joined at the step.
    Rezeroed = "rezeroed", Info, true;
    // Cross-checks (crate::crosscheck), for every stage.
    /// Ours and the instrument's printed result (modulus, strength, strain,
    /// yield, Ra, COF) disagree beyond the stated tolerance; the detail
    /// names both values. Both are in the table.
    InstrumentMismatch = "instrument_mismatch", Warning, true;
    /// Two channels or metadata values of one file that must agree do not
    /// (stress against force / area, strain against extension / L0, a
    /// section stated twice); the detail names the implied constant.
    ChannelMismatch = "channel_mismatch", Warning, true;
    /// A value physics rules out: a negative strength or yield stress, a
    /// strain beyond the stated bound of the material class, μ < 0. The
    /// value is kept beside the status; it is not a result.
    ImpossibleValue = "impossible_value", Error, false;
    /// A column's stated unit is contradicted by its values (a time column
    /// headed `(s)` that counts milliseconds).
    SuspectUnit = "suspect_unit", Warning, true;
    // Roughness (MODELS.md §4).
    /// A flat surface (Rq = 0): shape parameters undefined.
    Flat = "flat", Warning, true;
    /// The fractal dimension could not be estimated.
    FractalUndefined = "fractal_undefined", Warning, true;
    /// The RMS slope could not be computed.
    SlopeUndefined = "slope_undefined", Warning, true;
    /// The contact length could not be computed.
    ContactUndefined = "contact_undefined", Warning, true;
    /// More of a surface's points are not measured (NaN) than
    /// `max_invalid_fraction` (default 10 %) allows: the parameters are
    /// computed over the measured points, which stand for less of the
    /// surface than its size suggests (docs/roughness.md).
    TooManyInvalid = "too_many_invalid", Warning, true;
    /// A fit whose r² is below the analysis's threshold (the fractal
    /// dimension's log-log fit): its result is doubtful.
    PoorFit = "poor_fit", Warning, true;
    /// A parameter the data cannot support (named in the detail) is null;
    /// the row's other parameters stand.
    ParameterUndefined = "parameter_undefined", Warning, true;
    /// Points not measured were filled (with the mean line) for a
    /// transform that needs every point (the PSD, the ACF).
    GapsFilled = "gaps_filled", Info, true;
    /// Parameters computed at scales a stylus of the stated tip radius
    /// cannot follow (Sanner et al. 2022): the detail names the scale.
    BelowReliabilityCutoff = "below_reliability_cutoff", Warning, true;
    /// The evaluation window differs from the one the instrument states
    /// for its printed results, so the two are not compared.
    WindowDiffers = "window_differs", Info, true;
    // Wear (MODELS.md §9).
    /// The specific wear rate needs the normal load and the sliding
    /// distance (wear table: give `normal_force_N` and `sliding_distance_m`
    /// or `laps` in the manifest).
    WearRateUndefined = "wear_rate_undefined", Warning, true;
    // Fits and models.
    /// A fit with as many points as parameters: no standard errors.
    SeUndefined = "se_undefined", Warning, true;
    /// A fit with fewer points than its parameters + 2: not judged.
    FewPoints = "few_points", Warning, true;
    /// A fitted value with a sign the physics rules out.
    UnphysicalSign = "unphysical_sign", Warning, true;
    /// Some of the rows a result rests on (a fit's points, a group's
    /// members) carry a warning of their own (the detail names them, with
    /// their codes).
    DoubtfulPoints = "doubtful_points", Warning, true;
    /// Too few points for a fit.
    TooFewPoints = "too_few_points", Error, false;
    /// The fit's parameters cannot be separated: all points at one
    /// abscissa, or a rank-deficient Jacobian at the solution.
    SingularDesign = "singular_design", Error, false;
    /// The solver stopped before converging (iteration or evaluation limit,
    /// a stalled step, a gradient not orthogonal to the residuals); the
    /// values are its last iterate, not a result.
    NotConverged = "not_converged", Error, false;
    /// The fit converged but does not describe the data: its relative RMS
    /// residual exceeds `misfit_tol`.
    Misfit = "misfit", Warning, true;
    /// The model does not apply here (outside its stated validity: a
    /// locking slope, H ≤ 0, T above melting): values null.
    OutOfValidity = "out_of_validity", Error, false;
    /// The model was evaluated but its result lies outside its stated
    /// validity: a film thinner than a water molecule (3e-10 m), or μ above
    /// the scene's `mu_max` (default 1). Values kept beside the status.
    BeyondValidity = "beyond_validity", Warning, true;
    /// A numerical procedure failed (no convergence, divergence, a
    /// non-finite value at a named step).
    NumericalFailure = "numerical_failure", Error, false;
    // Simulations (MODELS.md §3, §5).
    /// The surfaces lock: D = cos φ S − μ0 tan φ cos β ≤ 0 at some slope, so
    /// no sliding solution exists (ALSFM; the detail names the slope).
    Locked = "locked", Error, false;
    /// No contact: the load per spring is not positive and adhesion is off.
    NoContact = "no_contact", Error, false;
    /// At a load L ≤ 0 (adhesion) μ = R_xy / L is undefined: the row
    /// reports the force R_xy instead of μ.
    NoCoefficient = "no_coefficient", Info, true;
    /// The sliding direction has no period on the surfaces' lattice: μ is
    /// the average over the sliding distance the detail states, not an
    /// exact period's mean.
    AveragedWindow = "averaged_window", Info, true;
    /// The averaging window of μ_d was only partly seen (the peak was
    /// recognised after it began): μ_d is the mean over the part seen.
    ShortWindow = "short_window", Warning, true;
    /// The simulation reached its time limit before the event it measures
    /// (the static peak and the μ_d window).
    TimeLimit = "time_limit", Error, false;
}

impl Severity {
    /// The stable text form.
    pub fn as_str(self) -> &'static str {
        match self {
            Info => "info",
            Warning => "warning",
            Error => "error",
        }
    }
}
