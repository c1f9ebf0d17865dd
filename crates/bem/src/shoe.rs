//! The shoe on the wall: adhesion under load control and the tilting rigid shoe.
//!
//! **Adhesion at a load** ([`BemSolver::adhesive_at_load`]). The Dugdale law (tension `sigma0`
//! where the gap is below the range `h0`) under load control, for either Green's function (the
//! non-periodic one has no mean-gap solve): for a fixed cohesive zone `Z` the problem is the
//! non-adhesive one with the heights `h + sigma0 K[1_Z]` and the contact pressure carrying the
//! external load plus the zone's pull, `mean(p_c) = L/A0 + sigma0 |Z|/N` (Polonsky-Keer); the zone
//! is then updated from the new gap and the solve repeated, warm-started, until it does not change.
//! Started from the non-adhesive state at the load (or from the state of a lower load on the same
//! path), the zone grows to the first fixed point above it: the state the shoe reaches when it is
//! pressed with `L` (the loading branch). Validated on the Dugdale sphere against the
//! Maugis-Dugdale curve (tests/shoe.rs).
//!
//! **The tilting shoe** ([`BemSolver::tilting_at_load`]). The shoe face is the plane
//! `w(x, y) = d + t_x (x - x0) + t_y (y - y0)` (the explicit solver's convention: slopes dw/dx,
//! dw/dy; `(x0, y0)` the centre of the patch, where the clamp acts), so the gap is
//! `g = w - h + u`: the flat problem with the heights `h - t_x (x - x0) - t_y (y - y0)`. Load
//! control fixes the force (its multiplier is `d`); the tilts are found from the two moment
//! balances `M_x = sum p (x - x0) dA = 0`, `M_y = sum p (y - y0) dA = 0`. Without adhesion
//! `M(t)` is the gradient of the concave dual energy, so its Jacobian is negative semi-definite: a
//! Newton iteration on `t` with the Jacobian from finite differences, in a trust region, falling
//! back to the ascent step along `M` where the Jacobian is singular (one contact: no tilt is
//! resisted until a second summit touches). Converged when `|M| < MOMENT_TOLERANCE F L/2` (`L`
//! the half-diagonal of the patch). Tilts are small angles; above [`MAX_TILT_RAD`] the shoe is
//! said to tip over (as in the explicit solver).

use crate::BemError;
use crate::grid::block_sum;
use crate::solver::{BemSolver, ContactSolution, Dugdale, SolverOptions};

/// Largest tilt of the shoe, rad: beyond it the small-angle plane is no longer a description of
/// the shoe (the explicit solver's limit).
pub const MAX_TILT_RAD: f64 = 0.05;

/// Moment residual, relative to `F L/2` (`L` the patch's half-diagonal), at which the tilting
/// shoe is in balance.
pub const MOMENT_TOLERANCE: f64 = 1e-4;

/// Most pose updates (solves, the Jacobian's included) of one tilting solve.
pub const MAX_POSE_SOLVES: usize = 200;

/// A tilting shoe in equilibrium.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TiltedShoe {
    /// The contact state in the shoe's pose (heights measured from the tilted face).
    pub solution: ContactSolution,
    /// Slope of the shoe face along x, dw/dx, rad.
    pub tilt_x_rad: f64,
    /// Slope of the shoe face along y, dw/dy, rad.
    pub tilt_y_rad: f64,
    /// Moment residuals `sum p (x - x0) dA`, `sum p (y - y0) dA`, N m.
    pub moment_residual_n_m: (f64, f64),
    /// Solves spent (the Jacobian's finite differences included).
    pub solves: usize,
}

impl BemSolver {
    /// Dugdale adhesion at the external mean pressure `target_pa` (Pa, > 0; the net of contact
    /// pressure and adhesive tension) under load control, on the loading branch (module docs).
    /// `warm`: the state of a lower load on the same path (its zone is the start), else the
    /// non-adhesive state at `target_pa` is. Works with either Green's function.
    pub fn adhesive_at_load(
        &mut self,
        target_pa: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        crate::error::check_positive("target_pa", target_pa, "a finite mean pressure > 0 (Pa)")?;
        crate::error::check_positive("stress_pa", law.stress_pa, "a finite Dugdale stress > 0 (Pa)")?;
        crate::error::check_positive("range_m", law.range_m, "a finite range > 0 (m)")?;
        let base = self.heights_m().to_vec();
        let result = self.adhesive_at_load_inner(&base, target_pa, law, opts, warm);
        // The heights were shifted by the zone's displacement: put them back whatever happened.
        self.set_heights(&base)?;
        result
    }

    fn adhesive_at_load_inner(
        &mut self,
        base: &[f64],
        target_pa: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        let n = base.len();
        let (mut contact_state, mut zone) = match warm {
            Some(w) if w.gap_m.len() == n && w.mean_pressure_pa <= target_pa => {
                let z: Vec<bool> = w.gap_m.iter().map(|&g| g < law.range_m).collect();
                let pc: Vec<f64> = w
                    .pressure_pa
                    .iter()
                    .zip(&z)
                    .map(|(p, &inz)| if inz { p + law.stress_pa } else { *p }.max(0.0))
                    .collect();
                let mut s = w.clone();
                s.mean_pressure_pa = block_sum(n, |r| pc[r].iter().sum()) / n as f64;
                s.pressure_pa = pc;
                (s, z)
            }
            _ => {
                let dry = self.solve_load(target_pa, opts, None)?;
                let z = dry.gap_m.iter().map(|&g| g < law.range_m).collect();
                (dry, z)
            }
        };
        let mut iterations = 0;
        for update in 1..=opts.max_zone_updates {
            let tension: Vec<f64> = zone.iter().map(|&z| if z { law.stress_pa } else { 0.0 }).collect();
            let nz = zone.iter().filter(|&&z| z).count();
            let u = self.half_space().displacement(&tension);
            let shifted: Vec<f64> = base.iter().zip(&u).map(|(h, u)| h + u).collect();
            self.set_heights(&shifted)?;
            let carried = target_pa + law.stress_pa * nz as f64 / n as f64;
            let s = self.solve_load(carried, opts, Some(&contact_state))?;
            iterations += s.iterations;
            if iterations > crate::error::PATH_WORK_FACTOR * opts.max_iterations {
                return Err(BemError::WorkBudget {
                    what: "Dugdale zone growth under load control",
                    iterations,
                    target_pa,
                    stress_pa: law.stress_pa,
                    range_m: law.range_m,
                });
            }
            let new_zone: Vec<bool> = s.gap_m.iter().map(|&g| g < law.range_m).collect();
            if new_zone == zone {
                let pressure: Vec<f64> = s.pressure_pa.iter().zip(&tension).map(|(p, t)| p - t).collect();
                return Ok(self.finish(pressure, s.gap_m, s.contact, nz, iterations, update, s.residual));
            }
            contact_state = s;
            zone = new_zone;
        }
        Err(BemError::NoConvergence {
            what: "Dugdale cohesive-zone update under load control",
            iterations: opts.max_zone_updates,
            residual: f64::NAN,
            tolerance: 0.0,
        })
    }

    /// Moments `(sum p (x - x0) dA, sum p (y - y0) dA)` (N m) of the traction about the centre.
    pub fn moments_n_m(&self, pressure_pa: &[f64]) -> (f64, f64) {
        let g = self.grid();
        let da = g.dx_m * g.dy_m;
        let (cx, cy) = (0.5 * (g.nx as f64 - 1.0), 0.5 * (g.ny as f64 - 1.0));
        let mx = block_sum(pressure_pa.len(), |r| r.map(|i| pressure_pa[i] * ((i % g.nx) as f64 - cx)).sum());
        let my = block_sum(pressure_pa.len(), |r| r.map(|i| pressure_pa[i] * ((i / g.nx) as f64 - cy)).sum());
        (mx * g.dx_m * da, my * g.dy_m * da)
    }

    /// The tilting rigid shoe at the external mean pressure `target_pa` (Pa, > 0): approach and
    /// both tilts from the force and moment balances (module docs); `law`: Dugdale adhesion
    /// ([`Self::adhesive_at_load`]) or none; `warm`: a previous pose on the same path.
    pub fn tilting_at_load(
        &mut self,
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&TiltedShoe>,
    ) -> Result<TiltedShoe, BemError> {
        crate::error::check_positive("target_pa", target_pa, "a finite mean pressure > 0 (Pa)")?;
        let base = self.heights_m().to_vec();
        let result = self.tilting_inner(&base, target_pa, law, opts, warm);
        self.set_heights(&base)?;
        result
    }

    fn tilting_inner(
        &mut self,
        base: &[f64],
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&TiltedShoe>,
    ) -> Result<TiltedShoe, BemError> {
        let g = self.grid();
        let (lx, ly) = (g.nx as f64 * g.dx_m, g.ny as f64 * g.dy_m);
        let half_diag = 0.5 * lx.hypot(ly);
        let force = target_pa * g.area_m2();
        let scale = force * half_diag;
        let (cx, cy) = (0.5 * (g.nx as f64 - 1.0), 0.5 * (g.ny as f64 - 1.0));
        let solves = std::cell::Cell::new(0usize);
        // One pose: heights seen from the tilted face, solved warm from `prev`.
        let pose = |s: &mut BemSolver, t: (f64, f64), prev: Option<&ContactSolution>| {
            let h: Vec<f64> = base
                .iter()
                .enumerate()
                .map(|(i, h)| h - t.0 * ((i % g.nx) as f64 - cx) * g.dx_m - t.1 * ((i / g.nx) as f64 - cy) * g.dy_m)
                .collect();
            s.set_heights(&h)?;
            solves.set(solves.get() + 1);
            let sol = match law {
                None => s.solve_load(target_pa, opts, prev),
                Some(l) => s.adhesive_at_load(target_pa, l, opts, prev.filter(|p| p.mean_pressure_pa <= target_pa)),
            }?;
            let m = s.moments_n_m(&sol.pressure_pa);
            Ok::<_, BemError>((sol, (m.0 / scale, m.1 / scale)))
        };
        let mut t = warm.map_or((0.0, 0.0), |w| (w.tilt_x_rad, w.tilt_y_rad));
        let (mut sol, mut m) = pose(self, t, warm.map(|w| &w.solution))?;
        // Characteristic tilt: the height range over the half-diagonal (at least one in 1e6).
        let (hmin, hmax) = base.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, &h| (a.0.min(h), a.1.max(h)));
        let tilt_scale = ((hmax - hmin) / half_diag).clamp(1e-6, MAX_TILT_RAD);
        let mut step = 0.25 * tilt_scale;
        let norm = |m: (f64, f64)| m.0.hypot(m.1);
        let dot = |a: (f64, f64), b: (f64, f64)| a.0 * b.0 + a.1 * b.1;
        let tip_over = || BemError::Value {
            name: "target_pa",
            value: target_pa,
            expected: "a load the shoe carries without tipping over (tilt below 0.05 rad)",
        };
        loop {
            if norm(m) < MOMENT_TOLERANCE {
                let moment_residual_n_m = (m.0 * scale, m.1 * scale);
                return Ok(TiltedShoe {
                    solution: sol,
                    tilt_x_rad: t.0,
                    tilt_y_rad: t.1,
                    moment_residual_n_m,
                    solves: solves.get(),
                });
            }
            if solves.get() >= MAX_POSE_SOLVES {
                return Err(BemError::NoConvergence {
                    what: "tilting shoe (moment balance)",
                    iterations: solves.get(),
                    residual: norm(m),
                    tolerance: MOMENT_TOLERANCE,
                });
            }
            // Jacobian dM/dt by forward differences, warm-started from the current state.
            let eps = 1e-4 * step.max(1e-3 * tilt_scale);
            let (_, mx) = pose(self, (t.0 + eps, t.1), Some(&sol))?;
            let (_, my) = pose(self, (t.0, t.1 + eps), Some(&sol))?;
            let j = [[(mx.0 - m.0) / eps, (my.0 - m.0) / eps], [(mx.1 - m.1) / eps, (my.1 - m.1) / eps]];
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let trace = j[0][0] + j[1][1];
            // The Newton step where the Jacobian is negative definite and well conditioned (an
            // ascent direction of the dual energy: m . dt > 0), else the moment itself (which
            // tilts the face down on the unloaded side).
            let newton = (det > 0.0 && trace < 0.0 && det > 1e-8 * trace * trace)
                .then(|| (-(j[1][1] * m.0 - j[0][1] * m.1) / det, -(-j[1][0] * m.0 + j[0][0] * m.1) / det))
                .filter(|d| dot(*d, m) > 0.0);
            let (dir, s0) = match newton {
                Some(d) => {
                    let len = d.0.hypot(d.1);
                    ((d.0 / len, d.1 / len), len.min(4.0 * tilt_scale))
                }
                None => ((m.0 / norm(m), m.1 / norm(m)), step),
            };
            // Along the direction, f(s) = M(t + s dir) . dir is non-increasing (the dual energy is
            // concave): take the Newton step if it halves |M|, else find the root of f by
            // bracketing and the Illinois rule.
            let at = |s: f64| (t.0 + s * dir.0, t.1 + s * dir.1);
            let f0 = dot(m, dir);
            // The largest step that keeps the tilt within MAX_TILT_RAD: |t + s dir| = MAX.
            let b = dot(t, dir);
            let s_max = -b + (b * b - dot(t, t) + MAX_TILT_RAD * MAX_TILT_RAD).max(0.0).sqrt();
            let s0 = s0.min(s_max);
            let mut trial =
                |s: f64| -> Result<(ContactSolution, (f64, f64)), BemError> { pose(self, at(s), Some(&sol)) };
            let (s_new, sol_new, m_new) = {
                let (s1, m1) = trial(s0)?;
                if newton.is_some() && norm(m1) < 0.5 * norm(m) {
                    (s0, s1, m1)
                } else {
                    let (mut lo, mut f_lo) = (0.0, f0);
                    let (mut hi, mut f_hi, mut best) = (s0, dot(m1, dir), (s0, s1, m1));
                    while f_hi > 0.0 {
                        if solves.get() >= MAX_POSE_SOLVES {
                            break;
                        }
                        if hi >= s_max {
                            return Err(tip_over());
                        }
                        lo = hi;
                        f_lo = f_hi;
                        hi = (2.0 * hi).min(s_max);
                        let (s2, m2) = trial(hi)?;
                        f_hi = dot(m2, dir);
                        best = (hi, s2, m2);
                    }
                    let mut side = 0i8;
                    while f_hi <= 0.0 && best.2 != m && dot(best.2, dir).abs() > 0.1 * f0 {
                        if solves.get() >= MAX_POSE_SOLVES {
                            break;
                        }
                        let s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
                        let s = if s.is_finite() && s > lo && s < hi { s } else { 0.5 * (lo + hi) };
                        let (s2, m2) = trial(s)?;
                        let f = dot(m2, dir);
                        if f > 0.0 {
                            lo = s;
                            f_lo = f;
                            if side == 1 {
                                f_hi *= 0.5;
                            }
                            side = 1;
                        } else {
                            hi = s;
                            f_hi = f;
                            if side == -1 {
                                f_lo *= 0.5;
                            }
                            side = -1;
                        }
                        best = (s, s2, m2);
                    }
                    best
                }
            };
            t = at(s_new);
            sol = sol_new;
            m = m_new;
            step = s_new.max(1e-6 * tilt_scale);
        }
    }
}
