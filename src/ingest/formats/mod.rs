//! One file per instrument format. Each declares its name and how it
//! recognises its files; the list lives in [`crate::ingest::READERS`].

pub mod al3d;
pub mod bluehill;
pub mod cetr_umt;
pub mod companion_file;
pub mod csm_pin_on_disc;
pub mod dektak;
pub mod delimited;
pub mod fixed_width_xyz;
pub mod gwy;
pub mod hbm_catman;
pub mod instron_blocks;
pub mod instron_parameters;
pub mod metropro;
pub mod mts793;
pub mod nanoscope;
pub mod nanovea;
pub mod netcdf;
pub mod npy;
pub mod opd;
pub mod opdx;
pub mod pcs_mtm;
pub mod plu;
pub mod profile_csv;
pub mod results_table;
pub mod rtec;
pub mod sdf;
pub mod stylus_heights;
pub mod sur;
pub mod surface_text;
pub mod surfcom_tx;
pub mod t150;
pub mod tmd;
pub mod x3p;
pub mod xz_line_scan;
pub mod zwick_testxpert;
