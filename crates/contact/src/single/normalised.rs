//! Maugis-Dugdale and JKR in the normalised (Maugis) variables of the [module docs](super): the
//! solution at one contact radius ([`maugis_state`], [`jkr_state`]), the load-controlled branch
//! of one Maugis parameter ([`MaugisCurve`]) and its table for the explicit solver
//! ([`MaugisTable`]). Dimensionless throughout; the dimensional laws are in `single.rs`.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::error::{ContactError, check_finite, check_positive};

// ---------------------------------------------------------------------------------------------
// Maugis-Dugdale in normalised variables
// ---------------------------------------------------------------------------------------------

/// State of the Maugis-Dugdale solution at one normalised contact radius (equations MD-1..3 of
/// the module docs, solved in the form regular at `A = 0`, see [`maugis_state`]).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct MaugisState {
    /// Normalised contact radius `A = a/(pi dgamma R^2 D)^(1/3)`.
    pub a_hat: f64,
    /// Normalised outer radius of the Dugdale zone `C = m A`.
    pub c_hat: f64,
    /// `Q = sqrt(C^2 - A^2) = A s` (the unknown of MD-1).
    pub q_hat: f64,
    /// Normalised load `P/(pi dgamma R)` (MD-2).
    pub p_bar: f64,
    /// Normalised interference `delta/(pi^2 dgamma^2 R D^2)^(1/3)` (MD-3).
    pub delta_bar: f64,
    /// `dP_bar/dA`.
    pub dp_bar_da: f64,
    /// `dDelta/dA`.
    pub ddelta_bar_da: f64,
}

/// `s - atan s`, accurate also for small `s`.
pub(super) fn s_minus_atan(s: f64) -> f64 {
    if s < 0.5 {
        // s^3/3 - s^5/5 + s^7/7 - ...
        let s2 = s * s;
        let mut term = s * s2;
        let mut sum = 0.0;
        let mut k = 3.0;
        let mut sign = 1.0;
        while term > 1e-18 * s * s2 {
            sum += sign * term / k;
            term *= s2;
            k += 2.0;
            sign = -sign;
        }
        sum
    } else {
        s - s.atan()
    }
}

/// MD-1 in the variables `A`, `Q = sqrt(C^2 - A^2)`, `theta = atan2(Q, A)`:
/// `F = (lambda/2) T1 + (4 lambda^2/3) T2 - 1` with `T1 = A Q + (Q^2 - A^2) theta`,
/// `T2 = Q theta - (C - A)`. Returns `(F, dF/dQ, dF/dA)`.
#[inline]
pub(super) fn md_residual(lambda: f64, a: f64, q: f64) -> (f64, f64, f64) {
    let theta = q.atan2(a);
    let c2 = a * a + q * q;
    let c = c2.sqrt();
    let c_minus_a = if a > 0.0 { q * q / (c + a) } else { c };
    // T1 = A^2 (s - atan s) + Q^2 theta, s = Q/A (no cancellation for Q << A)
    let t1 = if a > 2.0 * q { a * a * s_minus_atan(q / a) + q * q * theta } else { a * q + (q * q - a * a) * theta };
    let t2 = q * theta - c_minus_a;
    let (t1_q, t1_a, t2_q, t2_a) = if c2 > 0.0 {
        (
            2.0 * a * q * q / c2 + 2.0 * q * theta,
            2.0 * a * a * q / c2 - 2.0 * a * theta,
            theta - q * c_minus_a / c2,
            -a * q * q / (c2 * (c + a)),
        )
    } else {
        (0.0, 0.0, 0.0, 0.0)
    };
    let k1 = 0.5 * lambda;
    let k2 = 4.0 / 3.0 * lambda * lambda;
    (k1 * t1 + k2 * t2 - 1.0, k1 * t1_q + k2 * t2_q, k1 * t1_a + k2 * t2_a)
}

/// Solve MD-1 for `Q >= 0` at given `lambda > 0`, `A >= 0`. `guess <= 0` means none.
pub(super) fn maugis_q(lambda: f64, a_hat: f64, guess: f64) -> f64 {
    let mut q = if guess > 0.0 && guess.is_finite() {
        guess
    } else {
        // Q >> A (exact at A = 0): (pi lambda/4) Q^2 + (4 lambda^2/3)(pi/2 - 1) Q = 1;
        // Q << A: (2 lambda/(3A)) Q^3 + (2 lambda^2/(3A)) Q^2 = 1.
        let qa = PI * lambda / 4.0;
        let qb = 4.0 * lambda * lambda / 3.0 * (PI / 2.0 - 1.0);
        let q_large = 2.0 / (qb + (qb * qb + 4.0 * qa).sqrt());
        if a_hat > 0.0 {
            let q_small = (1.5 * a_hat / lambda).cbrt().min((1.5 * a_hat / (lambda * lambda)).sqrt());
            q_large.min(q_small)
        } else {
            q_large
        }
    };
    let mut lo = 0.0;
    let mut hi = f64::INFINITY;
    for _ in 0..300 {
        let (f, df, _) = md_residual(lambda, a_hat, q);
        if f == 0.0 {
            return q;
        }
        if f < 0.0 {
            lo = q;
        } else {
            hi = q;
        }
        let mut next = q - f / df;
        if !(next > lo && next < hi && next.is_finite()) {
            next = if hi.is_finite() { 0.5 * (lo + hi) } else { 2.0 * q.max(1e-300) };
        }
        if (next - q).abs() <= 4.0 * f64::EPSILON * q {
            return next;
        }
        q = next;
    }
    q
}

/// Maugis-Dugdale state at normalised contact radius `a_hat >= 0` for Maugis parameter
/// `lambda > 0`. MD-1..3 are solved with the unknown `Q = sqrt(C^2 - A^2)` (`C` the normalised
/// outer radius of the Dugdale zone), in which they are regular down to `A = 0`:
/// `P_bar = A^3 - lambda (A Q + C^2 theta)`, `Delta = A^2 - (4/3) lambda Q`,
/// `theta = atan2(Q, A)`. At `A = 0`: `(pi lambda/4) C^2 + (4 lambda^2/3)(pi/2 - 1) C = 1`,
/// `P_bar = -(pi/2) lambda C^2`, `Delta = -(4/3) lambda C`. `q_guess` (<= 0 for none) speeds up
/// the solve of MD-1 (Newton's method safeguarded by bisection, to machine precision).
pub fn maugis_state(lambda: f64, a_hat: f64, q_guess: f64) -> MaugisState {
    let a = a_hat.max(0.0);
    let q = maugis_q(lambda, a, q_guess);
    let (_, f_q, f_a) = md_residual(lambda, a, q);
    let dq_da = -f_a / f_q;
    let theta = q.atan2(a);
    let c2 = a * a + q * q;
    let p_bar = a * a * a - lambda * (a * q + c2 * theta);
    let dp = 3.0 * a * a - lambda * (2.0 * a * theta + (2.0 * a + 2.0 * q * theta) * dq_da);
    let delta_bar = a * a - 4.0 / 3.0 * lambda * q;
    let dd = 2.0 * a - 4.0 / 3.0 * lambda * dq_da;
    MaugisState { a_hat: a, c_hat: c2.sqrt(), q_hat: q, p_bar, delta_bar, dp_bar_da: dp, ddelta_bar_da: dd }
}

/// Solve `value(x) = target` for an increasing function on `[lo, hi]` with
/// `value(lo) <= target <= value(hi)` by Newton's method safeguarded with bisection.
/// `eval(x, hint)` returns `(value, derivative, hint)`; the hint (e.g. the MD `Q`) is passed to the
/// next evaluation.
pub(super) fn solve_increasing(
    target: f64,
    mut lo: f64,
    mut hi: f64,
    mut x: f64,
    mut hint: f64,
    mut eval: impl FnMut(f64, f64) -> (f64, f64, f64),
    what: &'static str,
) -> Result<(f64, f64), ContactError> {
    if !(x > lo && x < hi) {
        x = 0.5 * (lo + hi);
    }
    for _ in 0..300 {
        let (v, dv, h) = eval(x, hint);
        hint = h;
        let r = v - target;
        if r == 0.0 {
            return Ok((x, hint));
        }
        if r < 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let mut next = x - r / dv;
        if !(next > lo && next < hi && next.is_finite()) {
            next = 0.5 * (lo + hi);
        }
        if (next - x).abs() <= 2.0 * f64::EPSILON * x.abs() || hi - lo <= 2.0 * f64::EPSILON * hi {
            return Ok((next, hint));
        }
        x = next;
    }
    Err(ContactError::NoConvergence { what, iterations: 300 })
}

/// Minimum over `A >= 0` of `value(state)` (whose derivative is `deriv(state)`): the curve is
/// sampled on a grid (A = 0, 1e-6..1e-2 logarithmically, 0..6 in steps of 0.01), the lowest sample
/// is refined by bisection on the sign of the derivative (or kept at `A = 0`).
pub(super) fn maugis_min(
    lambda: f64,
    value: impl Fn(&MaugisState) -> f64,
    deriv: impl Fn(&MaugisState) -> f64,
) -> MaugisState {
    let mut grid: Vec<f64> = vec![0.0];
    grid.extend((0..=16).map(|i| 1e-6 * 10f64.powf(i as f64 / 4.0)));
    grid.extend((2..=600).map(|i| i as f64 * 0.01));
    let mut best = maugis_state(lambda, 0.0, 0.0);
    let mut best_i = 0;
    let mut q = best.q_hat;
    for (i, &a) in grid.iter().enumerate().skip(1) {
        let st = maugis_state(lambda, a, q);
        q = st.q_hat;
        if value(&st) < value(&best) {
            best = st;
            best_i = i;
        }
    }
    if best_i == 0 {
        return best;
    }
    let mut lo = grid[best_i - 1];
    let mut hi = grid[(best_i + 1).min(grid.len() - 1)];
    let mut q = best.q_hat;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        let st = maugis_state(lambda, mid, q);
        q = st.q_hat;
        if deriv(&st) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    maugis_state(lambda, 0.5 * (lo + hi), q)
}

/// The characteristic points of the Maugis-Dugdale curve for one `lambda`, and its solves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaugisCurve {
    /// Maugis parameter `lambda`.
    pub lambda: f64,
    /// State at `A = 0` (jump-in on loading under displacement control: `delta_in = Delta(0)`).
    pub zero_radius: MaugisState,
    /// Minimum of `P_bar(A)`: load-controlled pull-off (`P_bar` from -2 at `lambda -> 0` to -1.5
    /// at `lambda -> inf`).
    pub load_minimum: MaugisState,
    /// Minimum of `Delta(A)`: displacement-controlled pull-off (end of the unloading branch).
    pub interference_minimum: MaugisState,
}

impl MaugisCurve {
    /// Characteristic points for Maugis parameter `lambda` (finite, > 0).
    pub fn new(lambda: f64) -> Result<Self, ContactError> {
        check_positive("lambda", lambda, "a finite Maugis parameter > 0")?;
        Ok(MaugisCurve {
            lambda,
            zero_radius: maugis_state(lambda, 0.0, 0.0),
            load_minimum: maugis_min(lambda, |s| s.p_bar, |s| s.dp_bar_da),
            interference_minimum: maugis_min(lambda, |s| s.delta_bar, |s| s.ddelta_bar_da),
        })
    }

    /// State at normalised contact radius `a_hat >= 0`.
    pub fn state(&self, a_hat: f64) -> MaugisState {
        maugis_state(self.lambda, a_hat, 0.0)
    }

    fn upper_bracket(&self, start: MaugisState, target: f64, f: fn(&MaugisState) -> f64) -> MaugisState {
        let mut st = start;
        let mut a = start.a_hat.max(1.0);
        loop {
            a *= 2.0;
            st = maugis_state(self.lambda, a, st.q_hat);
            if f(&st) >= target || a > 1e150 {
                return st;
            }
        }
    }

    /// State on the load-controlled stable branch (`dP/dA > 0`) at normalised load `p_bar`;
    /// `Err(NoEquilibrium)` below the pull-off load.
    pub fn state_at_load(&self, p_bar: f64) -> Result<MaugisState, ContactError> {
        check_finite("p_bar", p_bar, "a finite normalised load")?;
        let low = self.load_minimum;
        if p_bar < low.p_bar {
            return Err(ContactError::NoEquilibrium {
                quantity: "p_bar",
                value: p_bar,
                pull_off: format!("{}", low.p_bar),
            });
        }
        if p_bar == low.p_bar {
            return Ok(low);
        }
        let hi = self.upper_bracket(low, p_bar, |s| s.p_bar);
        let guess = (p_bar.max(0.0) + 2.0).cbrt().clamp(low.a_hat, hi.a_hat);
        let lambda = self.lambda;
        let (a, s) = solve_increasing(
            p_bar,
            low.a_hat,
            hi.a_hat,
            guess,
            0.0,
            |a, h| {
                let st = maugis_state(lambda, a, h);
                (st.p_bar, st.dp_bar_da, st.q_hat)
            },
            "Maugis-Dugdale contact radius from load",
        )?;
        Ok(maugis_state(lambda, a, s))
    }

    /// State on the displacement-controlled stable branch (`dDelta/dA > 0`) at normalised
    /// interference `delta_bar`; `None` below the end of the branch
    /// (`interference_minimum.delta_bar`).
    pub fn state_at_interference(&self, delta_bar: f64) -> Option<MaugisState> {
        let low = self.interference_minimum;
        if delta_bar.is_nan() || delta_bar < low.delta_bar {
            return None;
        }
        if delta_bar == low.delta_bar {
            return Some(low);
        }
        let hi = self.upper_bracket(low, delta_bar, |s| s.delta_bar);
        let guess = delta_bar.max(0.0).sqrt().clamp(low.a_hat, hi.a_hat);
        let lambda = self.lambda;
        solve_increasing(
            delta_bar,
            low.a_hat,
            hi.a_hat,
            guess,
            0.0,
            |a, h| {
                let st = maugis_state(lambda, a, h);
                (st.delta_bar, st.ddelta_bar_da, st.q_hat)
            },
            "Maugis-Dugdale contact radius from interference",
        )
        .ok()
        .map(|(a, s)| maugis_state(lambda, a, s))
    }
}

/// A precomputed Maugis-Dugdale table for fast interference-controlled solves: the stable
/// (displacement-controlled) branch sampled at 257 radii from the end of the branch to `A = 40`
/// (quadratically spaced). A solve brackets the root in the table and refines it with a few
/// safeguarded Newton steps on the exact equations MD-1..3, so results are as exact as
/// [`MaugisCurve::state_at_interference`] (relative ~1e-15 in `A`), in a few microseconds.
#[derive(Clone, Debug, PartialEq)]
pub struct MaugisTable {
    /// The curve's characteristic points.
    pub curve: MaugisCurve,
    a_hat: Vec<f64>,
    q: Vec<f64>,
    delta_bar: Vec<f64>,
}

impl MaugisTable {
    /// Build the table for Maugis parameter `lambda` (finite, > 0).
    pub fn new(lambda: f64) -> Result<Self, ContactError> {
        let curve = MaugisCurve::new(lambda)?;
        let n = 256;
        let a0 = curve.interference_minimum.a_hat;
        let a_max = 40.0_f64.max(2.0 * a0);
        let mut a_hat = Vec::with_capacity(n + 1);
        let mut q = Vec::with_capacity(n + 1);
        let mut delta_bar = Vec::with_capacity(n + 1);
        let mut guess = curve.interference_minimum.q_hat;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let a = a0 + (a_max - a0) * t * t;
            let st = if i == 0 { curve.interference_minimum } else { maugis_state(lambda, a, guess) };
            guess = st.q_hat;
            a_hat.push(st.a_hat);
            q.push(st.q_hat);
            delta_bar.push(st.delta_bar);
        }
        Ok(MaugisTable { curve, a_hat, q, delta_bar })
    }

    /// Same as [`MaugisCurve::state_at_interference`], faster.
    pub fn state_at_interference(&self, delta_bar: f64) -> Option<MaugisState> {
        let lambda = self.curve.lambda;
        let low = self.curve.interference_minimum;
        if delta_bar.is_nan() || delta_bar < low.delta_bar {
            return None;
        }
        if delta_bar == low.delta_bar {
            return Some(low);
        }
        let i = self.delta_bar.partition_point(|&d| d < delta_bar);
        let (lo, hi, guess, s_guess) = if i >= self.delta_bar.len() {
            let last = self.a_hat.len() - 1;
            let mut hi = self.a_hat[last];
            loop {
                hi *= 2.0;
                let st = maugis_state(lambda, hi, 0.0);
                if st.delta_bar >= delta_bar || hi > 1e150 {
                    break;
                }
            }
            let g = delta_bar.sqrt().clamp(self.a_hat[last], hi);
            (self.a_hat[last], hi, g, self.q[last])
        } else {
            let i = i.max(1);
            let (d0, d1) = (self.delta_bar[i - 1], self.delta_bar[i]);
            let t = ((delta_bar - d0) / (d1 - d0)).clamp(0.0, 1.0);
            let g = self.a_hat[i - 1] + t * (self.a_hat[i] - self.a_hat[i - 1]);
            let sg = self.q[i - 1] + t * (self.q[i] - self.q[i - 1]);
            (self.a_hat[i - 1], self.a_hat[i], g, sg)
        };
        solve_increasing(
            delta_bar,
            lo,
            hi,
            guess,
            s_guess,
            |a, h| {
                let st = maugis_state(lambda, a, h);
                (st.delta_bar, st.ddelta_bar_da, st.q_hat)
            },
            "Maugis-Dugdale table solve",
        )
        .ok()
        .map(|(a, s)| maugis_state(lambda, a, s))
    }
}

// ---------------------------------------------------------------------------------------------
// JKR in normalised variables
// ---------------------------------------------------------------------------------------------

/// JKR (normalised): `P_bar = A^3 - sqrt(6 A^3)`, `Delta = A^2 - sqrt(8A/3)` and derivatives.
pub fn jkr_state(a_hat: f64) -> MaugisState {
    let k = (8.0_f64 / 3.0).sqrt();
    let sq = a_hat.sqrt();
    let a2 = a_hat * a_hat;
    MaugisState {
        a_hat,
        c_hat: a_hat,
        q_hat: 0.0,
        p_bar: a2 * a_hat - 6f64.sqrt() * a_hat * sq,
        delta_bar: a2 - k * sq,
        dp_bar_da: 3.0 * a2 - 1.5 * 6f64.sqrt() * sq,
        ddelta_bar_da: if a_hat > 0.0 { 2.0 * a_hat - 0.5 * k / sq } else { f64::NEG_INFINITY },
    }
}

/// JKR end of the unloading branch under displacement control: `A_c = 6^(-1/3)`,
/// `Delta_c = 6^(-2/3) - sqrt(8/3) 6^(-1/6) = -0.9086`, `P_bar = -5/6`.
pub fn jkr_interference_minimum() -> MaugisState {
    jkr_state(6f64.powf(-1.0 / 3.0))
}

/// JKR state on the displacement-controlled stable branch at `delta_bar >= Delta_c`.
pub(super) fn jkr_state_at_interference(delta_bar: f64) -> MaugisState {
    // x = sqrt(A): f(x) = x^4 - k x - delta, convex; Newton from the right converges monotonically.
    let k = (8.0_f64 / 3.0).sqrt();
    let xc = (k / 4.0).cbrt();
    let mut x = (2.0 * k).cbrt().max((2.0 * delta_bar.max(0.0)).sqrt().sqrt());
    for _ in 0..100 {
        let x3 = x * x * x;
        let f = x3 * x - k * x - delta_bar;
        let df = 4.0 * x3 - k;
        let next = (x - f / df).max(xc);
        if (next - x).abs() <= 2.0 * f64::EPSILON * x {
            x = next;
            break;
        }
        x = next;
    }
    jkr_state(x * x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn md_small_s_series_matches_direct() {
        // s - atan s: series vs direct at s = 0.49 (no cancellation problem there), rel 1e-14
        let s: f64 = 0.49;
        let direct = s - s.atan();
        assert!((s_minus_atan(s) - direct).abs() <= 1e-14 * direct);
    }
}
