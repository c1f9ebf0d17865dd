//! stiction-scenario: the scenario file format.
//!
//! A scenario is one JSON file that describes a whole experiment: the rough surfaces, the
//! materials, the contact law and solver model, the actuator arrays with their springs, the
//! voltage protocol and the outputs. Loading goes
//!
//! ```text
//! file --read--> serde_json::Value --`--set PATH=VALUE` overrides--> Value
//!      --typed parse (serde, path-tracking)--> Scenario --validate--> ready to run
//! ```
//!
//! Every quantity field accepts a number (SI), a string with a unit ("0.5 um") or an uncertain
//! parameter object (`{"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"}`); see
//! [`stiction_units`]. Unknown fields are rejected with the list of known ones. Every error names
//! the JSON path, the value and what was expected.

use std::path::Path;

use serde_json::Value;

pub mod design;
mod device;
pub mod domain;
mod error;
mod lab_reduction;
mod overrides;
mod scenario;
mod spec;
pub mod structure;
mod text;
mod warning;
pub use device::{Explanation, Quantity, SPRING_FORCE_RELATIVE_TOLERANCE};
pub use domain::MAX_VOLTAGE_V;
pub use error::{RELATIVE_HUMIDITY_MESSAGE, ScenarioError};
pub use scenario::{FORMAT_VERSION, Scenario};
pub mod strict_json;
pub use overrides::{absolutize_file_paths, apply_set, parse_set};
pub use spec::*;
pub use text::truncate;
pub use warning::Warning;

/// Largest scenario file read, bytes (16 MiB: the bundled ones are a few kB).
pub const MAX_SCENARIO_BYTES: u64 = 16 << 20;

impl Scenario {
    /// Reads, overrides (`--set`), parses and validates a scenario file.
    pub fn load(path: &Path, sets: &[String]) -> Result<Scenario, ScenarioError> {
        Scenario::from_value_with_sets(Scenario::load_json(path, sets)?, path, sets)
    }

    /// Reads a scenario file as JSON and applies the `--set` overrides, without the typed parse
    /// (a Monte Carlo study draws its uncertain parameters from this tree).
    pub fn load_json(path: &Path, sets: &[String]) -> Result<Value, ScenarioError> {
        let text = stiction_units::io::read_input_text(path, MAX_SCENARIO_BYTES)
            .map_err(|source| ScenarioError::Io { path: path.to_path_buf(), source })?;
        Scenario::json_with_sets(&text, path, sets)
    }

    /// Parses scenario text; `origin` names it in errors.
    pub fn from_str_with_sets(text: &str, origin: &Path, sets: &[String]) -> Result<Scenario, ScenarioError> {
        Scenario::from_value_with_sets(Scenario::json_with_sets(text, origin, sets)?, origin, sets)
    }

    /// Scenario text as JSON with the overrides applied; `origin` names it in errors.
    pub fn json_with_sets(text: &str, origin: &Path, sets: &[String]) -> Result<Value, ScenarioError> {
        let mut value: Value = strict_json::from_str(text).map_err(|e| ScenarioError::Syntax {
            path: origin.to_path_buf(),
            line: e.line(),
            column: e.column(),
            // serde_json's messages quote at most a key or a short token; truncated all the same,
            // so a wrong file (a binary, /etc/passwd) is never echoed.
            message: truncate(&e.to_string(), 200),
        })?;
        for set in sets {
            apply_set(&mut value, set)?;
        }
        Ok(value)
    }

    /// Parses and validates a JSON value; `origin` names it in errors.
    pub fn from_value(value: Value, origin: &Path) -> Result<Scenario, ScenarioError> {
        Scenario::from_value_with_sets(value, origin, &[])
    }

    /// Parses and validates a JSON value to which `sets` were applied: an error in a field that a
    /// `--set` wrote names that `--set`, not the file.
    pub fn from_value_with_sets(value: Value, origin: &Path, sets: &[String]) -> Result<Scenario, ScenarioError> {
        let field = |json_path: String, message: String| {
            // The last --set that wrote this field or one of its parents (or children) is to blame.
            let blamed = sets.iter().rev().find(|set| {
                parse_set(set).is_ok_and(|(segments, _)| {
                    let p = segments.join(".");
                    json_path == p
                        || json_path.starts_with(&format!("{p}."))
                        || json_path.starts_with(&format!("{p}["))
                        || p.starts_with(&format!("{json_path}."))
                })
            });
            match blamed {
                Some(set) => ScenarioError::Set { set: set.clone(), message: format!("at `{json_path}`: {message}") },
                None => ScenarioError::Field { path: origin.to_path_buf(), json_path, message },
            }
        };
        // Check the version first: a newer file should say so rather than fail on a new field.
        match value.get("format_version") {
            Some(Value::Number(n)) if n.as_u64() == Some(FORMAT_VERSION as u64) => {}
            Some(other) => {
                return Err(field(
                    "format_version".into(),
                    format!("{} is not supported; expected {FORMAT_VERSION}", truncate(&other.to_string(), 40)),
                ));
            }
            None => return Err(field("format_version".into(), format!("missing; expected {FORMAT_VERSION}"))),
        }
        // The humidity in the material section is refused with a pointer to where it belongs.
        if value.get("material").and_then(|m| m.get("relative_humidity")).is_some() {
            return Err(field("material.relative_humidity".into(), RELATIVE_HUMIDITY_MESSAGE.into()));
        }
        // One device per scenario: a `structure` built from parts has its own actuators and
        // protocol, so the paper's sections beside it (even empty: `"actuators": {}`) are refused
        // by name rather than ignored.
        if value.get("structure").is_some() {
            for name in ["actuators", "meter"] {
                if value.get(name).is_some() {
                    return Err(field(
                        name.into(),
                        format!(
                            "given beside `structure`: a scenario describes one device, a `structure` built from \
                             parts (its `normal` and `tangential` parts are its actuators, its `protocol` its \
                             meter) or the paper's `actuators` and `meter`; drop `{name}` or `structure`"
                        ),
                    ));
                }
            }
        }
        let source_json = value.clone();
        let mut scenario: Scenario = serde_path_to_error::deserialize(value).map_err(|e| {
            let p = e.path().to_string();
            field(if p == "." { "(top level)".into() } else { p }, truncate(&e.into_inner().to_string(), 300))
        })?;
        // Every number against its physical domain (crate::domain), by its key path, before the
        // cross-field checks (so that the field itself is named): refused outside it, a note
        // outside its usual range.
        let typed = serde_json::to_value(&scenario).map_err(|e| field("(top level)".into(), e.to_string()))?;
        let unusual = domain::check_tree(&typed).map_err(|e| field(e.field, e.message))?;
        scenario.validate().map_err(|(p, m)| field(p, m))?;
        scenario.check_physics().map_err(|(p, m)| field(p, m))?;
        scenario.source_json = source_json;
        scenario.notes.extend(unusual);
        scenario.check_reference_device();
        Ok(scenario)
    }

    /// Drops a `reference` measured on another device (its `device` fingerprint differs from
    /// this scenario's), with a note; notes a reference that states no device.
    fn check_reference_device(&mut self) {
        let Some(r) = &self.reference else { return };
        let own = self.device_fingerprint();
        match &r.device {
            Some(fp) if *fp == own => {}
            Some(fp) => {
                self.notes.push(Warning::new(
                    "reference_dropped",
                    format!(
                        "the `reference` ({}) was measured on device {fp}, and this scenario describes device {own} \
                         (its actuator arrays, calibrations, spring force, contact travel or shoe size differ), so \
                         the reference is not shown beside its results. For a measurement of this device, replace \
                         the reference's values and set `reference.device` to \"{own}\"",
                        r.source
                    ),
                ));
                self.reference = None;
            }
            None => self.notes.push(Warning::new(
                "reference_unchecked",
                format!(
                    "the `reference` ({}) states no `device`, so nothing checks that it was measured on this \
                     device; set `reference.device` to \"{own}\" (this scenario's device fingerprint) if it was",
                    r.source
                ),
            )),
        }
    }

    /// Cross-field checks that serde cannot express. Returns (JSON path, message).
    fn validate(&self) -> Result<(), (String, String)> {
        if let Some(s) = &self.surface {
            s.check().map_err(|(p, msg)| (format!("surface.{p}"), msg))?;
        }
        if let Some(m) = &self.material {
            m.validate().map_err(|(p, msg)| (format!("material.{p}"), msg))?;
        }
        if let Some(e) = &self.environment {
            e.validate().map_err(|(p, msg)| (format!("environment.{p}"), msg))?;
            if let Some(spec::LiquidSpec::Given(g)) = &e.liquid {
                let material_angle = self.material.as_ref().is_some_and(|m| m.contact_angle.is_some());
                if g.contact_angle.is_none() && g.counter_face_contact_angle.is_some() {
                    return Err((
                        "environment.liquid.counter_face_contact_angle".into(),
                        "given without `contact_angle`: give the sidewall's angle in `environment.liquid.contact_angle`"
                            .into(),
                    ));
                }
                if g.contact_angle.is_some() && material_angle {
                    return Err((
                        "environment.liquid.contact_angle".into(),
                        "the contact angle is given twice (here and in `material.contact_angle`): give it in one place"
                            .into(),
                    ));
                }
            }
        }
        if let Some(c) = &self.contact {
            // Dimples give the discrete model its number of contacts (one source of truth).
            let dimples = self.structure.as_ref().and_then(|st| match st.geometry {
                structure::GeometrySpec::Dimples { count, .. } => Some(count),
                _ => None,
            });
            if let Some(count) = dimples {
                if c.contacts.is_some() {
                    return Err((
                        "contact.contacts".into(),
                        format!(
                            "given beside `structure.geometry` dimples ({count}): the dimples are the contacts; drop \
                             `contact.contacts`"
                        ),
                    ));
                }
                let mut with = c.clone();
                with.contacts = Some(count as usize);
                with.validate().map_err(|(p, msg)| (format!("contact.{p}"), msg))?;
            } else {
                c.validate().map_err(|(p, msg)| (format!("contact.{p}"), msg))?;
            }
            let on_map = self.surface.as_ref().is_some_and(|s| s.source == stiction_surface::SurfaceSource::HeightMap);
            if c.model == ContactModel::Bem && !on_map {
                return Err((
                    "contact.model".into(),
                    "\"bem\" solves on a grid: it needs `surface.source` = \"height_map\" (a measured or generated \
                     `height_map`); summit lists have no surface between the summits"
                        .into(),
                ));
            }
        }
        if let Some(st) = &self.structure {
            st.validate().map_err(|(p, msg)| (format!("structure.{p}"), msg))?;
            if self.meter.is_some() || !self.actuators.is_empty() {
                return Err((
                    "structure".into(),
                    "a scenario describes one device: a `structure` built from parts, or the paper's `actuators` \
                     and `meter`, not both"
                        .into(),
                ));
            }
            if self.surface.is_none() {
                return Err(("surface".into(), "missing: a scenario with a `structure` needs a surface".into()));
            }
            if self.material.is_none() {
                return Err(("material".into(), "missing: a scenario with a `structure` needs a material".into()));
            }
            let model = self.contact_or_default().model;
            let dimples = matches!(st.geometry, structure::GeometrySpec::Dimples { .. });
            if dimples != (model == ContactModel::Discrete) {
                return Err((
                    "structure.geometry.kind".into(),
                    format!(
                        "dimples are the discrete model's N spheres and need `contact.model` = \"discrete\" (and a \
                         discrete model needs dimples here); found {model}"
                    ),
                ));
            }
        }
        if let Some(r) = &self.reference {
            r.validate().map_err(|(p, msg)| (format!("reference.{p}"), msg))?;
        }
        if let Some(m) = &self.meter {
            m.validate().map_err(|(p, msg)| (format!("meter.{p}"), msg))?;
            for name in ["clamp", "pull"] {
                if !self.actuators.contains_key(name) {
                    return Err((
                        format!("actuators.{name}"),
                        format!(
                            "missing: a scenario with a `meter` needs actuator arrays named `clamp` and `pull`; found {:?}",
                            self.actuators.keys().collect::<Vec<_>>()
                        ),
                    ));
                }
            }
            if self.surface.is_none() {
                return Err(("surface".into(), "missing: a scenario with a `meter` needs a surface".into()));
            }
            if self.material.is_none() {
                return Err(("material".into(), "missing: a scenario with a `meter` needs a material".into()));
            }
        }
        Ok(())
    }

    /// Cross-field physical rules that a range per field cannot state (after [`domain::check_tree`]):
    /// the Kelvin radius of the humid air must stay below the shoe (a meniscus of that curvature
    /// spans the whole contact: the gap floods and the meniscus model of separate summits does not
    /// hold). Returns (JSON path, message) naming the field that drives it.
    fn check_physics(&self) -> Result<(), (String, String)> {
        let (Some(env), Some(surface)) = (&self.environment, &self.surface) else { return Ok(()) };
        let Ok(Some(cap)) = self.capillarity_before_cut_off() else { return Ok(()) };
        let shoe_m = surface.apparent_length.min(surface.apparent_width);
        if cap.meniscus_height_m() >= shoe_m {
            return Err((
                "environment.relative_humidity".into(),
                format!(
                    "{} gives a Kelvin radius of {} m and a meniscus {} m high at {} K, not below the shoe's \
                     smaller side ({} m): the whole contact floods and no model of separate menisci holds; \
                     expected a humidity whose meniscus fits the shoe",
                    domain::short(env.relative_humidity),
                    domain::short(cap.kelvin_radius_m),
                    domain::short(cap.meniscus_height_m()),
                    domain::short(env.temperature),
                    domain::short(shoe_m)
                ),
            ));
        }
        Ok(())
    }

    /// The surface, or an error naming the missing section.
    pub fn require_surface(&self) -> Result<&stiction_surface::SurfaceSpec, String> {
        self.surface.as_ref().ok_or_else(|| "the scenario has no `surface` section".to_string())
    }

    /// The material, or an error naming the missing section.
    pub fn require_material(&self) -> Result<&MaterialSpec, String> {
        self.material.as_ref().ok_or_else(|| "the scenario has no `material` section".to_string())
    }

    /// The capillarity of the contact in the scenario's `environment` (water at its temperature,
    /// the material's contact angles); `None` when dry (no `environment`, relative humidity 0,
    /// hydrophobic faces with `cos theta_1 + cos theta_2 <= 0`, or a Kelvin radius below
    /// `environment.min_kelvin_radius`). `Err` names the field.
    pub fn capillarity(&self) -> Result<Option<stiction_contact::capillary::Capillarity>, String> {
        let min = self.environment.as_ref().and_then(|e| e.min_kelvin_radius);
        Ok(self.capillarity_before_cut_off()?.and_then(|c| c.above_min_kelvin_radius(min)))
    }

    /// [`Scenario::capillarity`] without the `min_kelvin_radius` cut-off (what would condense).
    pub fn capillarity_before_cut_off(&self) -> Result<Option<stiction_contact::capillary::Capillarity>, String> {
        use stiction_contact::capillary::Capillarity;
        let Some(env) = &self.environment else { return Ok(None) };
        if env.relative_humidity == 0.0 {
            return Ok(None);
        }
        let (a1, a2) = self.contact_angles_rad();
        let t = env.temperature;
        Capillarity::new(env.liquid_properties(), t, env.relative_humidity, a1, a2)
            .map_err(|e| format!("environment: {e}"))
    }

    /// The contact angles of the environment's liquid on the sidewall and on the shoe's face, rad:
    /// a given liquid's own `contact_angle` when it states one, else the material's (default 0).
    pub fn contact_angles_rad(&self) -> (f64, f64) {
        if let Some(spec::LiquidSpec::Given(g)) = self.environment.as_ref().and_then(|e| e.liquid.as_ref())
            && let Some(a) = g.contact_angle
        {
            return (a, g.counter_face_contact_angle.unwrap_or(a));
        }
        self.material.as_ref().map_or((0.0, 0.0), MaterialSpec::contact_angles_rad)
    }

    /// The contact section, or the paper's default (explicit solver, DMT, tilt free).
    pub fn contact_or_default(&self) -> ContactSpec {
        self.contact.clone().unwrap_or_default()
    }

    /// Whether the field at `path` (dotted, as `--set` names it) takes only whole numbers (a
    /// count such as `actuators.clamp.plate_count`), by the format's JSON Schema: the field's
    /// type is `integer` in every alternative that is not null. `false` for an unknown path.
    pub fn field_is_integer(path: &str) -> bool {
        overrides::field_is_integer(path)
    }
}

#[cfg(test)]
mod field_type_tests {
    use super::Scenario;

    /// Counts are integers by the schema (through `additionalProperties` for the named arrays and
    /// an optional section); quantities (unit strings or numbers) and unknown paths are not.
    #[test]
    fn integer_fields_are_found_through_the_schema() {
        assert!(Scenario::field_is_integer("actuators.clamp.plate_count"));
        assert!(Scenario::field_is_integer("actuators.pull.plate_count"));
        assert!(!Scenario::field_is_integer("actuators.clamp.front_gap"));
        assert!(!Scenario::field_is_integer("surface.summit_sd"));
        assert!(!Scenario::field_is_integer("environment.relative_humidity"));
        assert!(!Scenario::field_is_integer("actuators.clamp.no_such_field"));
        assert!(!Scenario::field_is_integer(""));
    }
}
