//! Actuators of the friction test structures beyond the paper's gap-closing arrays
//! (docs/actuators.md, "Other actuators"):
//!
//! * [`LateralComb`]: a lateral (interdigitated) comb drive, force `F = alpha N eps0 t V^2 / g`
//!   whatever the travel, with the side instability of its suspension (Legtenberg, Groeneveld,
//!   Elwenspoek, J. Micromech. Microeng. 6 (1996) 320-329);
//! * [`PlateElectrode`]: a plate pulled onto the substrate by an electrode underneath, through an
//!   air gap and dielectric layers, `F = eps0 A V^2 / (2 (g_air + sum t_i / eps_r,i)^2)`;
//! * [`ReleasedSpring`]: a suspension set to a displacement and released, tangential load `k x`.
//!
//! SI units and `f64` everywhere; every constructor checks its fields and names the bad one.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::{ActuatorError, nonnegative, positive};
use crate::plates::VACUUM_PERMITTIVITY;

fn one() -> f64 {
    1.0
}

/// A lateral comb drive: `N` movable fingers, each between two fixed fingers across the lateral
/// gap `g` on both sides, overlapping them over the engagement `x0 + x` (travel `x` along the
/// fingers), all of structural thickness `t`.
///
/// Per movable finger the capacitance is `C = eps0 t (x0 + x) [1/(g - y) + 1/(g + y)]` (`y` the
/// lateral offset), so at `y = 0`:
///
/// * drive force `F = 1/2 V^2 dC/dx = alpha N eps0 t V^2 / g`, independent of the travel (`alpha`
///   the fringing factor, >= 1, on the drive force only: the fields at the finger tips);
/// * lateral electrostatic (negative) stiffness `k_e = -dF_y/dy = 2 N eps0 t (x0 + x) V^2 / g^3`;
/// * side instability when `k_e` reaches the suspension's lateral stiffness `k_y`: at a fixed travel
///   `V_s(x)^2 = k_y g^3 / (2 N eps0 t (x0 + x))`; for a free comb (travel `x = F / k_x`)
///   `V_SI^2 = k_x g^2 / (2 alpha N eps0 t) [sqrt(2 alpha k_y / k_x + x0^2 / g^2) - x0 / g]`
///   (Legtenberg et al. 1996, eq. for the maximum stable voltage, with `alpha = 1` there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LateralComb {
    /// Movable fingers `N`.
    pub finger_count: u32,
    /// Structural thickness `t`, m.
    pub thickness_m: f64,
    /// Lateral gap `g` on each side of a finger, m.
    pub gap_m: f64,
    /// Engagement (finger overlap) at zero travel `x0`, m.
    pub engagement_m: f64,
    /// Fringing factor `alpha` on the drive force (1: parallel-plate fields only).
    pub fringing_factor: f64,
    /// Suspension stiffness along the drive `k_x`, N/m.
    pub axial_stiffness_n_per_m: f64,
    /// Suspension stiffness across the fingers `k_y`, N/m (None: side instability not assessed).
    pub lateral_stiffness_n_per_m: Option<f64>,
}

impl LateralComb {
    /// Checks every field.
    pub fn new(
        finger_count: u32,
        thickness_m: f64,
        gap_m: f64,
        engagement_m: f64,
        fringing_factor: f64,
        axial_stiffness_n_per_m: f64,
        lateral_stiffness_n_per_m: Option<f64>,
    ) -> Result<LateralComb, ActuatorError> {
        if finger_count == 0 {
            return Err(ActuatorError::InvalidField {
                field: "finger_count".into(),
                value: 0.0,
                expected: "at least 1 finger".into(),
            });
        }
        positive("thickness", thickness_m)?;
        positive("gap", gap_m)?;
        nonnegative("engagement", engagement_m)?;
        if !(fringing_factor.is_finite() && fringing_factor >= 1.0) {
            return Err(ActuatorError::InvalidField {
                field: "fringing_factor".into(),
                value: fringing_factor,
                expected: "a finite factor >= 1 (fringing adds to the parallel-plate force)".into(),
            });
        }
        positive("spring.stiffness", axial_stiffness_n_per_m)?;
        if let Some(k) = lateral_stiffness_n_per_m {
            positive("lateral_stiffness", k)?;
        }
        Ok(LateralComb {
            finger_count,
            thickness_m,
            gap_m,
            engagement_m,
            fringing_factor,
            axial_stiffness_n_per_m,
            lateral_stiffness_n_per_m,
        })
    }

    /// `N eps0 t / g`, N/V^2: the parallel-plate drive factor.
    fn parallel_factor(&self) -> f64 {
        self.finger_count as f64 * VACUUM_PERMITTIVITY * self.thickness_m / self.gap_m
    }

    /// Conversion factor `a = alpha N eps0 t / g`, N/V^2 (the same at every travel).
    pub fn conversion_factor_n_per_v2(&self) -> f64 {
        self.fringing_factor * self.parallel_factor()
    }

    /// Drive force `F = a V^2`, N.
    pub fn force_n(&self, voltage_v: f64) -> f64 {
        self.conversion_factor_n_per_v2() * voltage_v * voltage_v
    }

    /// Capacitance of the comb at travel `x` and lateral offset `y` (parallel plate,
    /// `C = N eps0 t (x0 + x) [1/(g - y) + 1/(g + y)]`), F. For the tests' energy derivatives.
    pub fn capacitance_f(&self, travel_m: f64, offset_m: f64) -> f64 {
        let n = self.finger_count as f64;
        n * VACUUM_PERMITTIVITY
            * self.thickness_m
            * (self.engagement_m + travel_m)
            * (1.0 / (self.gap_m - offset_m) + 1.0 / (self.gap_m + offset_m))
    }

    /// Lateral electrostatic stiffness at travel `x`, `k_e = 2 N eps0 t (x0 + x) V^2 / g^3`, N/m.
    pub fn lateral_electrostatic_stiffness_n_per_m(&self, travel_m: f64, voltage_v: f64) -> f64 {
        2.0 * self.parallel_factor() * (self.engagement_m + travel_m) * voltage_v * voltage_v
            / (self.gap_m * self.gap_m)
    }

    /// Side pull-in voltage at a fixed travel (the comb held there, e.g. by a contact),
    /// `V_s = sqrt(k_y g^3 / (2 N eps0 t (x0 + x)))`, V; None without a lateral stiffness or with
    /// no engagement.
    pub fn side_pull_in_voltage_at_v(&self, travel_m: f64) -> Option<f64> {
        let k_y = self.lateral_stiffness_n_per_m?;
        let overlap = self.engagement_m + travel_m;
        if overlap <= 0.0 {
            return None;
        }
        Some((k_y * self.gap_m * self.gap_m / (2.0 * self.parallel_factor() * overlap)).sqrt())
    }

    /// Side pull-in voltage of the free comb (travel `F / k_x`), Legtenberg et al. 1996:
    /// `V_SI^2 = k_x g^2 / (2 alpha N eps0 t) [sqrt(2 alpha k_y / k_x + x0^2 / g^2) - x0 / g]`, V.
    pub fn side_pull_in_voltage_v(&self) -> Option<f64> {
        let k_y = self.lateral_stiffness_n_per_m?;
        let (k_x, g, x0, alpha) = (self.axial_stiffness_n_per_m, self.gap_m, self.engagement_m, self.fringing_factor);
        let n_eps_t = self.finger_count as f64 * VACUUM_PERMITTIVITY * self.thickness_m;
        let r = x0 / g;
        // sqrt(a + r^2) - r written as a / (sqrt(a + r^2) + r): no cancellation at large x0/g.
        let a = 2.0 * alpha * k_y / k_x;
        let bracket = a / ((a + r * r).sqrt() + r);
        Some((k_x * g * g / (2.0 * alpha * n_eps_t) * bracket).sqrt())
    }

    /// Travel of the free comb at a voltage, `x = a V^2 / k_x`, m.
    pub fn free_travel_m(&self, voltage_v: f64) -> f64 {
        self.force_n(voltage_v) / self.axial_stiffness_n_per_m
    }
}

/// One dielectric layer between the plate and the electrode (e.g. a nitride on the electrode).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DielectricLayer {
    /// Layer thickness `t_i`, m.
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub thickness: f64,
    /// Relative permittivity `eps_r,i` (a plain number >= 1; silicon nitride about 7.5, silicon
    /// dioxide 3.9).
    pub relative_permittivity: f64,
}

/// A plate pulled onto the substrate by an electrode underneath (Lim et al. 1990): electrode
/// area `A` facing the plate, an air gap `g_air` and dielectric layers in series.
///
/// Series capacitance `C = eps0 A / (g_air + d)`, `d = sum t_i / eps_r,i` (the layers' equivalent
/// air thickness), so the force at constant voltage is
/// `F = -1/2 V^2 dC/dg_air = eps0 A V^2 / (2 (g_air + d)^2)`.
///
/// The plate starts `g0` above its contact position (the rest air gap minus the air gap at
/// contact, which is the stand-off dimples' height, or 0 when the underside lies on the top
/// layer) on a vertical suspension `k_z`. Its pull-in: `V_eq(z)^2 = 2 k_z z (G - z)^2 / (eps0 A)`
/// with `G = g0 + g_c + d` the effective gap at rest, maximum at `z = G/3`:
/// `V_pi = sqrt(8 k_z G^3 / (27 eps0 A))` when `G/3 < g0`; otherwise the plate reaches contact
/// on its stable branch at `V_c = sqrt(2 k_z g0 (g_c + d)^2 / (eps0 A))`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlateElectrode {
    /// Electrode area under the plate `A`, m^2.
    pub area_m2: f64,
    /// Air gap left at contact `g_c` (stand-off dimple height, 0 without dimples), m.
    pub air_gap_at_contact_m: f64,
    /// Dielectric layers between plate and electrode.
    pub dielectric: Vec<DielectricLayer>,
    /// Travel from rest to contact `g0`, m.
    pub travel_to_contact_m: f64,
    /// Vertical suspension stiffness `k_z`, N/m.
    pub vertical_stiffness_n_per_m: f64,
}

impl PlateElectrode {
    /// Checks every field.
    pub fn new(
        area_m2: f64,
        air_gap_at_contact_m: f64,
        dielectric: Vec<DielectricLayer>,
        travel_to_contact_m: f64,
        vertical_stiffness_n_per_m: f64,
    ) -> Result<PlateElectrode, ActuatorError> {
        positive("electrode_area", area_m2)?;
        nonnegative("air_gap_at_contact", air_gap_at_contact_m)?;
        for (i, layer) in dielectric.iter().enumerate() {
            positive(&format!("dielectric[{i}].thickness"), layer.thickness)?;
            if !(layer.relative_permittivity.is_finite() && layer.relative_permittivity >= 1.0) {
                return Err(ActuatorError::InvalidField {
                    field: format!("dielectric[{i}].relative_permittivity"),
                    value: layer.relative_permittivity,
                    expected: "a finite relative permittivity >= 1".into(),
                });
            }
        }
        nonnegative("travel_to_contact", travel_to_contact_m)?;
        nonnegative("spring.stiffness", vertical_stiffness_n_per_m)?;
        let plate = PlateElectrode {
            area_m2,
            air_gap_at_contact_m,
            dielectric,
            travel_to_contact_m,
            vertical_stiffness_n_per_m,
        };
        if plate.effective_gap_m(air_gap_at_contact_m) <= 0.0 {
            return Err(ActuatorError::Inconsistent(
                "the plate touches the electrode at contact: give an air gap at contact (stand-off dimples) or a \
                 dielectric layer"
                    .into(),
            ));
        }
        Ok(plate)
    }

    /// `d = sum t_i / eps_r,i`, m.
    pub fn dielectric_equivalent_gap_m(&self) -> f64 {
        self.dielectric.iter().map(|l| l.thickness / l.relative_permittivity).sum()
    }

    /// `g_air + d`, m.
    pub fn effective_gap_m(&self, air_gap_m: f64) -> f64 {
        air_gap_m + self.dielectric_equivalent_gap_m()
    }

    /// Series capacitance `eps0 A / (g_air + d)`, F.
    pub fn capacitance_f(&self, air_gap_m: f64) -> f64 {
        VACUUM_PERMITTIVITY * self.area_m2 / self.effective_gap_m(air_gap_m)
    }

    /// Force towards the electrode across the air gap `g_air`, `eps0 A V^2 / (2 (g_air + d)^2)`, N.
    pub fn force_n(&self, air_gap_m: f64, voltage_v: f64) -> f64 {
        let g = self.effective_gap_m(air_gap_m);
        VACUUM_PERMITTIVITY * self.area_m2 * voltage_v * voltage_v / (2.0 * g * g)
    }

    /// Conversion factor at contact `a = eps0 A / (2 (g_c + d)^2)`, N/V^2.
    pub fn conversion_factor_at_contact_n_per_v2(&self) -> f64 {
        self.force_n(self.air_gap_at_contact_m, 1.0)
    }

    /// Spring force at contact `k_z g0`, N.
    pub fn spring_force_at_contact_n(&self) -> f64 {
        self.vertical_stiffness_n_per_m * self.travel_to_contact_m
    }

    /// Normal load on the contact at a voltage, `a V^2 - k_z g0`, N (<= 0: no load).
    pub fn normal_load_n(&self, voltage_v: f64) -> f64 {
        self.conversion_factor_at_contact_n_per_v2() * voltage_v * voltage_v - self.spring_force_at_contact_n()
    }

    /// The voltage at which the plate reaches contact: its pull-in `sqrt(8 k_z G^3 / (27 eps0 A))`
    /// when the unstable point `G/3` lies before contact, else the stable-branch voltage at contact
    /// `sqrt(2 k_z g0 (g_c + d)^2 / (eps0 A))`, V. With `k_z g0 = 0` the plate touches at any voltage.
    pub fn contact_voltage_v(&self) -> f64 {
        let (k, g0) = (self.vertical_stiffness_n_per_m, self.travel_to_contact_m);
        let big_g = g0 + self.effective_gap_m(self.air_gap_at_contact_m);
        if big_g / 3.0 < g0 {
            (8.0 * k * big_g.powi(3) / (27.0 * VACUUM_PERMITTIVITY * self.area_m2)).sqrt()
        } else {
            let gc = self.effective_gap_m(self.air_gap_at_contact_m);
            (2.0 * k * g0 * gc * gc / (VACUUM_PERMITTIVITY * self.area_m2)).sqrt()
        }
    }
}

/// A suspension set to a displacement and released (Lim et al. 1990): while the structure holds,
/// the spring's restoring force `F_t = k x` is the tangential load on the contact.
///
/// The stiffness is given, or follows from a measured resonance: `k = m (2 pi f)^2`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReleasedSpring {
    /// Lateral stiffness `k`, N/m.
    pub stiffness_n_per_m: f64,
}

impl ReleasedSpring {
    /// A spring of given stiffness.
    pub fn new(stiffness_n_per_m: f64) -> Result<ReleasedSpring, ActuatorError> {
        Ok(ReleasedSpring { stiffness_n_per_m: positive("stiffness", stiffness_n_per_m)? })
    }

    /// The stiffness from a resonance: `k = m (2 pi f)^2` (mass in kg, frequency in Hz).
    pub fn from_resonance(mass_kg: f64, frequency_hz: f64) -> Result<ReleasedSpring, ActuatorError> {
        positive("resonance.mass", mass_kg)?;
        positive("resonance.frequency", frequency_hz)?;
        let w = 2.0 * std::f64::consts::PI * frequency_hz;
        ReleasedSpring::new(mass_kg * w * w)
    }

    /// Tangential load at a displacement, `k x`, N.
    pub fn tangential_load_n(&self, displacement_m: f64) -> f64 {
        self.stiffness_n_per_m * displacement_m
    }

    /// The displacement whose restoring force is `force`, `x = F / k`, m.
    pub fn displacement_for_load_m(&self, force_n: f64) -> f64 {
        force_n / self.stiffness_n_per_m
    }
}

/// A lateral comb drive as written in a scenario file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LateralCombSpec {
    /// What the comb is (printed).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Movable fingers `N`.
    pub finger_count: u32,
    /// Structural thickness `t`.
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub thickness: f64,
    /// Lateral gap `g` on each side of a finger.
    #[serde(deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub gap: f64,
    /// Finger engagement (overlap) at rest `x0`.
    #[serde(deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub engagement: f64,
    /// Fringing factor `alpha` on the drive force (default 1).
    #[serde(default = "one", deserialize_with = "stiction_units::de::dimensionless_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub fringing_factor: f64,
    /// Suspension stiffness along the drive `k_x`.
    #[serde(deserialize_with = "stiction_units::de::stiffness_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub stiffness: f64,
    /// Suspension stiffness across the fingers `k_y` (absent: side instability not assessed).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_stiffness_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub lateral_stiffness: Option<f64>,
}

impl LateralCombSpec {
    /// The model.
    pub fn to_model(&self) -> Result<LateralComb, ActuatorError> {
        LateralComb::new(
            self.finger_count,
            self.thickness,
            self.gap,
            self.engagement,
            self.fringing_factor,
            self.stiffness,
            self.lateral_stiffness,
        )
    }
}

/// A plate electrode to the substrate as written in a scenario file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlateElectrodeSpec {
    /// What the electrode is (printed).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Electrode area under the plate `A`.
    #[serde(deserialize_with = "stiction_units::de::area_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub electrode_area: f64,
    /// Air gap left at contact `g_c`: the stand-off dimples' height (default 0: the underside lies
    /// on the top layer).
    #[serde(default, deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub air_gap_at_contact: f64,
    /// Dielectric layers between plate and electrode (default none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub dielectric: Vec<DielectricLayer>,
    /// Travel from rest to contact `g0` (the released gap minus `air_gap_at_contact`).
    #[serde(deserialize_with = "stiction_units::de::length_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub travel_to_contact: f64,
    /// Vertical suspension stiffness `k_z`.
    #[serde(deserialize_with = "stiction_units::de::stiffness_nonnegative")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub stiffness: f64,
}

impl PlateElectrodeSpec {
    /// The model.
    pub fn to_model(&self) -> Result<PlateElectrode, ActuatorError> {
        PlateElectrode::new(
            self.electrode_area,
            self.air_gap_at_contact,
            self.dielectric.clone(),
            self.travel_to_contact,
            self.stiffness,
        )
    }
}

/// A measured resonance of the released structure, `k = m (2 pi f)^2`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ResonanceSpec {
    /// Resonant frequency `f`, Hz (a plain number).
    pub frequency: f64,
    /// Moving mass `m`.
    #[serde(deserialize_with = "stiction_units::de::mass_positive")]
    #[schemars(with = "stiction_units::QuantityInput")]
    pub mass: f64,
}

/// A spring set to a displacement and released, as written in a scenario file: exactly one of
/// `stiffness` and `resonance`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReleasedSpringSpec {
    /// What the spring is (printed).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// Lateral stiffness `k`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_stiffness_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<stiction_units::QuantityInput>")]
    pub stiffness: Option<f64>,
    /// The stiffness from a measured resonance instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub resonance: Option<ResonanceSpec>,
}

impl ReleasedSpringSpec {
    /// The model; exactly one of `stiffness` and `resonance` (one source of truth).
    pub fn to_model(&self) -> Result<ReleasedSpring, ActuatorError> {
        match (self.stiffness, &self.resonance) {
            (Some(k), None) => ReleasedSpring::new(k),
            (None, Some(r)) => ReleasedSpring::from_resonance(r.mass, r.frequency),
            (Some(_), Some(_)) => Err(ActuatorError::Inconsistent(
                "give the released spring's `stiffness` or its `resonance`, not both".into(),
            )),
            (None, None) => Err(ActuatorError::Inconsistent(
                "the released spring needs its `stiffness` or a `resonance` (frequency and mass)".into(),
            )),
        }
    }
}
