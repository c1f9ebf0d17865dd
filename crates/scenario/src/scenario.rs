//! The scenario type: a whole experiment as written in a scenario file, and its JSON Schema.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::design;
use crate::spec::*;
use crate::warning::Warning;

/// The format version this build reads.
pub const FORMAT_VERSION: u32 = 1;

/// A whole experiment, as written in a scenario file (SI units after parsing).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// Version of the scenario format; this build reads 1.
    pub format_version: u32,
    /// What the scenario is for; printed in reports.
    #[serde(default)]
    pub description: String,
    /// The rough sidewall and shoe face.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<stiction_surface::SurfaceSpec>,
    /// Material properties of the contact.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<MaterialSpec>,
    /// The air around the device (relative humidity, temperature): capillary adhesion. Absent: dry.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<EnvironmentSpec>,
    /// Contact law and solver model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<ContactSpec>,
    /// Electrostatic actuator arrays by name; the friction meter uses `clamp` and `pull`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub actuators: BTreeMap<String, stiction_actuator::ArraySpec>,
    /// The meter: spring force, voltage protocol, slip criterion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub meter: Option<MeterSpec>,
    /// A friction test structure built from parts (comb drives, a plate electrode, a released
    /// spring), instead of the paper's `actuators` and `meter` (docs/experiment.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub structure: Option<crate::structure::StructureSpec>,
    /// Measured data to compare with, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measured: Option<MeasuredSpec>,
    /// Measured values of this device to compare with (printed and drawn only when given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceSpec>,
    /// The design study this file offers (`stiction study`; command-line `--vary` overrides it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design: Option<design::DesignSpec>,
    /// The scenario as read, after `--set` (units and uncertain-parameter objects as written):
    /// the source of the uncertainties (`sd`) and of [`Scenario::to_input_json`].
    #[serde(skip)]
    pub source_json: Value,
    /// Notes made while loading: a `reference` of another device dropped, a reference whose
    /// device cannot be checked.
    #[serde(skip)]
    pub notes: Vec<Warning>,
}

impl Scenario {
    /// The JSON Schema of the format (draft 2020-12), as shipped in docs/scenario.schema.json.
    pub fn json_schema() -> Value {
        Self::schema().clone()
    }

    /// The JSON Schema, generated once per process (every `--set` walks it).
    pub(crate) fn schema() -> &'static Value {
        static SCHEMA: std::sync::OnceLock<Value> = std::sync::OnceLock::new();
        SCHEMA.get_or_init(|| serde_json::to_value(schemars::schema_for!(Scenario)).unwrap_or(Value::Null))
    }
}
