//! What the roughness stage produced for one file: the value the analysis
//! ([`super::stage`]) returns and the tables ([`super::tables`]) read.

use super::analyze::RoughnessReport;
use super::instrument::InstrumentRoughness;

/// Everything the stage produced for one file.
#[derive(Debug, Clone)]
pub struct RoughnessFile {
    /// The path as given.
    pub source: String,
    /// One report per profile or map in the file.
    pub reports: Vec<RoughnessReport>,
    /// `sample_id` and `pin` of the file's row in the sample manifest, so
    /// that the table joins the friction tables (and `tribo fit ice`).
    pub sample_id: Option<String>,
    /// See `sample_id`.
    pub pin: Option<String>,
    /// The instrument's own results printed in the file (the Dektak's
    /// "Analytical Results"), written next to ours.
    pub instrument: InstrumentRoughness,
}
