//! The scenario's `design` section: the design study the file offers, the same as
//! `stiction study --vary` (flags given on the command line override it).
//!
//! ```json
//! "design": {
//!   "vary": {"actuators.clamp.plate_count": [30, 60], "actuators.pull.spring.stiffness": ["1 N/m", "3 N/m"]},
//!   "ranges": {"meter.clamp_voltages.to": "29 V..40 V"},
//!   "points": 8,
//!   "criterion": "narrowest"
//! }
//! ```
//!
//! The varied fields are taken in the order of their paths (alphabetical), the first slowest.

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What ranks the designs of a design study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum DesignCriterion {
    /// Narrowest 5-95 % interval of mu_e,a first.
    Narrowest,
    /// Smallest |median bias of mu_e,a against each device's own s / p_mean| first.
    LeastBias,
    /// Largest fraction of experiments with a usable eq. 10 line first.
    MostUsable,
}

/// A value of a varied field, as `--set` takes it: a number (SI) or a string (with a unit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum DesignValue {
    /// A number, SI (kept as written: 30 stays a whole number).
    Number(serde_json::Number),
    /// A string, e.g. "3 N/m".
    Text(String),
}

impl DesignValue {
    /// The value as `--set` takes it.
    pub fn as_set_text(&self) -> String {
        match self {
            DesignValue::Number(x) => x.to_string(),
            DesignValue::Text(t) => t.clone(),
        }
    }
}

/// The `design` section.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// Fields and their listed values (the grid of all combinations), like
    /// `--vary PATH=V1,V2,...`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub vary: BTreeMap<String, Vec<DesignValue>>,
    /// Fields and their continuous ranges "LO..HI" (both ends in one unit), filled by a
    /// space-filling design of `points` points, like `--vary "PATH=LO..HI"`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub ranges: BTreeMap<String, String>,
    /// Number of space-filling design points over the ranges (like `--design-points`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub points: Option<usize>,
    /// How the designs are ranked (like `--rank-by`; default narrowest).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub criterion: Option<DesignCriterion>,
}

/// One varied field of the section: its path, its listed values (as `--set` takes them) and its
/// range text `LO..HI` (None for a list).
pub type VariedField = (String, Vec<String>, Option<String>);

impl DesignSpec {
    /// The section as `--vary` arguments would give it: `(path, listed values, range text)` for
    /// each varied field, lists first then ranges, each in path order. Errors name the field.
    pub fn varied(&self) -> Result<Vec<VariedField>, String> {
        if self.vary.is_empty() && self.ranges.is_empty() {
            return Err("`design`: give `vary` (fields and their values) or `ranges` (fields and LO..HI)".into());
        }
        let mut out = Vec::new();
        for (path, values) in &self.vary {
            if path.trim().is_empty() {
                return Err("`design.vary`: a field path is empty".into());
            }
            if values.is_empty() {
                return Err(format!("`design.vary.{path}`: expected a list of at least one value"));
            }
            let texts: Vec<String> = values.iter().map(DesignValue::as_set_text).collect();
            if let Some(k) = texts.iter().position(|t| t.trim().is_empty()) {
                return Err(format!("`design.vary.{path}`: value {} is empty", k + 1));
            }
            out.push((path.clone(), texts, None));
        }
        for (path, range) in &self.ranges {
            if path.trim().is_empty() {
                return Err("`design.ranges`: a field path is empty".into());
            }
            if self.vary.contains_key(path) {
                return Err(format!("`design.ranges.{path}`: the field is also in `design.vary`; give it once"));
            }
            if !range.contains("..") {
                return Err(format!("`design.ranges.{path}`: {range:?} is not a range LO..HI (\"20 V..40 V\")"));
            }
            out.push((path.clone(), Vec::new(), Some(range.clone())));
        }
        match (self.ranges.is_empty(), self.points) {
            (false, None) => return Err("`design.points`: the ranges need the number of design points".into()),
            (true, Some(_)) => return Err("`design.points`: given without `design.ranges` to fill".into()),
            _ => {}
        }
        Ok(out)
    }
}
