//! One file per instrument format. Each declares its name and how it
//! recognises its files; the list lives in [`crate::ingest::READERS`].

pub mod bluehill;
pub mod cetr_umt;
pub mod csm_pin_on_disc;
pub mod delimited;
pub mod t150;
