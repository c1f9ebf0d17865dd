//! Serde field helpers: `#[serde(deserialize_with = "stiction_units::de::length")]`.
//!
//! Each dimension has six helpers: `NAME` (any finite value), `NAME_positive`, `NAME_nonnegative`,
//! and `opt_NAME`, `opt_NAME_positive`, `opt_NAME_nonnegative` for `Option<f64>` fields (use them
//! with `#[serde(default, deserialize_with = ...)]`). Each accepts a JSON number (SI), a string with
//! a unit, or an uncertain-parameter object, of which it takes the nominal value.

use serde::de::Error as _;
use serde::{Deserialize, Deserializer};
use serde_json::Value;

use crate::{Constraint, Dimension, nominal_from_json};

/// Deserializes a quantity of dimension `dim` satisfying `constraint`, as an SI `f64`.
pub fn quantity<'de, D: Deserializer<'de>>(d: D, dim: Dimension, constraint: Constraint) -> Result<f64, D::Error> {
    let v = Value::deserialize(d)?;
    nominal_from_json(&v, dim, constraint).map_err(D::Error::custom)
}

/// Deserializes an optional quantity (JSON `null` is `None`).
pub fn opt_quantity<'de, D: Deserializer<'de>>(
    d: D,
    dim: Dimension,
    constraint: Constraint,
) -> Result<Option<f64>, D::Error> {
    let v = Value::deserialize(d)?;
    if v.is_null() {
        return Ok(None);
    }
    nominal_from_json(&v, dim, constraint).map(Some).map_err(D::Error::custom)
}

macro_rules! helpers {
    ($($name:ident, $pos:ident, $nonneg:ident, $opt:ident, $opt_pos:ident, $opt_nonneg:ident => $dim:expr;)*) => {$(
        #[doc = concat!("Deserializes ", stringify!($name), " (any finite value), in SI.")]
        pub fn $name<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> { quantity(d, $dim, Constraint::Finite) }
        #[doc = concat!("Deserializes a strictly positive ", stringify!($name), ", in SI.")]
        pub fn $pos<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> { quantity(d, $dim, Constraint::Positive) }
        #[doc = concat!("Deserializes a non-negative ", stringify!($name), ", in SI.")]
        pub fn $nonneg<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> { quantity(d, $dim, Constraint::NonNegative) }
        #[doc = concat!("Deserializes an optional ", stringify!($name), ", in SI.")]
        pub fn $opt<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> { opt_quantity(d, $dim, Constraint::Finite) }
        #[doc = concat!("Deserializes an optional, strictly positive ", stringify!($name), ", in SI.")]
        pub fn $opt_pos<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> { opt_quantity(d, $dim, Constraint::Positive) }
        #[doc = concat!("Deserializes an optional, non-negative ", stringify!($name), ", in SI.")]
        pub fn $opt_nonneg<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> { opt_quantity(d, $dim, Constraint::NonNegative) }
    )*};
}

helpers! {
    length, length_positive, length_nonnegative, opt_length, opt_length_positive, opt_length_nonnegative => Dimension::Length;
    area, area_positive, area_nonnegative, opt_area, opt_area_positive, opt_area_nonnegative => Dimension::Area;
    force, force_positive, force_nonnegative, opt_force, opt_force_positive, opt_force_nonnegative => Dimension::Force;
    pressure, pressure_positive, pressure_nonnegative, opt_pressure, opt_pressure_positive, opt_pressure_nonnegative => Dimension::Pressure;
    surface_energy, surface_energy_positive, surface_energy_nonnegative, opt_surface_energy, opt_surface_energy_positive, opt_surface_energy_nonnegative => Dimension::SurfaceEnergy;
    compliance, compliance_positive, compliance_nonnegative, opt_compliance, opt_compliance_positive, opt_compliance_nonnegative => Dimension::Compliance;
    areal_density, areal_density_positive, areal_density_nonnegative, opt_areal_density, opt_areal_density_positive, opt_areal_density_nonnegative => Dimension::ArealDensity;
    force_per_voltage_squared, force_per_voltage_squared_positive, force_per_voltage_squared_nonnegative, opt_force_per_voltage_squared, opt_force_per_voltage_squared_positive, opt_force_per_voltage_squared_nonnegative => Dimension::ForcePerVoltageSquared;
    voltage, voltage_positive, voltage_nonnegative, opt_voltage, opt_voltage_positive, opt_voltage_nonnegative => Dimension::Voltage;
    stiffness, stiffness_positive, stiffness_nonnegative, opt_stiffness, opt_stiffness_positive, opt_stiffness_nonnegative => Dimension::Stiffness;
    dimensionless, dimensionless_positive, dimensionless_nonnegative, opt_dimensionless, opt_dimensionless_positive, opt_dimensionless_nonnegative => Dimension::Dimensionless;
    angle, angle_positive, angle_nonnegative, opt_angle, opt_angle_positive, opt_angle_nonnegative => Dimension::Angle;
    time, time_positive, time_nonnegative, opt_time, opt_time_positive, opt_time_nonnegative => Dimension::Time;
    mass, mass_positive, mass_nonnegative, opt_mass, opt_mass_positive, opt_mass_nonnegative => Dimension::Mass;
    damping, damping_positive, damping_nonnegative, opt_damping, opt_damping_positive, opt_damping_nonnegative => Dimension::Damping;
    molar_volume, molar_volume_positive, molar_volume_nonnegative, opt_molar_volume, opt_molar_volume_positive, opt_molar_volume_nonnegative => Dimension::MolarVolume;
}

#[cfg(test)]
mod tests {
    use serde::Deserialize;

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    struct Spec {
        #[serde(deserialize_with = "super::length_positive")]
        radius: f64,
        #[serde(default, deserialize_with = "super::opt_force")]
        load: Option<f64>,
    }

    #[test]
    fn fields_accept_numbers_strings_and_uncertain_objects() {
        let s: Spec = serde_json::from_str(r#"{"radius": "0.5 um"}"#).unwrap();
        assert_eq!(s.radius, 0.5e-6);
        assert_eq!(s.load, None);
        let s: Spec = serde_json::from_str(r#"{"radius": 5e-7, "load": "3 uN"}"#).unwrap();
        assert_eq!((s.radius, s.load), (5e-7, Some(3e-6)));
        let s: Spec =
            serde_json::from_str(r#"{"radius": {"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"}}"#)
                .unwrap();
        assert_eq!(s.radius, 0.5e-6);
    }

    #[test]
    fn errors_carry_the_json_path_value_and_expectation() {
        let json = r#"{"radius": "-0.5 um"}"#;
        let de = &mut serde_json::Deserializer::from_str(json);
        let err = serde_path_to_error_lite(de);
        assert!(err.contains("-0.5 um") && err.contains("negative") && err.contains("a positive length"), "{err}");
        let err = serde_json::from_str::<Spec>(r#"{"radius": "0.5 N"}"#).unwrap_err().to_string();
        assert!(err.contains("is a force"), "{err}");
        let err =
            serde_json::from_str::<Spec>(r#"{"radius": {"value": "0.5 um", "sd": "-1 um"}}"#).unwrap_err().to_string();
        assert!(err.contains("`sd`"), "{err}");
        let err = serde_json::from_str::<Spec>(r#"{"radius": true}"#).unwrap_err().to_string();
        assert!(err.contains("neither a number nor a string"), "{err}");
    }

    fn serde_path_to_error_lite(de: &mut serde_json::Deserializer<serde_json::de::StrRead<'_>>) -> String {
        Spec::deserialize(de).unwrap_err().to_string()
    }
}
