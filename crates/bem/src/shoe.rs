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
//! resisted until a second summit touches). Every trial pose is a candidate and the iteration
//! moves only to a better one (smaller `|M|`). Converged when `|M| < MOMENT_TOLERANCE F L/2` (`L`
//! the half-diagonal of the patch). Contacts and cohesive zones change by whole pixels, so `M` is
//! not continuous in the tilt: when `|M|` has not halved over [`STALL_ITERATIONS`] outer steps
//! (or after [`MAX_POSE_SOLVES`] solves) a pose whose centre of pressure lies within one pixel of
//! the clamp point (`|M|/F <= max(dx, dy)`) is returned as the balance the grid resolves, and
//! anything further is a non-convergence error. Tilts are small angles; above [`MAX_TILT_RAD`]
//! the shoe is said to tip over (as in the explicit solver). The iteration starts from the
//! previous pose, then from the flat face, then (adhesive) from the dry balance with the Dugdale
//! stress switched on in steps; the first balance found is returned.

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

/// Outer steps without halving the moment residual after which the balance is taken as stalled
/// (then accepted within one pixel's resolution, or refused).
pub const STALL_ITERATIONS: usize = 4;

/// Most Illinois steps of one line search.
const MAX_BRACKET_STEPS: usize = 8;

/// Relative slack with which a state counts as below a target load when it warm-starts the
/// adhesive solve: a state solved at the same load carries it to rounding, either side.
pub(crate) const SAME_LOAD_SLACK: f64 = 1e-9;

/// A solved pose: the state and, with the hardness cap, its plastic fraction, area (m^2) and
/// largest depth (m).
type Pose = (ContactSolution, Option<(f64, f64, f64)>);

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
    /// With the hardness cap (`SolverOptions::hardness_pa`): the fraction of points at the
    /// hardness, the plastic area (m^2) and the largest plastic depth (m); None: elastic.
    pub plastic: Option<(f64, f64, f64)>,
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
        opts.validate()?;
        let n = self.heights_m().len();
        let warm = warm.filter(|w| w.gap_m.len() == n && w.mean_pressure_pa <= target_pa * (1.0 + SAME_LOAD_SLACK));
        // On the finite patch: first on a set of candidate points, verified on the whole grid
        // ([`crate::restricted`]); else the zone iteration below on the whole grid.
        if let Ok(s) = self.restricted_at_load(target_pa, Some(law), opts, warm, None) {
            return Ok(s.solution);
        }
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
            Some(w) if w.gap_m.len() == n && w.mean_pressure_pa <= target_pa * (1.0 + SAME_LOAD_SLACK) => {
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
    /// ([`Self::adhesive_at_load`]) or none; with `opts.hardness_pa` each pose is the capped
    /// solve ([`Self::plastic_at_load`]: the net traction at most the hardness); `warm`: a
    /// previous pose on the same path.
    pub fn tilting_at_load(
        &mut self,
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&TiltedShoe>,
    ) -> Result<TiltedShoe, BemError> {
        crate::error::check_positive("target_pa", target_pa, "a finite mean pressure > 0 (Pa)")?;
        let base = self.heights_m().to_vec();
        // The balance is looked for from the previous pose, then (if that fails) from the flat
        // face, then, for an adhesive shoe, from the dry shoe's balance at the same load with the
        // adhesion switched on in steps (a quarter, a half, all of the Dugdale stress, each pose
        // continued from the last): from a flat face the cohesive zone of a first summit can pull
        // the face over by whole pixels from pose to pose, while the dry balance puts the face on
        // the summits that carry the load. The first balance found is returned.
        // One work budget for every start: the conjugate-gradient iterations of all poses. Each
        // pose sets the heights it is solved on (the tilted `base`), so the starts need no reset
        // between them; the heights are put back once at the end.
        let work = std::cell::Cell::new(0usize);
        let mut result = self.tilting_inner(&base, target_pa, law, opts, warm, &work);
        if result.is_err() && warm.is_some() {
            result = self.tilting_inner(&base, target_pa, law, opts, None, &work);
        }
        if let (Err(_), Some(l)) = (&result, law) {
            let mut start = self.tilting_inner(&base, target_pa, None, opts, None, &work).ok();
            for f in [0.25, 0.5] {
                let weak = Dugdale { stress_pa: f * l.stress_pa, range_m: l.range_m };
                if let Ok(s) = self.tilting_inner(&base, target_pa, Some(&weak), opts, start.as_ref(), &work) {
                    start = Some(s);
                }
            }
            if start.is_some()
                && let Ok(s) = self.tilting_inner(&base, target_pa, law, opts, start.as_ref(), &work)
            {
                result = Ok(s);
            }
        }
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
        work: &std::cell::Cell<usize>,
    ) -> Result<TiltedShoe, BemError> {
        let g = self.grid();
        let (lx, ly) = (g.nx as f64 * g.dx_m, g.ny as f64 * g.dy_m);
        let half_diag = 0.5 * lx.hypot(ly);
        let force = target_pa * g.area_m2();
        let scale = force * half_diag;
        let (cx, cy) = (0.5 * (g.nx as f64 - 1.0), 0.5 * (g.ny as f64 - 1.0));
        let solves = std::cell::Cell::new(0usize);
        // The heights seen from the face of tilts `t`.
        let tilted = |base: &[f64], t: (f64, f64)| -> Vec<f64> {
            base.iter()
                .enumerate()
                .map(|(i, h)| h - t.0 * ((i % g.nx) as f64 - cx) * g.dx_m - t.1 * ((i / g.nx) as f64 - cy) * g.dy_m)
                .collect()
        };
        // One pose: heights seen from the tilted face, solved warm from `prev` (the pose the
        // outer iteration stands on). With adhesion the cohesive zone is therefore continued
        // from pose to pose: the adhesive contact is multistable, and growing every pose's zone
        // from one fixed start instead makes the moment jump by whole pixels between nearby
        // poses (measured on tas2000-bem.json: no load balanced, against six of seven with the
        // continuation). The state found is an equilibrium (forces, moments, a fixed zone) on
        // the path the iteration took.
        let pose = |s: &mut BemSolver, t: (f64, f64), prev: Option<&ContactSolution>| {
            s.set_heights(&tilted(base, t))?;
            solves.set(solves.get() + 1);
            let prev = prev.filter(|p| p.mean_pressure_pa <= target_pa * (1.0 + SAME_LOAD_SLACK));
            let (sol, plastic) = match (opts.hardness_pa, law) {
                // Capped poses continue from `prev` too, each solved exactly on a set of
                // candidate points (crate::restricted: bounded work, and a warm start cannot
                // stall it), on the whole grid only for a contact too large for a set.
                (Some(_), _) => {
                    let st = s.plastic_at_load_with(target_pa, law, opts, prev, false)?;
                    let pl = (st.plastic_fraction, st.plastic_area_m2, st.max_plastic_depth_m);
                    (st.solution, Some(pl))
                }
                (None, None) => (s.solve_load(target_pa, opts, prev)?, None),
                (None, Some(l)) => (s.adhesive_at_load(target_pa, l, opts, prev)?, None),
            };
            work.set(work.get() + sol.iterations);
            if work.get() > crate::error::PATH_WORK_FACTOR * opts.max_iterations {
                return Err(BemError::TiltWorkBudget { iterations: work.get(), target_pa });
            }
            let m = s.moments_n_m(&sol.pressure_pa);
            Ok::<_, BemError>(((sol, plastic), (m.0 / scale, m.1 / scale)))
        };
        let mut t = warm.map_or((0.0, 0.0), |w| (w.tilt_x_rad, w.tilt_y_rad));
        let (mut sol, mut m) = pose(self, t, warm.map(|w| &w.solution))?;
        // Characteristic tilt: the height range over the half-diagonal (at least one in 1e6).
        let (hmin, hmax) = base.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, &h| (a.0.min(h), a.1.max(h)));
        let tilt_scale = ((hmax - hmin) / half_diag).clamp(1e-6, MAX_TILT_RAD);
        // The grid's resolution of the balance: the centre of pressure one pixel from the clamp
        // point, |M|/F = max(dx, dy), in units of F L/2.
        let pixel_moment = g.dx_m.max(g.dy_m) / half_diag;
        let mut step = 0.25 * tilt_scale;
        let norm = |m: (f64, f64)| m.0.hypot(m.1);
        let dot = |a: (f64, f64), b: (f64, f64)| a.0 * b.0 + a.1 * b.1;
        let tip_over = || BemError::Value {
            name: "target_pa",
            value: target_pa,
            expected: "a load the shoe carries without tipping over (tilt below 0.05 rad)",
        };
        let done = |(sol, plastic): Pose, t: (f64, f64), m: (f64, f64), solves: usize| TiltedShoe {
            solution: sol,
            plastic,
            tilt_x_rad: t.0,
            tilt_y_rad: t.1,
            moment_residual_n_m: (m.0 * scale, m.1 * scale),
            solves,
        };
        // The outer iteration keeps the best pose (smallest |M|) and moves only to a better one;
        // it stops when |M| has not halved over STALL_ITERATIONS outer steps.
        let mut stalled = 0usize;
        let mut last_best = norm(m);
        let mut retry = false;
        loop {
            if norm(m) < MOMENT_TOLERANCE {
                return Ok(done(sol, t, m, solves.get()));
            }
            if stalled >= STALL_ITERATIONS || solves.get() >= MAX_POSE_SOLVES {
                // Cohesive zones and contacts change by whole pixels, so on a coarse grid the moment
                // jumps across zero and no pose balances it to MOMENT_TOLERANCE. A pose whose
                // centre of pressure lies within one pixel of the clamp point is the balance the
                // grid resolves; anything further is refused.
                if norm(m) <= pixel_moment {
                    return Ok(done(sol, t, m, solves.get()));
                }
                return Err(BemError::NoConvergence {
                    what: "tilting shoe (moment balance; the centre of pressure stays more than one pixel from the \
                           clamp point: refine the grid, contact.bem.pixel_size)",
                    iterations: solves.get(),
                    residual: norm(m),
                    tolerance: pixel_moment.max(MOMENT_TOLERANCE),
                });
            }
            // Jacobian dM/dt by forward differences, warm-started from the current state, over a
            // tilt that moves the face's edge by a part of the height range (not less: a smaller
            // step sees single pixels enter or leave the contact and the zone, not the slope).
            let eps = (0.1 * step).max(1e-3 * tilt_scale);
            let (_, mx) = pose(self, (t.0 + eps, t.1), Some(&sol.0))?;
            let (_, my) = pose(self, (t.0, t.1 + eps), Some(&sol.0))?;
            let j = [[(mx.0 - m.0) / eps, (my.0 - m.0) / eps], [(mx.1 - m.1) / eps, (my.1 - m.1) / eps]];
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let trace = j[0][0] + j[1][1];
            // The Newton step where the Jacobian is negative definite and well conditioned (an
            // ascent direction of the dual energy: m . dt > 0), else the moment itself (which
            // tilts the face down on the unloaded side).
            let newton = (det > 0.0 && trace < 0.0 && det > 1e-8 * trace * trace)
                .then(|| (-(j[1][1] * m.0 - j[0][1] * m.1) / det, -(-j[1][0] * m.0 + j[0][0] * m.1) / det))
                .filter(|d| dot(*d, m) > 0.0);
            // After an outer step that found no better pose the Newton step would repeat (the
            // same Jacobian): search along the moment's own direction instead.
            let newton = newton.filter(|_| !retry);
            let (dir, s0) = match newton {
                Some(d) => {
                    let len = d.0.hypot(d.1);
                    ((d.0 / len, d.1 / len), len.min(4.0 * tilt_scale))
                }
                None => ((m.0 / norm(m), m.1 / norm(m)), step),
            };
            let at = |s: f64| (t.0 + s * dir.0, t.1 + s * dir.1);
            let f0 = dot(m, dir);
            // The largest step that keeps the tilt within MAX_TILT_RAD: |t + s dir| = MAX.
            let b = dot(t, dir);
            let s_max = -b + (b * b - dot(t, t) + MAX_TILT_RAD * MAX_TILT_RAD).max(0.0).sqrt();
            let s0 = s0.min(s_max);
            // Every trial is a candidate; the best (smallest |M|) is kept.
            let mut best: Option<(f64, Pose, (f64, f64))> = None;
            let mut trial = |this: &mut BemSolver, s: f64| -> Result<(f64, f64), BemError> {
                let (st, mm) = pose(this, at(s), Some(&sol.0))?;
                let (f, n) = (dot(mm, dir), norm(mm));
                if best.as_ref().is_none_or(|b| n < norm(b.2)) {
                    best = Some((s, st, mm));
                }
                Ok((f, n))
            };
            let (f1, n1) = trial(self, s0)?;
            let halved = n1 < 0.5 * norm(m);
            if !(newton.is_some() && halved) {
                // Along the direction, f(s) = M(t + s dir) . dir is non-increasing (the dual
                // energy is concave): find its root by bracketing and the Illinois rule.
                let (mut lo, mut f_lo) = (0.0, f0);
                let (mut hi, mut f_hi) = (s0, f1);
                while f_hi > 0.0 && solves.get() < MAX_POSE_SOLVES {
                    if hi >= s_max {
                        return Err(tip_over());
                    }
                    lo = hi;
                    f_lo = f_hi;
                    hi = (2.0 * hi).min(s_max);
                    f_hi = trial(self, hi)?.0;
                }
                let mut side = 0i8;
                for _ in 0..MAX_BRACKET_STEPS {
                    if f_hi > 0.0 || solves.get() >= MAX_POSE_SOLVES || f_hi.abs() <= 0.1 * f0 {
                        break;
                    }
                    let s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
                    let s = if s.is_finite() && s > lo && s < hi { s } else { 0.5 * (lo + hi) };
                    let f = trial(self, s)?.0;
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
                }
            }
            // Move only to a better pose; from a worse one the next Jacobian would start astray.
            if let Some((s_new, sol_new, m_new)) = best.filter(|b| norm(b.2) < norm(m)) {
                t = at(s_new);
                sol = sol_new;
                m = m_new;
                step = s_new.max(1e-6 * tilt_scale);
                retry = false;
            } else {
                step *= 0.25;
                retry = true;
            }
            if norm(m) < 0.5 * last_best {
                last_best = norm(m);
                stalled = 0;
            } else {
                stalled += 1;
            }
        }
    }
}
