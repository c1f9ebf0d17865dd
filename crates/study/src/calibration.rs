//! How the virtual lab turns each sample's voltages into forces.

use serde::{Deserialize, Serialize};

/// How the virtual lab turns each sample's voltages into forces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Calibration {
    /// The nominal conversion factors and spring force of the file, as the paper did (default).
    #[default]
    Nominal,
    /// Each device's clamp and pull arrays are calibrated from their own pull-in voltages
    /// ([`stiction_actuator::calibrate_from_pull_in`]: the gap is inferred, the rest of the array
    /// model is the nominal one); the spring force stays nominal.
    PullIn,
}
stiction_units::display_serde_name!(Calibration);
