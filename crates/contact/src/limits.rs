//! Elastic limits (section 3.3): the maximum Hertz pressure (eq. 11), the mean real elastic
//! pressure against `0.24 H`, the plasticity index, and the friction-coefficient bounds
//! `s/p_e` (elastic) and `s/H` (plastic).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::error::{ContactError, check_nonnegative, check_positive};

/// Fraction of the hardness above which the mean real elastic pressure signals significant plastic
/// deformation (section 3.3: `p_e > 0.24 H`).
pub const PLASTIC_PRESSURE_FRACTION: f64 = 0.24;

/// Peak Hertz pressure `q0` (Pa) at interference (indentation) `z` (m), from eq. 11
/// `z = (4/9) pi^2 q0^2 D^2 R`: `q0 = 3/(2 pi D) sqrt(z/R)`. 0 for `z <= 0`.
pub fn max_hertz_pressure_pa(interference_m: f64, radius_m: f64, compliance_per_pa: f64) -> Result<f64, ContactError> {
    check_positive("radius_m", radius_m, "a finite radius > 0 (m)")?;
    check_positive("compliance_per_pa", compliance_per_pa, "a finite compliance > 0 (1/Pa)")?;
    if !interference_m.is_finite() {
        return Err(ContactError::InvalidParameter {
            field: "interference_m",
            value: interference_m,
            expected: "a finite interference (m)",
        });
    }
    Ok(if interference_m > 0.0 { 1.5 / (PI * compliance_per_pa) * (interference_m / radius_m).sqrt() } else { 0.0 })
}

/// Interference (m) at which the peak Hertz pressure reaches `pressure_pa` (eq. 11):
/// `z = (4/9) pi^2 q0^2 D^2 R`; with `pressure_pa = H` the elastic-limit interference.
pub fn interference_at_pressure_m(
    pressure_pa: f64,
    radius_m: f64,
    compliance_per_pa: f64,
) -> Result<f64, ContactError> {
    check_nonnegative("pressure_pa", pressure_pa, "a finite pressure >= 0 (Pa)")?;
    check_positive("radius_m", radius_m, "a finite radius > 0 (m)")?;
    check_positive("compliance_per_pa", compliance_per_pa, "a finite compliance > 0 (1/Pa)")?;
    Ok(4.0 / 9.0 * PI * PI * pressure_pa.powi(2) * compliance_per_pa.powi(2) * radius_m)
}

/// Plasticity index of Greenwood and Williamson, `psi = (E*/H) sqrt(sigma/R)` with
/// `E* = 3/(4D)` and `sigma` the SD of the summit heights (dimensionless). GW: contacts are
/// elastic for `psi < 0.6` and largely plastic for `psi > 1`.
pub fn plasticity_index(
    compliance_per_pa: f64,
    hardness_pa: f64,
    summit_sd_m: f64,
    summit_radius_m: f64,
) -> Result<f64, ContactError> {
    check_positive("compliance_per_pa", compliance_per_pa, "a finite compliance > 0 (1/Pa)")?;
    check_positive("hardness_pa", hardness_pa, "a finite hardness > 0 (Pa)")?;
    check_positive("summit_sd_m", summit_sd_m, "a finite summit-height SD > 0 (m)")?;
    check_positive("summit_radius_m", summit_radius_m, "a finite summit radius > 0 (m)")?;
    Ok(0.75 / compliance_per_pa / hardness_pa * (summit_sd_m / summit_radius_m).sqrt())
}

/// Whether the contact is elastic by the criterion of section 3.3.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub enum ContactRegime {
    /// `p_e <= 0.24 H`: elastic; the friction coefficient is `s/p_e`.
    Elastic,
    /// `p_e > 0.24 H`: significant plastic deformation; the friction coefficient tends to `s/H`.
    Plastic,
}
stiction_units::display_serde_name!(ContactRegime);

/// Friction-coefficient bounds of section 3.3.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct FrictionBounds {
    /// Elastic friction coefficient `mu = s/p_e` (eq. 2 with eq. 7).
    pub elastic_coefficient: f64,
    /// Plastic lower limit `mu_p = s/H`.
    pub plastic_coefficient: f64,
    /// `p_e/H`.
    pub pressure_over_hardness: f64,
    /// Regime by `p_e` against `0.24 H`.
    pub regime: ContactRegime,
    /// The coefficient that applies: `s/p_e` when elastic, `s/H` (the limit approached) when plastic.
    pub coefficient: f64,
}

/// Friction-coefficient bounds from the shear strength `s` (Pa), the mean real elastic pressure
/// `p_e` (Pa, eq. 7) and the hardness `H` (Pa).
pub fn friction_bounds(
    shear_strength_pa: f64,
    mean_elastic_pressure_pa: f64,
    hardness_pa: f64,
) -> Result<FrictionBounds, ContactError> {
    check_nonnegative("shear_strength_pa", shear_strength_pa, "a finite shear strength >= 0 (Pa)")?;
    check_positive("mean_elastic_pressure_pa", mean_elastic_pressure_pa, "a finite mean elastic pressure > 0 (Pa)")?;
    check_positive("hardness_pa", hardness_pa, "a finite hardness > 0 (Pa)")?;
    let elastic = shear_strength_pa / mean_elastic_pressure_pa;
    let plastic = shear_strength_pa / hardness_pa;
    let ratio = mean_elastic_pressure_pa / hardness_pa;
    let regime = if ratio > PLASTIC_PRESSURE_FRACTION { ContactRegime::Plastic } else { ContactRegime::Elastic };
    Ok(FrictionBounds {
        elastic_coefficient: elastic,
        plastic_coefficient: plastic,
        pressure_over_hardness: ratio,
        regime,
        coefficient: match regime {
            ContactRegime::Elastic => elastic,
            ContactRegime::Plastic => plastic,
        },
    })
}
