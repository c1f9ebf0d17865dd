//! Perfectly plastic contact: the contact pressure capped at the hardness ([`PlasticSolution`],
//! [`BemSolver::solve_load_plastic`]).
//!
//! The unknown is the pressure `p` in `[0, H]` (Pa) with `mean(p)` fixed; the complementarity
//! conditions are those of an elastic-perfectly-plastic interface (the saturated contact of
//! Almqvist et al. 2007, Tamaas's `KatoSaturated`):
//!
//! * `p = 0`: gap `g >= 0` (out of contact);
//! * `0 < p < H`: `g = 0` (elastic contact);
//! * `p = H`: `g <= 0`, the overlap `-g` the plastic depth (the pixel flows at the hardness).
//!
//! The iteration is the constrained conjugate gradient of Polonsky & Keer on the free points
//! `F = {0 < p < H}` (the rigid approach is the mean of the complementary field on `F`), with the
//! step projected on `[0, H]`, points released from either bound where the field says so
//! (`p = 0` with `g < 0`; `p = H` with `g > 0`), and the mean restored by a scale factor `f`
//! of the points below the cap solving `mean(min(f p, H)) = target` (Newton's method on this
//! concave piecewise-linear function, which from below rises monotonically to the root and
//! reaches it in a few steps), or, when a step has put so many points at the cap that they alone
//! carry more than the target, by a shift of the contact points clamped to `[0, H]` (bisection;
//! the projection of Kato-type methods). Residual: `eps = (sum_F p |g| + target sum_{p=0} max(-g, 0)
//! + H sum_{p=H} max(g, 0)) / (sum p * rms(h))`.

use rayon::prelude::*;
use serde::Serialize;

use crate::boxqp::{capped_violation, restore_mean};
use crate::error::{BemError, check_positive};
use crate::grid::{SUM_BLOCK, block_sum, block_sum2, in_pool};
use crate::restricted::{SetMiss, SetOutcome};
use crate::shoe::SAME_LOAD_SLACK;
use crate::solver::{BemSolver, ContactSolution, Dugdale, Operator, SolverOptions};

/// A contact state with the pressure capped at the hardness.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PlasticSolution {
    /// The state: pressure (capped), gap (0 on contact and plastic points), contact flags (p > 0),
    /// means, areas, iterations and residual as for an elastic solve.
    pub solution: ContactSolution,
    /// The hardness the pressure is capped at, Pa.
    pub hardness_pa: f64,
    /// Fraction of points at the hardness (flowing plastically), `A_p/A0`.
    pub plastic_fraction: f64,
    /// Plastic area `A_p`, m^2.
    pub plastic_area_m2: f64,
    /// Largest plastic depth (the overlap `-g` at a point at the hardness), m; 0 without plastic
    /// points.
    pub max_plastic_depth_m: f64,
}

/// Iteration cap of a tilting shoe's capped pose on the whole grid (a contact too large for a
/// set): such contacts converge in tens to hundreds of iterations (8-27 near full plasticity,
/// tests/plastic.rs), while a stalled pose would spend the solver's whole cap at every pose.
pub(crate) const TILT_WHOLE_GRID_ITERATIONS: usize = 1000;

impl BemSolver {
    /// Contact under load control with the pressure capped at the hardness `hardness_pa`
    /// (Pa, > 0): perfectly plastic pixels where the elastic pressure would exceed it (the method
    /// is in the module docs). `mean_pressure_pa` (Pa) must lie in `(0, hardness_pa)`: at the
    /// hardness every point flows and the approach is undetermined. `warm`: a previous state.
    ///
    /// Errors: bad values, no convergence within `opts.max_iterations`.
    pub fn solve_load_plastic(
        &mut self,
        mean_pressure_pa: f64,
        hardness_pa: f64,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<PlasticSolution, BemError> {
        opts.validate()?;
        check_positive("hardness_pa", hardness_pa, "a finite hardness > 0 (Pa)")?;
        check_positive("mean_pressure_pa", mean_pressure_pa, "a finite mean pressure > 0 (Pa)")?;
        if mean_pressure_pa >= hardness_pa {
            return Err(BemError::Value {
                name: "mean_pressure_pa",
                value: mean_pressure_pa,
                expected: "a mean pressure below the hardness (at the hardness the whole face flows)",
            });
        }
        // On the finite patch: first on a set of candidate points, solved exactly and verified
        // on the whole grid ([`crate::restricted`]).
        if let Ok(s) = self.restricted_at_load(mean_pressure_pa, None, opts, warm, Some(hardness_pa)) {
            return Ok(self.plastic_outcome(s, hardness_pa));
        }
        let start = warm.map(|w| w.pressure_pa.as_slice());
        in_pool(|| self.solve_load_plastic_on_worker(mean_pressure_pa, hardness_pa, opts, start))
    }

    /// The capped state of a solve on a set, with its plastic fraction and area.
    fn plastic_outcome(&self, s: SetOutcome, hardness_pa: f64) -> PlasticSolution {
        let grid = self.half.grid();
        let plastic_fraction = s.plastic_points as f64 / grid.len() as f64;
        PlasticSolution {
            solution: s.solution,
            hardness_pa,
            plastic_fraction,
            plastic_area_m2: plastic_fraction * grid.area_m2(),
            max_plastic_depth_m: s.max_plastic_depth_m,
        }
    }

    /// Contact at the external mean pressure `target_pa` (Pa, > 0, below the hardness; the net
    /// of contact pressure and adhesive tension) with the compressive traction capped at
    /// `opts.hardness_pa` (perfectly plastic pixels), with the Dugdale law `law` (`None`: no
    /// adhesion, then [`Self::solve_load_plastic`]) on the loading branch. Load control, either
    /// Green's function: the capped counterpart of [`Self::adhesive_at_load`].
    ///
    /// With adhesion the net traction a contact pixel transmits is capped, `p_c - sigma0 <= H`
    /// (every contact pixel is in the cohesive zone), so the contact pressure is capped at
    /// `H + sigma0`. For a fixed zone `Z` the problem is the capped one on the heights
    /// `h + sigma0 K[1_Z]` with the contacts carrying `mean(p_c) = target + sigma0 |Z|/N`; the zone
    /// is updated from the gap and the capped solve repeated, warm-started, until it does not
    /// change. Started from the non-adhesive capped state at the load, or from `warm` (a lower
    /// load's state on the same path: its zone is the start), the zone grows to the first fixed
    /// point above it (the loading branch, as [`Self::adhesive_at_load`]). The solution's
    /// `pressure_pa` is the net traction (`<= H`), `plastic_fraction` the points at `H`.
    ///
    /// Errors: no `opts.hardness_pa` or a bad one, a target at or above it, bad law values (all
    /// naming the field); no convergence within `opts.max_iterations` per solve or
    /// `opts.max_zone_updates` updates; the path's work budget ([`BemError::WorkBudget`]).
    pub fn plastic_at_load(
        &mut self,
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<PlasticSolution, BemError> {
        self.plastic_at_load_with(target_pa, law, opts, warm, true)
    }

    /// [`Self::plastic_at_load`]; with `whole_grid` false (the tilting shoe's capped poses) on a
    /// set of candidate points ([`crate::restricted`]: the exact solve of bounded work), on the
    /// whole grid only when the contact is too large for a set and then within
    /// [`TILT_WHOLE_GRID_ITERATIONS`], else [`BemError::CappedPoseOffSet`] (the whole-grid capped
    /// iteration can stall for minutes per pose on a contact of a few pixels).
    pub(crate) fn plastic_at_load_with(
        &mut self,
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
        whole_grid: bool,
    ) -> Result<PlasticSolution, BemError> {
        opts.validate()?;
        let hardness = opts.hardness_pa.ok_or(BemError::Value {
            name: "hardness_pa",
            value: f64::NAN,
            expected: "a hardness (SolverOptions::hardness_pa) for a capped solve",
        })?;
        check_positive("target_pa", target_pa, "a finite mean pressure > 0 (Pa)")?;
        if target_pa >= hardness {
            return Err(BemError::Value {
                name: "target_pa",
                value: target_pa,
                expected: "a mean pressure below the hardness (at the hardness the whole face flows)",
            });
        }
        if whole_grid && law.is_none() {
            return self.solve_load_plastic(target_pa, hardness, opts, warm);
        }
        if let Some(law) = law {
            check_positive("stress_pa", law.stress_pa, "a finite Dugdale stress > 0 (Pa)")?;
            check_positive("range_m", law.range_m, "a finite range > 0 (m)")?;
        }
        let n = self.heights.len();
        let warm = match law {
            Some(_) => warm.filter(|w| w.gap_m.len() == n && w.mean_pressure_pa <= target_pa * (1.0 + SAME_LOAD_SLACK)),
            None => warm,
        };
        let miss = match self.restricted_at_load(target_pa, law, opts, warm, Some(hardness)) {
            Ok(s) => return Ok(self.plastic_outcome(s, hardness)),
            Err(miss) => miss,
        };
        // A capped pose of the tilting shoe goes to the whole grid only when its contact is too
        // large for a set (where the capped iteration converges in tens to hundreds of
        // iterations), and then within [`TILT_WHOLE_GRID_ITERATIONS`].
        let whole_opts = if whole_grid {
            *opts
        } else if miss == SetMiss::TooLarge {
            SolverOptions { max_iterations: opts.max_iterations.min(TILT_WHOLE_GRID_ITERATIONS), ..*opts }
        } else {
            return Err(BemError::CappedPoseOffSet { target_pa });
        };
        let Some(law) = law else {
            let start = warm.map(|w| w.pressure_pa.as_slice());
            return in_pool(|| self.solve_load_plastic_on_worker(target_pa, hardness, &whole_opts, start));
        };
        let base = self.heights.clone();
        let result = in_pool(|| self.plastic_adhesive_on_worker(&base, target_pa, hardness, law, &whole_opts, warm));
        // The heights were shifted by the zone's displacement: put them back whatever happened.
        self.set_heights(&base)?;
        result
    }

    #[allow(clippy::too_many_arguments)]
    fn plastic_adhesive_on_worker(
        &mut self,
        base: &[f64],
        target: f64,
        hardness: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<PlasticSolution, BemError> {
        let n = base.len();
        let sigma0 = law.stress_pa;
        let cap = hardness + sigma0;
        let mut iterations = 0;
        let (mut contact_pressure, mut zone): (Vec<f64>, Vec<bool>) = match warm {
            Some(w) if w.gap_m.len() == n && w.mean_pressure_pa <= target * (1.0 + SAME_LOAD_SLACK) => {
                let z: Vec<bool> = w.gap_m.iter().map(|&g| g < law.range_m).collect();
                let pc = w
                    .pressure_pa
                    .iter()
                    .zip(&z)
                    .map(|(p, &inz)| if inz { p + sigma0 } else { *p }.clamp(0.0, cap))
                    .collect();
                (pc, z)
            }
            _ => {
                let dry = self.solve_load_plastic_on_worker(target, hardness, opts, None)?;
                iterations = dry.solution.iterations;
                let z = dry.solution.gap_m.iter().map(|&g| g < law.range_m).collect();
                (dry.solution.pressure_pa, z)
            }
        };
        for update in 1..=opts.max_zone_updates {
            let tension: Vec<f64> = zone.iter().map(|&z| if z { sigma0 } else { 0.0 }).collect();
            let nz = zone.iter().filter(|&&z| z).count();
            let u = self.half.displacement(&tension);
            let shifted: Vec<f64> = base.iter().zip(&u).map(|(h, u)| h + u).collect();
            self.set_heights(&shifted)?;
            let carried = target + sigma0 * nz as f64 / n as f64;
            let s = self.solve_load_plastic_on_worker(carried, cap, opts, Some(&contact_pressure))?;
            iterations += s.solution.iterations;
            if iterations > crate::error::PATH_WORK_FACTOR * opts.max_iterations {
                return Err(BemError::WorkBudget {
                    what: "Dugdale zone growth under load control with a hardness cap",
                    iterations,
                    target_pa: target,
                    stress_pa: sigma0,
                    range_m: law.range_m,
                });
            }
            let new_zone: Vec<bool> = s.solution.gap_m.iter().map(|&g| g < law.range_m).collect();
            if new_zone == zone {
                let PlasticSolution { solution: sol, plastic_fraction, plastic_area_m2, max_plastic_depth_m, .. } = s;
                let pressure: Vec<f64> = sol.pressure_pa.iter().zip(&tension).map(|(p, t)| p - t).collect();
                let solution = self.finish(pressure, sol.gap_m, sol.contact, nz, iterations, update, sol.residual);
                return Ok(PlasticSolution {
                    solution,
                    hardness_pa: hardness,
                    plastic_fraction,
                    plastic_area_m2,
                    max_plastic_depth_m,
                });
            }
            contact_pressure = s.solution.pressure_pa;
            zone = new_zone;
        }
        Err(BemError::NoConvergence {
            what: "Dugdale cohesive-zone update under load control with a hardness cap",
            iterations: opts.max_zone_updates,
            residual: f64::NAN,
            tolerance: 0.0,
        })
    }

    fn solve_load_plastic_on_worker(
        &mut self,
        target: f64,
        cap: f64,
        opts: &SolverOptions,
        start: Option<&[f64]>,
    ) -> Result<PlasticSolution, BemError> {
        let n = self.heights.len();
        let mut x: Vec<f64> = match start {
            Some(w) if w.len() == n && w.iter().any(|&p| p > 0.0) => w.iter().map(|p| p.clamp(0.0, cap)).collect(),
            _ => vec![target; n],
        };
        let fix = restore_mean(&x, cap, target).ok_or(BemError::Value {
            name: "mean_pressure_pa",
            value: target,
            expected: "a warm start with some pressure",
        })?;
        x.iter_mut().for_each(|v| *v = fix.apply(*v, cap));
        let b = self.heights.clone();
        let scale = if self.height_rms > 0.0 { self.height_rms } else { 1.0 };
        let op = Operator::Compliance;
        let mut r = vec![0.0; n];
        let mut ax = vec![0.0; n];
        let mut t = vec![0.0; n];
        let mut w = vec![0.0; n];
        let (mut g_old, mut delta, mut residual) = (1.0, 0.0, f64::INFINITY);
        self.half.apply(op, &x, &mut ax);
        let free = |v: f64| v > 0.0 && v < cap;
        let mut it = 0;
        let converged = loop {
            if it >= opts.max_iterations {
                break false;
            }
            r.par_iter_mut().zip(ax.par_iter()).zip(b.par_iter()).for_each(|((r, a), b)| *r = a - b);
            let (nf, sum_r) =
                block_sum2(n, |rg| rg.filter(|&i| free(x[i])).fold((0.0, 0.0), |a, i| (a.0 + 1.0, a.1 + r[i])));
            // With no free point (every contact point plastic) the approach is that of the
            // plastic points: the mean of the field over them.
            let (nf, sum_r) = if nf > 0.0 {
                (nf, sum_r)
            } else {
                block_sum2(n, |rg| rg.filter(|&i| x[i] > 0.0).fold((0.0, 0.0), |a, i| (a.0 + 1.0, a.1 + r[i])))
            };
            if nf == 0.0 {
                return Err(BemError::NoConvergence {
                    what: "plastic CG (empty contact set)",
                    iterations: it,
                    residual,
                    tolerance: opts.tolerance,
                });
            }
            let rbar = sum_r / nf;
            r.par_iter_mut().for_each(|r| *r -= rbar);
            let (sum_x, viol) = capped_violation(&x, &r, cap, target);
            residual = viol / (sum_x * scale);
            if residual < opts.tolerance {
                break true;
            }
            let g = block_sum(n, |rg| rg.filter(|&i| free(x[i])).map(|i| r[i] * r[i]).sum());
            let beta = if g_old > 0.0 { delta * g / g_old } else { 0.0 };
            t.par_iter_mut().zip(x.par_iter()).zip(r.par_iter()).for_each(|((t, x), r)| {
                *t = if free(*x) { r + beta * *t } else { 0.0 };
            });
            g_old = g;
            self.half.apply(op, &t, &mut w);
            let wbar = block_sum(n, |rg| rg.filter(|&i| free(x[i])).map(|i| w[i]).sum()) / nf;
            let (num, den) = block_sum2(n, |rg| {
                rg.filter(|&i| free(x[i])).fold((0.0, 0.0), |a, i| (a.0 + r[i] * t[i], a.1 + (w[i] - wbar) * t[i]))
            });
            let tau = if den > 0.0 && den.is_finite() && num.is_finite() { num / den } else { 0.0 };
            // Step on the free set, project on [0, H]; release the bound points the field
            // pushes off their bound (a steepest-descent step of the same length for them).
            let changed: usize = x
                .par_chunks_mut(SUM_BLOCK)
                .zip(t.par_chunks(SUM_BLOCK))
                .zip(r.par_chunks(SUM_BLOCK))
                .map(|((x, t), r)| {
                    let mut k = 0;
                    for ((x, t), r) in x.iter_mut().zip(t).zip(r) {
                        let old = *x;
                        if old > 0.0 && old < cap {
                            *x = (old - tau * t).clamp(0.0, cap);
                            if *x <= 0.0 || *x >= cap {
                                k += 1;
                            }
                        } else if old <= 0.0 && *r < 0.0 {
                            *x = (-tau.max(0.0) * r).min(cap);
                            k += 1;
                        } else if old >= cap && *r > 0.0 {
                            *x = (cap - tau.max(0.0) * r).max(0.0);
                            k += 1;
                        }
                    }
                    k
                })
                .sum();
            // A step of zero length (no descent on the free set) still releases by the
            // steepest-descent length of the field's scale.
            if tau <= 0.0 && changed == 0 {
                return Err(BemError::NoConvergence {
                    what: "plastic CG (no descent)",
                    iterations: it,
                    residual,
                    tolerance: opts.tolerance,
                });
            }
            delta = if changed == 0 { 1.0 } else { 0.0 };
            let fix = restore_mean(&x, cap, target).ok_or(BemError::NoConvergence {
                what: "plastic CG (all points released)",
                iterations: it,
                residual,
                tolerance: opts.tolerance,
            })?;
            x.par_iter_mut().for_each(|v| *v = fix.apply(*v, cap));
            self.half.apply(op, &x, &mut ax);
            it += 1;
        };
        if !converged {
            return Err(BemError::NoConvergence {
                what: "plastic conjugate gradient",
                iterations: opts.max_iterations,
                residual,
                tolerance: opts.tolerance,
            });
        }
        let contact: Vec<bool> = x.iter().map(|&v| v > 0.0).collect();
        let plastic = x.iter().filter(|&&v| v >= cap).count();
        let max_plastic_depth_m = x.iter().zip(&r).filter(|&(&v, _)| v >= cap).fold(0.0f64, |m, (_, &g)| m.max(-g));
        let gap: Vec<f64> = x.iter().zip(&r).map(|(&v, &g)| if v > 0.0 { 0.0 } else { g.max(0.0) }).collect();
        let sol = self.finish(x, gap, contact, 0, it, 1, residual);
        let grid = self.half.grid();
        let plastic_fraction = plastic as f64 / grid.len() as f64;
        Ok(PlasticSolution {
            solution: sol,
            hardness_pa: cap,
            plastic_fraction,
            plastic_area_m2: plastic_fraction * grid.area_m2(),
            max_plastic_depth_m,
        })
    }
}
