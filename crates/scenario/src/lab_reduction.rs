//! The laboratory's reduction of forces to a friction coefficient, a leaf module: the paper's
//! `meter` section (`spec`) and the test structures (`structure`) both name it.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use stiction_units::QuantityInput;

/// How the laboratory turned its forces into a friction coefficient (reported beside the
/// adhesion-aware mu_e,a of eq. 10).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum LabReductionSpec {
    /// Eq. 10: the slope of friction against applied load (the paper's mu_e,a) and its intercept.
    #[default]
    Eq10,
    /// The mean of friction over applied load, F_f / L, over the points with slip (adhesion folded
    /// into the coefficient, as a lab without an adhesion term reports it).
    FrictionOverLoad,
    /// The mean of F_f / (L + F_a), with an adhesion force F_a the lab measured separately.
    FrictionOverTotalLoad {
        /// The lab's adhesion force F_a.
        #[serde(deserialize_with = "stiction_units::de::force_nonnegative")]
        #[schemars(with = "QuantityInput")]
        adhesion_force: f64,
    },
}
