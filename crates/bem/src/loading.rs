//! Adhesive contact at a prescribed load on the loading branch.
//!
//! The Dugdale solver runs under mean-gap control (so that a retraction can pass the load
//! minimum). A friction meter prescribes the load instead: the clamp pushes the shoe with `L`
//! and the shoe comes down onto the wall. Under load control the state at `L > 0` on the loading
//! branch is the first equilibrium met on the approach: the flat comes down from separation
//! (cohesive zone empty) in decreasing mean gap, each state warm-started from the one before (the
//! load history), until the net load `mean(p) A0` (contact pressure minus the Dugdale tension, so
//! the adhesive pull is already inside it) first reaches `L`; that gap is then refined by the
//! Illinois variant of regula falsi, each trial warm-started from the bracket's upper (still
//! approaching) state. A jump-in (the load dipping negative as cohesive zones form) is passed by
//! the march, as a load-controlled approach would jump past it.

use crate::{BemError, BemSolver, ContactSolution, Dugdale, SolverOptions};

/// Relative tolerance on the load of the state returned by
/// [`BemSolver::adhesive_loading_at_pressure`].
pub const LOAD_TOLERANCE: f64 = 1e-4;

/// The approach path of an adhesive loading branch, kept between calls so that a rising sequence
/// of loads (the meter's clamp voltages) continues the same approach instead of starting again.
#[derive(Debug, Clone, Default)]
pub struct LoadingPath {
    /// The last state on the approach with a load below the last target, and its mean gap.
    below: Option<(f64, ContactSolution)>,
    /// The target of the last call, Pa.
    last_target_pa: f64,
    /// The Dugdale law of the path (a new law starts a new path).
    law: Option<Dugdale>,
}

impl BemSolver {
    /// Adhesive (Dugdale) contact at the mean pressure `target_pa` (Pa, > 0: the external load per
    /// nominal area, compressive; the net of contact pressure and adhesive tension) on the loading
    /// branch. `path` carries the approach between calls (see the module docs).
    pub fn adhesive_loading_at_pressure(
        &mut self,
        target_pa: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        path: &mut LoadingPath,
    ) -> Result<ContactSolution, BemError> {
        crate::error::check_positive("target_pa", target_pa, "a finite mean pressure > 0 (Pa)")?;
        let h0 = law.range_m;
        let top_gap = self.height_max - self.height_mean + h0;
        let max_step = (0.05 * self.height_rms).max(h0);
        let resume = path.law == Some(*law) && target_pa >= path.last_target_pa;
        let (mut gap, mut state) = match (&path.below, resume) {
            (Some((g, s)), true) => (*g, s.clone()),
            _ => {
                let s = self.solve_adhesive_mean_gap(top_gap, law, opts, None)?;
                (top_gap, s)
            }
        };
        path.law = Some(*law);
        let mut step = h0;
        // March down until the load reaches the target.
        let (lo_gap, lo_state) = loop {
            let next = gap - step;
            if next <= 0.0 {
                return Err(BemError::Value {
                    name: "target_pa",
                    value: target_pa,
                    expected: "a load the surface carries above full contact (mean gap > 0)",
                });
            }
            let s = self.solve_adhesive_mean_gap(next, law, opts, Some(&state))?;
            if s.mean_pressure_pa >= target_pa {
                break (next, s);
            }
            gap = next;
            state = s;
            step = (step * 1.5).min(max_step);
        };
        // Illinois regula falsi between (gap, state: below) and (lo_gap, lo_state: at or above).
        let (mut g_hi, mut f_hi) = (gap, state.mean_pressure_pa - target_pa);
        let (mut g_lo, mut f_lo) = (lo_gap, lo_state.mean_pressure_pa - target_pa);
        let mut best = lo_state;
        let mut side = 0i8;
        for _ in 0..60 {
            if (best.mean_pressure_pa - target_pa).abs() <= LOAD_TOLERANCE * target_pa {
                break;
            }
            let g = (g_lo * f_hi - g_hi * f_lo) / (f_hi - f_lo);
            let g = if g.is_finite() && g > g_lo && g < g_hi { g } else { 0.5 * (g_lo + g_hi) };
            let s = self.solve_adhesive_mean_gap(g, law, opts, Some(&state))?;
            let f = s.mean_pressure_pa - target_pa;
            if f >= 0.0 {
                g_lo = g;
                f_lo = f;
                if side == -1 {
                    f_hi *= 0.5;
                }
                side = -1;
                best = s;
            } else {
                g_hi = g;
                f_hi = f;
                if side == 1 {
                    f_lo *= 0.5;
                }
                side = 1;
                state = s.clone();
                best = s;
            }
            if g_hi - g_lo <= 1e-9 * h0 {
                break;
            }
        }
        path.below = Some((g_hi, state));
        path.last_target_pa = target_pa;
        Ok(best)
    }
}
