//! One source of truth for the device: which quantities the meter uses, where each comes from
//! (given, derived, calibrated), the checks between a calibration and the geometry it depends on,
//! and the device fingerprint a `reference` measurement is tied to.
//!
//! The rules (docs/scenario.md, "Calibrations and the device they belong to"):
//!
//! - A conversion factor is a calibration of a plate geometry (`calibrated_on`): it fixes the
//!   as-built front gap, and for another plate count, overlap or thickness the conversion factor
//!   is re-derived from that gap ([`stiction_actuator::ArraySpec::calibration_rederived`]).
//! - A given `meter.spring_force` is a measured calibration of the clamp spring times the contact
//!   travel, F_spring = k x_c: it must agree with k x_c within its uncertainty (its `sd`, or 1 %
//!   without one), else the meter refuses to run ([`Scenario::spring_force_conflict`]).
//! - A `reference` states the device it was measured on (`reference.device`, the
//!   [`Scenario::device_fingerprint`]); on another device it is dropped with a note.

use serde::Serialize;
use serde_json::Value;
use stiction_units::{Constraint, Dimension, format_quantity, nominal_from_json};

use crate::scenario::Scenario;
use crate::warning::Warning;

/// Relative tolerance between a given `meter.spring_force` without an `sd` and k x_c (1 %).
pub const SPRING_FORCE_RELATIVE_TOLERANCE: f64 = 0.01;

/// One quantity the meter uses, with its value, uncertainty and origin.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Quantity {
    /// Stable key: `front_gap_clamp`, `a_clamp`, `k_clamp` (and `_pull`), `contact_travel`,
    /// `spring_force`, `compliance`, `shear_strength`, ... (the material or surface field name).
    pub key: String,
    /// Name, with the scenario field where it is given (`a_clamp (actuators.clamp.conversion_factor)`).
    pub name: String,
    /// Value in SI.
    pub value: f64,
    /// SI unit of `value` and `uncertainty`.
    pub unit: String,
    /// Standard uncertainty as given (`sd` of an uncertain parameter), SI; None: none given.
    pub uncertainty: Option<f64>,
    /// Why `uncertainty` is null: the scenario gives no `sd` for this quantity.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uncertainty_note: Option<&'static str>,
    /// `given`, `calibrated`, `derived` or `default`, with the fields it comes from.
    pub origin: String,
    /// A disagreement or a re-derivation the user must know about.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flag: Option<String>,
    #[serde(skip)]
    dim: Option<Dimension>,
}

impl Quantity {
    /// The value with an SI prefix, 4 significant digits (`3.712 um`).
    pub fn value_text(&self) -> String {
        self.text(self.value)
    }

    /// The uncertainty the same way, or `-`.
    pub fn uncertainty_text(&self) -> String {
        self.uncertainty.map_or_else(|| "-".to_string(), |u| self.text(u))
    }

    fn text(&self, v: f64) -> String {
        match self.dim {
            Some(d) => format_quantity(v, d),
            None => format!("{} {}", sig4(v), self.unit),
        }
    }
}

/// `v` with 4 significant digits: fixed between 1e-3 and 1e6 (`7.8`, `0.1`), else scientific
/// (`1.400e-8`).
pub fn sig4(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-3..6).contains(&mag) {
        return format!("{v:.3e}");
    }
    let s = format!("{v:.*}", (3 - mag).max(0) as usize);
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

/// What `stiction scenario FILE --explain` prints: every quantity the meter uses and the notes.
#[derive(Debug, Clone, Serialize)]
pub struct Explanation {
    /// The device fingerprint ([`Scenario::device_fingerprint`]).
    pub device: String,
    /// The quantities.
    pub quantities: Vec<Quantity>,
    /// Re-derived calibrations, disagreements, dropped references.
    pub warnings: Vec<Warning>,
}

/// `v` with every number written with 12 significant digits, so that one quantity written two ways
/// ("100 um" is 1.0000000000000002e-4 m after parsing, 1e-4 is not) hashes the same.
fn rounded(v: Value) -> Value {
    match v {
        Value::Number(n) => match n.as_f64() {
            Some(x) if n.is_f64() => Value::String(format!("{x:.11e}")),
            _ => Value::Number(n),
        },
        Value::Array(a) => Value::Array(a.into_iter().map(rounded).collect()),
        Value::Object(o) => Value::Object(o.into_iter().map(|(k, v)| (k, rounded(v))).collect()),
        other => other,
    }
}

/// 64-bit FNV-1a of `bytes`.
fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

impl Scenario {
    /// The device fingerprint `"fnv1a64:<16 hex digits>"`: a hash of what the lab built and
    /// calibrated, parsed to SI (so `"100 um"` and `1e-4` give the same): every actuator array
    /// without its `description` (plates, gaps, conversion factors and the geometry they were
    /// calibrated on, springs, stops), `meter.spring_force`, the contact travel, and the shoe's
    /// apparent size. The surface statistics, the material and the contact model are not part of
    /// it: they are the model of the contact that a reference measurement is there to test. A
    /// Monte Carlo sample of a calibration is another device.
    pub fn device_fingerprint(&self) -> String {
        let mut arrays = serde_json::Map::new();
        for (name, spec) in &self.actuators {
            let mut v = serde_json::to_value(spec).unwrap_or(Value::Null);
            if let Some(o) = v.as_object_mut() {
                o.remove("description");
            }
            arrays.insert(name.clone(), v);
        }
        let mut device = serde_json::json!({
            "actuators": arrays,
            "spring_force": self.meter.as_ref().and_then(|m| m.spring_force),
            "contact_travel": self.contact_travel_m(),
            "apparent_length": self.surface.as_ref().map(|s| s.apparent_length),
            "apparent_width": self.surface.as_ref().map(|s| s.apparent_width),
        });
        // A structure built from parts: its parts (not the voltages or the protocol run on them).
        if let Some(st) = &self.structure
            && let Some(o) = device.as_object_mut()
        {
            let mut parts = serde_json::json!({
                "normal": st.normal, "tangential": st.tangential, "geometry": st.geometry
            });
            for part in ["normal", "tangential"] {
                if let Some(p) = parts.get_mut(part).and_then(|v| v.as_object_mut()) {
                    p.remove("description");
                    if let Some(c) = p.get_mut("comb").and_then(|v| v.as_object_mut()) {
                        c.remove("description");
                    }
                }
            }
            o.insert("structure".into(), parts);
        }
        format!("fnv1a64:{:016x}", fnv1a64(rounded(device).to_string().as_bytes()))
    }

    /// The travel x_c at which the shoe meets the wall: `meter.contact_travel`, else the clamp
    /// array's `operating_travel`, m.
    pub fn contact_travel_m(&self) -> Option<f64> {
        let clamp = self.actuators.get("clamp")?;
        Some(self.meter.as_ref().and_then(|m| m.contact_travel).unwrap_or(clamp.operating_travel))
    }

    /// The `sd` given for the field at `path` (an uncertain-parameter object in the scenario
    /// as read, after `--set`), SI.
    pub fn given_sd(&self, path: &[&str], dim: Dimension) -> Option<f64> {
        let mut node = &self.source_json;
        for seg in path {
            node = node.get(seg)?;
        }
        nominal_from_json(node.get("sd")?, dim, Constraint::NonNegative).ok()
    }

    /// F_spring = k x_c of the clamp spring (suspension plus parallel stiffness) at the contact
    /// travel, N; None without a meter or clamp array, or when the clamp cannot be built.
    pub fn derived_spring_force_n(&self) -> Option<f64> {
        let clamp = self.actuators.get("clamp")?.to_model().ok()?;
        Some(clamp.suspension.force_n(self.contact_travel_m()?))
    }

    /// When `meter.spring_force` is given and disagrees with k x_c by more than its uncertainty
    /// (its `sd`, or [`SPRING_FORCE_RELATIVE_TOLERANCE`] of it without one): the message naming
    /// both fields and the two ways out. The meter refuses to run such a scenario: one of the two
    /// statements is wrong and the program cannot tell which.
    pub fn spring_force_conflict(&self) -> Option<String> {
        let given = self.meter.as_ref()?.spring_force?;
        let derived = self.derived_spring_force_n()?;
        let sd = self.given_sd(&["meter", "spring_force"], Dimension::Force);
        let tolerance = sd.unwrap_or(SPRING_FORCE_RELATIVE_TOLERANCE * given.abs());
        let diff = (given - derived).abs();
        if diff <= tolerance {
            return None;
        }
        let f = |v: f64| format_quantity(v, Dimension::Force);
        let clamp = &self.actuators["clamp"];
        let k = clamp.suspension().map(|s| s.stiffness_n_per_m()).unwrap_or(f64::NAN);
        let x_c = self.contact_travel_m().unwrap_or(f64::NAN);
        let tol_text = match sd {
            Some(s) => format!("its uncertainty (sd {})", f(s)),
            None => format!("1 % (no `sd` given), {}", f(tolerance)),
        };
        Some(format!(
            "`meter.spring_force` = {} disagrees with the clamp spring `actuators.clamp.spring` times the contact \
             travel (`meter.contact_travel`): k x_c = {} N/m x {} = {}, by {}, more than {tol_text}; the meter \
             would use one and silently contradict the other. Resolve: remove `meter.spring_force` (F_spring is \
             then k x_c = {}; with --set: --set meter.spring_force=null), or restate it as the spring force \
             measured on this device, with its `sd`",
            f(given),
            sig4(k),
            format_quantity(x_c, Dimension::Length),
            f(derived),
            f(diff),
            f(derived),
        ))
    }

    /// The quantities of a structure built from parts: the normal part's factor at contact and
    /// suspension force, its side pull-in (comb), the tangential comb's factor or the released
    /// spring's stiffness.
    fn explain_structure(
        &self,
        st: &crate::structure::StructureSpec,
        q: &mut Vec<Quantity>,
        warnings: &mut Vec<Warning>,
    ) {
        use crate::structure::{NormalActuatorSpec, TangentialActuatorSpec};
        let mut push = |key: &str, name: String, value: f64, unit: &str, uncertainty: Option<f64>, origin: String| {
            let uncertainty_note = uncertainty.is_none().then_some(
                "no `sd` given, or a quantity derived from the parts (a Monte Carlo study samples the parts' own sd)",
            );
            q.push(Quantity {
                key: key.into(),
                name,
                value,
                unit: unit.into(),
                uncertainty,
                uncertainty_note,
                origin,
                flag: None,
                dim: None,
            });
        };
        let eps0 = stiction_actuator::VACUUM_PERMITTIVITY;
        match &st.normal {
            NormalActuatorSpec::LateralComb(c) => match c.comb.to_model() {
                Ok(m) => {
                    push(
                        "a_normal",
                        "a_normal = alpha N eps0 t / g (structure.normal.comb)".into(),
                        m.conversion_factor_n_per_v2(),
                        "N/V^2",
                        None,
                        "derived from structure.normal.comb (finger_count, thickness, gap, fringing_factor)".into(),
                    );
                    push(
                        "spring_force",
                        "F_0 = k_x x_c (structure.normal)".into(),
                        m.axial_stiffness_n_per_m * c.contact_travel,
                        "N",
                        None,
                        "derived from structure.normal.comb.stiffness times structure.normal.contact_travel".into(),
                    );
                    if let Some(v) = m.side_pull_in_voltage_at_v(c.contact_travel) {
                        push(
                            "side_pull_in_normal",
                            "side pull-in voltage of the normal comb at the wall".into(),
                            v,
                            "V",
                            None,
                            "derived: sqrt(k_y g^3 / (2 N eps0 t (x0 + x_c))) (Legtenberg et al. 1996)".into(),
                        );
                    }
                }
                Err(e) => warnings.push(Warning::new("actuator_invalid", format!("structure.normal: {e}"))),
            },
            NormalActuatorSpec::PlateElectrode(p) => match p.to_model() {
                Ok(m) => {
                    push(
                        "a_normal",
                        "a_normal = eps0 A / (2 (g_c + sum t_i/eps_r,i)^2) (structure.normal)".into(),
                        m.conversion_factor_at_contact_n_per_v2(),
                        "N/V^2",
                        None,
                        format!(
                            "derived from structure.normal (electrode_area, air_gap_at_contact, {} dielectric \
                             layer(s): {} m of air equivalent); eps0 = {eps0:e} F/m",
                            m.dielectric.len(),
                            sig4(m.dielectric_equivalent_gap_m())
                        ),
                    );
                    push(
                        "spring_force",
                        "F_0 = k_z g0 (structure.normal)".into(),
                        m.spring_force_at_contact_n(),
                        "N",
                        None,
                        "derived from structure.normal.stiffness times travel_to_contact".into(),
                    );
                    push(
                        "contact_voltage_normal",
                        "voltage that brings the plate down from rest".into(),
                        m.contact_voltage_v(),
                        "V",
                        None,
                        "derived: pull-in sqrt(8 k_z G^3 / (27 eps0 A)) when G/3 lies before contact, else the \
                         stable branch at contact"
                            .into(),
                    );
                }
                Err(e) => warnings.push(Warning::new("actuator_invalid", format!("structure.normal: {e}"))),
            },
        }
        match &st.tangential {
            TangentialActuatorSpec::LateralComb(c) => match c.to_model() {
                Ok(m) => push(
                    "a_tangential",
                    "a_tangential = alpha N eps0 t / g (structure.tangential)".into(),
                    m.conversion_factor_n_per_v2(),
                    "N/V^2",
                    None,
                    "derived from structure.tangential (finger_count, thickness, gap, fringing_factor); the same \
                     at every travel"
                        .into(),
                ),
                Err(e) => warnings.push(Warning::new("actuator_invalid", format!("structure.tangential: {e}"))),
            },
            TangentialActuatorSpec::ReleasedSpring(sp) => match sp.to_model() {
                Ok(m) => push(
                    "k_tangential",
                    "released spring stiffness k (structure.tangential)".into(),
                    m.stiffness_n_per_m,
                    "N/m",
                    self.given_sd(&["structure", "tangential", "stiffness"], Dimension::Stiffness),
                    if sp.stiffness.is_some() {
                        "given: structure.tangential.stiffness".into()
                    } else {
                        "derived from structure.tangential.resonance: k = m (2 pi f)^2".into()
                    },
                ),
                Err(e) => warnings.push(Warning::new("actuator_invalid", format!("structure.tangential: {e}"))),
            },
        }
    }

    /// Every quantity the meter uses, its value, uncertainty and origin, and the warnings
    /// (re-derived calibrations, disagreements, a dropped reference).
    pub fn explain(&self) -> Explanation {
        let mut q = Vec::new();
        let mut warnings = self.notes.clone();
        let push = |q: &mut Vec<Quantity>,
                    key: String,
                    name: String,
                    value: f64,
                    dim: Option<Dimension>,
                    unit: &str,
                    uncertainty: Option<f64>,
                    origin: String,
                    flag: Option<String>| {
            let uncertainty_note = uncertainty.is_none().then_some("no `sd` given: the quantity is taken as exact");
            q.push(Quantity { key, name, value, unit: unit.into(), uncertainty, uncertainty_note, origin, flag, dim });
        };
        if let Some(st) = &self.structure {
            self.explain_structure(st, &mut q, &mut warnings);
        }
        for name in ["clamp", "pull"] {
            let Some(spec) = self.actuators.get(name) else { continue };
            let model = match spec.to_model() {
                Ok(m) => m,
                Err(e) => {
                    warnings.push(Warning::new("actuator_invalid", format!("actuators.{name}: {e}")));
                    continue;
                }
            };
            let field = format!("actuators.{name}");
            let rederived = spec.calibration_rederived();
            let gap_origin = match (spec.front_gap, spec.conversion_factor) {
                (Some(_), _) => format!("given: {field}.front_gap (drawn) + 2 x undercut"),
                _ => format!(
                    "derived from {field}.conversion_factor on {} plates x overlap x thickness (inferred, as built)",
                    spec.calibrated_on.map_or(spec.plate_count, |c| c.plate_count)
                ),
            };
            let gap_sd = self.given_sd(&["actuators", name, "front_gap"], Dimension::Length);
            push(
                &mut q,
                format!("front_gap_{name}"),
                format!("front gap g_{name} ({field}, as built)"),
                model.plates.front_gap_m,
                Some(Dimension::Length),
                "m",
                gap_sd,
                gap_origin,
                None,
            );
            // The travel where the meter uses the conversion factor: the contact travel (clamp),
            // zero (pull: its gap is fixed while the shoe sticks).
            let travel = if name == "clamp" { self.contact_travel_m().unwrap_or(spec.operating_travel) } else { 0.0 };
            let a = model.conversion_factor_n_per_v2(travel);
            let sd = self.given_sd(&["actuators", name, "conversion_factor"], Dimension::ForcePerVoltageSquared);
            let (origin, a_sd) = match (spec.conversion_factor, &rederived) {
                (Some(given), None) => (
                    format!(
                        "calibrated: {field}.conversion_factor{} at operating_travel {}",
                        if spec.calibrated_on.is_some() {
                            " (measured on this geometry, calibrated_on)"
                        } else {
                            " (geometry it was measured on not stated: unchecked)"
                        },
                        format_quantity(spec.operating_travel, Dimension::Length)
                    ),
                    sd.map(|s| s * a / given),
                ),
                (Some(given), Some(_)) => (
                    format!(
                        "re-derived from {field}.conversion_factor (measured on {} plates) for {} plates, same \
                         as-built gap",
                        spec.calibrated_on.map_or(0, |c| c.plate_count),
                        spec.plate_count
                    ),
                    sd.map(|s| s * a / given),
                ),
                (None, _) => {
                    // The gap's sd propagated: half the change of a over g +/- sd.
                    let a_at = |dg: f64| {
                        let mut s2 = spec.clone();
                        s2.front_gap = spec.front_gap.map(|g| g + dg);
                        s2.to_model().ok().map(|m| m.conversion_factor_n_per_v2(travel))
                    };
                    let sd_a = gap_sd.and_then(|sd| Some(((a_at(-sd)? - a_at(sd)?) / 2.0).abs()));
                    (
                        format!(
                            "derived from {field} plate geometry and front_gap{}",
                            if sd_a.is_some() { " (sd propagated from front_gap's sd)" } else { "" }
                        ),
                        sd_a,
                    )
                }
            };
            push(
                &mut q,
                format!("a_{name}"),
                format!(
                    "a_{name} = F/V^2 at travel {} ({field})",
                    format_quantity(travel, Dimension::Length).replace("0 m", "0")
                ),
                a,
                None,
                "N/V^2",
                a_sd,
                origin,
                rederived.clone(),
            );
            if let Some(r) = rederived {
                warnings.push(Warning::new("calibration_rederived", format!("{field}: {r}")));
            }
            let k = model.suspension.stiffness_n_per_m();
            let k_origin = match (spec.spring.stiffness, &spec.spring.beams) {
                (Some(_), _) => format!("given: {field}.spring.stiffness"),
                _ => format!("derived from {field}.spring.beams"),
            };
            push(
                &mut q,
                format!("k_{name}"),
                format!("spring stiffness k_{name} ({field}.spring, total)"),
                k,
                None,
                "N/m",
                self.given_sd(&["actuators", name, "spring", "stiffness"], Dimension::Stiffness),
                k_origin,
                None,
            );
        }
        if let (Some(meter), Some(x_c)) = (&self.meter, self.contact_travel_m()) {
            push(
                &mut q,
                "contact_travel".into(),
                "contact travel x_c (meter.contact_travel)".into(),
                x_c,
                Some(Dimension::Length),
                "m",
                self.given_sd(&["meter", "contact_travel"], Dimension::Length),
                if meter.contact_travel.is_some() {
                    "given: meter.contact_travel".into()
                } else {
                    "default: actuators.clamp.operating_travel".into()
                },
                None,
            );
            let derived = self.derived_spring_force_n();
            let conflict = self.spring_force_conflict();
            match (meter.spring_force, derived) {
                (Some(given), _) => {
                    push(
                        &mut q,
                        "spring_force".into(),
                        "spring force F_spring (meter.spring_force)".into(),
                        given,
                        Some(Dimension::Force),
                        "N",
                        self.given_sd(&["meter", "spring_force"], Dimension::Force),
                        format!(
                            "calibrated: meter.spring_force (k x_c = {} from the clamp spring{})",
                            derived.map_or("-".into(), |d| format_quantity(d, Dimension::Force)),
                            if conflict.is_some() { ": DISAGREES" } else { ", agrees within its uncertainty" }
                        ),
                        conflict.clone(),
                    );
                    if let Some(c) = conflict {
                        warnings.push(Warning::new("spring_force_disagrees", c));
                    }
                }
                (None, Some(d)) => push(
                    &mut q,
                    "spring_force".into(),
                    "spring force F_spring (meter.spring_force)".into(),
                    d,
                    Some(Dimension::Force),
                    "N",
                    None,
                    "derived: actuators.clamp.spring x contact travel (k x_c)".into(),
                    None,
                ),
                (None, None) => {}
            }
        }
        if let Some(m) = &self.material {
            let p = |f: &str, dim| self.given_sd(&["material", f], dim);
            let d_origin = if m.compliance.is_some() {
                "given: material.compliance".to_string()
            } else {
                "derived: material.youngs_modulus, poisson_ratio (D = 1.5 (1 - nu^2) / E)".to_string()
            };
            push(
                &mut q,
                "compliance".into(),
                "compliance D (material.compliance)".into(),
                m.compliance_per_pa(),
                None,
                "1/Pa",
                p("compliance", Dimension::Compliance),
                d_origin,
                None,
            );
            for (name, field, value, dim, unit) in [
                ("shear strength s", "shear_strength", m.shear_strength, Some(Dimension::Pressure), "Pa"),
                ("work of adhesion", "work_of_adhesion", m.work_of_adhesion, None, "J/m^2"),
                ("hardness H", "hardness", m.hardness, Some(Dimension::Pressure), "Pa"),
                ("equilibrium spacing z0", "equilibrium_spacing", m.equilibrium_spacing, Some(Dimension::Length), "m"),
            ] {
                let sd_dim = dim.unwrap_or(Dimension::SurfaceEnergy);
                push(
                    &mut q,
                    field.to_string(),
                    format!("{name} (material.{field})"),
                    value,
                    dim,
                    unit,
                    p(field, sd_dim),
                    format!("given: material.{field}"),
                    None,
                );
            }
        }
        if let Some(s) = &self.surface {
            for (name, field, value) in [
                ("shoe length", "apparent_length", Some(s.apparent_length)),
                ("shoe width", "apparent_width", Some(s.apparent_width)),
                ("summit height sd", "summit_sd", s.summit_sd),
                ("summit radius", "summit_radius", s.summit_radius),
            ] {
                if let Some(v) = value {
                    push(
                        &mut q,
                        field.to_string(),
                        format!("{name} (surface.{field})"),
                        v,
                        Some(Dimension::Length),
                        "m",
                        self.given_sd(&["surface", field], Dimension::Length),
                        format!("given: surface.{field}"),
                        None,
                    );
                }
            }
            if let Some(eta) = s.summit_density {
                push(
                    &mut q,
                    "summit_density".into(),
                    "summit density (surface.summit_density)".into(),
                    eta,
                    None,
                    "1/m^2",
                    self.given_sd(&["surface", "summit_density"], Dimension::ArealDensity),
                    "given: surface.summit_density".into(),
                    None,
                );
            }
        }
        if let Some(env) = &self.environment {
            let given = |f: &str| self.source_json.pointer(&format!("/environment/{f}")).is_some();
            let origin = |f: &str, default: &str| {
                if given(f) { format!("given: environment.{f}") } else { format!("default: {default}") }
            };
            let water = env.is_water();
            let liquid = env.liquid_name().to_string();
            push(
                &mut q,
                "relative_humidity".into(),
                if water {
                    "relative humidity RH (environment.relative_humidity)".into()
                } else {
                    format!("relative vapour pressure p/p_sat of {liquid} (environment.relative_humidity)")
                },
                env.relative_humidity,
                None,
                "",
                self.given_sd(&["environment", "relative_humidity"], Dimension::Dimensionless),
                "given: environment.relative_humidity".into(),
                None,
            );
            push(
                &mut q,
                "temperature".into(),
                "temperature T (environment.temperature)".into(),
                env.temperature,
                None,
                "K",
                None,
                origin("temperature", "25 C"),
                None,
            );
            if !water {
                let l = env.liquid_properties();
                let named = !matches!(env.liquid, Some(crate::spec::LiquidSpec::Given(_)));
                let origin = |what: &str| {
                    if named {
                        format!("derived: {liquid} at T, {what} (stiction_contact::capillary, sources there)")
                    } else {
                        format!("given: environment.liquid ({liquid})")
                    }
                };
                push(
                    &mut q,
                    "surface_tension".into(),
                    format!("surface tension gamma of {liquid}"),
                    l.surface_tension_n_per_m,
                    // A tension, so printed in N/m, not as an energy per area (same number).
                    None,
                    "N/m",
                    None,
                    origin("handbook surface tension"),
                    None,
                );
                push(
                    &mut q,
                    "molar_volume".into(),
                    format!("molar volume V_m of {liquid}"),
                    l.molar_volume_m3_per_mol,
                    Some(Dimension::MolarVolume),
                    "m^3/mol",
                    None,
                    origin("molar mass over handbook density"),
                    None,
                );
                if let Some(p_sat) = env.saturation_pressure_pa() {
                    push(
                        &mut q,
                        "saturation_pressure".into(),
                        format!("saturation vapour pressure p_sat of {liquid}"),
                        p_sat,
                        Some(Dimension::Pressure),
                        "Pa",
                        None,
                        origin("saturation pressure"),
                        None,
                    );
                    push(
                        &mut q,
                        "partial_pressure".into(),
                        format!("partial pressure p of {liquid} vapour"),
                        p_sat * env.relative_humidity,
                        Some(Dimension::Pressure),
                        "Pa",
                        None,
                        "derived: p = (p/p_sat) p_sat".into(),
                        None,
                    );
                }
            }
            let (a1, a2) = self.contact_angles_rad();
            let on_liquid = matches!(&env.liquid, Some(crate::spec::LiquidSpec::Given(g)) if g.contact_angle.is_some());
            let angle_word = if water { "water".to_string() } else { liquid.clone() };
            for (key, name, field, v) in [
                ("contact_angle", format!("{angle_word} contact angle of the sidewall"), "contact_angle", a1),
                (
                    "counter_face_contact_angle",
                    format!("{angle_word} contact angle of the shoe"),
                    "counter_face_contact_angle",
                    a2,
                ),
            ] {
                let section = if on_liquid { "environment/liquid" } else { "material" };
                let given = self.source_json.pointer(&format!("/{section}/{field}")).is_some();
                let dotted = section.replace('/', ".");
                push(
                    &mut q,
                    key.into(),
                    format!("{name} ({dotted}.{field})"),
                    v,
                    Some(Dimension::Angle),
                    "rad",
                    if on_liquid { None } else { self.given_sd(&["material", field], Dimension::Angle) },
                    if given {
                        format!("given: {dotted}.{field}")
                    } else if field == "contact_angle" {
                        "default: 0 deg (a clean, fully wetting oxide)".into()
                    } else {
                        "default: material.contact_angle".into()
                    },
                    None,
                );
            }
            if let Some(m) = env.min_kelvin_radius {
                push(
                    &mut q,
                    "min_kelvin_radius".into(),
                    "smallest Kelvin radius (environment.min_kelvin_radius)".into(),
                    m,
                    Some(Dimension::Length),
                    "m",
                    None,
                    "given: environment.min_kelvin_radius".into(),
                    None,
                );
            }
            if let Ok(Some(cap)) = self.capillarity_before_cut_off() {
                push(
                    &mut q,
                    "kelvin_radius".into(),
                    "Kelvin radius r_K".into(),
                    cap.kelvin_radius_m,
                    Some(Dimension::Length),
                    "m",
                    None,
                    if water {
                        "derived: r_K = gamma V_m / (R T ln(1/RH)), water at T (IAPWS)".into()
                    } else {
                        format!("derived: r_K = gamma V_m / (R T ln(p_sat/p)), {liquid} at T")
                    },
                    None,
                );
                push(
                    &mut q,
                    "meniscus_height".into(),
                    "meniscus height h_m".into(),
                    cap.meniscus_height_m(),
                    Some(Dimension::Length),
                    "m",
                    None,
                    "derived: h_m = r_K (cos theta_1 + cos theta_2)".into(),
                    None,
                );
            }
        }
        Explanation { device: self.device_fingerprint(), quantities: q, warnings }
    }

    /// The relative standard uncertainty that the conversion factors' `sd`s give mu_e,a as the
    /// lab reduces it: the eq. 10 slope is (a_pull dV_pull^2) / (a_clamp dV_clamp^2), so
    /// u(mu)/mu = sqrt((u(a_pull)/a_pull)^2 + (u(a_clamp)/a_clamp)^2) (F_spring shifts the loads,
    /// not the slope). None when neither has an uncertainty.
    pub fn mu_calibration_relative_sd(&self) -> Option<f64> {
        let e = self.explain();
        let rel =
            |key: &str| e.quantities.iter().find(|q| q.key == key).and_then(|q| q.uncertainty.map(|u| u / q.value));
        match (rel("a_clamp"), rel("a_pull")) {
            (None, None) => None,
            (c, p) => Some(c.unwrap_or(0.0).hypot(p.unwrap_or(0.0))),
        }
    }

    /// The scenario as it is run, in its own format and readable as input: every field the file
    /// (or `--set`) gave, as written (units and uncertain-parameter objects kept), and every
    /// default the parse filled in, in SI.
    pub fn to_input_json(&self) -> Value {
        let typed = serde_json::to_value(self).unwrap_or(Value::Null);
        without_nulls(overlay(typed, &self.source_json))
    }
}

/// `v` without its null object members: in a scenario a null field is an absent one (`--set
/// PATH=null` removes it), so the printed form leaves it out.
fn without_nulls(v: Value) -> Value {
    match v {
        Value::Object(o) => {
            Value::Object(o.into_iter().filter(|(_, x)| !x.is_null()).map(|(k, x)| (k, without_nulls(x))).collect())
        }
        Value::Array(a) => Value::Array(a.into_iter().map(without_nulls).collect()),
        other => other,
    }
}

/// `typed` with every field that `raw` gives replaced by `raw`'s (recursively into objects that
/// are not uncertain parameters).
fn overlay(typed: Value, raw: &Value) -> Value {
    match (typed, raw) {
        (Value::Object(mut t), Value::Object(r)) if !r.contains_key("value") => {
            for (k, rv) in r {
                let v = match t.remove(k) {
                    Some(tv) if !tv.is_null() => overlay(tv, rv),
                    _ => rv.clone(),
                };
                t.insert(k.clone(), v);
            }
            Value::Object(t)
        }
        (_, raw) => raw.clone(),
    }
}
