//! Parameters with an uncertainty: `{"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"}`.

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::parse::check_value;
use crate::{Constraint, Dimension, QuantityError, parse_quantity_checked};

/// A plain scalar: a number in SI or a string with a unit.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum ScalarInput {
    /// A number in SI units.
    Number(f64),
    /// A number with a unit, such as "0.5 um".
    Text(String),
}

/// The distribution an uncertain parameter is drawn from in a Monte Carlo study.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum Distribution {
    /// Normal with mean `value` and standard deviation `sd` (the default).
    #[default]
    Normal,
    /// Lognormal whose own mean is `value` and own standard deviation is `sd`.
    Lognormal,
    /// Uniform on `[min, max]`, or on `value +/- sd * sqrt(3)` (same SD) when no bounds are given.
    Uniform,
}
crate::display_serde_name!(Distribution);

/// A value with an uncertainty. A nominal run uses `value`; a Monte Carlo study draws from
/// `distribution` with standard deviation `sd` (or between `min` and `max` for a uniform one).
/// All fields take the same dimension as `value`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct UncertainInput {
    /// The nominal (mean) value.
    pub value: ScalarInput,
    /// The standard deviation.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sd: Option<ScalarInput>,
    /// The distribution (default normal).
    #[serde(default)]
    pub distribution: Distribution,
    /// Lower bound of a uniform distribution.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<ScalarInput>,
    /// Upper bound of a uniform distribution.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<ScalarInput>,
}

impl std::fmt::Display for ScalarInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ScalarInput::Number(x) => write!(f, "{x}"),
            ScalarInput::Text(t) => f.write_str(t),
        }
    }
}

/// As written in a scenario, without JSON quotes: `{value: 0.5 um, sd: 0.3 um, distribution:
/// lognormal}` (error messages quote it whole).
impl std::fmt::Display for UncertainInput {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{{value: {}", self.value)?;
        if let Some(sd) = &self.sd {
            write!(f, ", sd: {sd}")?;
        }
        write!(f, ", distribution: {}", self.distribution)?;
        if let Some(min) = &self.min {
            write!(f, ", min: {min}")?;
        }
        if let Some(max) = &self.max {
            write!(f, ", max: {max}")?;
        }
        f.write_str("}")
    }
}

fn scalar_si(s: &ScalarInput, dim: Dimension, constraint: Constraint) -> Result<f64, QuantityError> {
    match s {
        ScalarInput::Number(x) => check_value(*x, &x.to_string(), dim, constraint),
        ScalarInput::Text(t) => parse_quantity_checked(t, dim, constraint),
    }
}

impl UncertainInput {
    /// The nominal value in SI, after checking that the uncertainty fields are consistent.
    pub fn nominal(&self, dim: Dimension, constraint: Constraint) -> Result<f64, QuantityError> {
        let value = scalar_si(&self.value, dim, constraint)?;
        if let Some(sd) = &self.sd {
            scalar_si(sd, dim, Constraint::NonNegative).map_err(|mut e| {
                e.problem = format!("`sd` {}", e.problem);
                e
            })?;
        }
        let lo = self.min.as_ref().map(|m| scalar_si(m, dim, Constraint::Finite)).transpose()?;
        let hi = self.max.as_ref().map(|m| scalar_si(m, dim, Constraint::Finite)).transpose()?;
        if let (Some(lo), Some(hi)) = (lo, hi)
            && !(lo <= value && value <= hi)
        {
            return Err(QuantityError::new(
                self.to_string(),
                format!("value {value} is not within [min, max] = [{lo}, {hi}]"),
                dim,
                constraint,
            ));
        }
        if self.distribution == Distribution::Lognormal && value <= 0.0 {
            return Err(QuantityError::new(
                self.to_string(),
                "a lognormal parameter needs a positive value",
                dim,
                constraint,
            ));
        }
        Ok(value)
    }
}

/// The nominal SI value of a JSON quantity: a number (SI), a string with a unit, or an
/// [`UncertainInput`] object.
pub fn nominal_from_json(v: &Value, dim: Dimension, constraint: Constraint) -> Result<f64, QuantityError> {
    match v {
        Value::Number(n) => {
            let x = n.as_f64().unwrap_or(f64::NAN);
            check_value(x, &n.to_string(), dim, constraint)
        }
        Value::String(s) => parse_quantity_checked(s, dim, constraint),
        Value::Object(_) => {
            let u: UncertainInput = serde_json::from_value(v.clone()).map_err(|e| {
                QuantityError::new(v.to_string(), format!("not a valid uncertain parameter ({e})"), dim, constraint)
            })?;
            u.nominal(dim, constraint)
        }
        other => {
            Err(QuantityError::new(other.to_string(), "neither a number nor a string with a unit", dim, constraint))
        }
    }
}

/// The JSON Schema of a quantity field: a number (SI), a string with a unit, or an uncertain
/// parameter object. Use it with `#[schemars(with = "stiction_units::QuantityInput")]`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum QuantityInput {
    /// A number in SI units.
    Number(f64),
    /// A number with a unit, such as "0.5 um" or "1.4 GPa".
    Text(String),
    /// A value with an uncertainty and a distribution.
    Uncertain(UncertainInput),
}

impl fmt::Display for QuantityInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            QuantityInput::Number(x) => write!(f, "{x}"),
            QuantityInput::Text(t) => write!(f, "{t}"),
            QuantityInput::Uncertain(u) => write!(f, "{u}"),
        }
    }
}
