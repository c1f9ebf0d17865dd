//! Dynamics of the slip event (paper section 5): once the static friction of the shoe is exceeded the
//! pull array is no longer held at its rest position and the shuttle (moving part of the pull array
//! plus the shoe) accelerates under a *step* of the pull voltage `V`:
//!
//! `m x'' = F_e(x, V) - k x - c x' - F_k sgn(x')`,   `x(0) = 0`, `x'(0) = 0`
//!
//! with `F_e` the electrostatic force of the pull array ([`GapClosingActuator::electrostatic_force_n`]),
//! `k x` its suspension, `c` an air-damping coefficient (see [`squeeze_film_damping_n_s_per_m`] and
//! [`couette_damping_n_s_per_m`] for estimates) and `F_k` the kinetic friction force on the shoe
//! (`mu_k L` or a given force). The motion ends when the shuttle hits the pull array's gap stop (or,
//! without a stop, when the plates close to [`SlipDynamics::contact_gap_m`]): the array *runs away*
//! (dynamic pull-in). Otherwise it turns back at a travel short of the stop and oscillates or
//! settles.
//!
//! The equation is integrated by rapier (`rapier3d-f64`): the shuttle is a dynamic rigid body whose
//! rotations and y/z translations are locked (a prismatic guide along x), sleeping is off, gravity
//! zero; the gap stop is a fixed cuboid collider. Each step the force `F_e(x, V) - k x` (evaluated at
//! the predicted mid-step travel `x + v dt/2`) plus the Coulomb friction is applied as the body's user
//! force (reset every step); damping is rapier's linear damping `c/m` (applied implicitly,
//! `v <- v/(1 + dt c/m)`). The impact is located inside its step from the step's initial state;
//! rapier's speculative-contact and CCD margins are made negligible so that they do not brake the
//! shuttle before it touches.
//!
//! **Scaling.** Rapier's tolerances are tuned for bodies of metres and seconds with masses and
//! forces of order one. The simulation therefore runs in scaled units (see [`SimulationScale`]):
//! one simulation metre is one micrometre (`L0 = 1 um`), the unit of mass is the shuttle mass
//! (`M0 = m`, the body has mass 1), the unit of time is the inverse natural angular frequency
//! `T0 = sqrt(m/k)` (spring stiffness 1), hence the unit of force is `F0 = M0 L0/T0^2 = k L0` and
//! the damping rate is `c T0/m = 2 zeta`. Travel, times and forces are then all of order one.
//! Every value crossing the boundary is converted with the same scale.

use rapier3d_f64::prelude::{
    ColliderBuilder, ColliderHandle, IntegrationParameters, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle,
};
use serde::{Deserialize, Serialize};

use crate::actuator::GapClosingActuator;
use crate::error::{ActuatorError, nonnegative, positive};
use crate::plates::PlateArray;

/// Density of polysilicon (kg/m^3), the structural material of the friction meter.
pub const POLYSILICON_DENSITY_KG_PER_M3: f64 = 2330.0;

/// Dynamic viscosity of air at 20 degC and 1 atm (Pa s).
pub const AIR_VISCOSITY_PA_S: f64 = 1.81e-5;

/// Largest number of time steps a single simulation may take (guards against a time step far too
/// small for the requested duration).
pub const MAX_STEPS: f64 = 1.0e8;

/// Mass of the sliding shuttle (kg): `m = rho (V_pull + V_shoe)`, the moving part of the pull array
/// (plates, spine, suspension share) plus the shoe, volumes in m^3 and density in kg/m^3
/// ([`POLYSILICON_DENSITY_KG_PER_M3`] for polysilicon).
pub fn shuttle_mass_kg(
    pull_array_moving_volume_m3: f64,
    shoe_volume_m3: f64,
    density_kg_per_m3: f64,
) -> Result<f64, ActuatorError> {
    positive("pull_array_moving_volume", pull_array_moving_volume_m3)?;
    nonnegative("shoe_volume", shoe_volume_m3)?;
    positive("density", density_kg_per_m3)?;
    Ok(density_kg_per_m3 * (pull_array_moving_volume_m3 + shoe_volume_m3))
}

/// Squeeze-film damping coefficient of a gap-closing plate array at rest (N s/m), incompressible
/// Reynolds equation for long rectangular plates (length `l` much larger than the width through
/// which the air escapes, here the structural thickness `t`):
/// `c = n mu l t^3 (1/g_f^3 + 1/g_b^3)` (Senturia, *Microsystem Design*, sec. 13.4; the back gap term
/// only with a back electrode). It grows as `1/(g_f - x)^3` with the travel; this value at `x = 0`
/// is a lower bound during the slip. Rarefaction (Knudsen number `lambda/g`, about 0.02 for a 3 um
/// gap) lowers it by some 10 %.
pub fn squeeze_film_damping_n_s_per_m(plates: &PlateArray, viscosity_pa_s: f64) -> Result<f64, ActuatorError> {
    plates.validate()?;
    positive("viscosity", viscosity_pa_s)?;
    let per_gap = |g: f64| viscosity_pa_s * plates.overlap_length_m * plates.thickness_m.powi(3) / g.powi(3);
    let mut c = per_gap(plates.front_gap_m);
    if let Some(b) = plates.back {
        c += per_gap(b.gap_m);
    }
    Ok(f64::from(plates.plate_count) * c)
}

/// Couette (slide-film) damping of a plate of area `A` moving parallel to the substrate at a height
/// `d` (N s/m): `c = mu A / d` (linear shear profile, continuum regime).
pub fn couette_damping_n_s_per_m(viscosity_pa_s: f64, area_m2: f64, gap_m: f64) -> Result<f64, ActuatorError> {
    positive("viscosity", viscosity_pa_s)?;
    positive("area", area_m2)?;
    positive("gap", gap_m)?;
    Ok(viscosity_pa_s * area_m2 / gap_m)
}

/// Density of single-crystal silicon (kg/m^3), the device layer of SOI actuators.
pub const SILICON_DENSITY_KG_PER_M3: f64 = 2329.0;

/// Mean free path of air molecules at 20 degC and 1 atm (m), about 68 nm (it scales as `1/p`).
pub const AIR_MEAN_FREE_PATH_M: f64 = 68e-9;

/// Standard atmospheric pressure (Pa).
pub const ATMOSPHERIC_PRESSURE_PA: f64 = 101_325.0;

/// Effective viscosity of a gas film of thickness `h` with rarefaction (Pa s), Veijola et al.'s
/// fit for the squeeze film (T. Veijola, H. Kuisma, J. Lahdenpera, T. Ryhanen, Sensors and
/// Actuators A 48, 239-248, 1995): `mu_eff = mu / (1 + 9.638 Kn^1.159)`, `Kn = lambda / h`, within
/// 5 % of the Fukui-Kaneko Boltzmann solution for `0 < Kn < 880`. Continuum limit `Kn -> 0`:
/// `mu`. For air at 1 atm and `h = 5.6 um` (`Kn = 0.012`) it is `mu / 1.057`; at `h = 1.1 um`
/// (`Kn = 0.06`) `mu / 1.37`.
pub fn veijola_effective_viscosity_pa_s(
    viscosity_pa_s: f64,
    mean_free_path_m: f64,
    film_thickness_m: f64,
) -> Result<f64, ActuatorError> {
    positive("viscosity", viscosity_pa_s)?;
    nonnegative("mean_free_path", mean_free_path_m)?;
    positive("film_thickness", film_thickness_m)?;
    let kn = mean_free_path_m / film_thickness_m;
    Ok(viscosity_pa_s / (1.0 + 9.638 * kn.powf(1.159)))
}

/// Aspect-ratio factor of the incompressible squeeze film of a rectangular plate with all four
/// edges at ambient pressure, `beta(eta) = 1 - (192/pi^5) eta sum_{n odd} tanh(n pi/(2 eta))/n^5`,
/// `eta = b/a <= 1` (short over long side); `beta(0) = 1` (long strip), `beta(1) = 0.4218`
/// (square). Series of the Reynolds equation's exact solution (W. S. Griffin, H. H. Richardson,
/// S. Yamanami, J. Basic Eng. 88, 451, 1966; Senturia, *Microsystem Design*, sec. 13.4), summed
/// to `n = 199`.
pub fn squeeze_film_aspect_factor(eta: f64) -> f64 {
    let eta = eta.clamp(0.0, 1.0);
    if eta == 0.0 {
        return 1.0;
    }
    let sum: f64 = (0..100)
        .map(|i| {
            let n = f64::from(2 * i + 1);
            (n * std::f64::consts::PI / (2.0 * eta)).tanh() / n.powi(5)
        })
        .sum();
    1.0 - 192.0 / std::f64::consts::PI.powi(5) * eta * sum
}

/// Incompressible squeeze-film damping of one rectangular plate `a x b` closing a gap `h` with all
/// edges open (N s/m), with `s = min(a, b)` the escape length and
/// `L = max(a, b)`: `c = mu L s^3 / h^3 beta(s/L)` ([`squeeze_film_aspect_factor`]); the long-strip
/// limit `mu L s^3/h^3` is the one used by [`squeeze_film_damping_n_s_per_m`]. Valid for a squeeze
/// number `12 mu omega s^2 / (p h^2) << 1` ([`squeeze_number`]); `mu` may be the rarefied
/// effective viscosity ([`veijola_effective_viscosity_pa_s`]).
pub fn rectangular_squeeze_film_damping_n_s_per_m(
    viscosity_pa_s: f64,
    side_a_m: f64,
    side_b_m: f64,
    gap_m: f64,
) -> Result<f64, ActuatorError> {
    positive("viscosity", viscosity_pa_s)?;
    positive("side_a", side_a_m)?;
    positive("side_b", side_b_m)?;
    positive("gap", gap_m)?;
    let (short, long) = (side_a_m.min(side_b_m), side_a_m.max(side_b_m));
    Ok(viscosity_pa_s * long * short.powi(3) / gap_m.powi(3) * squeeze_film_aspect_factor(short / long))
}

/// Squeeze number of a film (dimensionless), `sigma = 12 mu omega s^2 / (p h^2)` with `s` the
/// shorter plate side (the escape length), `h` the gap, `omega` the angular frequency (rad/s) and
/// `p` the ambient pressure. `sigma << 1` (below about 1): the gas escapes before it is compressed,
/// the film is a pure (incompressible) damper; `sigma >> 1`: it acts as a spring.
pub fn squeeze_number(
    viscosity_pa_s: f64,
    angular_frequency_rad_per_s: f64,
    escape_length_m: f64,
    gap_m: f64,
    pressure_pa: f64,
) -> Result<f64, ActuatorError> {
    positive("viscosity", viscosity_pa_s)?;
    nonnegative("angular_frequency", angular_frequency_rad_per_s)?;
    positive("escape_length", escape_length_m)?;
    positive("gap", gap_m)?;
    positive("pressure", pressure_pa)?;
    Ok(12.0 * viscosity_pa_s * angular_frequency_rad_per_s * escape_length_m.powi(2) / (pressure_pa * gap_m.powi(2)))
}

/// Parameters of the slip dynamics (SI units).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SlipDynamics {
    /// Mass of the shuttle `m` (kg), see [`shuttle_mass_kg`].
    pub shuttle_mass_kg: f64,
    /// Viscous (air) damping coefficient `c` (N s/m), 0 for none.
    pub damping_n_s_per_m: f64,
    /// Kinetic friction force on the sliding shoe `F_k` (N), e.g. `mu_k L`; 0 for none.
    pub kinetic_friction_n: f64,
    /// Time step `dt` (s); see [`SlipDynamics::with_defaults`] for a choice.
    pub time_step_s: f64,
    /// Longest simulated time (s).
    pub max_time_s: f64,
    /// Without a gap stop: the residual front gap `g_f - x` (m) at which the plates are taken to
    /// touch (native oxide, roughness). The parallel-plate force diverges as `1/(g_f - x)^2`, so the
    /// impact velocity depends on it. Ignored when the actuator has a stop.
    pub contact_gap_m: f64,
}

/// Number of time steps per undamped natural period `2 pi sqrt(m/k)` chosen by
/// [`SlipDynamics::with_defaults`].
pub const DEFAULT_STEPS_PER_PERIOD: f64 = 2000.0;

/// Simulated duration, in undamped natural periods, chosen by [`SlipDynamics::with_defaults`].
pub const DEFAULT_PERIODS: f64 = 20.0;

impl SlipDynamics {
    /// Parameters with a time step of `T/2000` and a duration of `20 T`, `T = 2 pi sqrt(m/k)` the
    /// undamped natural period of the shuttle on the pull spring, and a contact gap of 1 % of the
    /// front gap (used only without a stop).
    pub fn with_defaults(
        pull: &GapClosingActuator,
        shuttle_mass_kg: f64,
        damping_n_s_per_m: f64,
        kinetic_friction_n: f64,
    ) -> Result<Self, ActuatorError> {
        positive("shuttle_mass", shuttle_mass_kg)?;
        pull.validate()?;
        let period = 2.0 * std::f64::consts::PI * (shuttle_mass_kg / pull.stiffness_n_per_m()).sqrt();
        let out = Self {
            shuttle_mass_kg,
            damping_n_s_per_m,
            kinetic_friction_n,
            time_step_s: period / DEFAULT_STEPS_PER_PERIOD,
            max_time_s: DEFAULT_PERIODS * period,
            contact_gap_m: 0.01 * pull.plates.front_gap_m,
        };
        out.validate()?;
        Ok(out)
    }

    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        positive("shuttle_mass", self.shuttle_mass_kg)?;
        nonnegative("damping", self.damping_n_s_per_m)?;
        nonnegative("kinetic_friction", self.kinetic_friction_n)?;
        positive("time_step", self.time_step_s)?;
        positive("max_time", self.max_time_s)?;
        positive("contact_gap", self.contact_gap_m)?;
        if self.max_time_s < self.time_step_s {
            return Err(ActuatorError::InvalidField {
                field: "max_time".into(),
                value: self.max_time_s,
                expected: format!("at least one time step ({:e} s)", self.time_step_s),
            });
        }
        if self.max_time_s / self.time_step_s > MAX_STEPS {
            return Err(ActuatorError::InvalidField {
                field: "time_step".into(),
                value: self.time_step_s,
                expected: format!("at least max_time / {MAX_STEPS:e} = {:e} s", self.max_time_s / MAX_STEPS),
            });
        }
        Ok(())
    }
}

/// The unit system of the rapier simulation (see the module docs): lengths in `L0`, masses in
/// `M0`, times in `T0`; forces in `F0 = M0 L0 / T0^2`, velocities in `L0/T0`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SimulationScale {
    /// Length unit `L0` (m): 1 um.
    pub length_m: f64,
    /// Mass unit `M0` (kg): the shuttle mass.
    pub mass_kg: f64,
    /// Time unit `T0 = sqrt(m/k)` (s).
    pub time_s: f64,
}

impl SimulationScale {
    /// The scale for a shuttle of mass `m` (kg) on a spring `k` (N/m): `L0 = 1 um`, `M0 = m`,
    /// `T0 = sqrt(m/k)`.
    pub fn new(shuttle_mass_kg: f64, stiffness_n_per_m: f64) -> Self {
        Self { length_m: 1e-6, mass_kg: shuttle_mass_kg, time_s: (shuttle_mass_kg / stiffness_n_per_m).sqrt() }
    }

    /// Force unit `F0 = M0 L0 / T0^2` (N), equal to `k L0`.
    pub fn force_n(&self) -> f64 {
        self.mass_kg * self.length_m / (self.time_s * self.time_s)
    }

    /// Velocity unit `L0 / T0` (m/s).
    pub fn velocity_m_per_s(&self) -> f64 {
        self.length_m / self.time_s
    }
}

/// Result of a slip simulation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SlipTrajectory {
    /// The step voltage (V).
    pub voltage_v: f64,
    /// Whether the shuttle reached the stop (or the plates closed): dynamic pull-in.
    pub runs_away: bool,
    /// Travel at which the motion ends on the stop (m): the stop travel, or `g_f - contact_gap`.
    pub stop_travel_m: f64,
    /// Time from the slip to the impact on the stop (s), `None` when it does not run away.
    pub time_to_stop_s: Option<f64>,
    /// Velocity at the impact (m/s), `None` when it does not run away.
    pub impact_velocity_m_per_s: Option<f64>,
    /// Largest travel reached (m): the stop travel after a runaway, else the first turning point.
    pub max_travel_m: f64,
    /// Travel at the end of the simulation (m).
    pub final_travel_m: f64,
    /// True when the motion ended because kinetic friction holds the shuttle at rest (it sticks
    /// again) before `max_time`.
    pub stuck_again: bool,
    /// Travel history `(t (s), x (m), v (m/s))`, one sample per time step from `t = 0` (steps are
    /// `time_step` long, shortened near the electrode so that one step closes at most 1 % of the
    /// remaining front gap, and to end at `max_time`); after a
    /// runaway the last sample is the impact (interpolated within its step).
    pub samples: Vec<(f64, f64, f64)>,
    /// The simulation's unit system.
    pub scale: SimulationScale,
}

/// Where the travel ends in contact: the gap stop or, without one, `g_f - contact_gap`.
fn contact_travel_m(pull: &GapClosingActuator, dynamics: &SlipDynamics) -> Result<f64, ActuatorError> {
    match pull.stop_travel_m {
        Some(s) => Ok(s),
        None => {
            let g = pull.plates.front_gap_m;
            if dynamics.contact_gap_m >= g {
                return Err(ActuatorError::InvalidField {
                    field: "contact_gap".into(),
                    value: dynamics.contact_gap_m,
                    expected: format!("smaller than the front gap {g:e} m"),
                });
            }
            Ok(g - dynamics.contact_gap_m)
        }
    }
}

/// Simulates the slip of the shuttle under a step of the pull voltage `V` (V) applied at `t = 0`
/// from rest at `x = 0`: `m x'' = F_e(x, V) - k x - c x' - F_k sgn(x')` integrated by rapier until
/// the shuttle hits the stop (runaway), sticks again, or `max_time` passes. Errors: invalid
/// parameters (named), or `max_time` too short to decide the outcome (still moving towards the
/// stop). See the module docs for the model and the scaling.
pub fn simulate_slip(
    pull: &GapClosingActuator,
    voltage_v: f64,
    dynamics: &SlipDynamics,
) -> Result<SlipTrajectory, ActuatorError> {
    let c = dynamics.damping_n_s_per_m;
    run(pull, voltage_v, dynamics, &|_| c, true, false)
}

/// Dynamic pull-in voltage for a step input (V): the lowest step voltage at which the shuttle,
/// released from rest at `x = 0`, reaches the stop (or the plates close). Bisection on the voltage
/// with [`simulate_slip`] (each run stops as soon as the outcome is known), relative tolerance
/// `1e-6`. A shuttle still creeping towards the stop at `max_time` (heavy damping just above the
/// static pull-in voltage, where the passage past the vanished equilibrium is slow) counts as not
/// running away: the result is the pull-in voltage *within* `max_time`.
/// For a parallel-plate array on a linear spring without damping, friction or stop the closed form is
/// `V_dyn = sqrt(27/32) V_pi` (travel `g/2` at the threshold); damping raises it towards `V_pi`,
/// friction raises it further.
pub fn dynamic_pull_in_voltage(pull: &GapClosingActuator, dynamics: &SlipDynamics) -> Result<f64, ActuatorError> {
    let c = dynamics.damping_n_s_per_m;
    dynamic_pull_in_voltage_with_damping_law(pull, dynamics, &|_| c)
}

/// [`dynamic_pull_in_voltage`] with a damping coefficient that depends on the travel,
/// `c(x)` (N s/m at travel `x` in m; e.g. the squeeze film `~ 1/(g_f - x)^3`), instead of the
/// constant [`SlipDynamics::damping_n_s_per_m`] (ignored here):
/// `m x'' = F_e(x, V) - k x - c(x) x' - F_k sgn(x')`. The damping rate of the rapier body is set
/// every step from `c` at the predicted mid-step travel. `c(x)` must be finite and `>= 0` on
/// `[0, x_c]` (checked at every step).
pub fn dynamic_pull_in_voltage_with_damping_law(
    pull: &GapClosingActuator,
    dynamics: &SlipDynamics,
    damping_n_s_per_m: &dyn Fn(f64) -> f64,
) -> Result<f64, ActuatorError> {
    dynamics.validate()?;
    let static_pi = pull.pull_in()?.voltage_v;
    let reaches = |v: f64| -> Result<bool, ActuatorError> {
        Ok(run(pull, v, dynamics, damping_n_s_per_m, false, true)?.runs_away)
    };
    // Just above the static pull-in (exactly at it the shuttle creeps into the saddle-node forever).
    let mut hi = 1.01 * static_pi;
    let mut doublings = 0;
    while !reaches(hi)? {
        hi *= 2.0;
        doublings += 1;
        if doublings > 20 {
            return Err(ActuatorError::Solver(format!(
                "no runaway up to {hi:e} V (kinetic friction {:e} N too large?)",
                dynamics.kinetic_friction_n
            )));
        }
    }
    let mut lo = 0.0;
    while hi - lo > 1e-6 * hi {
        let m = 0.5 * (lo + hi);
        if reaches(m)? {
            hi = m;
        } else {
            lo = m;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// Undamped dynamic pull-in voltage from the energy balance (V), rigid plates only: with no damping
/// the shuttle released at `x = 0` reaches the stop `x_c` iff the work of the forces stays positive
/// on the way, `W(x) = V^2 [C(x) - C(0)]/2 - k x^2/2 - F_k x > 0` for `0 < x <= x_c`, so
/// `V_dyn^2 = max_x (k x^2/2 + F_k x) / ([C(x) - C(0)]/2)` (scan of 2000 points + golden section).
/// Parallel plates, no stop, no friction: `x = g/2`, `V_dyn^2 = k g^3/(4 n eps A) = (27/32) V_pi^2`.
pub fn undamped_dynamic_pull_in_voltage_v(
    pull: &GapClosingActuator,
    kinetic_friction_n: f64,
    contact_gap_m: f64,
) -> Result<f64, ActuatorError> {
    pull.validate()?;
    nonnegative("kinetic_friction", kinetic_friction_n)?;
    if pull.bending.is_some() {
        return Err(ActuatorError::NotAvailable(
            "the energy criterion needs rigid plates (F_e = f(x) V^2); use dynamic_pull_in_voltage".into(),
        ));
    }
    let probe = SlipDynamics {
        shuttle_mass_kg: 1.0,
        damping_n_s_per_m: 0.0,
        kinetic_friction_n,
        time_step_s: 1.0,
        max_time_s: 1.0,
        contact_gap_m,
    };
    positive("contact_gap", contact_gap_m)?;
    let xc = contact_travel_m(pull, &probe)?;
    let c0 = pull.plates.capacitance_f(0.0);
    let k = pull.stiffness_n_per_m();
    let v2 = |x: f64| (0.5 * k * x * x + kinetic_friction_n * x) / (0.5 * (pull.plates.capacitance_f(x) - c0));
    const N: usize = 2000;
    let at = |i: usize| xc * i as f64 / N as f64;
    let mut best = (N, v2(xc));
    for i in 1..N {
        let vi = v2(at(i));
        if vi > best.1 {
            best = (i, vi);
        }
    }
    if best.0 == N {
        return Ok(best.1.sqrt());
    }
    let (mut a, mut b) = (at(best.0 - 1).max(1e-3 * at(1)), at(best.0 + 1));
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if v2(c) > v2(d) {
            b = d;
        } else {
            a = c;
        }
        if b - a < 1e-14 * xc {
            break;
        }
    }
    Ok(v2(0.5 * (a + b)).max(best.1).sqrt())
}

/// The rapier world of one simulation.
struct World {
    world: PhysicsWorld,
    shuttle: RigidBodyHandle,
    shuttle_collider: ColliderHandle,
    stop_collider: ColliderHandle,
}

/// Half size of the shuttle's and the stop's cuboid colliders (simulation units, i.e. 0.5 um); their
/// faces are `x_c` apart at rest.
const HALF_SIZE: f64 = 0.5;

impl World {
    fn new(dt: f64, damping_rate: f64, contact_travel: f64) -> Self {
        use rapier3d_f64::math::Vector;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        world.integration_parameters = IntegrationParameters {
            dt,
            length_unit: 1.0,
            // A physics engine for games clamps speeds (400 length units per time unit); here the
            // speed is physics, never clamp it.
            normalized_max_linear_velocity: f64::MAX,
            // Speculative contacts (default: from 0.02 length units = 20 nm away) and the CCD clamp
            // (standoff 0.005 units) act on the shuttle a step or more before it touches and would
            // bias the impact velocity. The impact is an event of the model, located inside the
            // step from the step's initial state, so both margins are made negligible (1e-9 units,
            // 1 fm) and CCD is off: the stop collider only catches the shuttle after the impact.
            normalized_allowed_linear_error: 1e-9,
            normalized_prediction_distance: 1e-9,
            max_ccd_substeps: 0,
            ..IntegrationParameters::default()
        };
        let body = RigidBodyBuilder::dynamic()
            .enabled_translations(true, false, false)
            .lock_rotations()
            .can_sleep(false)
            .linear_damping(damping_rate)
            .additional_mass(1.0);
        let collider =
            ColliderBuilder::cuboid(HALF_SIZE, HALF_SIZE, HALF_SIZE).density(0.0).friction(0.0).restitution(0.0);
        let (shuttle, shuttle_collider) = world.insert(body, collider);
        let stop = RigidBodyBuilder::fixed().translation(Vector::new(contact_travel + 2.0 * HALF_SIZE, 0.0, 0.0));
        let stop_shape = ColliderBuilder::cuboid(HALF_SIZE, HALF_SIZE, HALF_SIZE).friction(0.0).restitution(0.0);
        let (_, stop_collider) = world.insert(stop, stop_shape);
        Self { world, shuttle, shuttle_collider, stop_collider }
    }

    /// Position and velocity along x (simulation units).
    fn state(&self) -> (f64, f64) {
        let b = &self.world.bodies[self.shuttle];
        (b.translation().x, b.linvel().x)
    }

    /// Applies the force `f` (simulation units) for the next step and advances.
    fn step(&mut self, force: f64) {
        use rapier3d_f64::math::Vector;
        let b = &mut self.world.bodies[self.shuttle];
        b.reset_forces(false);
        b.add_force(Vector::new(force, 0.0, 0.0), false);
        self.world.step();
    }

    /// Whether the stop pushed back on the shuttle during the last step.
    fn hit_stop(&self) -> bool {
        self.world
            .narrow_phase
            .contact_pair(self.shuttle_collider, self.stop_collider)
            .is_some_and(|p| p.has_any_active_contact() && p.total_impulse_magnitude() > 0.0)
    }
}

/// Work of the non-dissipative forces minus the kinetic friction along the forward path (scaled
/// units, mass 1): `Phi(y) = int_0^y (F_e - k s - F_k) ds` on a grid of the travel `[0, x_c]`
/// (trapezoid rule, 4000 intervals). Moving forward from `x` with kinetic energy `K` the shuttle can
/// only reach `y` if `K + Phi(y) - Phi(x) >= 0` (damping and friction only remove energy), so the
/// stop is out of reach when `K < Phi(x) - min_{y >= x} Phi(y)`.
struct WorkTable {
    step: f64,
    work: Vec<f64>,
    /// `min_{j >= i} work[j]`.
    suffix_min: Vec<f64>,
    /// Rounding margin on the energy comparison.
    margin: f64,
}

impl WorkTable {
    const N: usize = 4000;

    fn new(drive: &impl Fn(f64) -> Option<f64>, contact_travel: f64, friction: f64) -> Self {
        let step = contact_travel / Self::N as f64;
        let mut work: Vec<f64> = Vec::with_capacity(Self::N + 1);
        work.push(0.0);
        let mut prev = drive(0.0);
        for i in 1..=Self::N {
            let f = drive(i as f64 * step);
            let last = work[i - 1];
            work.push(match (prev, f) {
                // Beyond a finger collapse the force is unbounded: no barrier there.
                (Some(a), Some(b)) if last.is_finite() => last + 0.5 * step * (a + b) - friction * step,
                _ => f64::INFINITY,
            });
            prev = f;
        }
        let mut suffix_min = work.clone();
        for i in (0..Self::N).rev() {
            suffix_min[i] = suffix_min[i].min(suffix_min[i + 1]);
        }
        let scale = work.iter().filter(|w| w.is_finite()).fold(0.0f64, |m, w| m.max(w.abs()));
        Self { step, work, suffix_min, margin: 1e-9 * scale.max(f64::MIN_POSITIVE) }
    }

    /// True when kinetic energy `kinetic` at travel `x` cannot carry the shuttle to the stop.
    fn blocks(&self, x: f64, kinetic: f64) -> bool {
        let u = (x / self.step).max(0.0);
        let i = (u.floor() as usize).min(Self::N - 1);
        let frac = (u - i as f64).min(1.0);
        let here = self.work[i] + frac * (self.work[i + 1] - self.work[i]);
        let ahead = self.suffix_min[(i + 1).min(Self::N)];
        here.is_finite() && kinetic + self.margin < here - ahead
    }
}

/// Core of [`simulate_slip`] and [`dynamic_pull_in_voltage`]. `record`: keep the samples;
/// `decide_only`: stop as soon as the outcome is known.
fn run(
    pull: &GapClosingActuator,
    voltage_v: f64,
    dynamics: &SlipDynamics,
    damping_n_s_per_m: &dyn Fn(f64) -> f64,
    record: bool,
    decide_only: bool,
) -> Result<SlipTrajectory, ActuatorError> {
    pull.validate()?;
    dynamics.validate()?;
    nonnegative("pull_voltage", voltage_v)?;
    let xc_si = contact_travel_m(pull, dynamics)?;
    let scale = SimulationScale::new(dynamics.shuttle_mass_kg, pull.stiffness_n_per_m());
    let drive = |x_si: f64| -> Option<f64> {
        let fe = pull.electrostatic_force_n(x_si, voltage_v);
        fe.is_finite().then(|| fe - pull.suspension.force_n(x_si))
    };
    let electrode = Some(pull.plates.front_gap_m);
    integrate(&drive, damping_n_s_per_m, xc_si, electrode, 0.0, voltage_v, scale, dynamics, record, decide_only)
}

/// Simulates the same 1-DOF slip for an arbitrary driving force law `F(x)` (N, at travel `x` in m;
/// everything except damping and kinetic friction, which come from `dynamics`) from rest at `x = 0`
/// to a stop at `stop_travel_m` (m); [`SlipTrajectory::voltage_v`] is reported as 0. The time unit
/// of the scaling is `T0 = sqrt(m L0 / F_c)` with `F_c = |F(0)| + |F(x_s)|`. Used to validate the
/// integration against closed forms (constant force: `x = F t^2 / 2m`).
pub fn simulate_force_law(
    force_n: impl Fn(f64) -> f64,
    stop_travel_m: f64,
    dynamics: &SlipDynamics,
) -> Result<SlipTrajectory, ActuatorError> {
    dynamics.validate()?;
    positive("stop_travel", stop_travel_m)?;
    let characteristic = force_n(0.0).abs() + force_n(stop_travel_m).abs();
    if !(characteristic.is_finite() && characteristic > 0.0) {
        return Err(ActuatorError::InvalidField {
            field: "force_law".into(),
            value: characteristic,
            expected: "a finite, non-zero force at x = 0 or at the stop".into(),
        });
    }
    let length_m = 1e-6;
    let scale = SimulationScale {
        length_m,
        mass_kg: dynamics.shuttle_mass_kg,
        time_s: (dynamics.shuttle_mass_kg * length_m / characteristic).sqrt(),
    };
    let drive = |x: f64| -> Option<f64> { Some(force_n(x)).filter(|f| f.is_finite()) };
    let c = dynamics.damping_n_s_per_m;
    integrate(&drive, &|_| c, stop_travel_m, None, 0.0, 0.0, scale, dynamics, true, false)
}

/// The time loop: rapier world in the scaled units of `scale`, driving force `drive_si(x)` (N, None
/// for a collapse), damping coefficient `damping_si(x)` (N s/m), stop at `xc_si` (m), electrode
/// (where the force diverges) at `electrode_si` (m), from `x = 0` with the velocity
/// `initial_velocity_si` (m/s, towards the stop when positive).
#[allow(clippy::too_many_arguments)]
pub(crate) fn integrate(
    drive_si: &dyn Fn(f64) -> Option<f64>,
    damping_si: &dyn Fn(f64) -> f64,
    xc_si: f64,
    electrode_si: Option<f64>,
    initial_velocity_si: f64,
    voltage_v: f64,
    scale: SimulationScale,
    dynamics: &SlipDynamics,
    record: bool,
    decide_only: bool,
) -> Result<SlipTrajectory, ActuatorError> {
    let (l0, t0, f0, v0) = (scale.length_m, scale.time_s, scale.force_n(), scale.velocity_m_per_s());
    let dt = dynamics.time_step_s / t0;
    let t_end = dynamics.max_time_s / t0;
    let xc = xc_si / l0;
    let electrode = electrode_si.map(|e| e / l0);
    // Damping rate c(x) T0 / m (scaled), checked finite and >= 0.
    let rate_at = |x: f64| -> Result<f64, ActuatorError> {
        let c = damping_si(x * l0);
        nonnegative("damping", c)?;
        Ok(c * t0 / scale.mass_kg)
    };
    let mut damping_rate = rate_at(0.0)?;
    let damped = damping_rate > 0.0 || rate_at(xc)? > 0.0;
    let friction = dynamics.kinetic_friction_n / f0;
    let mut world = World::new(dt, damping_rate, xc);
    if initial_velocity_si != 0.0 {
        use rapier3d_f64::math::Vector;
        world.world.bodies[world.shuttle].set_linvel(Vector::new(initial_velocity_si / v0, 0.0, 0.0), true);
    }
    // Net driving force (scaled) at scaled travel x, without damping and friction.
    let drive = |x: f64| drive_si(x * l0).map(|f| f / f0);

    let mut samples = Vec::new();
    let mut out = SlipTrajectory {
        voltage_v,
        runs_away: false,
        stop_travel_m: xc_si,
        time_to_stop_s: None,
        impact_velocity_m_per_s: None,
        max_travel_m: 0.0,
        final_travel_m: 0.0,
        stuck_again: false,
        samples: Vec::new(),
        scale,
    };
    // With damping the shuttle may creep towards a stable equilibrium without ever turning back; the
    // outcome is then decided by the energy bound (see `WorkTable`). Without damping it always turns
    // back or sticks, and the decision is left to the rapier trajectory alone.
    let table = damped.then(|| WorkTable::new(&drive, xc, friction));
    let mut turned = false;
    let mut decided = false;
    let mut t = 0.0;
    let mut steps = 0u64;
    loop {
        let (x, v) = world.state();
        if record {
            samples.push((t * t0, x * l0, v * v0));
        }
        out.final_travel_m = x * l0;
        if !turned {
            out.max_travel_m = out.max_travel_m.max(x * l0);
        }
        if t >= t_end * (1.0 - 1e-12) {
            break;
        }
        // Step length: the given one, shortened so that the last step ends at max_time and, near the
        // electrode, so that one step closes at most 1 % of the remaining gap (the force grows as
        // 1/gap^2 and would otherwise change by a large factor within one step).
        let mut h = dt.min(t_end - t);
        if let Some(e) = electrode
            && v > 0.0
        {
            h = h.min(0.01 * (e - x) / v);
        }
        steps += 1;
        if steps as f64 > MAX_STEPS {
            return Err(ActuatorError::Solver(format!(
                "more than {MAX_STEPS:e} steps at t = {:e} s (x = {:e} m): the gap closes too slowly to resolve",
                t * t0,
                x * l0
            )));
        }
        // The force held over the step is taken at the predicted mid-step travel: the work per step
        // is then a midpoint rule (second order) instead of a left Riemann sum.
        let x_mid = (x + 0.5 * v * h).min(xc);
        let rate = rate_at(x_mid)?;
        if rate != damping_rate {
            damping_rate = rate;
            world.world.bodies[world.shuttle].set_linear_damping(rate);
        }
        let Some(f_other) = drive(x_mid) else {
            // Finger collapse: the plates snap shut; counted as reaching the electrode.
            out.runs_away = true;
            out.time_to_stop_s = Some(t * t0);
            out.impact_velocity_m_per_s = Some(v * v0);
            out.max_travel_m = x * l0;
            break;
        };
        // Coulomb friction, implicit: if it can stop the shuttle within this step it does
        // (sticking); otherwise it opposes the predicted velocity with its full value.
        let v_pred = v + f_other * h;
        let (f_fric, sticks) =
            if v_pred.abs() <= friction * h { (-v / h - f_other, true) } else { (-friction * v_pred.signum(), false) };
        if sticks && (f_other.abs() <= friction || steps == 1) {
            // Held at rest by friction (at the start: the pull force does not overcome kinetic
            // friction, no motion at all).
            out.stuck_again = true;
            break;
        }
        let force = f_other + f_fric;
        world.world.integration_parameters.dt = h;
        world.step(force);
        let (x1, v1) = world.state();
        if world.hit_stop() || x1 >= xc {
            // Impact inside this step: constant-acceleration kinematics from the step's start,
            // x + v tau + a tau^2/2 = x_c, with a the step's acceleration (damping included).
            let a = force - damping_rate * v;
            let gap = (xc - x).max(0.0);
            let disc = (v * v + 2.0 * a * gap).max(0.0);
            // Root of a tau^2/2 + v tau - gap = 0 written without cancellation.
            let tau = (2.0 * gap / (v + disc.sqrt()).max(1e-300)).min(h);
            let v_imp = v + a * tau;
            out.runs_away = true;
            out.time_to_stop_s = Some((t + tau) * t0);
            out.impact_velocity_m_per_s = Some(v_imp * v0);
            out.max_travel_m = xc_si;
            out.final_travel_m = xc_si;
            if record {
                samples.push(((t + tau) * t0, xc_si, v_imp * v0));
            }
            break;
        }
        t += h;
        if !turned && v > 0.0 && v1 <= 0.0 {
            turned = true;
            out.max_travel_m = out.max_travel_m.max(x1 * l0);
        }
        if !decided && (turned || table.as_ref().is_some_and(|w| w.blocks(x1, 0.5 * v1 * v1))) {
            decided = true;
            if decide_only {
                out.max_travel_m = out.max_travel_m.max(x1 * l0);
                out.final_travel_m = x1 * l0;
                break;
            }
        }
        if t >= t_end * (1.0 - 1e-12) && !decided && !decide_only {
            return Err(ActuatorError::Solver(format!(
                "max_time = {:e} s too short: at V = {voltage_v} V the shuttle is still moving towards the \
                 stop (x = {:e} m, v = {:e} m/s)",
                dynamics.max_time_s,
                x1 * l0,
                v1 * v0
            )));
        }
    }
    out.samples = samples;
    Ok(out)
}
