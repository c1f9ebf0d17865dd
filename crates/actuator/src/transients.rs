//! Pull-in and release *times* of a gap-closing actuator, simulated point by point and compared
//! with measured times (Rauf et al., JMEMS 31(1) 29-36, 2022; `data/gca-transients/`).
//!
//! **Events.** Pull-in: the voltage steps from 0 to `V` at `t = 0` with the spine at rest at its
//! open position `x = 0`; the time is when the spine reaches the gap stop `x_s`. Release: the spine
//! rests on the stop, held there by `V`; at `t = 0` the voltage drops to 0; the time is when the
//! spine is back at `x = 0`. Both integrate the same lumped equation
//!
//! `m x'' = F_e(x, V) - k x - c(x) x' - F_ext`
//!
//! with `F_e` the array's electrostatic force (co-energy derivative, Palmer fringing and the back
//! electrode of the spec; rigid fingers, see below), `k` the suspension, `F_ext` a constant external
//! force opposing closing (0 unless the measured file gives `external_force_n`) and the air damping
//!
//! `c(x) = n [c_sq(g_f - x) + c_sq(g_b + x)] + c_couette`,
//! `c_sq(h) = mu_eff(h) L s^3 / h^3 beta(s/L)`,   `s = min(l, t)`, `L = max(l, t)`
//!
//! (incompressible Reynolds squeeze film of each `l x t` finger face with all four edges open,
//! finite-aspect factor `beta` ([`crate::dynamics::squeeze_film_aspect_factor`]), Veijola's rarefied
//! viscosity `mu_eff(h)` ([`crate::dynamics::veijola_effective_viscosity_pa_s`]); Couette shear under
//! the moving planform `mu A / (d + 2 lambda)`), the moving mass from the as-built layout
//! ([`crate::protocol::Shuttle`]: spine minus etch holes, fingers, bumpers, 13/35 of the beams).
//! Every ingredient can be switched off ([`TransientPhysics`]) to measure what it does.
//!
//! **Rigid fingers.** Finger bending changes the GCA's static pull-in and release voltages by less
//! than 1e-4 (docs/actuators.md); in time it would cost a self-consistent beam solve per force
//! evaluation, so the transient model uses the rigid-plate force.
//!
//! **Integration.** Rapier (`rapier3d-f64`) rigid body on a prismatic guide, the same loop as the
//! slip dynamics ([`crate::dynamics`]), step `T/steps_per_period` (`T = 2 pi sqrt(m/k)`), force at
//! the predicted mid-step travel, impact located inside its step. Release runs in the mirrored
//! coordinate `y = x_s - x` (from the stop towards the open position). [`TransientModel::time_rk4_s`]
//! integrates the same equation with classical RK4 as the reference for the integration error.
//!
//! **Release kick** (optional, [`ReleaseKick`]): when the voltage drops, the elastic energy stored
//! at the stop in the bent fingers (cantilevers `k_f = 8 E I / L_f^3` under their share of the
//! force) and the axially compressed spine (force growing linearly along it, `U = F^2 L/(6 E A)`)
//! is handed to the shuttle as kinetic energy, `v0 = sqrt(2 U / m)`, an upper bound.

use std::collections::HashMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::actuator::GapClosingActuator;
use crate::dynamics::{
    SimulationScale, SlipDynamics, integrate, squeeze_film_aspect_factor, veijola_effective_viscosity_pa_s,
};
use crate::error::{ActuatorError, nonnegative, positive};
use crate::protocol::Shuttle;
use crate::spec::ArraySpec;

/// Largest measured-times file read (bytes), checked before reading.
pub const MAX_TRANSIENT_FILE_BYTES: u64 = 16 << 20;

/// Largest number of data rows in a measured-times file.
pub const MAX_TRANSIENT_ROWS: usize = 200_000;

/// Smallest finger length, voltage and time in a measured file, as a fraction of their largest:
/// 1e-9 (so 10 nm, 10 uV, 1 ps; a positive 5e-324 us would be 0 s after the conversion to seconds).
pub const MEASURED_MIN_FRACTION: f64 = 1e-9;

/// Largest finger length in a measured file: 10 000 um (1 cm; the devices' fingers are 10-100 um).
pub const MAX_FINGER_LENGTH_UM: f64 = 1e4;

/// Largest voltage in a measured file: 10 kV (as `stiction_scenario::MAX_VOLTAGE_V`).
pub const MAX_TRANSIENT_VOLTAGE_V: f64 = 1e4;

/// Largest measured time: 1e6 us (1 s; the measured transients are 10-1000 us).
pub const MAX_TRANSIENT_TIME_US: f64 = 1e6;

/// Largest |external force| in a measured file: 1 N (a GCA's force is of the order of 100 uN).
pub const MAX_EXTERNAL_FORCE_N: f64 = 1.0;

/// Default number of rapier steps per undamped natural period `2 pi sqrt(m/k)`.
pub const DEFAULT_TRANSIENT_STEPS_PER_PERIOD: f64 = 2000.0;

/// Simulated horizon in undamped natural periods: a point that has not arrived by then is reported
/// as not arriving.
pub const TRANSIENT_HORIZON_PERIODS: f64 = 20.0;

/// Which transient.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum TransientEvent {
    /// Voltage step from rest at the open position until the spine reaches the stop.
    #[serde(rename = "pull-in")]
    PullIn,
    /// From the stop, voltage switched to 0, until the spine is back at the open position.
    #[serde(rename = "release")]
    Release,
}
stiction_units::display_serde_name!(TransientEvent);

impl TransientEvent {
    /// `pull-in` or `release`, as in the measured file.
    pub fn name(self) -> &'static str {
        match self {
            Self::PullIn => "pull-in",
            Self::Release => "release",
        }
    }
}

/// One measured length-event-voltage point with its repeats.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeasuredTransient {
    /// Drawn finger length (m).
    pub finger_length_m: f64,
    /// The event.
    pub event: TransientEvent,
    /// Step voltage (pull-in) or hold voltage (release) (V).
    pub voltage_v: f64,
    /// Constant external force opposing closing (N), 0 when the file has no such column.
    pub external_force_n: f64,
    /// The measured times of the repeats (s).
    pub times_s: Vec<f64>,
}

impl MeasuredTransient {
    /// Mean of the repeats (s).
    pub fn mean_s(&self) -> f64 {
        self.times_s.iter().sum::<f64>() / self.times_s.len() as f64
    }

    /// Sample standard deviation of the repeats (s), 0 for one repeat.
    pub fn sd_s(&self) -> f64 {
        let n = self.times_s.len();
        if n < 2 {
            return 0.0;
        }
        let m = self.mean_s();
        (self.times_s.iter().map(|t| (t - m).powi(2)).sum::<f64>() / (n as f64 - 1.0)).sqrt()
    }
}

/// Reads a measured-times CSV file (regular file, at most [`MAX_TRANSIENT_FILE_BYTES`]), see
/// [`parse_transients`].
pub fn read_transients(path: &Path) -> Result<Vec<MeasuredTransient>, ActuatorError> {
    let bytes = stiction_units::io::read_input(path, MAX_TRANSIENT_FILE_BYTES).map_err(|e| ActuatorError::Data {
        path: path.display().to_string(),
        line: 0,
        message: e.to_string(),
    })?;
    parse_transients(&bytes, &path.display().to_string())
}

/// Parses measured times: a header with the columns `finger_length_um`, `event` (`pull-in` or
/// `release`), `voltage_v`, `time_us`, optionally `repeat` (a label, not used) and
/// `external_force_n` (N, opposing closing; default 0), in any order; then one measurement per
/// row. Lengths, voltages and times must be finite and positive, the force finite, each within its
/// limit (positive values at least [`MEASURED_MIN_FRACTION`] of it) ([`MAX_FINGER_LENGTH_UM`], [`MAX_TRANSIENT_VOLTAGE_V`], [`MAX_TRANSIENT_TIME_US`],
/// [`MAX_EXTERNAL_FORCE_N`]); no line longer than [`stiction_units::text::MAX_LINE_BYTES`]; errors
/// quote a cell only through [`stiction_units::text::excerpt`]. Rows with the
/// same length, event, voltage and force are the repeats of one point (in the order of first
/// appearance). Lines starting with `#` are comments. Errors carry the 1-based line.
pub fn parse_transients(bytes: &[u8], source: &str) -> Result<Vec<MeasuredTransient>, ActuatorError> {
    let err =
        |line: u64, message: String| ActuatorError::Data { path: source.to_string(), line: line as usize, message };
    stiction_units::text::check_line_bytes(bytes, stiction_units::text::MAX_LINE_BYTES)
        .map_err(|e| err(e.line, e.to_string()))?;
    let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).comment(Some(b'#')).from_reader(bytes);
    let headers = reader.headers().map_err(|e| err(1, format!("cannot read the header: {e}")))?.clone();
    let mut col = HashMap::new();
    for (i, h) in headers.iter().enumerate() {
        match h {
            "finger_length_um" | "event" | "voltage_v" | "time_us" | "repeat" | "external_force_n" => {
                if col.insert(h.to_string(), i).is_some() {
                    return Err(err(1, format!("column `{h}` appears twice")));
                }
            }
            other => {
                return Err(err(
                    1,
                    format!(
                        "column {}: unknown column {}: expected finger_length_um, event, voltage_v, time_us, and \
                         optionally repeat, external_force_n",
                        i + 1,
                        stiction_units::text::excerpt(other)
                    ),
                ));
            }
        }
    }
    for need in ["finger_length_um", "event", "voltage_v", "time_us"] {
        if !col.contains_key(need) {
            return Err(err(1, format!("missing column `{need}`")));
        }
    }
    let mut points: Vec<MeasuredTransient> = Vec::new();
    let mut index: HashMap<(u64, TransientEvent, u64, u64), usize> = HashMap::new();
    let mut rows = 0usize;
    for rec in reader.records() {
        let rec = rec.map_err(|e| err(e.position().map_or(0, |p| p.line()), format!("{e}")))?;
        let line = rec.position().map_or(0, |p| p.line());
        rows += 1;
        if rows > MAX_TRANSIENT_ROWS {
            return Err(err(line, format!("more than {MAX_TRANSIENT_ROWS} data rows")));
        }
        let cell = |name: &str| rec.get(col[name]).unwrap_or("");
        // A number in [limit * MEASURED_MIN_FRACTION, limit] (or [-limit, limit] when it may be negative).
        let number = |name: &str, positive_only: bool, limit: f64| -> Result<f64, ActuatorError> {
            let c = cell(name);
            let v: f64 = c.parse().map_err(|_| {
                err(line, format!("column `{name}`: {} is not a number", stiction_units::text::excerpt(c)))
            })?;
            let min = limit * MEASURED_MIN_FRACTION;
            let ok = v.is_finite() && v.abs() <= limit && (!positive_only || v >= min);
            if !ok {
                let range = if positive_only {
                    format!("in [{min:e}, {limit:e}]")
                } else {
                    format!("in [-{limit:e}, {limit:e}]")
                };
                return Err(err(line, format!("column `{name}`: {v:e} must be finite and {range}")));
            }
            Ok(v)
        };
        let event = match cell("event") {
            "pull-in" => TransientEvent::PullIn,
            "release" => TransientEvent::Release,
            other => {
                return Err(err(
                    line,
                    format!(
                        "column `event`: {}, expected `pull-in` or `release`",
                        stiction_units::text::excerpt(other)
                    ),
                ));
            }
        };
        let length = number("finger_length_um", true, MAX_FINGER_LENGTH_UM)? * 1e-6;
        let voltage = number("voltage_v", true, MAX_TRANSIENT_VOLTAGE_V)?;
        let time = number("time_us", true, MAX_TRANSIENT_TIME_US)? * 1e-6;
        let force = if col.contains_key("external_force_n") {
            number("external_force_n", false, MAX_EXTERNAL_FORCE_N)?
        } else {
            0.0
        };
        let key = (length.to_bits(), event, voltage.to_bits(), force.to_bits());
        match index.get(&key) {
            Some(&i) => points[i].times_s.push(time),
            None => {
                index.insert(key, points.len());
                points.push(MeasuredTransient {
                    finger_length_m: length,
                    event,
                    voltage_v: voltage,
                    external_force_n: force,
                    times_s: vec![time],
                });
            }
        }
    }
    if points.is_empty() {
        return Err(err(0, "no data rows".into()));
    }
    Ok(points)
}

/// Elastic energy handed to the shuttle when the voltage drops at release.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReleaseKick {
    /// None: the spine leaves the stop from rest (default).
    #[default]
    None,
    /// Finger bending and spine compression energy at the stop become kinetic energy (module docs).
    ElasticEnergy,
}

/// The physical ingredients of the transient model, each a switch (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransientPhysics {
    /// Squeeze film in the front gaps.
    pub front_film: bool,
    /// Squeeze film in the back gaps.
    pub back_film: bool,
    /// Veijola's rarefied viscosity in the films (else the bulk viscosity).
    pub rarefaction: bool,
    /// Finite-aspect factor `beta(s/L)` of the films (else the long-strip limit, `beta = 1`).
    pub finite_aspect: bool,
    /// Couette shear under the moving planform.
    pub couette: bool,
    /// Effective mass of the suspension beams (13/35 of it) in the moving mass.
    pub beam_mass: bool,
    /// The release kick.
    pub release_kick: ReleaseKick,
    /// Rapier steps per undamped natural period.
    pub steps_per_period: f64,
}

impl Default for TransientPhysics {
    fn default() -> Self {
        Self {
            front_film: true,
            back_film: true,
            rarefaction: true,
            finite_aspect: true,
            couette: true,
            beam_mass: true,
            release_kick: ReleaseKick::None,
            steps_per_period: DEFAULT_TRANSIENT_STEPS_PER_PERIOD,
        }
    }
}

/// Inputs of the release kick (as built, SI).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
struct KickInputs {
    finger_stiffness_n_per_m: f64,
    spine_axial_stiffness_n_per_m: f64,
}

/// One actuator geometry ready for transient simulation.
#[derive(Clone, Debug)]
pub struct TransientModel {
    /// Rigid-finger actuator (as built).
    pub actuator: GapClosingActuator,
    /// Moving mass and gas.
    pub shuttle: Shuttle,
    /// The switches.
    pub physics: TransientPhysics,
    /// Moving mass used (kg): the shuttle's, without the beam share when `beam_mass` is off.
    pub mass_kg: f64,
    /// Stop travel `x_s` (m).
    pub stop_travel_m: f64,
    /// Finite-aspect factor `beta(s/L)` of a finger face (1 when `finite_aspect` is off), computed once.
    pub aspect_factor: f64,
    kick: Option<KickInputs>,
}

impl TransientModel {
    /// The model of a spec (needs `stop` and `shuttle`; the release kick needs `finger_bending`
    /// for the finger root and modulus). Errors name the field.
    pub fn from_spec(spec: &ArraySpec, physics: TransientPhysics) -> Result<Self, ActuatorError> {
        positive("steps_per_period", physics.steps_per_period)?;
        if physics.steps_per_period < 50.0 || physics.steps_per_period > 1e6 {
            return Err(ActuatorError::InvalidField {
                field: "steps_per_period".into(),
                value: physics.steps_per_period,
                expected: "between 50 and 1e6".into(),
            });
        }
        let mut actuator = spec.to_model()?;
        actuator.bending = None;
        let stop_travel_m = actuator.stop_travel_m.ok_or_else(|| {
            ActuatorError::NotAvailable("transient times need a gap stop (`stop`): pull-in ends there".into())
        })?;
        let shuttle = Shuttle::from_spec(spec)?;
        let mass_kg = if physics.beam_mass {
            shuttle.mass_kg
        } else {
            shuttle.mass_kg - shuttle.mass_breakdown.beams_effective_kg
        };
        let kick = match (physics.release_kick, &spec.finger_bending, &spec.shuttle) {
            (ReleaseKick::None, _, _) => None,
            (ReleaseKick::ElasticEnergy, Some(b), Some(s)) => {
                let u = spec.undercut;
                let w = positive("finger_bending.width (after undercut)", b.width - 2.0 * u)?;
                let lf = spec.overlap_length - u + b.root_length;
                let e = b.youngs_modulus;
                let i = spec.thickness * w.powi(3) / 12.0;
                let ws = positive("shuttle.spine_width (after undercut)", s.spine_width - 2.0 * u)?;
                let ls = s.spine_length - 2.0 * u;
                Some(KickInputs {
                    finger_stiffness_n_per_m: 8.0 * e * i / lf.powi(3),
                    spine_axial_stiffness_n_per_m: e * spec.thickness * ws / ls,
                })
            }
            _ => {
                return Err(ActuatorError::NotAvailable(
                    "the release kick needs `finger_bending` (root length, modulus) and `shuttle`".into(),
                ));
            }
        };
        let p = &actuator.plates;
        let aspect_factor = if physics.finite_aspect {
            squeeze_film_aspect_factor(p.overlap_length_m.min(p.thickness_m) / p.overlap_length_m.max(p.thickness_m))
        } else {
            1.0
        };
        Ok(Self { actuator, shuttle, physics, mass_kg, stop_travel_m, aspect_factor, kick })
    }

    /// Squeeze-film damping of one `l x t` face at gap `h` (N s/m), with the switches.
    fn film_n_s_per_m(&self, h: f64) -> f64 {
        if h <= 0.0 {
            return f64::INFINITY;
        }
        let p = &self.actuator.plates;
        let mu = if self.physics.rarefaction {
            veijola_effective_viscosity_pa_s(self.shuttle.viscosity_pa_s, self.shuttle.mean_free_path_m, h)
                .unwrap_or(f64::INFINITY)
        } else {
            self.shuttle.viscosity_pa_s
        };
        let (s, l) = (p.overlap_length_m.min(p.thickness_m), p.overlap_length_m.max(p.thickness_m));
        mu * l * s.powi(3) / h.powi(3) * self.aspect_factor
    }

    /// Damping coefficient `c(x)` at travel `x` (N s/m), see the module docs.
    pub fn damping_n_s_per_m(&self, travel_m: f64) -> f64 {
        let p = &self.actuator.plates;
        let n = f64::from(p.plate_count);
        let mut c = 0.0;
        if self.physics.front_film {
            c += n * self.film_n_s_per_m(p.front_gap_m - travel_m);
        }
        if self.physics.back_film
            && let Some(b) = p.back
        {
            c += n * self.film_n_s_per_m(b.gap_m + travel_m);
        }
        if self.physics.couette {
            c += self.shuttle.couette_n_s_per_m;
        }
        c
    }

    /// Net force towards the stop without damping, `F_e(x, V) - k x - F_ext` (N).
    pub fn net_force_n(&self, travel_m: f64, voltage_v: f64, external_force_n: f64) -> f64 {
        self.actuator.electrostatic_force_n(travel_m, voltage_v)
            - self.actuator.suspension.force_n(travel_m)
            - external_force_n
    }

    /// Undamped natural period `2 pi sqrt(m/k)` (s).
    pub fn period_s(&self) -> f64 {
        2.0 * std::f64::consts::PI * (self.mass_kg / self.actuator.stiffness_n_per_m()).sqrt()
    }

    /// Initial speed away from the stop at release (m/s): 0, or the elastic-energy kick at `V`.
    pub fn release_kick_m_per_s(&self, voltage_v: f64, external_force_n: f64) -> f64 {
        let Some(k) = self.kick else { return 0.0 };
        let xs = self.stop_travel_m;
        // Contact force at the stop: electrostatic force minus spring and load.
        let f = self.net_force_n(xs, voltage_v, external_force_n).max(0.0);
        let n = f64::from(self.actuator.plates.plate_count);
        let ff = self.actuator.electrostatic_force_n(xs, voltage_v) / n;
        let fingers = n * 0.5 * ff * ff / k.finger_stiffness_n_per_m;
        let spine = f * f / (6.0 * k.spine_axial_stiffness_n_per_m);
        (2.0 * (fingers + spine) / self.mass_kg).sqrt()
    }

    fn dynamics(&self) -> Result<SlipDynamics, ActuatorError> {
        let period = self.period_s();
        let d = SlipDynamics {
            shuttle_mass_kg: self.mass_kg,
            damping_n_s_per_m: 0.0,
            kinetic_friction_n: 0.0,
            time_step_s: period / self.physics.steps_per_period,
            max_time_s: TRANSIENT_HORIZON_PERIODS * period,
            contact_gap_m: 0.01 * self.actuator.plates.front_gap_m,
        };
        d.validate()?;
        Ok(d)
    }

    /// Checks the release start: the spine must be held at the stop at `V` against spring and load.
    fn check_held(&self, voltage_v: f64, external_force_n: f64) -> Result<(), String> {
        let f = self.net_force_n(self.stop_travel_m, voltage_v, external_force_n);
        if f < 0.0 {
            return Err(format!(
                "not held at the stop at {voltage_v} V: spring and load exceed the electrostatic force there by {:.3e} N",
                -f
            ));
        }
        Ok(())
    }

    /// Simulated time of one event (s) with rapier; `Ok(Err(reason))` when the spine does not
    /// arrive within the horizon ([`TRANSIENT_HORIZON_PERIODS`]) or cannot start (release not held).
    pub fn time_s(
        &self,
        event: TransientEvent,
        voltage_v: f64,
        external_force_n: f64,
    ) -> Result<Result<f64, String>, ActuatorError> {
        nonnegative("voltage", voltage_v)?;
        if !external_force_n.is_finite() {
            return Err(ActuatorError::InvalidField {
                field: "external_force_n".into(),
                value: external_force_n,
                expected: "a finite force".into(),
            });
        }
        let dynamics = self.dynamics()?;
        let scale = SimulationScale::new(self.mass_kg, self.actuator.stiffness_n_per_m());
        let xs = self.stop_travel_m;
        let traj = match event {
            TransientEvent::PullIn => {
                let drive = |x: f64| -> Option<f64> {
                    let f = self.net_force_n(x, voltage_v, external_force_n);
                    f.is_finite().then_some(f)
                };
                let damping = |x: f64| self.damping_n_s_per_m(x);
                let electrode = Some(self.actuator.plates.front_gap_m);
                integrate(&drive, &damping, xs, electrode, 0.0, voltage_v, scale, &dynamics, false, true)?
            }
            TransientEvent::Release => {
                if let Err(reason) = self.check_held(voltage_v, external_force_n) {
                    return Ok(Err(reason));
                }
                let drive = |y: f64| -> Option<f64> {
                    let f = -self.net_force_n(xs - y, 0.0, external_force_n);
                    f.is_finite().then_some(f)
                };
                let damping = |y: f64| self.damping_n_s_per_m(xs - y);
                let v0 = self.release_kick_m_per_s(voltage_v, external_force_n);
                integrate(&drive, &damping, xs, None, v0, 0.0, scale, &dynamics, false, true)?
            }
        };
        Ok(traj.time_to_stop_s.ok_or_else(|| {
            format!(
                "does not arrive within {TRANSIENT_HORIZON_PERIODS} natural periods ({:.3e} s): turns back or creeps",
                dynamics.max_time_s
            )
        }))
    }

    /// Reference: the same equation integrated with classical fixed-step RK4 of step `h` (s), the
    /// arrival located by cubic Hermite interpolation within the step. `None` when it does not
    /// arrive within the horizon. For the integration-error check only (no early decision).
    pub fn time_rk4_s(
        &self,
        event: TransientEvent,
        voltage_v: f64,
        external_force_n: f64,
        step_s: f64,
    ) -> Result<Option<f64>, ActuatorError> {
        positive("step", step_s)?;
        let horizon = TRANSIENT_HORIZON_PERIODS * self.period_s();
        if horizon / step_s > 1e8 {
            return Err(ActuatorError::InvalidField {
                field: "step".into(),
                value: step_s,
                expected: format!("at least {:e} s (1e8 steps)", horizon / 1e8),
            });
        }
        let xs = self.stop_travel_m;
        let m = self.mass_kg;
        // State in the event's own coordinate (towards the target is positive).
        let acc = |y: f64, v: f64| -> f64 {
            match event {
                TransientEvent::PullIn => {
                    (self.net_force_n(y, voltage_v, external_force_n) - self.damping_n_s_per_m(y) * v) / m
                }
                TransientEvent::Release => {
                    (-self.net_force_n(xs - y, 0.0, external_force_n) - self.damping_n_s_per_m(xs - y) * v) / m
                }
            }
        };
        if event == TransientEvent::Release && self.check_held(voltage_v, external_force_n).is_err() {
            return Ok(None);
        }
        let mut y = 0.0;
        let mut v = match event {
            TransientEvent::PullIn => 0.0,
            TransientEvent::Release => self.release_kick_m_per_s(voltage_v, external_force_n),
        };
        let h = step_s;
        let mut t = 0.0;
        while t < horizon {
            let (k1x, k1v) = (v, acc(y, v));
            let (k2x, k2v) = (v + 0.5 * h * k1v, acc(y + 0.5 * h * k1x, v + 0.5 * h * k1v));
            let (k3x, k3v) = (v + 0.5 * h * k2v, acc(y + 0.5 * h * k2x, v + 0.5 * h * k2v));
            let (k4x, k4v) = (v + h * k3v, acc(y + h * k3x, v + h * k3v));
            let y1 = y + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
            let v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            if !(y1.is_finite() && v1.is_finite()) {
                return Err(ActuatorError::Solver(format!("RK4 diverged at t = {t:e} s")));
            }
            if y1 >= xs {
                // Cubic Hermite on [t, t + h] through (y, v) and (y1, v1); bisection for the crossing.
                let p = |s: f64| {
                    let (s2, s3) = (s * s, s * s * s);
                    (2.0 * s3 - 3.0 * s2 + 1.0) * y
                        + (s3 - 2.0 * s2 + s) * h * v
                        + (-2.0 * s3 + 3.0 * s2) * y1
                        + (s3 - s2) * h * v1
                };
                let (mut a, mut b) = (0.0, 1.0);
                for _ in 0..60 {
                    let c = 0.5 * (a + b);
                    if p(c) >= xs {
                        b = c;
                    } else {
                        a = c;
                    }
                }
                return Ok(Some(t + 0.5 * (a + b) * h));
            }
            y = y1;
            v = v1;
            t += h;
        }
        Ok(None)
    }
}

/// Model beside measurement at one point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransientComparison {
    /// Drawn finger length (m).
    pub finger_length_m: f64,
    /// The event.
    pub event: TransientEvent,
    /// Step or hold voltage (V).
    pub voltage_v: f64,
    /// External force opposing closing (N).
    pub external_force_n: f64,
    /// Number of repeats.
    pub repeats: usize,
    /// Mean of the measured times (s).
    pub measured_mean_s: f64,
    /// Sample SD of the repeats (s).
    pub measured_sd_s: f64,
    /// Predicted time (s); `null` with `no_prediction` when the model does not arrive.
    pub predicted_s: Option<f64>,
    /// `predicted / measured_mean - 1`.
    pub rel_error: Option<f64>,
    /// Why there is no prediction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub no_prediction: Option<String>,
}

/// Error statistics of a group of points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransientErrors {
    /// The event.
    pub event: TransientEvent,
    /// Drawn finger length (m), `null` for all lengths together.
    pub finger_length_m: Option<f64>,
    /// Points in the group.
    pub points: usize,
    /// Points the model could not predict (excluded from the statistics below).
    pub unpredicted: usize,
    /// Mean of `|rel_error|` (`null` when no point of the group was predicted).
    pub mean_abs_rel_error: Option<f64>,
    /// Mean of `rel_error` (the sign shows the bias; `null` when none was predicted).
    pub mean_rel_error: Option<f64>,
    /// Root mean square of `predicted - measured_mean` (s; `null` when none was predicted).
    pub rmse_s: Option<f64>,
    /// Why a value is null: the group of all finger lengths, or no point of it predicted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

fn errors(points: &[&TransientComparison], event: TransientEvent, length: Option<f64>) -> TransientErrors {
    let ok: Vec<(f64, f64)> = points
        .iter()
        .filter_map(|p| p.predicted_s.map(|t| (t / p.measured_mean_s - 1.0, t - p.measured_mean_s)))
        .collect();
    let n = ok.len() as f64;
    // None for an empty group (0/0) and for a sum that is not finite.
    let mean = |f: &dyn Fn(&(f64, f64)) -> f64| {
        (!ok.is_empty()).then(|| ok.iter().map(f).sum::<f64>() / n).filter(|v| v.is_finite())
    };
    TransientErrors {
        event,
        finger_length_m: length,
        points: points.len(),
        unpredicted: points.len() - ok.len(),
        mean_abs_rel_error: mean(&|e| e.0.abs()),
        mean_rel_error: mean(&|e| e.0),
        rmse_s: mean(&|e| e.1 * e.1).map(f64::sqrt),
        note: match (length.is_none(), ok.is_empty()) {
            (false, false) => None,
            (true, false) => Some("finger_length_m is null: the group of all finger lengths together".into()),
            (false, true) => Some("no point of this group was predicted (the model never switches there)".into()),
            (true, true) => {
                Some("finger_length_m is null: all finger lengths together; no point of the group was predicted".into())
            }
        },
    }
}

/// The comparison of a spec's transient model with measured times.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransientReport {
    /// The switches used.
    pub physics: TransientPhysics,
    /// Mean |relative error| of the pull-in times (over predicted points; `null` if none).
    pub pull_in_time_mean_abs_rel_error: Option<f64>,
    /// Mean |relative error| of the release times.
    pub release_time_mean_abs_rel_error: Option<f64>,
    /// RMSE of the pull-in times (s).
    pub pull_in_time_rmse_s: Option<f64>,
    /// RMSE of the release times (s).
    pub release_time_rmse_s: Option<f64>,
    /// Why an overall error is null: no point of that event was predicted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Per event over all lengths, then per event and length.
    pub errors: Vec<TransientErrors>,
    /// Every point.
    pub points: Vec<TransientComparison>,
}

/// Simulates every measured point with the spec (its `overlap_length` replaced by each point's
/// drawn finger length; models built once per length) and compares.
pub fn compare_transients(
    spec: &ArraySpec,
    physics: TransientPhysics,
    data: &[MeasuredTransient],
) -> Result<TransientReport, ActuatorError> {
    if data.is_empty() {
        return Err(ActuatorError::NotAvailable("no measured points".into()));
    }
    let mut models: Vec<(u64, TransientModel)> = Vec::new();
    let mut points = Vec::with_capacity(data.len());
    for d in data {
        let key = d.finger_length_m.to_bits();
        let i = match models.iter().position(|(k, _)| *k == key) {
            Some(i) => i,
            None => {
                let mut s = spec.clone();
                s.overlap_length = d.finger_length_m;
                let m = TransientModel::from_spec(&s, physics).map_err(|e| {
                    ActuatorError::Inconsistent(format!("finger length {:e} m: {e}", d.finger_length_m))
                })?;
                models.push((key, m));
                models.len() - 1
            }
        };
        let model = &models[i].1;
        let (predicted_s, no_prediction) = match model.time_s(d.event, d.voltage_v, d.external_force_n)? {
            Ok(t) => (Some(t), None),
            Err(r) => (None, Some(r)),
        };
        let mean = d.mean_s();
        points.push(TransientComparison {
            finger_length_m: d.finger_length_m,
            event: d.event,
            voltage_v: d.voltage_v,
            external_force_n: d.external_force_n,
            repeats: d.times_s.len(),
            measured_mean_s: mean,
            measured_sd_s: d.sd_s(),
            predicted_s,
            rel_error: predicted_s.map(|t| t / mean - 1.0),
            no_prediction,
        });
    }
    let mut lengths: Vec<f64> = points.iter().map(|p| p.finger_length_m).collect();
    lengths.sort_by(f64::total_cmp);
    lengths.dedup();
    let mut all = Vec::new();
    for event in [TransientEvent::PullIn, TransientEvent::Release] {
        let group: Vec<&TransientComparison> = points.iter().filter(|p| p.event == event).collect();
        if !group.is_empty() {
            all.push(errors(&group, event, None));
        }
    }
    for event in [TransientEvent::PullIn, TransientEvent::Release] {
        for &l in &lengths {
            let group: Vec<&TransientComparison> =
                points.iter().filter(|p| p.event == event && p.finger_length_m == l).collect();
            if !group.is_empty() {
                all.push(errors(&group, event, Some(l)));
            }
        }
    }
    let overall = |event: TransientEvent| all.iter().find(|e| e.event == event && e.finger_length_m.is_none());
    Ok(TransientReport {
        physics,
        pull_in_time_mean_abs_rel_error: overall(TransientEvent::PullIn).and_then(|e| e.mean_abs_rel_error),
        release_time_mean_abs_rel_error: overall(TransientEvent::Release).and_then(|e| e.mean_abs_rel_error),
        pull_in_time_rmse_s: overall(TransientEvent::PullIn).and_then(|e| e.rmse_s),
        release_time_rmse_s: overall(TransientEvent::Release).and_then(|e| e.rmse_s),
        note: [TransientEvent::PullIn, TransientEvent::Release]
            .iter()
            .any(|ev| overall(*ev).and_then(|e| e.rmse_s).is_none())
            .then(|| "an overall error is null where no point of that event was predicted (or measured)".to_string()),
        errors: all,
        points,
    })
}

/// Effect of one ingredient on the time errors.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TransientSwitchEffect {
    /// What was changed from the spec and the default physics.
    pub switch: String,
    /// Pull-in mean |rel. error|.
    pub pull_in_time_mean_abs_rel_error: Option<f64>,
    /// Release mean |rel. error|.
    pub release_time_mean_abs_rel_error: Option<f64>,
    /// Pull-in mean signed rel. error.
    pub pull_in_time_mean_rel_error: Option<f64>,
    /// Release mean signed rel. error.
    pub release_time_mean_rel_error: Option<f64>,
    /// Points without a prediction.
    pub unpredicted: usize,
}

/// Runs [`compare_transients`] with each ingredient changed, one at a time, from `spec` and
/// `physics`: the damping terms, the beam mass, the release kick, fringing off, no back electrode,
/// no stop contact standoff, and the undercut +/- 0.1 um (a sensitivity, not a fit).
pub fn transient_switch_effects(
    spec: &ArraySpec,
    physics: TransientPhysics,
    data: &[MeasuredTransient],
) -> Result<Vec<TransientSwitchEffect>, ActuatorError> {
    let mut variants: Vec<(String, ArraySpec, TransientPhysics)> = vec![("as specified".into(), spec.clone(), physics)];
    let mut with = |name: &str, f: &dyn Fn(&mut TransientPhysics)| {
        let mut p = physics;
        f(&mut p);
        if p != physics {
            variants.push((name.into(), spec.clone(), p));
        }
    };
    with("no back-gap squeeze film", &|p| p.back_film = false);
    with("no rarefaction (bulk viscosity)", &|p| p.rarefaction = false);
    with("long-strip film (no finite-aspect factor)", &|p| p.finite_aspect = false);
    with("no Couette shear", &|p| p.couette = false);
    with("no beam mass", &|p| p.beam_mass = false);
    if spec.finger_bending.is_some() {
        with("release kick: elastic energy of fingers and spine", &|p| p.release_kick = ReleaseKick::ElasticEnergy);
        with("no release kick", &|p| p.release_kick = ReleaseKick::None);
    }
    if spec.fringing != crate::plates::Fringing::Off {
        let mut s = spec.clone();
        s.fringing = crate::plates::Fringing::Off;
        variants.push(("fringing off".into(), s, physics));
    }
    if spec.back_gap.is_some() {
        let mut s = spec.clone();
        s.back_gap = None;
        variants.push(("no back electrode (force and film)".into(), s, physics));
    }
    if spec.stop.as_ref().is_some_and(|s| s.contact_standoff > 0.0) {
        let mut s = spec.clone();
        if let Some(st) = s.stop.as_mut() {
            st.contact_standoff = 0.0;
        }
        variants.push(("no stop contact standoff".into(), s, physics));
    }
    for du in [-0.1e-6, 0.1e-6] {
        let mut s = spec.clone();
        s.undercut = (s.undercut + du).max(0.0);
        variants.push((format!("undercut {:+.1} um", du * 1e6), s, physics));
    }
    let mut out = Vec::with_capacity(variants.len());
    for (name, s, p) in variants {
        let r = compare_transients(&s, p, data)?;
        let get = |event: TransientEvent| r.errors.iter().find(|e| e.event == event && e.finger_length_m.is_none());
        out.push(TransientSwitchEffect {
            switch: name,
            pull_in_time_mean_abs_rel_error: r.pull_in_time_mean_abs_rel_error,
            release_time_mean_abs_rel_error: r.release_time_mean_abs_rel_error,
            pull_in_time_mean_rel_error: get(TransientEvent::PullIn).and_then(|e| e.mean_rel_error),
            release_time_mean_rel_error: get(TransientEvent::Release).and_then(|e| e.mean_rel_error),
            unpredicted: r.errors.iter().filter(|e| e.finger_length_m.is_none()).map(|e| e.unpredicted).sum(),
        });
    }
    Ok(out)
}
