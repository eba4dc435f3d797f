//! Physics models as pure functions over `f64` values and slices, with
//! validated `…Params` structs.

pub mod alsfm;
pub mod makkonen;
pub mod spring_block;
pub mod stribeck;
