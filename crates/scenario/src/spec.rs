//! Scenario sections owned by this crate: material, contact model, meter protocol, measured data.

use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value;
use stiction_contact::single::AdhesionLaw;
use stiction_units::{Constraint, Dimension, QuantityInput, nominal_from_json};

use crate::domain::MAX_VOLTAGE_V;

/// Material properties of the contacting pair (the paper's Table 1 and section 5).
///
/// Give either the composite `compliance` D (eq. 3) or `youngs_modulus` and `poisson_ratio` of two
/// identical bodies, for which D = (3/4) * 2 (1 - nu^2) / E.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Composite compliance D = (3/4) ((1 - nu1^2)/E1 + (1 - nu2^2)/E2), 1/Pa (Table 1: 9.1e-12 1/Pa).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_compliance_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub compliance: Option<f64>,
    /// Young's modulus of both bodies, Pa (used when `compliance` is not given).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_pressure_positive",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub youngs_modulus: Option<f64>,
    /// Poisson's ratio of both bodies (used with `youngs_modulus`).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_dimensionless",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub poisson_ratio: Option<f64>,
    /// Work of adhesion dgamma, J/m^2 (Table 1: 0.1 J/m^2).
    #[serde(deserialize_with = "stiction_units::de::surface_energy_nonnegative")]
    #[schemars(with = "QuantityInput")]
    pub work_of_adhesion: f64,
    /// Interfacial shear strength s of eq. 1, Pa (the paper's fit: 1.4 GPa).
    #[serde(deserialize_with = "stiction_units::de::pressure_positive")]
    #[schemars(with = "QuantityInput")]
    pub shear_strength: f64,
    /// Hardness H, Pa, for the elastic limit (section 3.3); default 9 GPa (polysilicon, section 5).
    #[serde(default = "default_hardness", deserialize_with = "stiction_units::de::pressure_positive")]
    #[schemars(with = "QuantityInput")]
    pub hardness: f64,
    /// Equilibrium spacing z0 of the surface forces, m, for the Tabor and Maugis parameters; default 0.3 nm.
    #[serde(default = "default_spacing", deserialize_with = "stiction_units::de::length_positive")]
    #[schemars(with = "QuantityInput")]
    pub equilibrium_spacing: f64,
    /// Contact angle theta of the environment's liquid (water unless `environment.liquid` names
    /// another) on both faces ("0 deg" for water on a clean hydrophilic oxide, "110 deg" for water on
    /// a hydrophobic FOTS/OTS monolayer); used only with an `environment` section. Default 0 deg. A
    /// liquid given by its properties may state its own angles instead (not both).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_angle_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub contact_angle: Option<f64>,
    /// Contact angle of the shoe's face, when it differs from `contact_angle` (the sidewall's); default
    /// `contact_angle`.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_angle_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub counter_face_contact_angle: Option<f64>,
}

fn default_hardness() -> f64 {
    9e9
}
fn default_spacing() -> f64 {
    0.3e-9
}

impl MaterialSpec {
    /// The composite compliance D, 1/Pa (eq. 3).
    pub fn compliance_per_pa(&self) -> f64 {
        match (self.compliance, self.youngs_modulus, self.poisson_ratio) {
            (Some(d), _, _) => d,
            (None, Some(e), nu) => 0.75 * 2.0 * (1.0 - nu.unwrap_or(0.0).powi(2)) / e,
            // validate() guarantees one of the two forms.
            (None, None, _) => f64::NAN,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        match (self.compliance, self.youngs_modulus, self.poisson_ratio) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => Err((
                "compliance".into(),
                "give either `compliance` or `youngs_modulus` with `poisson_ratio`, not both".into(),
            )),
            (None, None, _) => Err((
                "compliance".into(),
                "missing: give `compliance` (like \"9.1e-12 1/Pa\") or `youngs_modulus` with `poisson_ratio`".into(),
            )),
            (None, Some(_), None) => Err(("poisson_ratio".into(), "missing: needed with `youngs_modulus`".into())),
            (None, Some(_), Some(nu)) if !(-1.0..0.5).contains(&nu) => {
                Err(("poisson_ratio".into(), format!("{nu} is outside the physical range [-1, 0.5)")))
            }
            _ => Ok(()),
        }?;
        for (name, angle) in
            [("contact_angle", self.contact_angle), ("counter_face_contact_angle", self.counter_face_contact_angle)]
        {
            if let Some(a) = angle
                && a > std::f64::consts::PI
            {
                return Err((
                    name.into(),
                    format!("{} deg is above 180 deg; expected a contact angle in [0, 180] deg", a.to_degrees()),
                ));
            }
        }
        Ok(())
    }

    /// Contact angles of the sidewall and of the shoe's face, rad (default 0: fully wetting oxide).
    pub fn contact_angles_rad(&self) -> (f64, f64) {
        let a = self.contact_angle.unwrap_or(0.0);
        (a, self.counter_face_contact_angle.unwrap_or(a))
    }
}

/// The air around the device: the vapour of a liquid (water by default) condensing in the narrow
/// gaps of the contact (capillary adhesion), and the temperature.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EnvironmentSpec {
    /// Relative vapour pressure `p/p_sat` of the condensing liquid: for water the relative humidity
    /// of the air. A fraction in [0, 1) or a percentage ("35 %"); may be an uncertain parameter
    /// (`{"value": "35 %", "sd": "5 %"}`) for a study to draw. 0: dry. With a liquid other than
    /// water (`liquid`) it is that liquid's relative vapour pressure (0.95: 95 % of saturation).
    #[serde(deserialize_with = "stiction_units::de::dimensionless_nonnegative")]
    #[schemars(with = "QuantityInput")]
    pub relative_humidity: f64,
    /// Temperature: "25 C" (degrees Celsius), "298.15 K" or a number in kelvin; default 25 C. Sets
    /// the surface tension and molar volume of the liquid (water: IAPWS; 1-pentanol: handbook
    /// values, 15 C to 35 C) and the Kelvin radius.
    #[serde(default = "default_temperature", deserialize_with = "temperature_k")]
    #[schemars(with = "TemperatureInput")]
    pub temperature: f64,
    /// Smallest Kelvin radius at which a meniscus condenses ("0.28 nm", a water molecule's
    /// diameter; optional, default none: the continuum meniscus at every humidity). Below it the
    /// contact is dry (the dry regime of rough hydrophilic surfaces at low humidity).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "stiction_units::de::opt_length_positive"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub min_kelvin_radius: Option<f64>,
    /// The condensing liquid: "water" (default: the IAPWS correlations), "1-pentanol" (handbook
    /// values with their sources, `stiction_contact::capillary`), or a liquid given by its surface
    /// tension, molar volume, saturation pressure (and optionally contact angles) with their source.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub liquid: Option<LiquidSpec>,
}

/// A liquid the program knows by name.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
pub enum LiquidName {
    /// Water: IAPWS surface tension and saturated-liquid density.
    #[serde(rename = "water")]
    Water,
    /// 1-pentanol (n-pentanol, the vapour-phase lubricant of MEMS sidewalls): handbook surface
    /// tension and density, saturation pressure about 25 C; used from 15 C to 35 C.
    #[serde(rename = "1-pentanol")]
    Pentanol,
}

/// The condensing liquid of the `environment`: a name, or the liquid's properties.
#[derive(Debug, Clone, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum LiquidSpec {
    /// "water" or "1-pentanol".
    Named(LiquidName),
    /// A liquid given by its properties at the scenario's temperature, with their source.
    Given(GivenLiquid),
}

impl<'de> Deserialize<'de> for LiquidSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        match Value::deserialize(d)? {
            Value::String(name) => match name.as_str() {
                "water" => Ok(LiquidSpec::Named(LiquidName::Water)),
                "1-pentanol" => Ok(LiquidSpec::Named(LiquidName::Pentanol)),
                other => Err(D::Error::custom(format!(
                    "unknown liquid {:?}; expected \"water\", \"1-pentanol\" or an object giving `name`, \
                     `surface_tension`, `molar_volume`, `saturation_pressure` and `source`",
                    crate::text::truncate(other, 40)
                ))),
            },
            v @ Value::Object(_) => GivenLiquid::deserialize(v).map(LiquidSpec::Given).map_err(D::Error::custom),
            other => Err(D::Error::custom(format!(
                "{}: expected a liquid's name (\"water\", \"1-pentanol\") or an object giving its properties",
                crate::text::truncate(&other.to_string(), 40)
            ))),
        }
    }
}

/// A condensing liquid given by its properties at the scenario's temperature (no temperature
/// dependence is assumed: state the values at `environment.temperature`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GivenLiquid {
    /// The liquid's name, for the outputs ("ethanol").
    pub name: String,
    /// Surface tension against its vapour, N/m ("22.0 mN/m").
    #[serde(deserialize_with = "stiction_units::de::surface_energy_positive")]
    #[schemars(with = "QuantityInput")]
    pub surface_tension: f64,
    /// Molar volume of the liquid, m^3/mol ("58.7 cm^3/mol").
    #[serde(deserialize_with = "stiction_units::de::molar_volume_positive")]
    #[schemars(with = "QuantityInput")]
    pub molar_volume: f64,
    /// Saturation vapour pressure at the temperature, Pa ("7.9 kPa"): the partial pressure a
    /// relative pressure stands for (the Kelvin radius needs only `p/p_sat`).
    #[serde(deserialize_with = "stiction_units::de::pressure_positive")]
    #[schemars(with = "QuantityInput")]
    pub saturation_pressure: f64,
    /// Contact angle of the liquid on both faces (optional; else `material.contact_angle`, not both).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_angle_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub contact_angle: Option<f64>,
    /// Contact angle on the shoe's face when it differs (optional; default `contact_angle`).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_angle_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub counter_face_contact_angle: Option<f64>,
    /// Where the values were read (a handbook, a paper): required.
    pub source: String,
}

/// A temperature: a number (kelvin) or a string "25 C", "25 degC", "298.15 K".
#[derive(JsonSchema)]
#[serde(untagged)]
#[allow(dead_code)]
enum TemperatureInput {
    /// Kelvin.
    Kelvin(f64),
    /// With a unit: "25 C", "298.15 K".
    Text(String),
}

/// Default temperature, 25 C, K.
pub const DEFAULT_TEMPERATURE_K: f64 = 298.15;

fn default_temperature() -> f64 {
    DEFAULT_TEMPERATURE_K
}

/// Parses a temperature (see [`EnvironmentSpec::temperature`]) to kelvin and checks it against
/// its domain (`crate::domain`: the water correlations' validity, 273.16 K to 647.096 K); `Err`
/// names what was expected. The one rule for the scenario's `environment.temperature`, `bem
/// --temperature` and Python.
pub fn parse_temperature_k(v: &Value) -> Result<f64, String> {
    const EXPECTED: &str = "expected a temperature of liquid water from 273.16 K (0.01 C) to 647.096 K (water's \
                            critical point), like \"25 C\", \"298.15 K\" or 298.15 (a bare number is kelvin)";
    let (k, bare) = match v {
        Value::Number(n) => (n.as_f64().unwrap_or(f64::NAN), true),
        Value::String(s) => {
            let t = s.trim();
            let (num, unit) = match t.find(|c: char| c.is_alphabetic() || c == '\u{b0}') {
                Some(i) => (t[..i].trim(), t[i..].trim()),
                None => (t, ""),
            };
            let x: f64 = num
                .parse()
                .map_err(|_| format!("{:?}: not a temperature; {EXPECTED}", crate::text::truncate(s, 40)))?;
            match unit {
                "C" | "degC" | "\u{b0}C" => (x + 273.15, false),
                "K" => (x, false),
                "" => (x, true),
                _ => {
                    return Err(format!(
                        "{:?}: unknown temperature unit `{}`; {EXPECTED}",
                        crate::text::truncate(s, 40),
                        crate::text::truncate(unit, 20)
                    ));
                }
            }
        }
        other => return Err(format!("{}: {EXPECTED}", crate::text::truncate(&other.to_string(), 40))),
    };
    let domain = crate::domain::lookup("environment.temperature").expect("the temperature has a domain");
    if domain.contains(k) {
        return Ok(k);
    }
    let hint = if bare && k.is_finite() && domain.contains(k + 273.15) {
        format!(" (a bare number is kelvin: for {k} degrees Celsius write \"{k} C\")")
    } else {
        String::new()
    };
    Err(format!("{} K is outside {}{hint}; {EXPECTED}", crate::domain::short(k), domain.range_text()))
}

fn temperature_k<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    use serde::de::Error;
    parse_temperature_k(&Value::deserialize(d)?).map_err(D::Error::custom)
}

impl EnvironmentSpec {
    /// The condensing liquid's name ("water", "1-pentanol", or the given liquid's `name`).
    pub fn liquid_name(&self) -> &str {
        match &self.liquid {
            None | Some(LiquidSpec::Named(LiquidName::Water)) => "water",
            Some(LiquidSpec::Named(LiquidName::Pentanol)) => "1-pentanol",
            Some(LiquidSpec::Given(g)) => &g.name,
        }
    }

    /// Whether the liquid is water (no `liquid`, or "water").
    pub fn is_water(&self) -> bool {
        matches!(self.liquid, None | Some(LiquidSpec::Named(LiquidName::Water)))
    }

    /// The liquid's surface tension and molar volume at the scenario's temperature.
    pub fn liquid_properties(&self) -> stiction_contact::capillary::Liquid {
        use stiction_contact::capillary::Liquid;
        let t = self.temperature;
        match &self.liquid {
            None | Some(LiquidSpec::Named(LiquidName::Water)) => Liquid::water(t),
            Some(LiquidSpec::Named(LiquidName::Pentanol)) => Liquid::pentanol(t),
            Some(LiquidSpec::Given(g)) => {
                Liquid { surface_tension_n_per_m: g.surface_tension, molar_volume_m3_per_mol: g.molar_volume }
            }
        }
    }

    /// The liquid's saturation vapour pressure at the temperature, Pa (water: not computed, None).
    pub fn saturation_pressure_pa(&self) -> Option<f64> {
        match &self.liquid {
            None | Some(LiquidSpec::Named(LiquidName::Water)) => None,
            Some(LiquidSpec::Named(LiquidName::Pentanol)) => {
                Some(stiction_contact::capillary::pentanol_saturation_pressure_pa(self.temperature))
            }
            Some(LiquidSpec::Given(g)) => Some(g.saturation_pressure),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        if let Some(LiquidSpec::Named(LiquidName::Pentanol)) = self.liquid {
            let (lo, hi) = stiction_contact::capillary::PENTANOL_TEMPERATURE_RANGE_K;
            if !(lo..=hi).contains(&self.temperature) {
                return Err((
                    "temperature".into(),
                    format!(
                        "{} K is outside the range of the 1-pentanol correlations, {lo} K to {hi} K (15 C to 35 C, \
                         handbook values about 25 C); give the liquid by its properties at this temperature",
                        crate::domain::short(self.temperature)
                    ),
                ));
            }
        }
        if let Some(LiquidSpec::Given(g)) = &self.liquid {
            for (field, text) in [("name", &g.name), ("source", &g.source)] {
                if text.trim().is_empty() || text.chars().count() > 400 {
                    return Err((
                        format!("liquid.{field}"),
                        format!(
                            "expected a non-empty text of at most 400 characters, got {} characters",
                            text.chars().count()
                        ),
                    ));
                }
            }
        }
        if self.relative_humidity >= 1.0 {
            return Err((
                "relative_humidity".into(),
                format!(
                    "{} is not below 1 (100 %): at saturation the Kelvin radius is infinite and the gap floods; \
                     expected a fraction in [0, 1) like 0.35 or \"35 %\"",
                    self.relative_humidity
                ),
            ));
        }
        Ok(())
    }
}

/// Which contact model turns the load into real area.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ContactModel {
    /// The explicit asperity-by-asperity solver on the generated surface (default).
    #[default]
    Explicit,
    /// Greenwood-Williamson statistics with DMT adhesion (eq. 5, 8).
    Gw,
    /// The discrete model with `contacts` equally loaded summits (eq. 12).
    Discrete,
    /// The FFT boundary-element solver on the height-map patch under the shoe (elastic interaction
    /// between all points of the face; settings in `bem`).
    Bem,
}

/// Degrees of freedom of the rigid shoe in the explicit solver.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ShoeMode {
    /// Approach and two tilts free (default).
    #[default]
    Tilt,
    /// Approach only, no tilt (the GW situation).
    Flat,
    /// A fixed number of contacts (`contacts`), for comparison with eq. 12.
    Fixed,
}
stiction_units::display_serde_name!(ContactModel, ShoeMode);

/// Contact law and model.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Single-asperity law: "dmt" (default, as in the paper), "hertz", "jkr", "maugis-dugdale".
    #[serde(default = "default_law")]
    pub law: AdhesionLaw,
    /// "explicit" (default), "gw", "discrete" or "bem".
    #[serde(default)]
    pub model: ContactModel,
    /// Shoe degrees of freedom for the explicit model: "tilt" (default), "flat", "fixed".
    #[serde(default)]
    pub mode: ShoeMode,
    /// Number of contacts for the discrete model (1, 2 or 3; the paper uses 3) and for mode "fixed".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contacts: Option<usize>,
    /// Settings of the boundary-element model (`model` = "bem"): grid spacing or points, tolerance,
    /// Dugdale range.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bem: Option<stiction_bem::BemSpec>,
}

fn default_law() -> AdhesionLaw {
    AdhesionLaw::Dmt
}

impl Default for ContactSpec {
    fn default() -> Self {
        ContactSpec {
            law: AdhesionLaw::Dmt,
            model: ContactModel::Explicit,
            mode: ShoeMode::Tilt,
            contacts: None,
            bem: None,
        }
    }
}

impl ContactSpec {
    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        if let Some(b) = &self.bem {
            if self.model != ContactModel::Bem {
                return Err(("bem".into(), "only with `model` = \"bem\"".into()));
            }
            b.validate().map_err(|(p, msg)| (format!("bem.{p}"), msg))?;
        }
        let needs_contacts = self.model == ContactModel::Discrete || self.mode == ShoeMode::Fixed;
        match self.contacts {
            None if needs_contacts => Err((
                "contacts".into(),
                "missing: the discrete model and mode \"fixed\" need a number of contacts (the paper: 3)".into(),
            )),
            Some(0) => Err(("contacts".into(), "0 is not a number of contacts; expected 1, 2 or 3".into())),
            Some(n) if self.model == ContactModel::Discrete && n > 3 => {
                Err(("contacts".into(), format!("{n}: the discrete model (eq. 12) takes 1, 2 or 3 contacts")))
            }
            _ => Ok(()),
        }
    }
}

/// Voltages as a list (`["10 V", "20 V"]`) or a ramp (`{"from": "10 V", "to": "40 V", "steps": 7}`).
#[derive(Debug, Clone, Serialize, JsonSchema, PartialEq)]
#[serde(untagged)]
pub enum VoltageSchedule {
    /// Explicit voltages, V.
    List(#[schemars(with = "Vec<QuantityInput>")] Vec<f64>),
    /// `steps` evenly spaced voltages from `from` to `to` inclusive.
    Ramp {
        /// First voltage, V.
        #[schemars(with = "QuantityInput")]
        from: f64,
        /// Last voltage, V.
        #[schemars(with = "QuantityInput")]
        to: f64,
        /// Number of voltages (at least 2).
        steps: usize,
    },
}

impl VoltageSchedule {
    /// The voltages, V.
    pub fn voltages(&self) -> Vec<f64> {
        match self {
            VoltageSchedule::List(v) => v.clone(),
            VoltageSchedule::Ramp { from, to, steps } => {
                (0..*steps).map(|i| from + (to - from) * i as f64 / (*steps - 1).max(1) as f64).collect()
            }
        }
    }
}

impl<'de> Deserialize<'de> for VoltageSchedule {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let v = Value::deserialize(d)?;
        let volt = |x: &Value, what: &str| {
            nominal_from_json(x, Dimension::Voltage, Constraint::NonNegative)
                .map_err(|e| D::Error::custom(format!("{what}: {e}")))
        };
        match &v {
            Value::Array(items) => {
                if items.is_empty() {
                    return Err(D::Error::custom(
                        "an empty list of voltages; expected at least one, like [\"20 V\", \"30 V\"]",
                    ));
                }
                items
                    .iter()
                    .enumerate()
                    .map(|(i, x)| volt(x, &format!("[{i}]")))
                    .collect::<Result<_, _>>()
                    .map(VoltageSchedule::List)
            }
            Value::Object(map) => {
                for key in map.keys() {
                    if !["from", "to", "steps"].contains(&key.as_str()) {
                        return Err(D::Error::custom(format!(
                            "unknown field `{key}`, expected one of `from`, `to`, `steps`"
                        )));
                    }
                }
                let get = |k: &str| {
                    map.get(k).ok_or_else(|| D::Error::custom(format!("missing field `{k}` of a voltage ramp")))
                };
                let from = volt(get("from")?, "from")?;
                let to = volt(get("to")?, "to")?;
                let steps = get("steps")?
                    .as_u64()
                    .filter(|s| *s >= 2)
                    .ok_or_else(|| D::Error::custom(format!("steps: {} is not a whole number >= 2", map["steps"])))?;
                Ok(VoltageSchedule::Ramp { from, to, steps: steps as usize })
            }
            other => Err(D::Error::custom(format!(
                "{other}: expected a list of voltages or a ramp {{\"from\", \"to\", \"steps\"}}"
            ))),
        }
    }
}

/// When the shoe slips.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Default)]
#[serde(rename_all = "kebab-case", tag = "kind", deny_unknown_fields)]
pub enum SlipCriterion {
    /// F_pull >= s * A_r (eq. 1), the default.
    #[default]
    ShearArea,
    /// F_pull >= (s / H) * L_total: the plastic limit of section 1.2 / 3.3.
    Plastic,
    /// F_pull >= sum over contacts of (s0 + alpha * p_mean,i) * A_i: a pressure-dependent shear strength.
    PressureDependent {
        /// The pressure coefficient alpha (dimensionless).
        #[serde(deserialize_with = "stiction_units::de::dimensionless_nonnegative")]
        #[schemars(with = "QuantityInput")]
        alpha: f64,
    },
}

/// The friction meter: protocol and the parts of the device not in the actuator arrays.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeterSpec {
    /// F_spring: suspension plus pull connection beam times the initial gap, N (paper: 7 +/- 2 uN).
    /// When absent it is computed from the clamp array's spring and travel.
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_force_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub spring_force: Option<f64>,
    /// Travel of the clamp array at which the shoe meets the wall, m; default: the clamp array's
    /// `operating_travel` (where its conversion factor is defined).
    #[serde(
        default,
        deserialize_with = "stiction_units::de::opt_length_nonnegative",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub contact_travel: Option<f64>,
    /// Clamp voltages to measure at.
    pub clamp_voltages: VoltageSchedule,
    /// Step of the pull-voltage ramp, V (default 0.05 V).
    #[serde(default = "default_pull_step", deserialize_with = "stiction_units::de::voltage_positive")]
    #[schemars(with = "QuantityInput")]
    pub pull_voltage_step: f64,
    /// Highest pull voltage tried before giving up on slip, V (default 200 V).
    #[serde(default = "default_pull_max", deserialize_with = "stiction_units::de::voltage_positive")]
    #[schemars(with = "QuantityInput")]
    pub pull_voltage_max: f64,
    /// Slip criterion (default shear strength times real area).
    #[serde(default)]
    pub slip: SlipCriterion,
    /// Release the clamp between clamp voltages, so the shoe comes down anew at each (default
    /// true); false keeps it in contact and carries the load path over (the explicit solver's
    /// equilibria depend on it).
    #[serde(default = "yes")]
    pub reclamp: bool,
    /// Simulate the motion of the pull shuttle after each slip (rigid-body dynamics with rapier);
    /// absent: only the quasi-static runaway test.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip_dynamics: Option<SlipDynamicsSpec>,
    /// Largest number of clamp voltages (default 100 000): checked before the run starts; raise it
    /// for a longer sweep.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_clamp_voltages: Option<u64>,
    /// How the laboratory turned its forces into a friction coefficient, reported as
    /// `lab_coefficient` beside mu_e,a (absent: eq. 10 itself, the paper's reduction, and no
    /// `lab_coefficient`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lab_reduction: Option<crate::lab_reduction::LabReductionSpec>,
}

/// The pull shuttle's dynamics after slip: `m x'' = F_e(x, V) - k x - c x' - F_k`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SlipDynamicsSpec {
    /// Moving mass of the pull array and the shoe, kg ("107 ng"; polysilicon 2330 kg/m^3 times the volume).
    #[serde(deserialize_with = "stiction_units::de::mass_positive")]
    #[schemars(with = "QuantityInput")]
    pub shuttle_mass: f64,
    /// Viscous (air) damping coefficient c, N s/m (squeeze film plus Couette; default 0).
    #[serde(default, deserialize_with = "stiction_units::de::damping_nonnegative")]
    #[schemars(with = "QuantityInput")]
    pub damping: f64,
    /// Kinetic friction coefficient mu_k on the total (clamp plus adhesive) load: F_k = mu_k (L + L_adh); default 0.
    #[serde(default, deserialize_with = "stiction_units::de::dimensionless_nonnegative")]
    #[schemars(with = "QuantityInput")]
    pub kinetic_friction_coefficient: f64,
}

fn yes() -> bool {
    true
}
fn default_pull_step() -> f64 {
    0.05
}
fn default_pull_max() -> f64 {
    200.0
}

impl MeterSpec {
    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        self.check_limits()?;
        if self.pull_voltage_step >= self.pull_voltage_max {
            return Err((
                "pull_voltage_step".into(),
                format!("{} V is not below pull_voltage_max = {} V", self.pull_voltage_step, self.pull_voltage_max),
            ));
        }
        Ok(())
    }
}

/// Largest number of pull-ramp steps `pull_voltage_max / pull_voltage_step`: 2^53, the largest
/// count that f64 holds exactly (the ramp's step index is an f64). A numerical limit, not raisable.
pub const MAX_PULL_RAMP_STEPS: f64 = 9_007_199_254_740_992.0;

/// Default of `meter.max_clamp_voltages`: each clamp voltage costs one contact solve (about a
/// millisecond on the paper's surface, more on large ones) and one row of every output.
pub const DEFAULT_MAX_CLAMP_VOLTAGES: u64 = 100_000;

impl MeterSpec {
    /// Checks the protocol's sizes and ranges before any work (see [`MAX_VOLTAGE_V`],
    /// [`MAX_PULL_RAMP_STEPS`], [`DEFAULT_MAX_CLAMP_VOLTAGES`]). Returns (field, message).
    pub fn check_limits(&self) -> Result<(), (String, String)> {
        let limit = self.max_clamp_voltages.unwrap_or(DEFAULT_MAX_CLAMP_VOLTAGES);
        if limit == 0 {
            return Err(("max_clamp_voltages".into(), "0: expected a positive count".into()));
        }
        let count = match &self.clamp_voltages {
            VoltageSchedule::List(v) => v.len() as u64,
            VoltageSchedule::Ramp { steps, .. } => *steps as u64,
        };
        if count > limit {
            return Err((
                "clamp_voltages".into(),
                format!(
                    "{count} clamp voltages (about {:.1e} bytes of results and one contact solve each) exceed the \
                     limit of {limit} (`meter.max_clamp_voltages`, default {DEFAULT_MAX_CLAMP_VOLTAGES}); raise \
                     `meter.max_clamp_voltages` if you mean it",
                    count as f64 * 512.0
                ),
            ));
        }
        let too_high = |v: f64| v > MAX_VOLTAGE_V;
        match &self.clamp_voltages {
            VoltageSchedule::List(v) => {
                if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| too_high(**x)) {
                    return Err((
                        format!("clamp_voltages[{i}]"),
                        format!("{x:e} V is above {MAX_VOLTAGE_V:e} V, the highest voltage stiction applies"),
                    ));
                }
            }
            VoltageSchedule::Ramp { from, to, .. } => {
                for (name, x) in [("from", *from), ("to", *to)] {
                    if too_high(x) {
                        return Err((
                            format!("clamp_voltages.{name}"),
                            format!("{x:e} V is above {MAX_VOLTAGE_V:e} V, the highest voltage stiction applies"),
                        ));
                    }
                }
            }
        }
        if too_high(self.pull_voltage_max) {
            return Err((
                "pull_voltage_max".into(),
                format!(
                    "{:e} V is above {MAX_VOLTAGE_V:e} V, the highest voltage stiction applies",
                    self.pull_voltage_max
                ),
            ));
        }
        let steps = self.pull_voltage_max / self.pull_voltage_step;
        if steps.is_nan() || steps > MAX_PULL_RAMP_STEPS {
            return Err((
                "pull_voltage_step".into(),
                format!(
                    "{:e} V gives pull_voltage_max / pull_voltage_step = {steps:.3e} ramp steps, more than 2^53 = \
                     {MAX_PULL_RAMP_STEPS:.3e} (the largest step count f64 holds exactly); take a larger step",
                    self.pull_voltage_step
                ),
            ));
        }
        Ok(())
    }
}

/// Measured (V_clamp, V_pull) data to compare with: a CSV with columns `v_clamp_v,v_pull_v`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct MeasuredSpec {
    /// The CSV file; a relative path is resolved against the scenario file's folder (given with
    /// `--set` on the command line: against the current directory).
    #[schemars(extend("x-stiction-path" = true))]
    pub voltages_csv: PathBuf,
}

/// Measured values to compare the model with (such as the paper's own measurement of the device the
/// scenario describes). Printed and drawn beside the model's results only when a scenario has this
/// section: a user's own device gets no paper numbers it was never measured against.
///
/// Values are plain quantities (not uncertain-parameter objects: a Monte Carlo study must not draw
/// them); the uncertainty is a separate half-width, and `uncertainty_meaning` says what it is
/// (printed with every `+/-`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ReferenceSpec {
    /// Where the values come from, printed and shown in figure legends
    /// (e.g. "Tas et al., MEMS 2000, section 5").
    pub source: String,
    /// The device the values were measured on: its fingerprint (`stiction scenario FILE
    /// --explain` prints it; see `Scenario::device_fingerprint`). A scenario that describes
    /// another device (a copy with other arrays, springs, calibrations or shoe) does not show the
    /// reference, and says so. Absent: shown, with a note that nothing checks it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub device: Option<String>,
    /// Measured apparent friction coefficient mu_e,a of eq. 10 (dimensionless, > 0).
    #[serde(default, deserialize_with = "plain_dimensionless_positive", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<f64>")]
    pub mu_apparent: Option<f64>,
    /// Half-width of the uncertainty of `mu_apparent` (dimensionless, >= 0).
    #[serde(default, deserialize_with = "plain_dimensionless_nonnegative", skip_serializing_if = "Option::is_none")]
    #[schemars(with = "Option<f64>")]
    pub mu_apparent_uncertainty: Option<f64>,
    /// Measured apparent zero-load adhesion force F_a0 of eq. 10, N ("2.0 uN").
    #[serde(
        default,
        deserialize_with = "plain_force",
        serialize_with = "force_with_unit",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub apparent_adhesion_force: Option<f64>,
    /// Half-width of the uncertainty of `apparent_adhesion_force`, N ("1.3 uN", >= 0).
    #[serde(
        default,
        deserialize_with = "plain_force_nonnegative",
        serialize_with = "force_with_unit",
        skip_serializing_if = "Option::is_none"
    )]
    #[schemars(with = "Option<QuantityInput>")]
    pub apparent_adhesion_force_uncertainty: Option<f64>,
    /// What the +/- is, printed with it (e.g. "uncertainty stated by the paper, from the
    /// conversion factors' uncertainty"); required when an uncertainty is given.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub uncertainty_meaning: String,
}

fn plain<'de, D: Deserializer<'de>>(d: D, dim: Dimension, constraint: Constraint) -> Result<Option<f64>, D::Error> {
    use serde::de::Error;
    let v = Value::deserialize(d)?;
    if v.is_object() {
        return Err(D::Error::custom(
            "expected a plain value (a number or a string with a unit), not an uncertain-parameter object: \
             the uncertainty of a reference value goes in its `..._uncertainty` field",
        ));
    }
    nominal_from_json(&v, dim, constraint).map(Some).map_err(D::Error::custom)
}
/// Writes a force as a string with its unit, `"2e-6 N"` (exact, and read back by the same parser),
/// so that a key without a unit in an output (study.json, the log header) is not ambiguous.
fn force_with_unit<S: serde::Serializer>(v: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match v {
        Some(v) => s.serialize_str(&format!("{v:e} N")),
        None => s.serialize_none(),
    }
}

fn plain_dimensionless_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    plain(d, Dimension::Dimensionless, Constraint::Positive)
}
fn plain_dimensionless_nonnegative<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    plain(d, Dimension::Dimensionless, Constraint::NonNegative)
}
fn plain_force<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    plain(d, Dimension::Force, Constraint::Finite)
}
fn plain_force_nonnegative<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
    plain(d, Dimension::Force, Constraint::NonNegative)
}

impl ReferenceSpec {
    /// Cross-field checks: a source, at least one value, an uncertainty only with its value and
    /// with a meaning. Returns (field, message).
    pub(crate) fn validate(&self) -> Result<(), (String, String)> {
        if self.source.trim().is_empty() {
            return Err(("source".into(), "missing: say where the reference values come from".into()));
        }
        if self.mu_apparent.is_none() && self.apparent_adhesion_force.is_none() {
            return Err((
                "mu_apparent".into(),
                "missing: a reference needs `mu_apparent` or `apparent_adhesion_force` (or both)".into(),
            ));
        }
        for (u, v, name) in [
            (self.mu_apparent_uncertainty, self.mu_apparent, "mu_apparent"),
            (self.apparent_adhesion_force_uncertainty, self.apparent_adhesion_force, "apparent_adhesion_force"),
        ] {
            if u.is_some() && v.is_none() {
                return Err((format!("{name}_uncertainty"), format!("given without `{name}`")));
            }
            if u.is_some() && self.uncertainty_meaning.trim().is_empty() {
                return Err((
                    "uncertainty_meaning".into(),
                    format!(
                        "missing: `{name}_uncertainty` is given; say what the +/- is (a standard deviation, \
                         a stated uncertainty, a range of devices, ...)"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `value +/- uncertainty` of mu_e,a for text, or `value` alone.
    pub fn mu_text(&self) -> Option<String> {
        self.mu_apparent.map(|m| match self.mu_apparent_uncertainty {
            Some(u) => format!("{m} +/- {u}"),
            None => format!("{m}"),
        })
    }

    /// `value +/- uncertainty uN` of F_a0 for text, or `value uN` alone.
    pub fn adhesion_text(&self) -> Option<String> {
        self.apparent_adhesion_force.map(|f| match self.apparent_adhesion_force_uncertainty {
            Some(u) => format!("{} +/- {} uN", round6(f * 1e6), round6(u * 1e6)),
            None => format!("{} uN", round6(f * 1e6)),
        })
    }
}

/// Rounds to 6 decimals, so that 2.0e-6 N prints as 2 uN, not 1.9999999999999998.
fn round6(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}
