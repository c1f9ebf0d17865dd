//! How the pull-in voltage is applied and observed: quasi-static (a slow ramp, the saddle-node of
//! the static equilibrium) or a voltage *step* from rest (the dynamic pull-in of an underdamped
//! shuttle), with the moving mass and the air damping that the step needs, both from geometry.
//!
//! **Step protocol.** From rest at `x = 0` the voltage jumps to `V`:
//!
//! `m x'' = F_e(x, V) - k x - c(x) x'`
//!
//! (the actuator's own force law, so fringing, the back gap and finger bending carry over). The
//! observed pull-in is the lowest step `V` for which the shuttle *reaches the gap stop and stays
//! there*: it reaches the stop from the lowest step `V_reach` ([`crate::dynamics::
//! dynamic_pull_in_voltage_with_damping_law`], rapier + bisection) and stays iff the electrostatic
//! force at the stop beats the spring there, `V >= V_r` (the quasi-static release voltage; the
//! impact is taken as perfectly inelastic). So `V_step = max(V_reach, V_r)`. With the stop beyond
//! the dynamic barrier (`x ~ g/2`) `V_reach` does not depend on the stop position; with a stop
//! closer than that the shuttle can reach it without any instability and then `V_r` may decide.
//!
//! **Mass** ([`Shuttle::mass_kg`]): `rho t` times the as-built planform of the spine (minus its
//! etch holes), the fingers (overlap + root) and any extra moving area (gap-stop bumpers), plus the
//! effective mass of the suspension beams, `13/35` of their mass for a clamped-guided beam (Rayleigh:
//! static shape `3s^2 - 2s^3`, `int_0^1 (3s^2 - 2s^3)^2 ds = 13/35`).
//!
//! **Damping** ([`Shuttle::damping_n_s_per_m`]), at travel `x`: the squeeze film of every finger in
//! its front gap `g_f - x` and its back gap `g_b + x`, each an `l x t` rectangle with all edges open,
//! incompressible Reynolds solution with the finite-aspect factor
//! ([`crate::dynamics::rectangular_squeeze_film_damping_n_s_per_m`]) and Veijola's rarefied
//! viscosity for that gap ([`crate::dynamics::veijola_effective_viscosity_pa_s`]); plus, when a
//! substrate gap `d` is given, Couette shear under the whole moving planform
//! `c = mu A / (d + 2 lambda)` (first-order slip on both walls).

use serde::{Deserialize, Serialize};

use crate::actuator::GapClosingActuator;
use crate::dynamics::{
    ATMOSPHERIC_PRESSURE_PA, SlipDynamics, dynamic_pull_in_voltage_with_damping_law,
    rectangular_squeeze_film_damping_n_s_per_m, squeeze_number, veijola_effective_viscosity_pa_s,
};
use crate::error::{ActuatorError, nonnegative, positive};
use crate::spec::ArraySpec;
/// The data types of the protocol in a scenario file, defined with the other actuator specs.
pub use crate::spec::{PullInProtocol, ShuttleSpec};

/// Mass contributions of the shuttle (kg).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MassBreakdown {
    /// Fingers, `n (l + l_root) w t rho`.
    pub fingers_kg: f64,
    /// Spine minus its etch holes.
    pub spine_kg: f64,
    /// Extra moving area.
    pub extra_kg: f64,
    /// Effective mass of the suspension beams, `13/35` of their mass (clamped-guided) or of the
    /// moving segments (folded: the outer segments carry half the travel; taken as `13/35` too).
    pub beams_effective_kg: f64,
}

/// The as-built shuttle: mass and the inputs of the air damping law (SI).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Shuttle {
    /// Total moving mass `m` (kg).
    pub mass_kg: f64,
    /// Its parts.
    pub mass_breakdown: MassBreakdown,
    /// Moving planform area (m^2), for Couette shear.
    pub planform_area_m2: f64,
    /// Gas viscosity (Pa s).
    pub viscosity_pa_s: f64,
    /// Gas mean free path (m).
    pub mean_free_path_m: f64,
    /// Couette damping under the planform (N s/m), 0 without a substrate gap.
    pub couette_n_s_per_m: f64,
}

impl Shuttle {
    /// The as-built shuttle of a spec (`spec.shuttle` required; errors name the field).
    pub fn from_spec(spec: &ArraySpec) -> Result<Self, ActuatorError> {
        let s = spec.shuttle.as_ref().ok_or_else(|| {
            ActuatorError::NotAvailable(
                "`shuttle` (moving mass and damping inputs) is needed for the step protocol".into(),
            )
        })?;
        let u = nonnegative("undercut", spec.undercut)?;
        let t = positive("thickness", spec.thickness)?;
        let rho = positive("shuttle.density", s.density)?;
        let overlap = positive("overlap_length (after undercut)", spec.overlap_length - u)?;
        let finger_w = positive("shuttle.finger_width (after undercut)", s.finger_width - 2.0 * u)?;
        let finger_l = overlap + nonnegative("shuttle.finger_root_length", s.finger_root_length)?;
        let fingers_area = f64::from(spec.plate_count) * finger_l * finger_w;
        let spine_w = positive("shuttle.spine_width (after undercut)", s.spine_width - 2.0 * u)?;
        let spine_l = positive("shuttle.spine_length (after undercut)", s.spine_length - 2.0 * u)?;
        nonnegative("shuttle.spine_hole_size", s.spine_hole_size)?;
        let hole = if s.spine_hole_count > 0 { s.spine_hole_size + 2.0 * u } else { 0.0 };
        let spine_area = spine_w * spine_l - f64::from(s.spine_hole_count) * hole * hole;
        if spine_area <= 0.0 {
            return Err(ActuatorError::Inconsistent(format!(
                "shuttle: {} etch holes of {hole:e} m leave no spine ({spine_w:e} x {spine_l:e} m)",
                s.spine_hole_count
            )));
        }
        let extra_area = nonnegative("shuttle.extra_area", s.extra_area)?;
        let beams_effective_kg = match &spec.spring.beams {
            Some(b) => {
                let w = positive("spring.beams.width (after undercut)", b.width - 2.0 * u)?;
                let bt = b.thickness.unwrap_or(t);
                let segments = match b.kind {
                    crate::spring::BeamKind::ClampedGuided => 1.0,
                    crate::spring::BeamKind::Folded => 2.0,
                };
                13.0 / 35.0 * rho * segments * f64::from(b.count) * b.length * w * bt
            }
            None => 0.0,
        };
        let mass_breakdown = MassBreakdown {
            fingers_kg: rho * t * fingers_area,
            spine_kg: rho * t * spine_area,
            extra_kg: rho * t * extra_area,
            beams_effective_kg,
        };
        let mass_kg =
            mass_breakdown.fingers_kg + mass_breakdown.spine_kg + mass_breakdown.extra_kg + beams_effective_kg;
        let viscosity_pa_s = positive("shuttle.viscosity", s.viscosity)?;
        let mean_free_path_m = nonnegative("shuttle.mean_free_path", s.mean_free_path)?;
        let planform_area_m2 = fingers_area + spine_area + extra_area;
        let couette_n_s_per_m = match s.substrate_gap {
            Some(d) => {
                viscosity_pa_s * planform_area_m2 / (positive("shuttle.substrate_gap", d)? + 2.0 * mean_free_path_m)
            }
            None => 0.0,
        };
        Ok(Self { mass_kg, mass_breakdown, planform_area_m2, viscosity_pa_s, mean_free_path_m, couette_n_s_per_m })
    }

    /// Squeeze-film damping of the fingers at travel `x` (N s/m): for each of the `n` fingers the
    /// `l x t` film in the front gap `g_f - x` and, with a back electrode (whatever its potential),
    /// in the back gap `g_b + x`, rarefied viscosity per gap (see the module docs). Infinite when
    /// the front gap is closed.
    pub fn squeeze_film_n_s_per_m(&self, actuator: &GapClosingActuator, travel_m: f64) -> f64 {
        let p = &actuator.plates;
        let film = |h: f64| -> f64 {
            if h <= 0.0 {
                return f64::INFINITY;
            }
            veijola_effective_viscosity_pa_s(self.viscosity_pa_s, self.mean_free_path_m, h)
                .and_then(|mu| rectangular_squeeze_film_damping_n_s_per_m(mu, p.overlap_length_m, p.thickness_m, h))
                .unwrap_or(f64::INFINITY)
        };
        let mut c = film(p.front_gap_m - travel_m);
        if let Some(b) = p.back {
            c += film(b.gap_m + travel_m);
        }
        f64::from(p.plate_count) * c
    }

    /// Total damping at travel `x` (N s/m): squeeze film plus Couette.
    pub fn damping_n_s_per_m(&self, actuator: &GapClosingActuator, travel_m: f64) -> f64 {
        self.squeeze_film_n_s_per_m(actuator, travel_m) + self.couette_n_s_per_m
    }
}

/// Result of the step protocol at one geometry.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StepPullIn {
    /// Observed step pull-in voltage `max(V_reach, V_r)` (V).
    pub voltage_v: f64,
    /// Lowest step voltage that brings the shuttle to the stop (V).
    pub reach_voltage_v: f64,
    /// Quasi-static release voltage from the stop (V): below it the shuttle would not stay.
    pub release_voltage_v: f64,
    /// Quasi-static pull-in voltage of the same model (V), for comparison.
    pub quasi_static_voltage_v: f64,
    /// Moving mass (kg).
    pub mass_kg: f64,
    /// Damping at rest `c(0)` (N s/m).
    pub damping_at_rest_n_s_per_m: f64,
    /// Damping ratio at rest `c(0) / (2 sqrt(m k))`.
    pub damping_ratio_at_rest: f64,
    /// Undamped natural frequency `sqrt(k/m)` (rad/s).
    pub natural_angular_frequency_rad_per_s: f64,
    /// Squeeze number of the front-gap film at rest at the natural frequency,
    /// `12 mu omega s^2/(p g_f^2)`, `s = min(l, t)` (incompressible when << 1).
    pub squeeze_number_at_rest: f64,
}

/// Step pull-in of an actuator with a shuttle (see the module docs), the dynamic threshold with
/// rigid fingers (the release voltage and the quasi-static pull-in with the actuator's bending, if
/// any). The rapier time step is
/// `T/2000` and the horizon `20 T` (`T = 2 pi sqrt(m/k)`), the defaults of
/// [`SlipDynamics::with_defaults`]; no kinetic friction. Needs a gap stop.
pub fn step_pull_in(actuator: &GapClosingActuator, shuttle: &Shuttle) -> Result<StepPullIn, ActuatorError> {
    if actuator.stop_travel_m.is_none() {
        return Err(ActuatorError::NotAvailable(
            "the step protocol needs a gap stop (pull-in = the shuttle reaches the stop and stays)".into(),
        ));
    }
    // The dynamic threshold is found with rigid fingers: bending changes this GCA's force by
    // < 1e-4 (docs/actuators.md) but would cost a beam solve per force evaluation (seconds per
    // length instead of ~0.1 s). Release and the quasi-static pull-in keep the bending.
    let mut rigid = *actuator;
    rigid.bending = None;
    let dynamics = SlipDynamics::with_defaults(&rigid, shuttle.mass_kg, 0.0, 0.0)?;
    let law = |x: f64| shuttle.damping_n_s_per_m(&rigid, x);
    let reach = dynamic_pull_in_voltage_with_damping_law(&rigid, &dynamics, &law)?;
    let release = actuator.release_voltage_v()?;
    let quasi = actuator.pull_in()?.voltage_v;
    let k = actuator.stiffness_n_per_m();
    let c0 = law(0.0);
    let omega = (k / shuttle.mass_kg).sqrt();
    let p = &actuator.plates;
    let mu0 = veijola_effective_viscosity_pa_s(shuttle.viscosity_pa_s, shuttle.mean_free_path_m, p.front_gap_m)?;
    let sigma =
        squeeze_number(mu0, omega, p.overlap_length_m.min(p.thickness_m), p.front_gap_m, ATMOSPHERIC_PRESSURE_PA)?;
    Ok(StepPullIn {
        voltage_v: reach.max(release),
        reach_voltage_v: reach,
        release_voltage_v: release,
        quasi_static_voltage_v: quasi,
        mass_kg: shuttle.mass_kg,
        damping_at_rest_n_s_per_m: c0,
        damping_ratio_at_rest: c0 / (2.0 * (shuttle.mass_kg * k).sqrt()),
        natural_angular_frequency_rad_per_s: omega,
        squeeze_number_at_rest: sigma,
    })
}
