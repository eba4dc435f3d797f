//! Pipeline files: a serde spec, a validated plan, and the run.
