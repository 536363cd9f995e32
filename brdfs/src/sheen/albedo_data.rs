//! Bootstrap (zeros): regenerate with the generator.
use super::albedo_table::{N_MU, N_R, SheenAlbedoTable};
pub(crate) const STATED_ERROR: f32 = 1.0;
pub(crate) static SHEEN: SheenAlbedoTable = SheenAlbedoTable { values: [[0.0; N_MU]; N_R] };
