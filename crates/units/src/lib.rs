//! Quantities at the edge of stiction.
//!
//! # Internal unit system
//!
//! Everything inside stiction is SI, stored as `f64`: metres, newtons, pascals, joules per square
//! metre, volts, seconds, radians. Users may write quantities with units: scenario files and
//! command-line flags accept a bare number (taken as SI) or a string such as `"0.5 um"`, `"0.5um"`,
//! `"1.4 GPa"`, `"3 uN"`, `"0.1 J/m^2"`, `"9.1e-12 1/Pa"`, `"4e12 m^-2"`, `"100 um^2"`,
//! `"1.4e-8 N/V^2"` or `"35 %"`. [`parse_quantity`] converts such a string once, at the edge, to
//! SI, and checks that its unit has the dimension the field expects.
//!
//! Units are products and quotients of symbols (`m g s A N Pa J V W C F Hz rad deg %`) with SI
//! prefixes (`f p n u µ m c k M G T`) and integer powers (`m^2`, `m^-2`, `m2`). A `/` divides by
//! everything after it up to the next `/`; `*`, `.` or a space multiply.
//!
//! Scenario fields take such values through the serde helpers in [`de`], which also accept an
//! uncertain-parameter object (`{"value": "0.5 um", "sd": "0.3 um", "distribution": "normal"}`),
//! see [`UncertainInput`]: a nominal run takes its `value`; Monte Carlo studies sample it.

use std::fmt;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

mod parse;
pub use parse::{format_quantity, parse_any, parse_quantity, parse_quantity_checked};

pub mod de;
pub mod finite;
pub mod io;
pub mod text;
mod uncertain;
pub use uncertain::{Distribution, ScalarInput, UncertainInput, nominal_from_json};

/// The name serde gives a value: for a unit enum variant the string the scenario files and every
/// JSON output spell it with (`"maugis-dugdale"`, `"tilt"`); anything else its compact JSON.
///
/// Text output uses the same names as JSON through [`display_serde_name!`](crate::display_serde_name),
/// so each enum is spelled one way everywhere and the spelling lives only in its serde attributes.
pub fn serde_name<T: Serialize + ?Sized>(value: &T) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(other) => other.to_string(),
        Err(e) => format!("<{e}>"),
    }
}

/// The suffix that names an SI unit in a JSON key or CSV column (`name_unit`, as `load_n`,
/// `real_area_m2`): "N/V^2" -> "n_per_v2", "m^-2" -> "per_m2", "1/Pa" -> "per_pa",
/// "N s/m" -> "n_s_per_m"; "" or "1" (a pure number) -> "" (no suffix).
pub fn unit_key_suffix(si_unit: &str) -> String {
    let unit = si_unit.trim();
    if unit.is_empty() || unit == "1" {
        return String::new();
    }
    // Terms with a negative power move behind "per": "m^-2" is "per m^2".
    let (num, den) = unit.split_once('/').unwrap_or((unit, ""));
    let mut over: Vec<String> = Vec::new();
    let mut under: Vec<String> = Vec::new();
    for term in num.split([' ', '*', '.']).filter(|t| !t.is_empty() && *t != "1") {
        match term.split_once("^-") {
            Some((base, power)) => under.push(format!("{base}{power}")),
            None => over.push(term.replace('^', "")),
        }
    }
    for term in den.split([' ', '*', '.']).filter(|t| !t.is_empty()) {
        under.push(term.replace('^', ""));
    }
    let mut key = over.join("_");
    if !under.is_empty() {
        key =
            if key.is_empty() { format!("per_{}", under.join("_")) } else { format!("{key}_per_{}", under.join("_")) };
    }
    key.to_lowercase()
}

/// `name` with the unit suffix of [`unit_key_suffix`]: ("surface.summit_radius", "m") ->
/// "surface.summit_radius_m"; a pure number keeps its bare name.
pub fn key_with_unit(name: &str, si_unit: &str) -> String {
    match unit_key_suffix(si_unit) {
        s if s.is_empty() => name.to_string(),
        s => format!("{name}_{s}"),
    }
}

/// Implements `Display` for enums with their serde names (see [`serde_name`]):
/// `stiction_units::display_serde_name!(AdhesionLaw, Branch);` makes `AdhesionLaw::MaugisDugdale`
/// print as `maugis-dugdale`, as it is written in a scenario file and in JSON.
#[macro_export]
macro_rules! display_serde_name {
    ($($t:ty),+ $(,)?) => {
        $(
            impl ::std::fmt::Display for $t {
                fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                    f.write_str(&$crate::serde_name(self))
                }
            }
        )+
    };
}

/// Exponents of the base dimensions (metre, kilogram, second, ampere) of a unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DimensionVector(pub [i8; 4]);

/// Largest |exponent| of a base dimension in a unit expression (m^-2, V^-2 are far below it).
pub const MAX_UNIT_EXPONENT: i32 = 24;

impl DimensionVector {
    /// `self * other^power`; None when an exponent leaves [-MAX_UNIT_EXPONENT, MAX_UNIT_EXPONENT]
    /// (checked arithmetic: "N^64 N^64 N^64 N^64" must not wrap around to a length).
    fn mul(self, other: Self, power: i8) -> Option<Self> {
        let mut out = self.0;
        for (o, b) in out.iter_mut().zip(other.0) {
            let v = i32::from(*o) + i32::from(b) * i32::from(power);
            if v.abs() > MAX_UNIT_EXPONENT {
                return None;
            }
            *o = v as i8;
        }
        Some(DimensionVector(out))
    }
}

/// The physical dimension a field expects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dimension {
    /// Length, m.
    Length,
    /// Area, m^2.
    Area,
    /// Force, N.
    Force,
    /// Pressure, stress, Young's modulus, hardness, shear strength: Pa.
    Pressure,
    /// Work of adhesion, surface energy: J/m^2 (equal in dimension to N/m).
    SurfaceEnergy,
    /// Compliance (the paper's D), 1/Pa.
    Compliance,
    /// Number per area (summit density eta), m^-2.
    ArealDensity,
    /// Actuator conversion factor F / V^2, N/V^2.
    ForcePerVoltageSquared,
    /// Electric potential, V.
    Voltage,
    /// Spring stiffness, N/m (equal in dimension to J/m^2).
    Stiffness,
    /// A pure number; `%` is accepted (35 % = 0.35).
    Dimensionless,
    /// Plane angle in radians; `rad` and `deg` are accepted.
    Angle,
    /// Time, s.
    Time,
    /// Mass, kg (written in g with a prefix: "0.1 ng", "107 ng").
    Mass,
    /// Viscous damping coefficient, N s/m.
    Damping,
}

impl Dimension {
    /// The base-dimension exponents (m, kg, s, A) of this dimension.
    pub fn vector(self) -> DimensionVector {
        DimensionVector(match self {
            Dimension::Length => [1, 0, 0, 0],
            Dimension::Area => [2, 0, 0, 0],
            Dimension::Force => [1, 1, -2, 0],
            Dimension::Pressure => [-1, 1, -2, 0],
            Dimension::SurfaceEnergy | Dimension::Stiffness => [0, 1, -2, 0],
            Dimension::Compliance => [1, -1, 2, 0],
            Dimension::ArealDensity => [-2, 0, 0, 0],
            Dimension::ForcePerVoltageSquared => [-3, -1, 4, 2],
            Dimension::Voltage => [2, 1, -3, -1],
            Dimension::Dimensionless | Dimension::Angle => [0, 0, 0, 0],
            Dimension::Time => [0, 0, 1, 0],
            Dimension::Mass => [0, 1, 0, 0],
            Dimension::Damping => [0, 1, -1, 0],
        })
    }

    /// A name for messages: "a length".
    pub fn description(self) -> &'static str {
        match self {
            Dimension::Length => "a length",
            Dimension::Area => "an area",
            Dimension::Force => "a force",
            Dimension::Pressure => "a pressure",
            Dimension::SurfaceEnergy => "a work of adhesion (energy per area)",
            Dimension::Compliance => "a compliance (1/pressure)",
            Dimension::ArealDensity => "a number per area",
            Dimension::ForcePerVoltageSquared => "a force per voltage squared",
            Dimension::Voltage => "a voltage",
            Dimension::Stiffness => "a stiffness (force per length)",
            Dimension::Dimensionless => "a pure number",
            Dimension::Angle => "an angle",
            Dimension::Time => "a time",
            Dimension::Mass => "a mass",
            Dimension::Damping => "a damping coefficient (force per velocity)",
        }
    }

    /// The SI unit symbol the bare number is taken in.
    pub fn si_unit(self) -> &'static str {
        match self {
            Dimension::Length => "m",
            Dimension::Area => "m^2",
            Dimension::Force => "N",
            Dimension::Pressure => "Pa",
            Dimension::SurfaceEnergy => "J/m^2",
            Dimension::Compliance => "1/Pa",
            Dimension::ArealDensity => "m^-2",
            Dimension::ForcePerVoltageSquared => "N/V^2",
            Dimension::Voltage => "V",
            Dimension::Stiffness => "N/m",
            Dimension::Dimensionless => "",
            Dimension::Angle => "rad",
            Dimension::Time => "s",
            Dimension::Mass => "kg",
            Dimension::Damping => "N s/m",
        }
    }

    /// An example a user could type.
    pub fn example(self) -> &'static str {
        match self {
            Dimension::Length => "\"0.5 um\"",
            Dimension::Area => "\"100 um^2\"",
            Dimension::Force => "\"3 uN\"",
            Dimension::Pressure => "\"1.4 GPa\"",
            Dimension::SurfaceEnergy => "\"0.1 J/m^2\"",
            Dimension::Compliance => "\"9.1e-12 1/Pa\"",
            Dimension::ArealDensity => "\"4e12 m^-2\"",
            Dimension::ForcePerVoltageSquared => "\"1.4e-8 N/V^2\"",
            Dimension::Voltage => "\"20 V\"",
            Dimension::Stiffness => "\"2.5 N/m\"",
            Dimension::Dimensionless => "\"0.35\" or \"35 %\"",
            Dimension::Angle => "\"1 mrad\" or \"0.1 deg\"",
            Dimension::Time => "\"10 ms\"",
            Dimension::Mass => "\"107 ng\"",
            Dimension::Damping => "\"2.1e-7 N s/m\"",
        }
    }
}

/// The sign a field requires.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Constraint {
    /// Any finite value.
    Finite,
    /// Finite and strictly positive.
    Positive,
    /// Finite and not negative.
    NonNegative,
}

/// Why a quantity was rejected. Its `Display` names the value and what was expected; the caller
/// (a scenario path, a flag) adds the field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{value:?}: {problem}; expected {expected}")]
pub struct QuantityError {
    /// The text (or number) as given.
    pub value: String,
    /// What is wrong with it.
    pub problem: String,
    /// What was expected: the dimension, an example and the SI unit of a bare number.
    pub expected: String,
}

impl QuantityError {
    pub(crate) fn new(
        value: impl Into<String>,
        problem: impl Into<String>,
        dim: Dimension,
        constraint: Constraint,
    ) -> Self {
        let sign = match constraint {
            Constraint::Finite => "",
            Constraint::Positive => "positive ",
            Constraint::NonNegative => "non-negative ",
        };
        // "a positive length", "a non-negative area": the sign goes after the article.
        let what = match (sign, dim.description().split_once(' ')) {
            ("", _) | (_, None) => dim.description().to_string(),
            (_, Some((_article, noun))) => format!("a {sign}{noun}"),
        };
        let si = dim.si_unit();
        let bare = if si.is_empty() { "a number".to_string() } else { format!("a number in {si}") };
        QuantityError {
            value: value.into(),
            problem: problem.into(),
            expected: format!("{what} such as {} (or {bare})", dim.example()),
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

#[cfg(test)]
mod name_tests {
    use super::*;

    /// Text and JSON spell an enum the same way, the way a scenario file writes it.
    #[test]
    fn display_is_the_serde_name() {
        assert_eq!(Distribution::Lognormal.to_string(), "lognormal");
        assert_eq!(serde_json::to_string(&Distribution::Lognormal).unwrap(), "\"lognormal\"");
        let back: Distribution = serde_json::from_str(&format!("\"{}\"", Distribution::Uniform)).unwrap();
        assert_eq!(back, Distribution::Uniform);
        assert_eq!(serde_name(&3), "3");
        // An uncertain parameter in an error: as written, not as a Rust value.
        let u: UncertainInput =
            serde_json::from_str(r#"{"value": "0.5 um", "sd": "0.3 um", "min": "0.6 um", "max": 7e-7}"#).unwrap();
        let e = u.nominal(Dimension::Length, Constraint::Positive).unwrap_err().to_string();
        assert!(
            e.starts_with(r#""{value: 0.5 um, sd: 0.3 um, distribution: normal, min: 0.6 um, max: 0.0000007}": value"#),
            "{e}"
        );
    }

    /// The unit suffixes of keys and columns, as the hand-written keys spell them.
    #[test]
    fn unit_suffixes() {
        for (unit, key) in [
            ("N", "n"),
            ("m^2", "m2"),
            ("N/V^2", "n_per_v2"),
            ("m^-2", "per_m2"),
            ("1/Pa", "per_pa"),
            ("J/m^2", "j_per_m2"),
            ("N s/m", "n_s_per_m"),
            ("N/m", "n_per_m"),
            ("1", ""),
            ("", ""),
        ] {
            assert_eq!(unit_key_suffix(unit), key, "{unit}");
        }
        assert_eq!(key_with_unit("surface.summit_radius", "m"), "surface.summit_radius_m");
        assert_eq!(key_with_unit("meter.slip_mu", "1"), "meter.slip_mu");
    }

    /// "expected a positive length", not "expected positive a length".
    #[test]
    fn expected_reads_as_english() {
        let e = parse_quantity_checked("-0.5 um", Dimension::Length, Constraint::Positive).unwrap_err();
        assert!(e.to_string().contains("expected a positive length such as"), "{e}");
        let e = parse_quantity_checked("-1 um^2", Dimension::Area, Constraint::NonNegative).unwrap_err();
        assert!(e.to_string().contains("expected a non-negative area such as"), "{e}");
        let e = parse_quantity_checked("1 N", Dimension::Length, Constraint::Finite).unwrap_err();
        assert!(e.to_string().contains("expected a length such as"), "{e}");
    }
}
