//! Load paths from the current equilibrium: a sweep over a sequence of loads, the pull-off load by
//! bracketing and bisection, and the loading curve of the paper's experiments.

use super::{ExplicitSolver, invalid};
use crate::explicit::types::*;
use crate::single::Branch;

impl ExplicitSolver {
    /// Solves a sequence of loads in order, each from the previous equilibrium.
    ///
    /// `direction` states the intent (`Loading`: loads must not decrease; `Unloading`: must not
    /// increase); each summit follows its own hysteresis (JKR/MD) whatever the direction. Contact
    /// changes are reported as [`SweepEvent::JumpIn`] / [`SweepEvent::Release`]; when the shoe comes
    /// off, a [`SweepEvent::PullOff`] ends the sweep (the remaining loads are not solved).
    pub fn sweep(&mut self, loads_n: &[f64], direction: Branch) -> Result<Sweep, SolveError> {
        for w in loads_n.windows(2) {
            let ok = match direction {
                Branch::Loading => w[1] >= w[0],
                Branch::Unloading => w[1] <= w[0],
            };
            if !ok {
                return Err(invalid(
                    "loads_n",
                    format!("{} then {}", w[0], w[1]),
                    format!(
                        "{} loads for a {direction} sweep",
                        if direction == Branch::Loading { "non-decreasing" } else { "non-increasing" }
                    ),
                ));
            }
        }
        let mut points: Vec<Equilibrium> = Vec::with_capacity(loads_n.len());
        let mut events = Vec::new();
        let mut before = self.state.members;
        for &l in loads_n {
            match self.solve(l) {
                Ok(eq) => {
                    let after = eq.contacts;
                    let point = points.len();
                    if after > before {
                        events.push(SweepEvent::JumpIn {
                            point,
                            load_n: l,
                            contacts_before: before,
                            contacts_after: after,
                        });
                    } else if after < before {
                        events.push(SweepEvent::Release {
                            point,
                            load_n: l,
                            contacts_before: before,
                            contacts_after: after,
                        });
                    }
                    before = after;
                    points.push(eq);
                }
                Err(SolveError::NoEquilibrium { .. }) if direction == Branch::Unloading => {
                    let last = points.last().map(|p| p.load_n);
                    let note = last.is_none().then(|| {
                        "the first load of the sweep has no equilibrium: the shoe is off at every load of it"
                            .to_string()
                    });
                    events.push(SweepEvent::PullOff { load_n: l, last_stable_load_n: last, note });
                    break;
                }
                Err(e) => return Err(e),
            }
        }
        Ok(Sweep { points, events })
    }

    /// Unloads from the current equilibrium until the shoe comes off and returns the last
    /// equilibrium: its load is the pull-off load of this contact history, found by bisection to
    /// `relative_tolerance_load` of the adhesion scale (the state is left at that equilibrium).
    /// The current state must be an equilibrium at `from_load_n` (call [`Self::solve`] first).
    pub fn pull_off(&mut self, from_load_n: f64, relative_tolerance_load: f64) -> Result<Equilibrium, SolveError> {
        let mut hi_eq = self.solve(from_load_n)?;
        let scale = self.adhesion_ref.max(1e-3 * from_load_n.abs()).max(1e-15);
        let mut step = scale;
        // Bracket: walk down until no equilibrium.
        let mut lo;
        loop {
            let trial = hi_eq.load_n - step;
            match self.solve(trial) {
                Ok(eq) => {
                    hi_eq = eq;
                    step *= 2.0;
                }
                Err(SolveError::NoEquilibrium { .. }) => {
                    lo = trial;
                    break;
                }
                Err(e) => return Err(e),
            }
            if step > 1e6 * scale * (self.len() as f64) {
                return Err(SolveError::NoEquilibrium {
                    load_n: trial,
                    reason: "no pull-off found: contact never breaks".into(),
                });
            }
        }
        while hi_eq.load_n - lo > relative_tolerance_load * scale {
            let mid = 0.5 * (lo + hi_eq.load_n);
            match self.solve(mid) {
                Ok(eq) => hi_eq = eq,
                Err(SolveError::NoEquilibrium { .. }) => lo = mid,
                Err(e) => return Err(e),
            }
        }
        Ok(hi_eq)
    }

    /// The loading curve the paper's experiments follow: from the initial state the shoe is
    /// brought into contact at zero load, unloaded to its pull-off ([`Self::pull_off`]), then loaded
    /// in `points` equal steps from the pull-off load to `max_load_n`.
    pub fn loading_curve(&mut self, max_load_n: f64, points: usize) -> Result<Sweep, SolveError> {
        if points < 2 {
            return Err(invalid("points", points, "at least 2"));
        }
        self.reset();
        let po = self.pull_off(0.0, 1e-6)?;
        let l0 = po.load_n;
        if max_load_n <= l0 {
            return Err(invalid("max_load_n", max_load_n, format!("a load above the pull-off load {l0:e} N")));
        }
        let loads: Vec<f64> = (0..points).map(|k| l0 + (max_load_n - l0) * k as f64 / (points - 1) as f64).collect();
        self.sweep(&loads, Branch::Loading)
    }
}
