//! stiction-meter: the virtual MEMS friction meter of the paper's section 5.
//!
//! A clamp array presses the shoe against the rough sidewall with `L = F_elec - F_spring`; the
//! pull array's voltage then ramps in steps until its force exceeds the static friction (by default
//! `s A_r(L)`, eq. 1, with `A_r` from the contact model at the load). The meter records what the
//! lab records (the pull voltage at slip, for each clamp voltage: Fig. 5) and reduces it the way
//! the paper does: forces from the nominal conversion factors, `F_f = a_pull V_pull^2`,
//! `L = a_clamp V_clamp^2 - F_spring`, and a straight line `F_f = mu_e,a (F_a0 + L)` over `L > 0`
//! (eq. 10). Beside that it reports what the lab cannot see: real area, contacts, adhesive load,
//! tilt, peak pressure.

use std::path::Path;

use serde::Serialize;
use stiction_actuator::GapClosingActuator;
use stiction_actuator::meter::{SlipResponse, clamp_force, pull_force_stuck_n, slip_response};
use stiction_scenario::{ContactModel as ModelKind, MaterialSpec, MeterSpec, Scenario, ShoeMode};
use stiction_surface::SurfaceSpec;

mod contact_model;
mod error;
pub mod fit;
pub mod invariants;
pub mod measured;
pub mod slip;
pub mod structure;
pub mod structure_measured;
pub use contact_model::{BemContact, BemShoe, ContactModel, ContactState, Pose};
pub use error::MeterError;
pub use slip::SlipPath;
use stiction_contact::explicit;
use stiction_contact::gw::GwSurface;
use stiction_contact::single::AsperityParams;

/// How the lab turns voltages into forces (section 5): `F_elec = a_clamp V_clamp^2`,
/// `L = F_elec - F_spring`, `F_f = a_pull V_pull^2`, with the *nominal* conversion factors and
/// spring force. A virtual device may differ from its nominal values (a Monte Carlo sample); the
/// reduction then keeps the nominal ones, exactly as the lab does, and the difference shows up as
/// scatter in mu_e,a and F_a0.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reduction {
    /// Clamp conversion factor a_clamp, N/V^2.
    pub a_clamp_n_per_v2: f64,
    /// Pull conversion factor a_pull, N/V^2.
    pub a_pull_n_per_v2: f64,
    /// Spring force F_spring, N.
    pub spring_force_n: f64,
}

/// One clamp voltage of the experiment.
#[derive(Debug, Clone, Serialize)]
pub struct MeterPoint {
    /// Clamp voltage, V (JSON `v_clamp_v`).
    #[serde(rename = "v_clamp_v")]
    pub v_clamp: f64,
    /// Clamp voltage squared, V^2 (Fig. 5 abscissa; JSON `v_clamp_sq_v2`).
    #[serde(rename = "v_clamp_sq_v2")]
    pub v_clamp_sq: f64,
    /// Whether the shoe touches the wall at this clamp voltage.
    pub in_contact: bool,
    /// Clamp load as the lab reports it, a_clamp V_clamp^2 - F_spring with the nominal values
    /// ([`Reduction`]), N. Equal to `true_load_n` unless the device differs from its nominal values.
    pub load_n: f64,
    /// The load the device really applies, F_elec(x_c, V) - F_spring, N.
    pub true_load_n: f64,
    /// Pull voltage at slip, V (None: no slip up to the maximum pull voltage, or no contact;
    /// JSON `v_pull_v`).
    #[serde(rename = "v_pull_v")]
    pub v_pull: Option<f64>,
    /// Pull voltage squared at slip, V^2 (Fig. 5 ordinate; JSON `v_pull_sq_v2`).
    #[serde(rename = "v_pull_sq_v2")]
    pub v_pull_sq: Option<f64>,
    /// Friction as the lab reduces it: a_pull V_pull^2 at slip with the nominal a_pull, N.
    pub friction_n: Option<f64>,
    /// The pull force the device really applied at slip, N.
    pub true_friction_n: Option<f64>,
    /// The static friction capacity of the contact by the slip criterion, N.
    pub friction_capacity_n: f64,
    /// Whether the pull array ran away (pulled in) at once when the shoe slipped: from the
    /// shuttle dynamics when the scenario has `meter.slip_dynamics`, else quasi-static.
    pub pull_in_at_slip: Option<bool>,
    /// With slip dynamics: time from slip to the pull array's stop, s.
    pub slip_time_to_stop_s: Option<f64>,
    /// With slip dynamics: shuttle speed when it reaches the stop, m/s.
    pub slip_impact_velocity_m_per_s: Option<f64>,
    /// Why the slip dynamics give no time to the stop and no impact speed at a slip: the shuttle
    /// finds an equilibrium before its stop.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip_note: Option<String>,
    /// Release protocol (`structure`): the largest displacement of the released spring that
    /// sticks, m; the friction is reported as `k` times it. Absent for the other protocols.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub displacement_m: Option<f64>,
    /// Real contact area A_r, m^2.
    pub real_area_m2: f64,
    /// Summits in contact.
    pub contacts: f64,
    /// Adhesive load, N.
    pub adhesive_load_n: f64,
    /// Capillary part of the adhesive load (the water menisci), N: written when the scenario's
    /// `environment` has a relative humidity above 0 (0 where no meniscus forms, e.g. hydrophobic
    /// faces); absent when dry.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub capillary_load_n: Option<f64>,
    /// Shoe tilt along x, rad.
    pub tilt_x_rad: f64,
    /// Shoe tilt along y, rad.
    pub tilt_y_rad: f64,
    /// Largest peak Hertz pressure (eq. 11), Pa.
    pub max_pressure_pa: f64,
    /// Whether that pressure exceeds the hardness (plastic deformation would start), or, with the
    /// hardness cap (`contact.bem.plastic`), whether any point flows at the hardness.
    pub over_elastic_limit: bool,
    /// With the hardness cap (`contact.bem.plastic`): the part of the real area at the hardness
    /// (perfectly plastic pixels), m^2; absent for an elastic model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_area_m2: Option<f64>,
    /// With the hardness cap: what the plastic area means when points flow (absent when none
    /// does, or for an elastic model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_note: Option<String>,
    /// Why the contact model found no state at this load (e.g. the shoe tips over), if it did
    /// not; the point then has no slip and is left out of the fit, and the run goes on.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Why this point has no contact, no slip or no equilibrium (absent when it has all three):
    /// the clamp stops short of the wall below its contact voltage, the load does not exceed
    /// zero, the pull array cannot reach the friction, or the contact model's error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

/// The experiment's outcome.
#[derive(Debug, Clone, Serialize)]
pub struct MeterResult {
    /// The contact model used.
    pub contact_model: String,
    /// The points, one per clamp voltage.
    pub points: Vec<MeterPoint>,
    /// Apparent friction coefficient mu_e,a: slope of F_f against L over L > 0 (eq. 10).
    pub mu_apparent: Option<f64>,
    /// Apparent zero-load adhesion force F_a0 = F_f(L = 0) / mu_e,a, N (eq. 10).
    pub apparent_adhesion_force_n: Option<f64>,
    /// The straight-line fit behind the two numbers.
    pub fit: Option<fit::LineFit>,
    /// Why there is no mu_e,a (fewer than three distinct loads with slip, a flat line, a slope not
    /// above zero, slips at the first pull step), exactly when there is none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit_note: Option<String>,
    /// F_spring used, N.
    pub spring_force_n: f64,
    /// Pull-in voltage of the pull array with the shoe free, V.
    pub pull_array_pull_in_v: Option<f64>,
    /// The conversion used to report forces.
    pub reduction: Reduction,
    /// The air: relative humidity, temperature and the meniscus it gives; absent when dry (no
    /// `environment` or relative humidity 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub environment: Option<Humidity>,
    /// What the user must know about the fit (few points, part of the clamp range), with a
    /// stable `code` each.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<stiction_scenario::Warning>,
    /// The parts of a `structure` scenario (absent for the paper's meter).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub structure: Option<structure::StructureReport>,
    /// The coefficient by the laboratory's own reduction (`structure.lab_reduction` or
    /// `meter.lab_reduction`), beside mu_e,a; absent when the scenario states none for the
    /// paper's meter (its reduction is eq. 10 itself).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lab_coefficient: Option<structure::LabCoefficient>,
    /// Why there is no pull-array pull-in voltage (a `structure` has no pull array).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pull_array_note: Option<String>,
}

/// The pressure fields of a point from its contact state: the largest pressure, whether it
/// passes the hardness `hardness_pa` (Pa), and with the hardness cap the plastic area and a note
/// when points flow.
pub(crate) fn fill_pressure(point: &mut MeterPoint, state: &ContactState, hardness_pa: f64) {
    point.max_pressure_pa = state.max_pressure_pa;
    let plastic = state.plastic_area_m2.unwrap_or(0.0);
    point.over_elastic_limit = state.max_pressure_pa > hardness_pa || plastic > 0.0;
    point.plastic_area_m2 = state.plastic_area_m2;
    point.plastic_note = (plastic > 0.0).then(|| {
        format!(
            "the contact pressure is capped at the hardness {} Pa (contact.bem.plastic): {} m^2, {} % of the real \
             area, flows plastically",
            stiction_scenario::domain::short(hardness_pa),
            stiction_scenario::domain::short(plastic),
            stiction_scenario::domain::short(100.0 * plastic / state.real_area_m2.max(f64::MIN_POSITIVE))
        )
    });
}

/// Why a Kelvin radius or meniscus height is null (the meter's humidity, `bem --rh`).
pub const NO_MENISCUS_NOTE: &str = "no meniscus: dry (RH 0), faces that do not condense water (cos theta_1 + cos theta_2 <= 0), or a Kelvin radius below the smallest one (min_kelvin_radius)";

/// The humid air of a run and the meniscus it condenses in the contact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Humidity {
    /// The condensing liquid when it is not water (absent: water).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub liquid: Option<String>,
    /// Relative humidity (fraction): the relative vapour pressure `p/p_sat` of the liquid.
    pub relative_humidity: f64,
    /// Temperature, K.
    pub temperature_k: f64,
    /// Contact angles of the sidewall and the shoe face, rad.
    pub contact_angles_rad: (f64, f64),
    /// Kelvin radius r_K, m (None: no meniscus forms, cos th1 + cos th2 <= 0).
    pub kelvin_radius_m: Option<f64>,
    /// Largest gap a meniscus bridges h_m = r_K (cos th1 + cos th2), m (None: no meniscus, also
    /// when r_K lies below `min_kelvin_radius_m`).
    pub meniscus_height_m: Option<f64>,
    /// The scenario's `environment.min_kelvin_radius`, m (absent: none): below it no meniscus
    /// condenses and the contact is dry.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_kelvin_radius_m: Option<f64>,
    /// Why the Kelvin radius or the meniscus height is null.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meniscus_note: Option<&'static str>,
}

impl Humidity {
    /// The humid air of a scenario, or None when dry (no `environment`, relative humidity 0).
    pub fn of(s: &Scenario) -> Result<Option<Humidity>, MeterError> {
        let Some(env) = &s.environment else { return Ok(None) };
        if env.relative_humidity == 0.0 {
            return Ok(None);
        }
        let air = s.capillarity_before_cut_off().map_err(MeterError::Scenario)?;
        let cap = air.and_then(|c| c.above_min_kelvin_radius(env.min_kelvin_radius));
        Ok(Some(Humidity {
            liquid: (!env.is_water()).then(|| env.liquid_name().to_string()),
            relative_humidity: env.relative_humidity,
            temperature_k: env.temperature,
            contact_angles_rad: s.contact_angles_rad(),
            kelvin_radius_m: air.map(|c| c.kelvin_radius_m),
            meniscus_height_m: cap.map(|c| c.meniscus_height_m()),
            min_kelvin_radius_m: env.min_kelvin_radius,
            meniscus_note: cap.is_none().then_some(NO_MENISCUS_NOTE),
        }))
    }
}

/// The assembled device.
pub struct Meter {
    clamp: Option<GapClosingActuator>,
    pull: Option<GapClosingActuator>,
    /// A structure built from parts (scenario `structure`), run instead of the clamp and pull.
    structure: Option<structure::StructureDevice>,
    /// The nominal parts a lab reduces a structure's readings with, when they differ from the
    /// device's own (a Monte Carlo sample); None: the device's own.
    lab_structure: Option<structure::StructureDevice>,
    contact_travel_m: f64,
    spring_force_n: Option<f64>,
    material: MaterialSpec,
    protocol: MeterSpec,
    contact: ContactModel,
    reduction: Option<Reduction>,
    slip_path: SlipPath,
    humidity: Option<Humidity>,
    /// The apparent (shoe) area A_a, m^2: no real area exceeds it.
    apparent_area_m2: f64,
}

impl Meter {
    /// Assembles the meter from a loaded scenario; `base_dir` resolves relative file paths.
    pub fn from_scenario(s: &Scenario, base_dir: &Path) -> Result<Meter, MeterError> {
        if let Some(st) = &s.structure {
            return Self::from_structure(s, st, base_dir);
        }
        let protocol = s.meter.clone().ok_or_else(|| MeterError::Scenario("no `meter` section".into()))?;
        let material = s.require_material().map_err(MeterError::Scenario)?.clone();
        let build = |name: &str| -> Result<GapClosingActuator, MeterError> {
            let spec = s.actuators.get(name).ok_or_else(|| MeterError::Scenario(format!("no actuator `{name}`")))?;
            spec.to_model().map_err(|e| MeterError::Actuator { array: name.into(), message: e.to_string() })
        };
        let clamp = build("clamp")?;
        let pull = build("pull")?;
        let contact_travel_m = protocol.contact_travel.unwrap_or(s.actuators["clamp"].operating_travel);
        let contact = build_contact_model(s, &material, base_dir)?;
        let humidity = Humidity::of(s)?;
        let surface = s.require_surface().map_err(MeterError::Scenario)?;
        let apparent_area_m2 = surface.apparent_length * surface.apparent_width;
        Ok(Meter {
            apparent_area_m2,
            humidity,
            clamp: Some(clamp),
            pull: Some(pull),
            structure: None,
            lab_structure: None,
            contact_travel_m,
            spring_force_n: protocol.spring_force,
            material,
            protocol,
            contact,
            reduction: None,
            slip_path: SlipPath::default(),
        })
    }

    /// A structure built from parts: the contact model of the scenario (dimples: the discrete
    /// model with one sphere of the dimple radius per dimple), no clamp or pull array.
    fn from_structure(
        s: &Scenario,
        st: &stiction_scenario::structure::StructureSpec,
        base_dir: &Path,
    ) -> Result<Meter, MeterError> {
        let material = s.require_material().map_err(MeterError::Scenario)?.clone();
        let device = structure::StructureDevice::from_spec(st)?;
        let contact = match st.geometry {
            stiction_scenario::structure::GeometrySpec::Dimples { count, radius } => ContactModel::Discrete {
                contacts: count as usize,
                law: s.contact_or_default().law,
                params: asperity_params(&material, radius),
                capillarity: s.capillarity().map_err(MeterError::Scenario)?,
            },
            _ => build_contact_model(s, &material, base_dir)?,
        };
        let humidity = Humidity::of(s)?;
        let surface = s.require_surface().map_err(MeterError::Scenario)?;
        let protocol = MeterSpec {
            spring_force: Some(device.normal.spring_force_n()),
            contact_travel: None,
            clamp_voltages: st.normal_voltages.clone(),
            pull_voltage_step: 1.0,
            pull_voltage_max: 2.0,
            slip: st.slip,
            reclamp: true,
            slip_dynamics: None,
            max_clamp_voltages: None,
            lab_reduction: None,
        };
        Ok(Meter {
            apparent_area_m2: surface.apparent_length * surface.apparent_width,
            humidity,
            clamp: None,
            pull: None,
            structure: Some(device),
            lab_structure: None,
            contact_travel_m: 0.0,
            spring_force_n: protocol.spring_force,
            material,
            protocol,
            contact,
            reduction: None,
            slip_path: SlipPath::default(),
        })
    }

    /// The clamp and pull arrays of the paper's meter (an error for a `structure`).
    fn arrays(&self) -> Result<(&GapClosingActuator, &GapClosingActuator), MeterError> {
        match (&self.clamp, &self.pull) {
            (Some(c), Some(p)) => Ok((c, p)),
            _ => Err(MeterError::Scenario(
                "this scenario's device is a `structure` built from parts: it has no clamp and pull arrays".into(),
            )),
        }
    }

    /// The device's own conversion: its conversion factors at the contact travel (clamp) and at
    /// zero travel (pull, the gap is fixed while the shoe sticks) and its spring force.
    pub fn device_reduction(&self) -> Result<Reduction, MeterError> {
        if let Some(st) = &self.structure {
            return Ok(st.reduction());
        }
        let (clamp_array, pull_array) = self.arrays()?;
        let spring = match self.spring_force_n {
            Some(f) => f,
            None => {
                clamp_force(clamp_array, self.contact_travel_m, 0.0)
                    .map_err(|e| MeterError::Actuator { array: "clamp".into(), message: e.to_string() })?
                    .spring_force_n
            }
        };
        Ok(Reduction {
            a_clamp_n_per_v2: clamp_array.conversion_factor_n_per_v2(self.contact_travel_m),
            a_pull_n_per_v2: pull_array.conversion_factor_n_per_v2(0.0),
            spring_force_n: spring,
        })
    }

    /// Reports forces with these (nominal) values instead of the device's own.
    pub fn set_reduction(&mut self, reduction: Reduction) {
        self.reduction = Some(reduction);
    }

    /// A structure's readings reduced with these (nominal) parts instead of the device's own, as
    /// the lab reduces them: `load_n` and `friction_n` from the lab's parts, `true_load_n` and
    /// `true_friction_n` from the device's (a Monte Carlo sample whose parts were drawn).
    pub fn set_lab_structure(&mut self, parts: structure::StructureDevice) {
        self.lab_structure = Some(parts);
    }

    /// Follows the shuttle after slip with this path (default: the rapier rigid body).
    pub fn set_slip_path(&mut self, path: SlipPath) {
        self.slip_path = path;
    }

    /// The contact model in use (for reports and extra curves).
    pub fn contact_model(&mut self) -> &mut ContactModel {
        &mut self.contact
    }

    /// Runs the protocol: for each clamp voltage, clamp, then ramp the pull voltage until slip.
    /// `progress(done, total)` is called after each clamp voltage.
    pub fn run(&mut self, progress: &mut dyn FnMut(usize, usize)) -> Result<MeterResult, MeterError> {
        let voltages = self.protocol.clamp_voltages.voltages();
        self.run_at(&voltages, progress)
    }

    /// Runs the protocol at the given clamp voltages (V) instead of the scenario's.
    pub fn run_at(
        &mut self,
        voltages: &[f64],
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<MeterResult, MeterError> {
        if let Some(device) = &self.structure {
            let mut run = structure::StructureRun {
                device,
                contact: &mut self.contact,
                material: &self.material,
                apparent_area_m2: self.apparent_area_m2,
                humid: self.humidity.is_some(),
            };
            let mut points = run.run(voltages, progress)?;
            if let Some(lab) = &self.lab_structure {
                structure::reduce_as_the_lab(&mut points, lab);
            }
            let mut result =
                structure::result(self.contact.name(), points, device, self.apparent_area_m2, self.humidity.clone());
            if let Some(r) = self.reduction {
                result.reduction = r;
            }
            return Ok(result);
        }
        let (Some(clamp_array), Some(pull_array)) = (&self.clamp, &self.pull) else {
            return Err(self.arrays().err().unwrap_or_else(|| MeterError::Scenario("no clamp and pull arrays".into())));
        };
        let a_pull = pull_array.conversion_factor_n_per_v2(0.0);
        let actuator_err = |array: &str, e: stiction_actuator::ActuatorError| MeterError::Actuator {
            array: array.into(),
            message: e.to_string(),
        };
        let pull_in_v = pull_array.pull_in().ok().map(|p| p.voltage_v);
        let reduction = match self.reduction {
            Some(r) => r,
            None => self.device_reduction()?,
        };
        let clamp_pull_in = clamp_array.pull_in().map_err(|e| actuator_err("clamp", e))?;
        let mut points = Vec::with_capacity(voltages.len());
        let mut spring_force_used = f64::NAN;
        let mut previous_in_contact = false;
        for (k, &v_clamp) in voltages.iter().enumerate() {
            let clamp =
                clamp_force(clamp_array, self.contact_travel_m, v_clamp).map_err(|e| actuator_err("clamp", e))?;
            let spring = self.spring_force_n.unwrap_or(clamp.spring_force_n);
            spring_force_used = spring;
            let load_n = clamp.electrostatic_force_n - spring;
            let in_contact = clamp.in_contact && load_n > 0.0;
            let mut point = MeterPoint {
                load_n: reduction.a_clamp_n_per_v2 * v_clamp * v_clamp - reduction.spring_force_n,
                ..structure::empty_point(v_clamp, load_n, in_contact, self.humidity.is_some())
            };
            if !clamp.in_contact {
                let x_c = self.contact_travel_m * 1e6;
                point.reason = Some(if self.contact_travel_m > clamp_pull_in.travel_m {
                    format!(
                        "no contact: V_clamp is below the clamp's pull-in voltage {:.2} V; the clamp rests short of \
                         the wall (pull-in travel {:.3} um < contact travel {x_c:.3} um) and reaches it only by \
                         pulling in",
                        clamp.contact_voltage_v,
                        clamp_pull_in.travel_m * 1e6
                    )
                } else {
                    format!(
                        "no contact: V_clamp is below {:.2} V, where the clamp's equilibrium reaches the wall \
                         (contact travel {x_c:.3} um): the spring holds the shoe off",
                        clamp.contact_voltage_v
                    )
                });
            } else if !in_contact {
                point.reason = Some(format!(
                    "no load: the electrostatic force {:.4} uN does not exceed the spring force {:.4} uN at the wall",
                    clamp.electrostatic_force_n * 1e6,
                    spring * 1e6
                ));
            }
            if in_contact {
                // Re-clamping releases the shoe between clamp voltages; otherwise it stays in
                // contact and the load path carries over from the previous voltage.
                let fresh = self.protocol.reclamp || !previous_in_contact;
                let state = match self.contact.state_at_load(load_n, fresh) {
                    Ok(state) => state,
                    Err(e) => {
                        point.error = Some(e.to_string());
                        point.reason = Some(format!("no equilibrium: {e}"));
                        previous_in_contact = false;
                        points.push(point);
                        progress(k + 1, voltages.len());
                        continue;
                    }
                };
                invariants::check_state(&state, self.apparent_area_m2, self.contact.summit_count(), v_clamp)?;
                let capacity = self.slip_threshold_n(&state);
                point.friction_capacity_n = capacity;
                point.real_area_m2 = state.real_area_m2;
                point.contacts = state.contacts;
                point.adhesive_load_n = state.adhesive_load_n;
                if self.humidity.is_some() {
                    point.capillary_load_n = Some(state.capillary_load_n);
                }
                point.tilt_x_rad = state.tilt_x_rad;
                point.tilt_y_rad = state.tilt_y_rad;
                fill_pressure(&mut point, &state, self.material.hardness);
                // The pull ramp: V_n = n * step, n = 1..=n_max with n_max = floor(V_max / step)
                // (at most MAX_PULL_RAMP_STEPS, checked when the scenario is loaded, so every n is
                // exact in f64). While the shoe sticks the pull gap is fixed, so F_pull(V_n) rises
                // monotonically in n: slip happens at the first n with F_pull >= capacity. The
                // closed-form guess a_pull V^2 = capacity is confirmed by the force itself and, when
                // it is off, corrected by bisection over [1, n_max]: at most ~60 force evaluations
                // whatever the step, the capacity or the conversion factor.
                let step = self.protocol.pull_voltage_step;
                let n_max = (self.protocol.pull_voltage_max / step).floor().max(1.0);
                let force = |n: f64| pull_force_stuck_n(pull_array, n * step).map_err(|e| actuator_err("pull", e));
                let top = force(n_max)?;
                let n = if !capacity.is_finite() || top.is_nan() || top < capacity {
                    // No slip up to pull_voltage_max (or a capacity that no force reaches).
                    point.reason = Some(format!(
                        "no slip: the friction capacity {:.4} uN exceeds the pull force {:.4} uN at \
                         pull_voltage_max = {} V",
                        capacity * 1e6,
                        top * 1e6,
                        self.protocol.pull_voltage_max
                    ));
                    n_max + 1.0
                } else {
                    let guess = ((capacity / a_pull).sqrt() / step).ceil();
                    let guess = if guess.is_finite() { guess.clamp(1.0, n_max) } else { n_max };
                    if force(guess)? >= capacity && (guess <= 1.0 || force(guess - 1.0)? < capacity) {
                        guess
                    } else {
                        // Invariant: force(hi) >= capacity, force(lo) < capacity (or lo = 0).
                        let (mut lo, mut hi) = (0.0f64, n_max);
                        while hi - lo > 1.0 {
                            let mid = (lo + (hi - lo) / 2.0).floor();
                            if mid <= lo || mid >= hi {
                                break; // cannot happen below 2^53; a guard against an endless loop
                            }
                            if force(mid)? >= capacity {
                                hi = mid;
                            } else {
                                lo = mid;
                            }
                        }
                        hi
                    }
                };
                let v_pull = n * step;
                if n <= 1.0 {
                    // Slip at the first step: the friction lies anywhere below a_pull step^2, so the
                    // point bounds it and does not measure it.
                    point.reason = Some(format!(
                        "slip at the first pull step ({step} V): the friction is at most {:.4} uN, not measured; \
                         left out of the eq. 10 fit (refine meter.pull_voltage_step)",
                        reduction.a_pull_n_per_v2 * step * step * 1e6
                    ));
                }
                if n <= n_max {
                    point.v_pull = Some(v_pull);
                    point.v_pull_sq = Some(v_pull * v_pull);
                    point.true_friction_n = Some(force(n)?);
                    point.friction_n = Some(reduction.a_pull_n_per_v2 * v_pull * v_pull);
                    // Once it slips, does the pull array run away to its stop?
                    match &self.protocol.slip_dynamics {
                        Some(dyn_spec) => {
                            // After slip the shoe slides: kinetic friction on the total load.
                            let kinetic = dyn_spec.kinetic_friction_coefficient * state.elastic_load_n();
                            let t = slip::slip_outcome(
                                self.slip_path,
                                pull_array,
                                v_pull,
                                dyn_spec.shuttle_mass,
                                dyn_spec.damping,
                                kinetic,
                            )
                            .map_err(|e| actuator_err("pull", e))?;
                            point.pull_in_at_slip = Some(t.runs_away);
                            point.slip_time_to_stop_s = t.time_to_stop_s;
                            point.slip_impact_velocity_m_per_s = t.impact_velocity_m_per_s;
                            if t.time_to_stop_s.is_none() || t.impact_velocity_m_per_s.is_none() {
                                point.slip_note = Some(
                                    "after slip the pull shuttle settles before its stop: no time to the stop and \
                                     no impact speed"
                                        .into(),
                                );
                            }
                        }
                        None => {
                            // Quasi-static: with kinetic friction taken as zero, does the pull array
                            // find an equilibrium before its stop?
                            let response =
                                slip_response(pull_array, v_pull, 0.0).map_err(|e| actuator_err("pull", e))?;
                            point.pull_in_at_slip = Some(matches!(response, SlipResponse::RunsAway { .. }));
                        }
                    }
                }
            }
            if point.v_pull.is_some()
                && (point.slip_time_to_stop_s.is_none() || point.slip_impact_velocity_m_per_s.is_none())
                && point.slip_note.is_none()
            {
                point.slip_note = Some(
                    "no slip dynamics in the scenario (meter.slip_dynamics): only the quasi-static runaway test, no \
                     time to the stop and no impact speed"
                        .into(),
                );
            }
            previous_in_contact = in_contact;
            points.push(point);
            progress(k + 1, voltages.len());
        }
        // A slip at the first pull step bounds the friction, it does not measure it: such points
        // stay out of the fit.
        let step = self.protocol.pull_voltage_step;
        let first_step = |p: &MeterPoint| p.v_pull.is_some_and(|v| v <= step);
        let used = |p: &&MeterPoint| p.load_n > 0.0 && p.friction_n.is_some() && !first_step(p);
        let pairs: Vec<(f64, f64)> =
            points.iter().filter(used).filter_map(|p| p.friction_n.map(|f| (p.load_n, f))).collect();
        let fitted: Vec<f64> = points.iter().filter(used).map(|p| p.v_clamp).collect();
        let mut eq10 = fit::eq10(&pairs);
        let censored: Vec<&MeterPoint> = points.iter().filter(|p| first_step(p)).collect();
        let mut warnings = match &eq10.line {
            Some(l) => fit::eq10_warnings(l, voltages, &fitted, &points),
            None => Vec::new(),
        };
        if !censored.is_empty() {
            // The step that resolves the smallest friction capacity in ten steps.
            let smallest = censored.iter().map(|p| p.friction_capacity_n).fold(f64::INFINITY, f64::min);
            let v_slip = (smallest / a_pull).sqrt();
            let refine = format!(
                "{} of {} clamp voltages slipped at the first pull step ({step} V), where the friction is only \
                 bounded; refine meter.pull_voltage_step to at most {} V (a tenth of the {} V at which the \
                 smallest friction capacity, {:.4} uN, slips)",
                censored.len(),
                points.len(),
                stiction_scenario::domain::short(v_slip / 10.0),
                stiction_scenario::domain::short(v_slip),
                smallest * 1e6
            );
            match &mut eq10.note {
                Some(note) => *note = format!("{note}; {refine}"),
                None => warnings.push(stiction_scenario::Warning::new("coarse_pull_step", refine)),
            }
        }
        let lab_coefficient =
            self.protocol.lab_reduction.as_ref().map(|spec| structure::lab_coefficient(spec, &pairs, &eq10));
        Ok(MeterResult {
            contact_model: self.contact.name(),
            points,
            mu_apparent: eq10.mu_apparent,
            apparent_adhesion_force_n: eq10.apparent_adhesion_force_n,
            fit_note: eq10.note,
            fit: eq10.line,
            spring_force_n: spring_force_used,
            pull_array_pull_in_v: pull_in_v,
            reduction,
            environment: self.humidity.clone(),
            warnings,
            structure: None,
            lab_coefficient,
            pull_array_note: None,
        })
    }

    /// The pull force at which the shoe slips, by the scenario's criterion, N.
    ///
    /// Eq. 1 `F_f = s A_r`; the plastic limit `mu_p = s / H` on the total (external plus adhesive)
    /// load; a pressure-dependent shear strength `sum_i (s0 + alpha p_i) A_i = s0 A_r + alpha sum_i P_i`
    /// ([`structure::slip_threshold_n`], shared with the structures).
    pub fn slip_threshold_n(&self, state: &ContactState) -> f64 {
        structure::slip_threshold_n(&self.material, self.protocol.slip, state)
    }
}

/// `text` cut to 120 characters for an error message (a user's file is quoted only in part).
pub(crate) fn short(text: &str) -> String {
    stiction_scenario::truncate(text, 120)
}

/// The summit parameters of a scenario's material and surface (mean radius).
pub fn asperity_params(material: &MaterialSpec, radius_m: f64) -> AsperityParams {
    AsperityParams {
        radius_m,
        compliance_per_pa: material.compliance_per_pa(),
        work_of_adhesion_j_per_m2: material.work_of_adhesion,
        equilibrium_spacing_m: material.equilibrium_spacing,
    }
}

/// The summit radius R the discrete and statistical curves use: the scenario's `summit_radius`
/// for a single generated face; otherwise (summits read from a file, or two faces whose pairs
/// have a composite radius) the mean radius of the summits of the built surface, m.
pub fn model_summit_radius_m(spec: &SurfaceSpec, base_dir: &Path) -> Result<f64, MeterError> {
    match (spec.summit_radius, &spec.counter_face) {
        (Some(r), None) => Ok(r),
        _ => {
            let surface = spec.build(base_dir).map_err(|e| MeterError::Surface(e.to_string()))?;
            if surface.is_empty() {
                return Err(MeterError::Surface(
                    "the surface has no summits, so it has no mean summit radius (raise `summit_density` or the \
                     apparent area)"
                        .into(),
                ));
            }
            Ok(surface.stats().radius_mean_m)
        }
    }
}

/// Builds the contact model a scenario asks for.
///
/// With humid air (`environment`, [`Scenario::capillarity`]) every summit within the meniscus
/// height of the counter face carries a water meniscus (explicit, GW; the discrete model at its N
/// contacts); the boundary-element model has no meniscus and refuses humid air.
pub fn build_contact_model(s: &Scenario, material: &MaterialSpec, base_dir: &Path) -> Result<ContactModel, MeterError> {
    let c = s.contact_or_default();
    let capillarity = s.capillarity().map_err(MeterError::Scenario)?;
    let surface_spec = s.require_surface().map_err(MeterError::Scenario)?;
    match c.model {
        ModelKind::Explicit => {
            let surface = surface_spec.build(base_dir).map_err(|e| MeterError::Surface(e.to_string()))?;
            let mode = match c.mode {
                ShoeMode::Tilt => explicit::ShoeMode::TiltFree,
                ShoeMode::Flat => explicit::ShoeMode::Flat,
                ShoeMode::Fixed => explicit::ShoeMode::FixedContacts { count: c.contacts.unwrap_or(3) },
            };
            let config = explicit::SolverConfig {
                mode,
                shear_strength_pa: material.shear_strength,
                hardness_pa: Some(material.hardness),
                detail: explicit::Detail::Summary,
                ..Default::default()
            };
            // Each summit carries its own radius; the mean only sets the solver's adhesion scale.
            let params = asperity_params(material, surface.stats().radius_mean_m);
            let mut solver = explicit::ExplicitSolver::new(surface, c.law, params, config)
                .map_err(|e| MeterError::Contact(e.to_string()))?;
            if let Some(cap) = &capillarity {
                solver
                    .set_meniscus(Some(explicit::Meniscus::from_capillarity(cap)))
                    .map_err(|e| MeterError::Contact(e.to_string()))?;
            }
            Ok(ContactModel::Explicit(Box::new(solver)))
        }
        ModelKind::Gw => {
            let (face, _) = surface_spec.face_params_in(base_dir).map_err(|e| MeterError::Surface(e.to_string()))?;
            let gw = GwSurface {
                summit_density_per_m2: face.summit_density_per_m2,
                summit_radius_m: face.summit_radius_m,
                summit_sd_m: face.summit_sd_m,
                compliance_per_pa: material.compliance_per_pa(),
                work_of_adhesion_j_per_m2: material.work_of_adhesion,
                apparent_area_m2: surface_spec.apparent_length * surface_spec.apparent_width,
            };
            Ok(ContactModel::Gw(gw, capillarity))
        }
        ModelKind::Bem => {
            if capillarity.is_some() {
                return Err(MeterError::Scenario(
                    "environment.relative_humidity: the meter's boundary-element model (`contact.model` = \"bem\") \
                     has no water meniscus; use \"explicit\", \"gw\" or \"discrete\" for a humid run, or drop the \
                     `environment` section"
                        .into(),
                ));
            }
            build_bem(s, material, base_dir).map(|b| ContactModel::Bem(Box::new(b)))
        }
        ModelKind::Discrete => {
            // On a height map: the mean radius counted on the whole map, as `stiction topography`
            // prints it.
            let radius = if surface_spec.source == stiction_surface::SurfaceSource::HeightMap {
                surface_spec.face_params_in(base_dir).map_err(|e| MeterError::Surface(e.to_string()))?.0.summit_radius_m
            } else {
                model_summit_radius_m(surface_spec, base_dir)?
            };
            Ok(ContactModel::Discrete {
                contacts: c.contacts.unwrap_or(3),
                law: c.law,
                params: asperity_params(material, radius),
                capillarity,
            })
        }
    }
}

/// The boundary-element model of a scenario (`contact.model` = "bem"): the composite height patch
/// under the shoe ([`stiction_surface::height_map_patch`]), coarsened as `contact.bem` asks and
/// checked against its point limit before the solver allocates; E* = 3/(4D); the Dugdale law with
/// the material's work of adhesion and `contact.bem.range` (default z0/1.03) unless the law is
/// "hertz" or the work of adhesion is 0; the Green's function of `contact.bem.boundary` (default
/// the finite patch on the wall); a flat shoe, or a tilting one with `contact.bem.tilt`.
pub fn build_bem(s: &Scenario, material: &MaterialSpec, base_dir: &Path) -> Result<BemContact, MeterError> {
    let c = s.contact_or_default();
    let spec = c.bem.clone().unwrap_or_default();
    let surface_spec = s.require_surface().map_err(MeterError::Scenario)?;
    let (patch, _) =
        stiction_surface::height_map_patch(surface_spec, base_dir).map_err(|e| MeterError::Surface(e.to_string()))?;
    let (kx, ky) = spec
        .coarsening(patch.nx(), patch.ny(), patch.dx_m(), patch.dy_m())
        .map_err(|e| MeterError::Scenario(format!("contact.bem: {e}")))?;
    let (nx, ny) = (patch.nx() / kx, patch.ny() / ky);
    let grid = stiction_bem::Grid::new(nx, ny, patch.dx_m() * kx as f64, patch.dy_m() * ky as f64)
        .map_err(|e| MeterError::Scenario(format!("contact.bem: {e}")))?;
    let heights = stiction_bem::spec::coarsen(patch.heights_m(), patch.nx(), patch.ny(), kx, ky);
    drop(patch);
    stiction_bem::spec::check_complete(&heights).map_err(|e| MeterError::Surface(e.to_string()))?;
    let adhesive = c.law != stiction_contact::single::AdhesionLaw::Hertz && material.work_of_adhesion > 0.0;
    let law = if adhesive {
        let range =
            spec.range.unwrap_or(material.equilibrium_spacing * stiction_bem::spec::RANGE_PER_EQUILIBRIUM_SPACING);
        Some(
            stiction_bem::Dugdale::from_work_and_range(material.work_of_adhesion, range)
                .map_err(|e| MeterError::Scenario(format!("contact.bem: {e}")))?,
        )
    } else {
        None
    };
    let e_star = 0.75 / material.compliance_per_pa();
    // A Dugdale stress above E* (the theoretical strength of a solid is about E/10) describes no
    // interface, and its cohesive zone cannot settle on any grid: refused before any solve.
    if let Some(l) = law.filter(|l| l.stress_pa > e_star) {
        return Err(MeterError::Scenario(format!(
            "contact.bem.range (or material.equilibrium_spacing, material.work_of_adhesion): the Dugdale stress \
             w/h0 = {:e} Pa (w = {:e} J/m^2 over h0 = {:e} m) exceeds E* = {e_star:e} Pa; a solid breaks near E/10: \
             give a longer range",
            l.stress_pa, material.work_of_adhesion, l.range_m
        )));
    }
    let shoe = BemShoe {
        boundary: spec.boundary(),
        tilting: spec.tilt(),
        hardness_pa: spec.plastic().then_some(material.hardness),
    };
    BemContact::new(grid, &heights, e_star, law, spec.tolerance(), (kx, ky), shoe)
}
