//! A voltage-driven gap-closing actuator: plate array + suspension + optional gap stop.
//!
//! Quasi-static equilibrium at voltage `V`: `F_e(x, V) = k x`, with `F_e = f(x) V^2` for rigid
//! plates ([`PlateArray::force_per_volt2`]). Along the equilibrium branch
//! `V^2(x) = k x / f(x)`; pull-in is its maximum, where `f(x) - x f'(x) = 0`. For a linear
//! spring, parallel plates, no back gap and no fringing this gives the classical
//! `x_pi = g/3`, `V_pi = sqrt(8 k g^3 / (27 n eps0 A))` with `A = l t`.
//!
//! After pull-in the plates rest on the gap stop at travel `x_s` (or collapse onto the electrode
//! without a stop). Release on unloading happens where the spring force at the stop exceeds
//! the electrostatic force there: `V_r = sqrt(k x_s / f(x_s))`.

use serde::{Deserialize, Serialize};

use crate::bending::FingerBending;
use crate::error::{ActuatorError, positive};
use crate::plates::PlateArray;
use crate::spring::Suspension;

/// A complete gap-closing actuator model (SI units).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct GapClosingActuator {
    /// The electrostatic plate array.
    pub plates: PlateArray,
    /// The suspension.
    pub suspension: Suspension,
    /// Travel at which the moving part hits the gap stop (m); `None`: no stop, the plates
    /// close the gap completely after pull-in.
    pub stop_travel_m: Option<f64>,
    /// Finger bending; `None` for rigid plates.
    pub bending: Option<FingerBending>,
}

/// The pull-in point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PullIn {
    /// Travel at the instability (m); equals the stop travel when `limited_by_stop`.
    pub travel_m: f64,
    /// Pull-in voltage (V).
    pub voltage_v: f64,
    /// True when the stop is reached before the instability (no snap, no hysteresis).
    pub limited_by_stop: bool,
}

/// Pull-in, release and the hysteresis between them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Hysteresis {
    /// Pull-in voltage (V).
    pub pull_in_voltage_v: f64,
    /// Pull-in travel (m).
    pub pull_in_travel_m: f64,
    /// Release voltage from the stop (V).
    pub release_voltage_v: f64,
    /// Hysteresis width `V_pi - V_r` (V).
    pub width_v: f64,
}

/// Quasi-static state at one voltage.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "state", rename_all = "snake_case")]
pub enum Equilibrium {
    /// Free (stable branch) at travel `travel_m` (m).
    Free {
        /// Travel (m).
        travel_m: f64,
    },
    /// Resting on the stop, pressed with `stop_force_n = F_e - k x_s` (N).
    AtStop {
        /// Stop travel (m).
        travel_m: f64,
        /// Contact force on the stop (N).
        stop_force_n: f64,
    },
    /// No stop: the plates closed the gap (shorted in a real device).
    Collapsed,
}

impl Equilibrium {
    /// Travel (m); the full front gap for [`Equilibrium::Collapsed`] is not known here, so NaN.
    pub fn travel_m(&self) -> f64 {
        match *self {
            Equilibrium::Free { travel_m } | Equilibrium::AtStop { travel_m, .. } => travel_m,
            Equilibrium::Collapsed => f64::NAN,
        }
    }
}

/// One point of a voltage sweep.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepPoint {
    /// Applied voltage (V).
    pub voltage_v: f64,
    /// Travel (m), NaN when collapsed.
    pub travel_m: f64,
    /// Electrostatic force `F_e` (N).
    pub electrostatic_force_n: f64,
    /// Spring force `k x` (N).
    pub spring_force_n: f64,
    /// Force delivered at the stop `F_e - k x_s` (N), 0 when free.
    pub stop_force_n: f64,
    /// Whether the actuator rests on the stop.
    pub at_stop: bool,
}

/// Loading (0 to `V_max`) and unloading (`V_max` to 0) sweeps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Sweep {
    /// Increasing voltage, starting from rest.
    pub loading: Vec<SweepPoint>,
    /// Decreasing voltage, starting from the loading end state.
    pub unloading: Vec<SweepPoint>,
}

/// Bisection for a sign change of `h` on `[a, b]` with `h(a) h(b) <= 0`, to machine precision.
fn bisect(mut a: f64, mut b: f64, h: impl Fn(f64) -> f64) -> f64 {
    let mut ha = h(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        let hm = h(m);
        if hm == 0.0 {
            return m;
        }
        if (hm > 0.0) == (ha > 0.0) {
            a = m;
            ha = hm;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Number of scan intervals used to bracket roots and maxima.
const SCAN: usize = 400;

impl GapClosingActuator {
    /// Builds and validates a model; errors name the field.
    pub fn new(
        plates: PlateArray,
        suspension: Suspension,
        stop_travel_m: Option<f64>,
        bending: Option<FingerBending>,
    ) -> Result<Self, ActuatorError> {
        let model = Self { plates, suspension, stop_travel_m, bending };
        model.validate()?;
        Ok(model)
    }

    /// Checks all parts and their consistency.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        self.plates.validate()?;
        self.suspension.validate()?;
        if let Some(b) = self.bending {
            b.validate()?;
        }
        if let Some(s) = self.stop_travel_m {
            positive("stop_travel", s)?;
            if s >= self.plates.front_gap_m {
                return Err(ActuatorError::Inconsistent(format!(
                    "stop_travel = {s:e} m must be smaller than the front gap {:e} m",
                    self.plates.front_gap_m
                )));
            }
        }
        if self.plates.force_per_volt2(0.0) <= 0.0 {
            return Err(ActuatorError::Inconsistent(
                "the back electrode pulls harder than the front one at rest (back_gap too small)".into(),
            ));
        }
        Ok(())
    }

    /// Total suspension stiffness `k` (N/m).
    pub fn stiffness_n_per_m(&self) -> f64 {
        self.suspension.stiffness_n_per_m()
    }

    /// Largest travel the model may take (m): the stop, or just short of closing the gap.
    fn travel_limit_m(&self) -> f64 {
        self.stop_travel_m.unwrap_or(self.plates.front_gap_m * (1.0 - 1e-9))
    }

    /// Electrostatic force `F_e(x, V)` (N): `f(x) V^2` for rigid plates, the self-consistent
    /// bent-finger force otherwise (infinite if the fingers collapse).
    pub fn electrostatic_force_n(&self, travel_m: f64, voltage_v: f64) -> f64 {
        match self.bending {
            None => self.plates.force_n(travel_m, voltage_v),
            Some(b) => b.force_and_tip_deflection(&self.plates, travel_m, voltage_v).0,
        }
    }

    /// Conversion factor `a = F_e / V^2` at travel `x` (N/V^2), paper section 5 (`F = a V^2`),
    /// rigid plates.
    pub fn conversion_factor_n_per_v2(&self, travel_m: f64) -> f64 {
        self.plates.force_per_volt2(travel_m)
    }

    /// Voltage holding the actuator in equilibrium at travel `x` (V): solves
    /// `F_e(x, V) = k x`; rigid: `V = sqrt(k x / f(x))`.
    pub fn equilibrium_voltage_v(&self, travel_m: f64) -> f64 {
        let spring = self.suspension.force_n(travel_m);
        if self.bending.is_none() {
            return (spring / self.plates.force_per_volt2(travel_m)).sqrt();
        }
        // F_e is close to V^2 f(x): fixed point V <- V sqrt(k x / F_e(x, V)) converges in a few
        // steps while bending is a small correction; bisection is the fallback.
        let mut v = (spring / self.plates.force_per_volt2(travel_m)).sqrt();
        for _ in 0..60 {
            let f = self.electrostatic_force_n(travel_m, v);
            if !f.is_finite() || f <= 0.0 {
                break;
            }
            let next = v * (spring / f).sqrt();
            if (next - v).abs() <= 1e-14 * v {
                return next;
            }
            v = next;
        }
        let mut hi = v.max(1e-12);
        while self.electrostatic_force_n(travel_m, hi) < spring {
            hi *= 2.0;
        }
        bisect(0.0, hi, |v| self.electrostatic_force_n(travel_m, v) - spring)
    }

    /// Pull-in travel and voltage. Rigid plates: root of `f(x) - x f'(x)` (linear spring),
    /// bracketed by a scan and bisected to machine precision. With finger bending: maximum of
    /// the equilibrium voltage [`Self::equilibrium_voltage_v`] over the travel (golden section).
    pub fn pull_in(&self) -> Result<PullIn, ActuatorError> {
        let limit = self.travel_limit_m();
        if self.bending.is_none() {
            let h = |x: f64| {
                let (f, df) = self.plates.force_per_volt2_and_slope(x);
                f - x * df
            };
            let mut prev = 0.0;
            for i in 1..=SCAN {
                let x = limit * i as f64 / SCAN as f64;
                if h(x) <= 0.0 {
                    let x_pi = bisect(prev, x, h);
                    return Ok(PullIn {
                        travel_m: x_pi,
                        voltage_v: self.equilibrium_voltage_v(x_pi),
                        limited_by_stop: false,
                    });
                }
                prev = x;
            }
            return match self.stop_travel_m {
                Some(s) => Ok(PullIn { travel_m: s, voltage_v: self.equilibrium_voltage_v(s), limited_by_stop: true }),
                None => Err(ActuatorError::Solver("no pull-in found before the gap closes".into())),
            };
        }
        // Generic path: maximise V_eq(x), bracketed around the rigid-plate pull-in travel.
        let rigid = Self { bending: None, ..*self }.pull_in()?;
        let v = |x: f64| self.equilibrium_voltage_v(x);
        let (lo, hi) = (0.5 * rigid.travel_m, (1.5 * rigid.travel_m).min(limit));
        const NB: usize = 24;
        let at = |i: usize| lo + (hi - lo) * i as f64 / NB as f64;
        let mut best = (0usize, f64::NEG_INFINITY);
        for i in 0..=NB {
            let vi = v(at(i));
            if vi.is_finite() && vi > best.1 {
                best = (i, vi);
            }
        }
        if best.0 == NB
            && hi >= limit
            && let Some(s) = self.stop_travel_m
        {
            return Ok(PullIn { travel_m: s, voltage_v: best.1, limited_by_stop: true });
        }
        if best.0 == 0 {
            return Err(ActuatorError::Solver(
                "finger bending moved the pull-in travel below half the rigid value".into(),
            ));
        }
        let mut a = at(best.0 - 1);
        let mut b = at((best.0 + 1).min(NB));
        let r = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..100 {
            let c = b - r * (b - a);
            let d = a + r * (b - a);
            if v(c) > v(d) {
                b = d;
            } else {
                a = c;
            }
            if b - a < 1e-12 * limit {
                break;
            }
        }
        let x = 0.5 * (a + b);
        Ok(PullIn { travel_m: x, voltage_v: v(x), limited_by_stop: false })
    }

    /// Release voltage from the stop (V): the voltage below which the spring force at the stop
    /// exceeds the electrostatic force there, `F_e(x_s, V_r) = k x_s`. Needs a stop.
    pub fn release_voltage_v(&self) -> Result<f64, ActuatorError> {
        let s = self.stop_travel_m.ok_or_else(|| {
            ActuatorError::NotAvailable(
                "release voltage needs a gap stop (stop_travel); without one the plates touch".into(),
            )
        })?;
        Ok(self.equilibrium_voltage_v(s))
    }

    /// Pull-in, release and hysteresis width.
    pub fn hysteresis(&self) -> Result<Hysteresis, ActuatorError> {
        let p = self.pull_in()?;
        let r = if p.limited_by_stop { p.voltage_v } else { self.release_voltage_v()? };
        Ok(Hysteresis {
            pull_in_voltage_v: p.voltage_v,
            pull_in_travel_m: p.travel_m,
            release_voltage_v: r,
            width_v: p.voltage_v - r,
        })
    }

    /// Free equilibrium on the stable branch at voltage `V` (m), or `None` above pull-in.
    /// Bisection of `k x - F_e(x, V)` on `[0, x_pi]`.
    pub fn stable_travel_m(&self, voltage_v: f64, pull_in: &PullIn) -> Option<f64> {
        if voltage_v < 0.0 || !voltage_v.is_finite() {
            return None;
        }
        if voltage_v == 0.0 {
            return Some(0.0);
        }
        if voltage_v > pull_in.voltage_v {
            return None;
        }
        let g = |x: f64| self.suspension.force_n(x) - self.electrostatic_force_n(x, voltage_v);
        if g(pull_in.travel_m) < 0.0 {
            return None;
        }
        Some(bisect(0.0, pull_in.travel_m, g))
    }

    /// State at voltage `V` when arriving from below (`from_stop = false`, loading) or from the
    /// stop (`from_stop = true`, unloading).
    pub fn equilibrium(&self, voltage_v: f64, from_stop: bool) -> Result<Equilibrium, ActuatorError> {
        if !(voltage_v.is_finite() && voltage_v >= 0.0) {
            return Err(ActuatorError::InvalidField {
                field: "voltage".into(),
                value: voltage_v,
                expected: "a finite voltage >= 0 V".into(),
            });
        }
        let p = self.pull_in()?;
        let on_stop = |s: f64| Equilibrium::AtStop {
            travel_m: s,
            stop_force_n: self.electrostatic_force_n(s, voltage_v) - self.suspension.force_n(s),
        };
        if from_stop && !p.limited_by_stop {
            if let Some(s) = self.stop_travel_m {
                if voltage_v >= self.release_voltage_v()? {
                    return Ok(on_stop(s));
                }
            } else if voltage_v > 0.0 {
                return Ok(Equilibrium::Collapsed);
            }
        }
        match self.stable_travel_m(voltage_v, &p) {
            Some(x) if !p.limited_by_stop || x < p.travel_m => Ok(Equilibrium::Free { travel_m: x }),
            _ => Ok(match self.stop_travel_m {
                Some(s) => on_stop(s),
                None => Equilibrium::Collapsed,
            }),
        }
    }

    /// Force delivered at the stop at voltage `V` (N): `F_e(x_s, V) - k x_s`; negative means the
    /// actuator would not stay on the stop.
    pub fn force_at_stop_n(&self, voltage_v: f64) -> Result<f64, ActuatorError> {
        let s = self
            .stop_travel_m
            .ok_or_else(|| ActuatorError::NotAvailable("force at the stop needs a gap stop".into()))?;
        Ok(self.electrostatic_force_n(s, voltage_v) - self.suspension.force_n(s))
    }

    /// Quasi-static loading sweep 0 -> `V_max` and unloading sweep `V_max` -> 0, `steps + 1`
    /// points each. Data for the x(V) and F(V) hysteresis plots.
    pub fn sweep(&self, max_voltage_v: f64, steps: usize) -> Result<Sweep, ActuatorError> {
        positive("max_voltage", max_voltage_v)?;
        if steps == 0 {
            return Err(ActuatorError::InvalidField {
                field: "steps".into(),
                value: 0.0,
                expected: "at least 1".into(),
            });
        }
        let point = |v: f64, eq: Equilibrium| {
            let x = eq.travel_m();
            let (fe, fs, stop, at) = match eq {
                Equilibrium::Free { travel_m } => {
                    (self.electrostatic_force_n(travel_m, v), self.suspension.force_n(travel_m), 0.0, false)
                }
                Equilibrium::AtStop { travel_m, stop_force_n } => {
                    (self.electrostatic_force_n(travel_m, v), self.suspension.force_n(travel_m), stop_force_n, true)
                }
                Equilibrium::Collapsed => (f64::INFINITY, f64::NAN, f64::NAN, false),
            };
            SweepPoint {
                voltage_v: v,
                travel_m: x,
                electrostatic_force_n: fe,
                spring_force_n: fs,
                stop_force_n: stop,
                at_stop: at,
            }
        };
        let mut loading = Vec::with_capacity(steps + 1);
        let mut latched = false;
        for i in 0..=steps {
            let v = max_voltage_v * i as f64 / steps as f64;
            let eq = self.equilibrium(v, latched)?;
            latched = matches!(eq, Equilibrium::AtStop { .. } | Equilibrium::Collapsed);
            loading.push(point(v, eq));
        }
        let mut unloading = Vec::with_capacity(steps + 1);
        for i in (0..=steps).rev() {
            let v = max_voltage_v * i as f64 / steps as f64;
            let eq = self.equilibrium(v, latched)?;
            latched = matches!(eq, Equilibrium::AtStop { .. } | Equilibrium::Collapsed);
            unloading.push(point(v, eq));
        }
        Ok(Sweep { loading, unloading })
    }
}
