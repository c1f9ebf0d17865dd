//! The friction test structures built from parts (scenario section `structure`,
//! docs/experiment.md "Other test structures"): the normal part presses the contact
//! (`L = a_n V_n^2 - F_0`), the tangential part loads it (`a_t V_t^2` from a comb, `k x` from a
//! released spring), and one of three protocols finds the slip:
//!
//! * ramp: at each normal voltage the tangential comb's voltage rises in steps until
//!   `a_t V_t^2 >= F_cap(L)`;
//! * release: at each normal voltage the spring is set to `x_n = n dx` and released; the largest
//!   `x_n` with `k x_n < F_cap(L)` sticks, and `k x_stick` is the reported friction (the next step
//!   slips, so the threshold lies in `[k x_stick, k (x_stick + dx))`);
//! * lower-normal: at each tangential voltage the normal voltage is lowered through the scenario's
//!   normal voltages (highest first, the contact kept) until `F_cap(L) <= a_t V_t^2`.
//!
//! Every protocol writes the points of `run` (normal voltage in `v_clamp_v`, tangential voltage in
//! `v_pull_v`, friction and load as the lab reduces them) with a reason where a point has no slip,
//! and the eq. 10 fit over them; [`LabCoefficient`] adds the number the laboratory reports.

use serde::Serialize;
use stiction_actuator::{LateralComb, PlateElectrode, ReleasedSpring};
use stiction_scenario::structure::{
    GeometrySpec, LabReductionSpec, NormalActuatorSpec, ProtocolSpec, StructureSpec, TangentialActuatorSpec,
};
use stiction_scenario::{MaterialSpec, SlipCriterion};

use crate::contact_model::{ContactModel, ContactState};
use crate::error::MeterError;
use crate::{MeterPoint, MeterResult, Reduction, fit, invariants};

/// What presses the contact.
#[derive(Debug, Clone)]
pub enum NormalPart {
    /// A lateral comb pushing a shoe across `contact_travel_m` to a sidewall.
    Comb {
        /// The comb.
        comb: LateralComb,
        /// Its travel from rest to the wall, m.
        contact_travel_m: f64,
    },
    /// A plate electrode under the plate or pad.
    Plate(PlateElectrode),
}

impl NormalPart {
    /// From the scenario's part.
    pub fn from_spec(spec: &NormalActuatorSpec) -> Result<NormalPart, MeterError> {
        let err = |e: stiction_actuator::ActuatorError| MeterError::Actuator {
            array: "structure.normal".into(),
            message: e.to_string(),
        };
        Ok(match spec {
            NormalActuatorSpec::LateralComb(c) => {
                NormalPart::Comb { comb: c.comb.to_model().map_err(err)?, contact_travel_m: c.contact_travel }
            }
            NormalActuatorSpec::PlateElectrode(p) => NormalPart::Plate(p.to_model().map_err(err)?),
        })
    }

    /// Conversion factor at contact `a_n`, N/V^2.
    pub fn conversion_factor_n_per_v2(&self) -> f64 {
        match self {
            NormalPart::Comb { comb, .. } => comb.conversion_factor_n_per_v2(),
            NormalPart::Plate(p) => p.conversion_factor_at_contact_n_per_v2(),
        }
    }

    /// The suspension's force at contact `F_0` (`k_x x_c` or `k_z g0`), N.
    pub fn spring_force_n(&self) -> f64 {
        match self {
            NormalPart::Comb { comb, contact_travel_m } => comb.axial_stiffness_n_per_m * contact_travel_m,
            NormalPart::Plate(p) => p.spring_force_at_contact_n(),
        }
    }

    /// The lowest voltage at which the structure touches, V: the comb's `sqrt(k_x x_c / a)`, the
    /// plate's pull-in or stable-branch contact voltage.
    pub fn contact_voltage_v(&self) -> f64 {
        match self {
            NormalPart::Comb { .. } => (self.spring_force_n() / self.conversion_factor_n_per_v2()).sqrt(),
            NormalPart::Plate(p) => p.contact_voltage_v(),
        }
    }

    /// The comb's side pull-in voltage held at the wall, V (None: a plate, or no lateral stiffness).
    pub fn side_pull_in_voltage_v(&self) -> Option<f64> {
        match self {
            NormalPart::Comb { comb, contact_travel_m } => comb.side_pull_in_voltage_at_v(*contact_travel_m),
            NormalPart::Plate(_) => None,
        }
    }
}

/// What loads the contact sideways.
#[derive(Debug, Clone, Copy)]
pub enum TangentialPart {
    /// A lateral comb, `a_t V^2`.
    Comb(LateralComb),
    /// A released spring, `k x`.
    Spring(ReleasedSpring),
}

/// The structure's parts and protocol, as the meter runs them.
#[derive(Clone)]
pub struct StructureDevice {
    /// The scenario's section.
    pub spec: StructureSpec,
    /// What presses.
    pub normal: NormalPart,
    /// What pulls.
    pub tangential: TangentialPart,
}

/// The structure's parts in a run's result.
#[derive(Debug, Clone, Serialize)]
pub struct StructureReport {
    /// Normal part: "lateral_comb" or "plate_electrode".
    pub normal: &'static str,
    /// Tangential part: "lateral_comb" or "released_spring".
    pub tangential: &'static str,
    /// Geometry: "sidewall_shoe", "pad" or "dimples".
    pub geometry: &'static str,
    /// Protocol: "ramp", "release" or "lower_normal".
    pub protocol: &'static str,
    /// Normal conversion factor at contact a_n, N/V^2.
    pub normal_conversion_factor_n_per_v2: f64,
    /// The normal suspension's force at contact F_0, N.
    pub normal_spring_force_n: f64,
    /// The normal voltage that first brings the structure into contact from rest (the plate's
    /// pull-in), V; once down it is held at lower voltages while `a_n V^2 > F_0`.
    pub contact_voltage_v: f64,
    /// The normal comb's side pull-in voltage at the wall, V (null with the reason beside it).
    pub side_pull_in_voltage_v: Option<f64>,
    /// Why there is no side pull-in voltage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub side_pull_in_voltage_v_reason: Option<&'static str>,
    /// The tangential comb's factor a_t, N/V^2 (null for a released spring, reason beside).
    pub tangential_conversion_factor_n_per_v2: Option<f64>,
    /// Why there is no tangential factor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential_conversion_factor_n_per_v2_reason: Option<&'static str>,
    /// The released spring's stiffness k, N/m (null for a comb, reason beside).
    pub tangential_stiffness_n_per_m: Option<f64>,
    /// Why there is no spring stiffness.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tangential_stiffness_n_per_m_reason: Option<&'static str>,
    /// The apparent contact area A_a (shoe or pad), m^2.
    pub apparent_area_m2: f64,
}

/// The coefficient the laboratory reports, by its own reduction, beside the adhesion-aware mu_e,a.
#[derive(Debug, Clone, Serialize)]
pub struct LabCoefficient {
    /// The reduction: "eq10", "friction_over_load" or "friction_over_total_load".
    pub kind: &'static str,
    /// The lab's friction coefficient (null with the reason beside it).
    pub coefficient: Option<f64>,
    /// Why there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficient_reason: Option<String>,
    /// Its standard deviation over the points (mean-of-ratios reductions), or the slope's
    /// standard error (eq. 10); null with the reason beside it.
    pub spread: Option<f64>,
    /// Why there is no spread.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spread_reason: Option<String>,
    /// The adhesion force the reduction uses or finds, N (eq. 10: F_a0; total load: the lab's F_a;
    /// friction over load: none, reason beside).
    pub adhesion_force_n: Option<f64>,
    /// Why there is no adhesion force.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adhesion_force_n_reason: Option<&'static str>,
    /// Points the reduction used.
    pub points: usize,
}

/// The lab's coefficient from the (load, friction) pairs the eq. 10 fit used.
///
/// * eq. 10: `mu_e,a` and `F_a0` of [`fit::eq10`];
/// * friction over load: the mean of `F_f / L` (and its sample standard deviation);
/// * friction over total load: the mean of `F_f / (L + F_a)`.
pub fn lab_coefficient(spec: &LabReductionSpec, pairs: &[(f64, f64)], eq10: &fit::Eq10Fit) -> LabCoefficient {
    let ratios = |extra: f64| -> Vec<f64> { pairs.iter().map(|(l, f)| f / (l + extra)).collect() };
    let mean_sd = |r: &[f64]| -> (Option<f64>, Option<f64>, Option<String>, Option<String>) {
        if r.is_empty() {
            let why = "no point with a load above zero and a slip".to_string();
            return (None, None, Some(why.clone()), Some(why));
        }
        let mean_ok = r.iter().sum::<f64>().is_finite() && r.iter().map(|x| x * x).sum::<f64>().is_finite();
        if r.iter().any(|x| !x.is_finite()) || !mean_ok {
            let why = "a ratio of friction to load, or their sum, is not a finite number (a load too close to zero)"
                .to_string();
            return (None, None, Some(why.clone()), Some(why));
        }
        let n = r.len() as f64;
        let mean = r.iter().sum::<f64>() / n;
        if r.len() < 2 {
            return (Some(mean), None, None, Some("one point: no spread".into()));
        }
        let var = r.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
        (Some(mean), Some(var.sqrt()), None, None)
    };
    match spec {
        LabReductionSpec::Eq10 => LabCoefficient {
            kind: "eq10",
            coefficient: eq10.mu_apparent,
            coefficient_reason: eq10.mu_apparent.is_none().then(|| eq10.note.clone().unwrap_or_default()),
            spread: eq10.line.map(|l| l.slope_se),
            spread_reason: eq10.line.is_none().then(|| "no eq. 10 line".to_string()),
            adhesion_force_n: eq10.apparent_adhesion_force_n,
            adhesion_force_n_reason: eq10.apparent_adhesion_force_n.is_none().then_some("no eq. 10 line"),
            points: eq10.line.map_or(0, |l| l.points),
        },
        LabReductionSpec::FrictionOverLoad => {
            let (c, s, cr, sr) = mean_sd(&ratios(0.0));
            LabCoefficient {
                kind: "friction_over_load",
                coefficient: c,
                coefficient_reason: cr,
                spread: s,
                spread_reason: sr,
                adhesion_force_n: None,
                adhesion_force_n_reason: Some("folded into the coefficient by this reduction"),
                points: pairs.len(),
            }
        }
        LabReductionSpec::FrictionOverTotalLoad { adhesion_force } => {
            let (c, s, cr, sr) = mean_sd(&ratios(*adhesion_force));
            LabCoefficient {
                kind: "friction_over_total_load",
                coefficient: c,
                coefficient_reason: cr,
                spread: s,
                spread_reason: sr,
                adhesion_force_n: Some(*adhesion_force),
                adhesion_force_n_reason: None,
                points: pairs.len(),
            }
        }
    }
}

/// The static friction capacity of a contact state by a slip criterion, N.
pub fn slip_threshold_n(material: &MaterialSpec, slip: SlipCriterion, state: &ContactState) -> f64 {
    let s = material.shear_strength;
    match slip {
        SlipCriterion::ShearArea => s * state.real_area_m2,
        SlipCriterion::Plastic => s / material.hardness * state.elastic_load_n(),
        SlipCriterion::PressureDependent { alpha } => s * state.real_area_m2 + alpha * state.elastic_load_n(),
    }
}

fn name_of_geometry(g: &GeometrySpec) -> &'static str {
    match g {
        GeometrySpec::SidewallShoe => "sidewall_shoe",
        GeometrySpec::Pad => "pad",
        GeometrySpec::Dimples { .. } => "dimples",
    }
}

impl StructureDevice {
    /// Builds the parts of a `structure` section.
    pub fn from_spec(spec: &StructureSpec) -> Result<StructureDevice, MeterError> {
        let normal = NormalPart::from_spec(&spec.normal)?;
        let err = |e: stiction_actuator::ActuatorError| MeterError::Actuator {
            array: "structure.tangential".into(),
            message: e.to_string(),
        };
        let tangential = match &spec.tangential {
            TangentialActuatorSpec::LateralComb(c) => TangentialPart::Comb(c.to_model().map_err(err)?),
            TangentialActuatorSpec::ReleasedSpring(s) => TangentialPart::Spring(s.to_model().map_err(err)?),
        };
        Ok(StructureDevice { spec: spec.clone(), normal, tangential })
    }

    /// The conversion the lab uses: `a_clamp` the normal factor, `a_pull` the tangential comb's
    /// (0 for a released spring, whose load `k x` takes no voltage; the stiffness is in the
    /// [`StructureReport`]), `spring_force` the normal suspension's force at contact.
    pub fn reduction(&self) -> Reduction {
        Reduction {
            a_clamp_n_per_v2: self.normal.conversion_factor_n_per_v2(),
            a_pull_n_per_v2: match self.tangential {
                TangentialPart::Comb(c) => c.conversion_factor_n_per_v2(),
                TangentialPart::Spring(_) => 0.0,
            },
            spring_force_n: self.normal.spring_force_n(),
        }
    }

    /// The report of the parts.
    pub fn report(&self, apparent_area_m2: f64) -> StructureReport {
        let side = self.normal.side_pull_in_voltage_v();
        let side_reason = side.is_none().then_some(match self.normal {
            NormalPart::Plate(_) => "a plate electrode has no lateral fingers",
            NormalPart::Comb { .. } => "no lateral_stiffness given for the normal comb",
        });
        let (a_t, k) = match self.tangential {
            TangentialPart::Comb(c) => (Some(c.conversion_factor_n_per_v2()), None),
            TangentialPart::Spring(s) => (None, Some(s.stiffness_n_per_m)),
        };
        StructureReport {
            normal: match self.normal {
                NormalPart::Comb { .. } => "lateral_comb",
                NormalPart::Plate(_) => "plate_electrode",
            },
            tangential: match self.tangential {
                TangentialPart::Comb(_) => "lateral_comb",
                TangentialPart::Spring(_) => "released_spring",
            },
            geometry: name_of_geometry(&self.spec.geometry),
            protocol: match self.spec.protocol {
                ProtocolSpec::Ramp { .. } => "ramp",
                ProtocolSpec::Release { .. } => "release",
                ProtocolSpec::LowerNormal { .. } => "lower_normal",
            },
            normal_conversion_factor_n_per_v2: self.normal.conversion_factor_n_per_v2(),
            normal_spring_force_n: self.normal.spring_force_n(),
            contact_voltage_v: self.normal.contact_voltage_v(),
            side_pull_in_voltage_v: side,
            side_pull_in_voltage_v_reason: side_reason,
            tangential_conversion_factor_n_per_v2: a_t,
            tangential_conversion_factor_n_per_v2_reason: a_t.is_none().then_some("a released spring takes no voltage"),
            tangential_stiffness_n_per_m: k,
            tangential_stiffness_n_per_m_reason: k.is_none().then_some("the tangential part is a comb"),
            apparent_area_m2,
        }
    }
}

/// Everything a structure run needs besides the parts.
pub struct StructureRun<'a> {
    /// The parts and protocol.
    pub device: &'a StructureDevice,
    /// The contact.
    pub contact: &'a mut ContactModel,
    /// The material (shear strength, hardness).
    pub material: &'a MaterialSpec,
    /// The apparent area, m^2.
    pub apparent_area_m2: f64,
    /// Whether the air is humid (points then carry the capillary load).
    pub humid: bool,
}

/// A point at normal voltage `v_normal` (V) and load `load_n` (N) before any friction is read: no
/// pull voltage, no friction, no contact state (the capillary load 0 where the air is humid), no
/// reason. The paper's meter and every structure protocol start their points from it.
pub(crate) fn empty_point(v_normal: f64, load_n: f64, in_contact: bool, humid: bool) -> MeterPoint {
    MeterPoint {
        v_clamp: v_normal,
        v_clamp_sq: v_normal * v_normal,
        in_contact,
        load_n,
        true_load_n: load_n,
        v_pull: None,
        v_pull_sq: None,
        friction_n: None,
        true_friction_n: None,
        friction_capacity_n: 0.0,
        pull_in_at_slip: None,
        slip_time_to_stop_s: None,
        slip_impact_velocity_m_per_s: None,
        slip_note: None,
        displacement_m: None,
        real_area_m2: 0.0,
        contacts: 0.0,
        adhesive_load_n: 0.0,
        capillary_load_n: humid.then_some(0.0),
        tilt_x_rad: 0.0,
        tilt_y_rad: 0.0,
        max_pressure_pa: 0.0,
        over_elastic_limit: false,
        plastic_area_m2: None,
        plastic_note: None,
        error: None,
        reason: None,
    }
}

impl StructureRun<'_> {
    fn fill_state(&self, point: &mut MeterPoint, state: &ContactState, capacity: f64) {
        point.friction_capacity_n = capacity;
        point.real_area_m2 = state.real_area_m2;
        point.contacts = state.contacts;
        point.adhesive_load_n = state.adhesive_load_n;
        if self.humid {
            point.capillary_load_n = Some(state.capillary_load_n);
        }
        point.tilt_x_rad = state.tilt_x_rad;
        point.tilt_y_rad = state.tilt_y_rad;
        crate::fill_pressure(point, state, self.material.hardness);
    }

    /// The contact at a normal voltage: the load, or the reason there is none.
    fn load_at(&self, v: f64) -> Result<f64, String> {
        let n = &self.device.normal;
        let load = n.conversion_factor_n_per_v2() * v * v - n.spring_force_n();
        // The structure is brought into contact once (a plate pulls in at its contact voltage) and
        // then held at each normal voltage: it stays down while the electrostatic force exceeds
        // the suspension's force at contact.
        if load <= 0.0 {
            return Err(format!(
                "no load: the normal force {:.4} uN does not exceed the suspension's {:.4} uN at contact, so the \
                 structure leaves the contact",
                (load + n.spring_force_n()) * 1e6,
                n.spring_force_n() * 1e6
            ));
        }
        if let Some(v_side) = n.side_pull_in_voltage_v()
            && v >= v_side
        {
            return Err(format!(
                "side pull-in: the normal comb is laterally unstable at and above {v_side:.3} V (its fingers snap \
                 sideways)"
            ));
        }
        Ok(load)
    }

    /// Runs the protocol over the normal voltages.
    pub fn run(
        &mut self,
        normal_voltages: &[f64],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<Vec<MeterPoint>, MeterError> {
        let slip = self.device.spec.slip;
        let mut points = Vec::new();
        match (&self.device.spec.protocol, self.device.tangential) {
            (ProtocolSpec::Ramp { voltage_step, voltage_max }, TangentialPart::Comb(comb)) => {
                let a_t = comb.conversion_factor_n_per_v2();
                for (k, &v) in normal_voltages.iter().enumerate() {
                    let mut point = self.point_at(v, slip, true)?;
                    if let Some(capacity) = point.as_ref().ok().map(|p| p.friction_capacity_n) {
                        let p = point.as_mut().map_err(|_| MeterError::Scenario("unreachable".into()))?;
                        let n_max = (voltage_max / voltage_step).floor();
                        let n = (capacity / a_t).sqrt() / voltage_step;
                        // The first step n with a_t (n dV)^2 >= capacity, checked on the force itself;
                        // the guess is kept within [1, n_max + 1] (n_max <= MAX_PROTOCOL_STEPS), so
                        // both corrections below end after a few steps.
                        let mut n = if n.is_finite() { n.ceil().clamp(1.0, n_max + 1.0) } else { n_max + 1.0 };
                        while n > 1.0 && a_t * ((n - 1.0) * voltage_step).powi(2) >= capacity {
                            n -= 1.0;
                        }
                        while n <= n_max && a_t * (n * voltage_step).powi(2) < capacity {
                            n += 1.0;
                        }
                        let side = comb.side_pull_in_voltage_at_v(0.0);
                        if n > n_max {
                            p.reason = Some(format!(
                                "no slip: the friction capacity {:.4} uN exceeds the tangential comb's {:.4} uN at \
                                 voltage_max = {voltage_max} V",
                                capacity * 1e6,
                                a_t * voltage_max * voltage_max * 1e6
                            ));
                        } else if let Some(v_side) = side.filter(|v| n * voltage_step >= *v) {
                            p.reason = Some(format!(
                                "no slip: the tangential comb pulls in sideways at {v_side:.3} V (its side \
                                 instability, held at zero travel) before its force reaches the friction capacity \
                                 {:.4} uN",
                                capacity * 1e6
                            ));
                        } else {
                            let vt = n * voltage_step;
                            p.v_pull = Some(vt);
                            p.v_pull_sq = Some(vt * vt);
                            p.friction_n = Some(a_t * vt * vt);
                            p.true_friction_n = p.friction_n;
                            let step_n = a_t * (vt * vt - (vt - voltage_step).powi(2));
                            invariants::check_reading(a_t * vt * vt, capacity, step_n, v)?;
                            if n <= 1.0 {
                                p.reason = Some(format!(
                                    "slip at the first tangential step ({voltage_step} V): the friction is only \
                                     bounded; left out of the eq. 10 fit"
                                ));
                            }
                        }
                    }
                    points.push(point.unwrap_or_else(|p| p));
                    progress(k + 1, normal_voltages.len());
                }
            }
            (ProtocolSpec::Release { displacement_step, displacement_max }, TangentialPart::Spring(spring)) => {
                let k_n_per_m = spring.stiffness_n_per_m;
                for (k, &v) in normal_voltages.iter().enumerate() {
                    let mut point = self.point_at(v, slip, true)?;
                    if let Ok(p) = point.as_mut() {
                        let capacity = p.friction_capacity_n;
                        let n_max = (displacement_max / displacement_step).floor();
                        // Sticks while k x_n < capacity: the largest such n (0: even the first slips).
                        let guess = (capacity / (k_n_per_m * displacement_step)).floor();
                        let mut n = if guess.is_finite() { guess.clamp(0.0, n_max + 1.0) } else { n_max + 1.0 };
                        while n > 0.0 && k_n_per_m * n * displacement_step >= capacity {
                            n -= 1.0;
                        }
                        while n < n_max + 1.0 && k_n_per_m * (n + 1.0) * displacement_step < capacity {
                            n += 1.0;
                        }
                        if n > n_max {
                            p.reason = Some(format!(
                                "no slip: every displacement up to displacement_max = {displacement_max} m sticks \
                                 (k x = {:.4} uN below the friction capacity {:.4} uN)",
                                k_n_per_m * displacement_max * 1e6,
                                capacity * 1e6
                            ));
                        } else if n < 1.0 {
                            p.reason = Some(format!(
                                "slips at the first displacement ({displacement_step} m): the friction is below {:.4} \
                                 uN, not measured; left out of the eq. 10 fit",
                                k_n_per_m * displacement_step * 1e6
                            ));
                        } else {
                            let x = n * displacement_step;
                            p.displacement_m = Some(x);
                            p.friction_n = Some(k_n_per_m * x);
                            p.true_friction_n = p.friction_n;
                            invariants::check_reading(k_n_per_m * x, capacity, k_n_per_m * displacement_step, v)?;
                        }
                    }
                    points.push(point.unwrap_or_else(|p| p));
                    progress(k + 1, normal_voltages.len());
                }
            }
            (ProtocolSpec::LowerNormal { tangential_voltages }, TangentialPart::Comb(comb)) => {
                let mut lowered: Vec<f64> = normal_voltages.to_vec();
                lowered.sort_by(|a, b| b.total_cmp(a));
                let tangential = tangential_voltages.voltages();
                for (k, &vt) in tangential.iter().enumerate() {
                    let force = comb.conversion_factor_n_per_v2() * vt * vt;
                    let mut found: Option<MeterPoint> = None;
                    let mut last_held: Option<MeterPoint> = None;
                    for (i, &v) in lowered.iter().enumerate() {
                        let point = self.point_at(v, slip, i == 0)?;
                        match point {
                            Ok(p) if p.friction_capacity_n > force => last_held = Some(p),
                            Ok(mut p) if i == 0 => {
                                p.reason = Some(format!(
                                    "slips at the highest normal voltage under the tangential voltage {vt} V: the \
                                     load at slip is only bounded; left out of the eq. 10 fit"
                                ));
                                found = Some(p);
                                break;
                            }
                            Ok(mut p) => {
                                p.v_pull = Some(vt);
                                p.v_pull_sq = Some(vt * vt);
                                p.friction_n = Some(force);
                                p.true_friction_n = Some(force);
                                found = Some(p);
                                break;
                            }
                            Err(mut p) => {
                                // Out of contact (or unloaded) while the tangential load is held:
                                // it slipped on the way, at a load not resolved.
                                p.reason = Some(format!(
                                    "{}; the tangential voltage {vt} V ({:.4} uN) slipped it on the way there, at a \
                                     load between this normal voltage and the one before",
                                    p.reason.unwrap_or_default(),
                                    force * 1e6
                                ));
                                found = Some(p);
                                break;
                            }
                        }
                    }
                    let point = match found {
                        Some(p) => p,
                        None => {
                            let mut p = last_held.unwrap_or_else(|| empty_point(0.0, 0.0, false, self.humid));
                            p.reason = Some(format!(
                                "no slip: the tangential voltage {vt} V ({:.4} uN) is held down to the lowest normal \
                                 voltage",
                                force * 1e6
                            ));
                            p
                        }
                    };
                    points.push(point);
                    progress(k + 1, tangential.len());
                }
            }
            _ => {
                return Err(MeterError::Scenario(
                    "structure.protocol: the protocol does not fit the tangential part (ramp and lower_normal need a \
                     comb, release a released spring)"
                        .into(),
                ));
            }
        }
        Ok(points)
    }

    /// The point at a normal voltage: Ok with the contact state and capacity filled, or Err with
    /// the reason there is no contact (a point to write all the same).
    fn point_at(
        &mut self,
        v: f64,
        slip: SlipCriterion,
        fresh: bool,
    ) -> Result<Result<MeterPoint, MeterPoint>, MeterError> {
        let load = match self.load_at(v) {
            Ok(l) => l,
            Err(reason) => {
                let n = &self.device.normal;
                let load = n.conversion_factor_n_per_v2() * v * v - n.spring_force_n();
                let mut p = empty_point(v, load, false, self.humid);
                p.reason = Some(reason);
                return Ok(Err(p));
            }
        };
        let mut point = empty_point(v, load, true, self.humid);
        let state = match self.contact.state_at_load(load, fresh) {
            Ok(s) => s,
            Err(e) => {
                point.error = Some(e.to_string());
                point.reason = Some(format!("no equilibrium: {e}"));
                return Ok(Err(point));
            }
        };
        invariants::check_state(&state, self.apparent_area_m2, self.contact.summit_count(), v)?;
        let capacity = slip_threshold_n(self.material, slip, &state);
        self.fill_state(&mut point, &state, capacity);
        Ok(Ok(point))
    }
}

/// Reduces the readings of `points` (the normal voltage, the tangential comb's voltage at slip or
/// the displacement that sticks) with the `lab`'s nominal parts, as the laboratory does: `load_n =
/// a_n V^2 - F_0` and `friction_n = a_t V_t^2` or `k x` with its parts, while `true_load_n` and
/// `true_friction_n` keep the forces the device's own parts applied.
pub fn reduce_as_the_lab(points: &mut [MeterPoint], lab: &StructureDevice) {
    let (a_n, f0) = (lab.normal.conversion_factor_n_per_v2(), lab.normal.spring_force_n());
    for p in points.iter_mut() {
        p.load_n = a_n * p.v_clamp * p.v_clamp - f0;
        if p.friction_n.is_none() {
            continue;
        }
        p.friction_n = match lab.tangential {
            TangentialPart::Comb(c) => p.v_pull.map(|v| c.conversion_factor_n_per_v2() * v * v),
            TangentialPart::Spring(s) => p.displacement_m.map(|x| s.stiffness_n_per_m * x),
        };
    }
}

/// The eq. 10 fit and the lab's coefficient over a structure's points.
pub fn reduce(points: &[MeterPoint], lab: &LabReductionSpec) -> (fit::Eq10Fit, LabCoefficient) {
    let pairs: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.load_n > 0.0 && p.reason.is_none())
        .filter_map(|p| p.friction_n.map(|f| (p.load_n, f)))
        .collect();
    let eq10 = fit::eq10(&pairs);
    let lab = lab_coefficient(lab, &pairs, &eq10);
    (eq10, lab)
}

/// The note on every slipped point of a structure: the motion after slip is not simulated.
pub const STRUCTURE_SLIP_NOTE: &str = "a structure built from parts: the motion after slip is not simulated (no \
                                       runaway test, time to a stop or impact speed)";

/// Assembles a [`MeterResult`] from a structure's points.
pub fn result(
    contact_model: String,
    points: Vec<MeterPoint>,
    device: &StructureDevice,
    apparent_area_m2: f64,
    environment: Option<crate::Humidity>,
) -> MeterResult {
    let (eq10, lab) = reduce(&points, &device.spec.lab_reduction);
    let mut points = points;
    for p in points.iter_mut().filter(|p| p.reason.is_none()) {
        p.slip_note = Some(STRUCTURE_SLIP_NOTE.into());
    }
    MeterResult {
        contact_model,
        points,
        mu_apparent: eq10.mu_apparent,
        apparent_adhesion_force_n: eq10.apparent_adhesion_force_n,
        fit: eq10.line,
        fit_note: eq10.note,
        spring_force_n: device.normal.spring_force_n(),
        pull_array_pull_in_v: None,
        reduction: device.reduction(),
        environment,
        warnings: Vec::new(),
        structure: Some(device.report(apparent_area_m2)),
        lab_coefficient: Some(lab),
        pull_array_note: Some("a structure built from parts has no gap-closing pull array".into()),
    }
}
