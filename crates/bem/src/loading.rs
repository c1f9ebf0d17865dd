//! Adhesive contact at a prescribed load on the loading branch.
//!
//! The Dugdale solver runs under mean-gap control (so that a retraction can pass the load
//! minimum). A friction meter prescribes the load instead: the clamp pushes the shoe with `L`
//! and the shoe comes down onto the wall. Under load control the state at `L > 0` on the loading
//! branch is the first equilibrium met on the approach, where the net load `mean(p) A0` (contact
//! pressure minus the Dugdale tension, so the adhesive pull is already inside it) first reaches
//! `L`. At the same load the adhesive state lies closer than the non-adhesive one (the tension
//! adds to what the contacts must carry), so the approach starts at the non-adhesive
//! (Polonsky-Keer) state at `L`, whose adhesive load is below `L`; the cohesive zones grow from
//! its contacts. The flat then comes down in mean gap, each state warm-started from the one before
//! (the load history), with steps from the secant of the last two states (at least the range
//! `h0`, at most four times the previous step), until the load reaches `L`; that gap is refined by
//! the Illinois variant of regula falsi, each trial warm-started from the bracket's upper (still
//! approaching) state. The load is a step function of the gap where cohesive-zone pixels switch:
//! the refinement stops at [`LOAD_TOLERANCE`] or at a gap bracket of [`GAP_RESOLUTION`] `h0`,
//! and then returns the first state past `L` (under load control the shoe sits where the load is
//! carried). The approach is kept in a [`LoadingPath`], so a rising sequence of loads continues it.
//! Validated on a Dugdale sphere against the Maugis-Dugdale curve (tests/validation.rs: radius
//! within 0.12 pixels).

use crate::BemError;
use crate::solver::{BemSolver, ContactSolution, Dugdale, SolverOptions};

/// Relative tolerance on the load of the state returned by
/// [`BemSolver::adhesive_loading_at_pressure`].
pub const LOAD_TOLERANCE: f64 = 1e-3;

/// Width of the final mean-gap bracket, in Dugdale ranges, at which the refinement stops when the
/// load tolerance cannot be met (the load jumps where a cohesive-zone pixel switches).
pub const GAP_RESOLUTION: f64 = 1e-3;

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
        let mut spent = 0usize;
        let budget = crate::error::PATH_WORK_FACTOR * opts.max_iterations;
        let over = |spent: usize| BemError::WorkBudget {
            what: "adhesive loading path (periodic)",
            iterations: spent,
            target_pa,
            stress_pa: law.stress_pa,
            range_m: law.range_m,
        };
        let resume = path.law == Some(*law) && target_pa >= path.last_target_pa;
        let (mut gap, mut state) = match (&path.below, resume) {
            (Some((g, s)), true) => (*g, s.clone()),
            _ => {
                // At the same load the adhesive state lies closer than the non-adhesive one (the
                // tension adds to the load), so the approach may start at the non-adhesive mean
                // gap, from its state: the cohesive zones then grow from the contacts there as
                // they would on the approach.
                let dry = self.solve_load(target_pa, opts, None)?;
                let g = dry.mean_gap_m;
                let s = self.solve_adhesive_mean_gap(g, law, opts, Some(&dry))?;
                (g, s)
            }
        };
        path.law = Some(*law);
        if state.mean_pressure_pa >= target_pa {
            // A resumed path already past the target (cannot happen from the dry start, whose
            // load is below the target): refine between it and the gap one range above.
            let up = self.solve_adhesive_mean_gap(gap + h0, law, opts, Some(&state))?;
            if up.mean_pressure_pa < target_pa {
                let below = up;
                return self.refine(target_pa, law, opts, path, (gap + h0, below), (gap, state), 0);
            }
        }
        // March down until the load reaches the target; the step follows the secant of the last
        // two states (at least the range h0, at most four times the previous step).
        let mut step = h0;
        let mut prev: Option<(f64, f64)> = None;
        let (lo_gap, lo_state) = loop {
            if let Some((g_prev, p_prev)) = prev {
                let slope = (state.mean_pressure_pa - p_prev) / (g_prev - gap);
                if slope > 0.0 && slope.is_finite() {
                    step = (1.2 * (target_pa - state.mean_pressure_pa) / slope).clamp(h0, 4.0 * step);
                }
            }
            let next = gap - step;
            if next <= 0.0 {
                return Err(BemError::Value {
                    name: "target_pa",
                    value: target_pa,
                    expected: "a load the surface carries above full contact (mean gap > 0)",
                });
            }
            let s = self.solve_adhesive_mean_gap(next, law, opts, Some(&state))?;
            spent += s.iterations;
            if spent > budget {
                return Err(over(spent));
            }
            if s.mean_pressure_pa >= target_pa {
                break (next, s);
            }
            prev = Some((gap, state.mean_pressure_pa));
            gap = next;
            state = s;
        };
        self.refine(target_pa, law, opts, path, (gap, state), (lo_gap, lo_state), spent)
    }

    /// Illinois regula falsi on the mean gap between `upper` (load below the target) and `lower`
    /// (load at or above it), each trial warm-started from the current upper state; `spent`: the
    /// iterations the path has taken so far (the budget is [`crate::error::PATH_WORK_FACTOR`] times
    /// the per-solve cap).
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &mut self,
        target_pa: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        path: &mut LoadingPath,
        upper: (f64, ContactSolution),
        lower: (f64, ContactSolution),
        mut spent: usize,
    ) -> Result<ContactSolution, BemError> {
        let h0 = law.range_m;
        let budget = crate::error::PATH_WORK_FACTOR * opts.max_iterations;
        let (gap, mut state) = upper;
        let (lo_gap, lo_state) = lower;
        let (mut g_hi, mut f_hi) = (gap, state.mean_pressure_pa - target_pa);
        let (mut g_lo, mut f_lo) = (lo_gap, lo_state.mean_pressure_pa - target_pa);
        let mut lower_state = lo_state;
        let mut side = 0i8;
        let within = |f: f64| f.abs() <= LOAD_TOLERANCE * target_pa;
        for _ in 0..60 {
            if within(f_lo) || within(f_hi) || g_hi - g_lo <= GAP_RESOLUTION * h0 {
                // The load is a step function of the gap where cohesive-zone pixels switch, so
                // the load tolerance may be out of reach: stop at a gap bracket of
                // GAP_RESOLUTION h0 as well.
                break;
            }
            let g = (g_lo * f_hi - g_hi * f_lo) / (f_hi - f_lo);
            let g = if g.is_finite() && g > g_lo && g < g_hi { g } else { 0.5 * (g_lo + g_hi) };
            let s = self.solve_adhesive_mean_gap(g, law, opts, Some(&state))?;
            spent += s.iterations;
            if spent > budget {
                return Err(BemError::WorkBudget {
                    what: "adhesive loading path (periodic)",
                    iterations: spent,
                    target_pa,
                    stress_pa: law.stress_pa,
                    range_m: law.range_m,
                });
            }
            let f = s.mean_pressure_pa - target_pa;
            if f >= 0.0 {
                g_lo = g;
                f_lo = f;
                if side == -1 {
                    f_hi *= 0.5;
                }
                side = -1;
                lower_state = s;
            } else {
                g_hi = g;
                f_hi = f;
                if side == 1 {
                    f_lo *= 0.5;
                }
                side = 1;
                state = s;
            }
        }
        // The state that carries the target: within the tolerance, or else the first one past it
        // (under load control the shoe sits where the load is reached).
        let result = if within(state.mean_pressure_pa - target_pa) { state.clone() } else { lower_state };
        path.below = Some((g_hi, state));
        path.last_target_pa = target_pa;
        Ok(result)
    }
}
