//! The Newton iteration of one solve: the first evaluation and the load history
//! ([`equilibrate`]), the clipped-Hessian phase and the exact-Hessian phase ([`iterate`]), each a
//! loop of active-set updates, direction, trust radius and line search ([`iterate_phase`]), the
//! release of members past their release interference, and the tip of a neutral equilibrium
//! towards the next contact.

use nalgebra::Matrix3;

use super::direction::direction;
use super::eval::Eval;
use super::exact_hessian::exact_newton_direction;
use super::geometry::{Geom, State, interference};
use super::pass::evaluate;
use super::shortcuts::{linear_step, predictor};
use crate::explicit::laws::LawEval;
use crate::explicit::types::*;

/// Largest tilt of a tilt-free shoe \[rad\]: beyond it the small-angle plane `w = d + t x` is no
/// longer the shoe face (error 1e-3 of the movement) and the solve reports that the shoe tips over.
/// Equilibria of the Table 1 surfaces stay below 3e-3 rad.
pub(crate) const MAX_TILT_RAD: f64 = 0.05;

/// Relative residual below which members past their release interference leave the contact set.
pub(super) const RELEASE_RESIDUAL: f64 = 1e-4;

#[allow(clippy::too_many_arguments)]
pub(super) fn equilibrate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
) -> Result<usize, SolveError> {
    let fixed = g.support.is_some();
    let tau_min = 1e-15 * height_range.max(1e-9);
    st.tau = st.tau.max(tau_min).max(1e-3 * height_range);
    let phi0 = g.phi_at(g.load_point.0, g.load_point.1);
    let mut predict = None;
    let mut ev = match st.cache {
        // The previous solve ended here: only the load term of the gradient changes.
        Some((generation, q, mut cached)) if generation == st.generation && q == st.q => {
            cached.g.iter_mut().zip(&phi0).for_each(|(gj, pj)| *gj += load * pj);
            touch.clear();
            predict = if g.shortcuts { predictor(st, load) } else { None };
            cached
        }
        _ => evaluate(g, law, st, &st.q, load, !fixed, true, touch),
    };
    for &i in touch.iter() {
        st.join(g, i as usize);
    }
    let result = iterate(g, law, st, touch, load, cfg, adhesion_ref, height_range, &mut ev, predict);
    st.cache = match result {
        Ok(_) => {
            let mut e = ev;
            e.g.iter_mut().zip(&phi0).for_each(|(gj, pj)| *gj -= load * pj);
            if st.history_len == 3 {
                st.history.rotate_left(1);
                st.history_len = 2;
            }
            st.history[st.history_len] = (load, st.q);
            st.history_len += 1;
            Some((st.generation, st.q, e))
        }
        Err(_) => None,
    };
    result
}

/// The Newton iteration of one solve: [`iterate_phase`] with the Hessian of the evaluation pass
/// (each summit's stiffness clipped at >= 0, the meniscus tails left out), and, only if that does
/// not converge within `max_iterations`, a second phase of up to `max_iterations` more on the
/// Hessian of the exact forces (central differences of the gradient).
///
/// Why: the clipped Hessian is exact for Hertz/DMT dry, but it overestimates the stiffness of a
/// summit on the falling part of its JKR/Maugis-Dugdale branch (dP/dz < 0 between its
/// load-controlled pull-off and its release) and of a meniscus tail (`-f R / h_m`). Newton's
/// method with a stiffness `K_c` above the true `K` converges linearly with the ratio
/// `1 - K / K_c`; near the pull-off of the contact `K -> 0` (at a load `eps` above it
/// `K ~ sqrt(eps)`), so a pull-off bisection, which probes ever closer to the fold, ran out of
/// iterations (NotConverged a few parts per million above the pull-off, e.g. one JKR summit with
/// a meniscus at -0.665 uN), and just below the pull-off a solve crawled towards separation (steps
/// of 1e-17 m: the clipped stiffness resists a force excess of 1e-15 N). With the exact Hessian the
/// convergence is quadratic again; where it is not positive definite (beyond the fold: the load is
/// below the pull-off of this contact) the step goes down the energy along its negative curvature,
/// capped by the trust radius, and the shoe comes off in a few steps
/// ([`super::exact_hessian::exact_newton_direction`]).
/// Every solve that converged in the first phase is unchanged to the bit.
#[allow(clippy::too_many_arguments)]
pub(super) fn iterate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
    ev: &mut Eval,
    predict: Option<[f64; 3]>,
) -> Result<usize, SolveError> {
    let phase = |st: &mut State, touch: &mut Vec<u32>, ev: &mut Eval, predict, fd: Option<f64>, it, limit| {
        iterate_phase(g, law, st, touch, load, cfg, adhesion_ref, height_range, ev, predict, fd, it, limit)
    };
    match phase(st, touch, ev, predict, None, 0, cfg.max_iterations) {
        Err(SolveError::NotConverged { iterations, .. }) => {
            // Difference step: 1e-5 of the law's reach (JKR/MD release, meniscus height), or of
            // a thousandth of the height range for Hertz/DMT dry.
            let fd = 1e-5 * (-law.z_min()).max(1e-3 * height_range.max(1e-9));
            phase(st, touch, ev, None, Some(fd), iterations, iterations + cfg.max_iterations)
        }
        other => other,
    }
}

/// One phase of the Newton iteration (see [`iterate`]): from iteration `it` up to `limit`; `fd`:
/// the difference step of the exact Hessian (None: the pass's clipped Hessian).
#[allow(clippy::too_many_arguments)]
pub(super) fn iterate_phase<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
    ev: &mut Eval,
    mut predict: Option<[f64; 3]>,
    fd: Option<f64>,
    mut it: usize,
    limit: usize,
) -> Result<usize, SolveError> {
    let fixed = g.support.is_some();
    let tau_min = 1e-15 * height_range.max(1e-9);
    let tau_max = 1e3 * height_range + 1e-6;
    loop {
        let scale = load.abs().max(ev.force_abs).max(adhesion_ref).max(1e-300);
        let tol = cfg.relative_tolerance * scale;
        let resid = ev.g[..g.ndof].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // Active-set update once the Newton iteration has nearly converged on the current set
        // (the last steps are small, so no member is released by an overshoot).
        // DMT/Hertz: a member past its release interference pulls with its largest tension
        // p_rel. When every contributor is past release and together they cannot carry the
        // (tensile) load, no pose with this contact set is an equilibrium: the shoe comes off.
        if !fixed
            && load < 0.0
            && law.release_force_is_extreme()
            && st.members > 0
            && ev.releases == st.members
            && ev.contacts == ev.releases
            && ev.force > load
        {
            return Err(separates(load));
        }
        if resid <= tol.max(RELEASE_RESIDUAL * scale) && ev.releases > 0 && !fixed {
            release(g, law, st, ev);
            if st.members == 0 && load <= 0.0 {
                return Err(separates(load));
            }
            it += 1;
            if it >= limit {
                break;
            }
            continue;
        }
        if resid <= tol {
            if ev.releases == 0 {
                if st.members == 0 {
                    return Err(SolveError::NoEquilibrium { load_n: load, reason: "no summit in contact".into() });
                }
                // A neutral equilibrium (a tilt no contact resists, e.g. one summit at zero load)
                // is not stable: tip the shoe until the nearest summit touches, then go on.
                if !fixed
                    && g.ndof > 1
                    && it < limit
                    && let Some(dq) = tip_to_next_contact(g, law, st, ev)
                {
                    st.q = [st.q[0] + dq[0], st.q[1] + dq[1], st.q[2] + dq[2]];
                    *ev = evaluate(g, law, st, &st.q, load, true, true, touch);
                    for &i in touch.iter() {
                        st.join(g, i as usize);
                    }
                    it += 1;
                    continue;
                }
                return Ok(it);
            }
            if fixed {
                // Report the first support that left contact.
                let (a, b, c) = g.plane(&st.q);
                for i in 0..g.support.unwrap_or(0) {
                    let z = g.hs[i] - (a + b * f64::from(g.xs[i]) + c * f64::from(g.ys[i]));
                    if z < law.z_rel(i) {
                        return Err(SolveError::ContactLost {
                            load_n: load,
                            index: g.original_index(i),
                            interference_m: z,
                        });
                    }
                }
            }
            // Release the members below their release interference (active-set update).
            release(g, law, st, ev);
            if st.members == 0 && load <= 0.0 {
                return Err(separates(load));
            }
            it += 1;
            if it >= limit {
                break;
            }
            continue;
        }
        if st.members == 0 && load < 0.0 {
            return Err(separates(load));
        }
        it += 1;
        if it >= limit {
            break;
        }
        // Direction, capped by the trust radius.
        let mut dq = match fd {
            Some(h) => exact_newton_direction(g, law, st, touch, load, ev, h, tol)
                .unwrap_or_else(|| direction(ev, g.ndof, tol, st.tau)),
            None => direction(ev, g.ndof, tol, st.tau),
        };
        // First step of a solve along a smooth load path: the extrapolated pose, when it agrees
        // with the Newton step (whose stiffness misses the summits that will touch and the
        // change of the stiffness along the step) to 10 % of the step.
        if let Some(qp) = predict.take() {
            let dp = [qp[0] - st.q[0], qp[1] - st.q[1], qp[2] - st.q[2]];
            let diff = [dp[0] - dq[0], dp[1] - dq[1], dp[2] - dq[2]];
            if g.movement(&diff) <= 0.1 * g.movement(&dq) {
                dq = dp;
            }
        }
        let mv = g.movement(&dq);
        let mut capped = false;
        if mv > st.tau {
            let s = st.tau / mv;
            dq.iter_mut().for_each(|v| *v *= s);
            capped = true;
        }
        if !capped && !fixed && g.shortcuts && fd.is_none() && linear_step(g, law, st, ev, &dq, mv, tol) {
            continue;
        }
        let slope0: f64 = (0..3).map(|j| ev.g[j] * dq[j]).sum();
        if slope0 >= 0.0 {
            // No descent possible within rounding: accept the current point as converged only if
            // the residual is small; otherwise report.
            break;
        }
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..60 {
            let qt = [st.q[0] + alpha * dq[0], st.q[1] + alpha * dq[1], st.q[2] + alpha * dq[2]];
            // The first step of a solve carries the load increment: it is never the last one, so
            // its pass skips the statistics of a linear step.
            let evt = evaluate(g, law, st, &qt, load, !fixed, it > 1, touch);
            let slope: f64 = (0..3).map(|j| evt.g[j] * dq[j]).sum();
            if slope <= 0.9 * slope0.abs() {
                accepted = Some((qt, evt));
                break;
            }
            let sec = slope0 / (slope0 - slope);
            alpha *= sec.clamp(0.1, 0.5);
        }
        let Some((qt, evt)) = accepted else { break };
        st.q = qt;
        *ev = evt;
        for &i in touch.iter() {
            st.join(g, i as usize);
        }
        if alpha == 1.0 && capped {
            st.tau = (2.0 * st.tau).min(tau_max);
            if st.tau >= tau_max && st.members < 3 && g.ndof == 3 && ev.contacts == 0 {
                return Err(SolveError::NoEquilibrium {
                    load_n: load,
                    reason: "the shoe tips over: nothing supports the load point".into(),
                });
            }
        } else if alpha < 1.0 {
            st.tau = (alpha * mv.min(st.tau)).max(tau_min);
        }
        if st.tau >= tau_max {
            return Err(SolveError::NoEquilibrium {
                load_n: load,
                reason: "the shoe moves without bound (tips over or separates)".into(),
            });
        }
        if g.ndof == 3 && !fixed {
            let (_, tx, ty) = g.plane(&st.q);
            if tx.hypot(ty) > MAX_TILT_RAD {
                return Err(SolveError::NoEquilibrium {
                    load_n: load,
                    reason: format!(
                        "the shoe tips over (tilt above {MAX_TILT_RAD} rad, outside the small-angle model)"
                    ),
                });
            }
        }
    }
    let scale = load.abs().max(ev.force_abs).max(adhesion_ref);
    let resid = ev.g[..g.ndof].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if resid <= cfg.relative_tolerance * scale && ev.releases == 0 && st.members > 0 {
        return Ok(it);
    }
    Err(SolveError::NotConverged { load_n: load, iterations: it, residual_n: resid, contacts: st.members })
}

/// Active-set update at the current pose: members below their release interference leave the
/// contact set. They were off the contact branch (constant force p_rel, zero stiffness) in the
/// evaluation `ev` at this pose, so their terms are removed from it without a new pass (no other
/// summit can touch at the same pose: touching summits joined when `ev` was computed).
pub(super) fn release<L: LawEval + ?Sized>(g: &Geom, law: &L, st: &mut State, ev: &mut Eval) {
    let q = st.q;
    let (x0, y0) = g.load_point;
    let words = st.bound.div_ceil(64);
    // The fast pass names the words holding members past release (members only leave the set
    // here, and summits that joined at this pose have z >= 0, so no other word can hold one).
    let (lo, hi) = match ev.release_words {
        Some((lo, hi)) => (lo, (hi + 1).min(words)),
        None => (0, words),
    };
    for w in lo..hi {
        let mut bits = st.member[w];
        while bits != 0 {
            let i = w * 64 + bits.trailing_zeros() as usize;
            bits &= bits - 1;
            if interference(g, law, &q, i) < law.z_rel(i) {
                st.leave(g, i);
                let p = law.p_rel(i);
                let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
                let phi = g.phi_at(x, y);
                for (gj, fj) in ev.g.iter_mut().zip(&phi) {
                    *gj += p * fj;
                }
                ev.force -= p;
                ev.force_abs = (ev.force_abs - p.abs()).max(0.0);
                ev.moment_x -= p * (x - x0);
                ev.moment_y -= p * (y - y0);
                ev.contacts -= 1;
                ev.releases = ev.releases.saturating_sub(1);
                ev.released = true;
            }
        }
    }
}

/// For a converged pose whose Hessian is singular on the used degrees of freedom, the smallest
/// rotation along a zero-stiffness direction (either sense) that brings a non-member summit to its
/// jump-in interference; None when the Hessian is regular or nothing can be reached.
pub(super) fn tip_to_next_contact<L: LawEval + ?Sized>(g: &Geom, law: &L, st: &State, ev: &Eval) -> Option<[f64; 3]> {
    let mut m = Matrix3::zeros();
    for j in 0..g.ndof {
        for k in 0..g.ndof {
            m[(j, k)] = ev.h[j][k];
        }
    }
    let eig = m.symmetric_eigen();
    let lam_max = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b));
    let (a, b, c) = g.plane(&st.q);
    let mut best: Option<(f64, [f64; 3])> = None;
    for k in 0..3 {
        if eig.eigenvalues[k] > 1e-12 * lam_max && lam_max > 0.0 {
            continue;
        }
        let v = eig.eigenvectors.column(k);
        let mut vq = [v[0], v[1], v[2]];
        vq.iter_mut().skip(g.ndof).for_each(|v| *v = 0.0);
        if vq.iter().all(|x| x.abs() < 1e-12) {
            continue;
        }
        let (da, db, dc) = g.plane(&vq);
        // Lower bound of the step that brings summit i to touch: its gap is at least
        // z_min + w_min - h_i (w_min the lowest plane point over the apparent area) and the plane
        // moves by at most dw_max per unit step there (a linear function: largest at a corner).
        // It grows down the height-sorted list, so the scan stops once it exceeds the best step
        // (summits lie inside the apparent area: Surface::new checks it).
        let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
        let dw_max = g.movement(&vq) * (1.0 + 1e-9);
        let z_min = law.z_min();
        for i in 0..g.hs.len() {
            if let Some((b0, _)) = best
                && (z_min + wmin - g.hs[i]) > b0 * dw_max + 1e-12 * (wmin.abs() + g.hs[i].abs())
            {
                break;
            }
            if st.is_member(i) {
                continue;
            }
            let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
            let gap = law.z_in(i) - (g.hs[i] - (a + b * x + c * y));
            let dw = da + db * x + dc * y;
            if gap <= 0.0 || dw == 0.0 {
                continue;
            }
            // Moving by alpha * (sign * v) lowers the plane at i by alpha * sign * (-dw).
            let alpha = gap / dw.abs();
            let sign = if dw < 0.0 { 1.0 } else { -1.0 };
            if best.is_none_or(|(b0, _)| alpha < b0) {
                let s = sign * alpha * (1.0 + 1e-9);
                best = Some((alpha, [s * vq[0], s * vq[1], s * vq[2]]));
            }
        }
    }
    best.map(|(_, dq)| dq)
}

/// The shoe comes off: the load is below the pull-off of the current contact.
pub(super) fn separates(load_n: f64) -> SolveError {
    SolveError::NoEquilibrium { load_n, reason: "the shoe separates from the surface (load below pull-off)".into() }
}
