//! What the pull shuttle does after the shoe slips, by one of two paths.
//!
//! The motion is the 1-DOF equation of [`stiction_actuator::dynamics`]:
//! `m x'' = F_e(x, V) - k x - c x' - F_k` while `x' > 0` (forward motion, Coulomb friction
//! `F_k` opposing it), from rest at `x = 0`, until the shuttle reaches the stop `x_c` (a runaway)
//! or turns back (it does not run away).
//!
//! * [`SlipPath::RigidBody`]: the full rapier trajectory ([`stiction_actuator::simulate_slip`]),
//!   ~2 ms per slip.
//! * [`SlipPath::Light`] (default for studies): the same outcome at ~1 % of the cost:
//!   1. **energy criterion** (rigid plates, linear spring): the work of the conservative forces and
//!      friction from rest, `W(x) = [C(x) - C(0)] V^2/2 - k x^2/2 - F_k x` (J). Damping only removes
//!      energy, so if `W(x) <= 0` somewhere on `(0, x_c]` the stop is out of reach: no runaway,
//!      nothing to integrate. The minima of `W` sit at the unstable equilibria (net force turning
//!      from restoring to driving) or at `x_c`; they are found by a 64-point scan of the net force
//!      and bisection.
//!   2. otherwise a **light integrator**: classical RK4 on `(x, v)` with a step of `T/100`
//!      (`T = 2 pi sqrt(m/k)`), shortened near the electrode so that a step closes at most 5 % of
//!      the remaining gap (the force grows as `1/gap^2`); the impact is located inside its step on the cubic Hermite
//!      interpolant of `(x, v)` (bisection), the impact velocity from its derivative. The motion
//!      is also decided as soon as the kinetic energy cannot carry the shuttle over the next
//!      minimum of `W` (the creeping, over-damped case). A shuttle still undecided after
//!      `20 T` is an error, as in the rigid-body path.
//!
//!   Finger bending (a force that is not `f(x) V^2`) falls back to the rigid-body path.
//!   The light path is validated against the rapier trajectory in `tests/slip.rs` (state,
//!   time to the stop and impact velocity).

use stiction_actuator::{ActuatorError, GapClosingActuator, SlipDynamics, simulate_slip};

/// Which integrator follows the shuttle after slip.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SlipPath {
    /// The rapier rigid-body trajectory (default for single runs).
    #[default]
    RigidBody,
    /// Energy criterion plus an RK4 integrator (default for studies).
    Light,
}
stiction_units::display_serde_name!(SlipPath);

/// The outcome of a slip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipOutcome {
    /// Whether the shuttle reaches the stop (dynamic pull-in).
    pub runs_away: bool,
    /// Time from slip to the stop, s.
    pub time_to_stop_s: Option<f64>,
    /// Speed at the stop, m/s.
    pub impact_velocity_m_per_s: Option<f64>,
}

/// Slip outcome of the pull array `pull` under a step to `voltage_v` (V), shuttle mass
/// `mass_kg`, damping `damping_n_s_per_m`, kinetic friction `kinetic_friction_n`, by `path`.
pub fn slip_outcome(
    path: SlipPath,
    pull: &GapClosingActuator,
    voltage_v: f64,
    mass_kg: f64,
    damping_n_s_per_m: f64,
    kinetic_friction_n: f64,
) -> Result<SlipOutcome, ActuatorError> {
    let d = SlipDynamics::with_defaults(pull, mass_kg, damping_n_s_per_m, kinetic_friction_n)?;
    if path == SlipPath::Light && pull.bending.is_none() {
        return light(pull, voltage_v, &d, None);
    }
    let t = simulate_slip(pull, voltage_v, &d)?;
    Ok(SlipOutcome {
        runs_away: t.runs_away,
        time_to_stop_s: t.time_to_stop_s,
        impact_velocity_m_per_s: t.impact_velocity_m_per_s,
    })
}

/// A trajectory: `(t (s), x (m), v (m/s))` samples.
pub type Trajectory = Vec<(f64, f64, f64)>;

/// The light path's trajectory `(t (s), x (m), v (m/s))`, one sample per RK4 step, the impact
/// last (for validation against the rigid-body path).
pub fn light_trajectory(
    pull: &GapClosingActuator,
    voltage_v: f64,
    dynamics: &SlipDynamics,
) -> Result<(SlipOutcome, Trajectory), ActuatorError> {
    let mut samples = Vec::new();
    let out = light(pull, voltage_v, dynamics, Some(&mut samples))?;
    Ok((out, samples))
}

fn light(
    pull: &GapClosingActuator,
    voltage_v: f64,
    d: &SlipDynamics,
    mut record: Option<&mut Trajectory>,
) -> Result<SlipOutcome, ActuatorError> {
    let still = SlipOutcome { runs_away: false, time_to_stop_s: None, impact_velocity_m_per_s: None };
    let m = d.shuttle_mass_kg;
    let c = d.damping_n_s_per_m;
    let fk = d.kinetic_friction_n;
    let k = pull.stiffness_n_per_m();
    let gap = pull.plates.front_gap_m;
    let xc = match pull.stop_travel_m {
        Some(s) => s,
        None => gap - d.contact_gap_m,
    };
    if !(xc > 0.0 && xc < gap) {
        return Err(ActuatorError::InvalidField {
            field: "stop.travel".into(),
            value: xc,
            expected: format!("between 0 and the front gap {gap:e} m"),
        });
    }
    let v2 = voltage_v * voltage_v;
    // Net driving force without damping (N) and the work from rest (J).
    let net = |x: f64| pull.plates.force_per_volt2(x) * v2 - k * x - fk;
    let c0 = pull.plates.capacitance_f(0.0);
    let work = |x: f64| 0.5 * (pull.plates.capacitance_f(x) - c0) * v2 - 0.5 * k * x * x - fk * x;
    if net(0.0) <= 0.0 {
        return Ok(still);
    }
    // Minima of W on (0, x_c]: net force crossing from < 0 to > 0 (bisected), and x_c.
    const SCAN: usize = 64;
    let mut minima: Vec<(f64, f64)> = Vec::new();
    let mut prev = (0.0, net(0.0));
    for i in 1..=SCAN {
        let x = xc * i as f64 / SCAN as f64;
        let f = net(x);
        if prev.1 < 0.0 && f >= 0.0 {
            let (mut a, mut b) = (prev.0, x);
            for _ in 0..40 {
                let mid = 0.5 * (a + b);
                if net(mid) < 0.0 { a = mid } else { b = mid }
            }
            let xu = 0.5 * (a + b);
            minima.push((xu, work(xu)));
        }
        prev = (x, f);
    }
    minima.push((xc, work(xc)));
    let scale = minima.iter().fold(work(xc).abs(), |s, w| s.max(w.1.abs())).max(f64::MIN_POSITIVE);
    if minima.iter().any(|&(_, w)| w <= 1e-12 * scale) {
        // Energy criterion: even without damping the stop is out of reach.
        return Ok(still);
    }
    // RK4 in SI on y = (x, v), forward motion only.
    let accel = |x: f64, v: f64| (pull.plates.force_per_volt2(x) * v2 - k * x - fk - c * v) / m;
    let period = 2.0 * std::f64::consts::PI * (m / k).sqrt();
    let h0 = period / 100.0;
    let t_end = d.max_time_s;
    let (mut t, mut x, mut v) = (0.0f64, 0.0f64, 0.0f64);
    if let Some(r) = record.as_deref_mut() {
        r.push((t, x, v));
    }
    let mut steps = 0u64;
    while t < t_end {
        let mut h = h0;
        if v > 0.0 {
            h = h.min(0.05 * (gap - x) / v);
        }
        steps += 1;
        if steps > 10_000_000 {
            return Err(ActuatorError::Solver(format!(
                "light slip integrator: more than 1e7 steps at t = {t:e} s (x = {x:e} m)"
            )));
        }
        let a0 = accel(x, v);
        let (k1x, k1v) = (v, a0);
        let (k2x, k2v) = (v + 0.5 * h * k1v, accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, accel(x + h * k3x, v + h * k3v));
        let x1 = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let v1 = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if x1 >= xc {
            // Impact inside the step: cubic Hermite through (x, v a0) and (x1, v1 a1).
            let herm = |s: f64| {
                let (s2, s3) = (s * s, s * s * s);
                let p = (2.0 * s3 - 3.0 * s2 + 1.0) * x
                    + (s3 - 2.0 * s2 + s) * h * v
                    + (-2.0 * s3 + 3.0 * s2) * x1
                    + (s3 - s2) * h * v1;
                let dp = ((6.0 * s2 - 6.0 * s) * x
                    + (3.0 * s2 - 4.0 * s + 1.0) * h * v
                    + (-6.0 * s2 + 6.0 * s) * x1
                    + (3.0 * s2 - 2.0 * s) * h * v1)
                    / h;
                (p, dp)
            };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if herm(mid).0 < xc { lo = mid } else { hi = mid }
            }
            let s = 0.5 * (lo + hi);
            let v_imp = herm(s).1;
            let t_imp = t + s * h;
            if let Some(r) = record.as_deref_mut() {
                r.push((t_imp, xc, v_imp));
            }
            return Ok(SlipOutcome {
                runs_away: true,
                time_to_stop_s: Some(t_imp),
                impact_velocity_m_per_s: Some(v_imp),
            });
        }
        t += h;
        x = x1;
        v = v1;
        if let Some(r) = record.as_deref_mut() {
            r.push((t, x, v));
        }
        if v <= 0.0 {
            // Turned back before the stop: it cannot reach the stop any more.
            return Ok(still);
        }
        // Creeping: the kinetic energy cannot carry it over the next minimum of W. Only checked
        // while the shuttle slows down (an accelerating shuttle is not held back).
        if a0 < 0.0 {
            let w_here = work(x);
            let ahead = minima.iter().filter(|(xm, _)| *xm >= x).fold(f64::INFINITY, |a, w| a.min(w.1));
            if 0.5 * m * v * v + 1e-9 * scale < w_here - ahead {
                return Ok(still);
            }
        }
    }
    Err(ActuatorError::Solver(format!(
        "max_time = {t_end:e} s too short: at V = {voltage_v} V the shuttle is still moving towards the stop \
         (x = {x:e} m, v = {v:e} m/s)"
    )))
}
