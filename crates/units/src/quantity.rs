//! What a quantity is: the dimension its unit must have ([`Dimension`], [`DimensionVector`]), the
//! constraint on its value ([`Constraint`]) and the error naming what was wrong ([`QuantityError`]).

/// Exponents of the base dimensions (metre, kilogram, second, ampere, mole) of a unit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct DimensionVector(pub [i8; 5]);

/// Largest |exponent| of a base dimension in a unit expression (m^-2, V^-2 are far below it).
pub const MAX_UNIT_EXPONENT: i32 = 24;

impl DimensionVector {
    /// `self * other^power`; None when an exponent leaves [-MAX_UNIT_EXPONENT, MAX_UNIT_EXPONENT]
    /// (checked arithmetic: "N^64 N^64 N^64 N^64" must not wrap around to a length).
    pub(crate) fn mul(self, other: Self, power: i8) -> Option<Self> {
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
    /// Molar volume of a liquid, m^3/mol ("108.7 cm^3/mol").
    MolarVolume,
}

impl Dimension {
    /// The base-dimension exponents (m, kg, s, A) of this dimension.
    pub fn vector(self) -> DimensionVector {
        DimensionVector(match self {
            Dimension::Length => [1, 0, 0, 0, 0],
            Dimension::Area => [2, 0, 0, 0, 0],
            Dimension::Force => [1, 1, -2, 0, 0],
            Dimension::Pressure => [-1, 1, -2, 0, 0],
            Dimension::SurfaceEnergy | Dimension::Stiffness => [0, 1, -2, 0, 0],
            Dimension::Compliance => [1, -1, 2, 0, 0],
            Dimension::ArealDensity => [-2, 0, 0, 0, 0],
            Dimension::ForcePerVoltageSquared => [-3, -1, 4, 2, 0],
            Dimension::Voltage => [2, 1, -3, -1, 0],
            Dimension::Dimensionless | Dimension::Angle => [0, 0, 0, 0, 0],
            Dimension::Time => [0, 0, 1, 0, 0],
            Dimension::Mass => [0, 1, 0, 0, 0],
            Dimension::Damping => [0, 1, -1, 0, 0],
            Dimension::MolarVolume => [3, 0, 0, 0, -1],
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
            Dimension::MolarVolume => "a molar volume (volume per amount of substance)",
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
            Dimension::MolarVolume => "m^3/mol",
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
            Dimension::MolarVolume => "\"108.7 cm^3/mol\"",
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
