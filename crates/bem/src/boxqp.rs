//! The capped contact problem on a small set of points, solved exactly by a primal active-set
//! method ([`solve_capped`]).
//!
//! On a set `S` of `m` candidate points with the influence matrix `K` (m/Pa, symmetric positive
//! definite), heights `b` (m) and a total `T = sum_S x` (Pa times points) the capped problem is
//! the convex quadratic programme
//!
//! ```text
//! min 1/2 x^T K x - b^T x   subject to   0 <= x_i <= c,   sum_i x_i = T,
//! ```
//!
//! whose optimality conditions are those of the elastic-perfectly-plastic interface of
//! [`crate::BemSolver::solve_load_plastic`]: with the gap `g = K x - b - lambda` (`lambda` the
//! multiplier of the sum, the rigid approach), `g >= 0` where `x = 0`, `g = 0` where
//! `0 < x < c` and `g <= 0` where `x = c` (the overlap `-g` is the plastic depth).
//!
//! The method (Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006, Algorithm 16.3) keeps
//! a working set of points held at a bound (0 or the cap `c`) and a feasible iterate. Each step
//! solves the equality-constrained problem on the free points `F` exactly (a Cholesky
//! factorisation of `K_FF`, nalgebra):
//!
//! ```text
//! K_FF y = b_F - c K_{F,W_c} 1 + lambda 1,   sum_F y = T - c |W_c|,
//! ```
//!
//! so `y = z1 + lambda z2` with `z1 = K_FF^-1 (b_F - c K_{F,W_c} 1)`, `z2 = K_FF^-1 1` and
//! `lambda = (T - c |W_c| - sum z1) / sum z2`. If `y` lies within the bounds the iterate moves
//! there and the multipliers of the held points (their gaps) are read: a point at 0 with `g < 0`
//! or at the cap with `g > 0` is released (the most violating one); with none, the iterate is
//! the solution. Otherwise the iterate moves toward `y` until the first free point reaches a
//! bound, which joins the working set. The objective falls at every step, so no working set
//! repeats and the method ends in finitely many steps (bounded here by `max_steps`).
//!
//! Why by hand: the problem's structure (a box and one sum, a feasible warm start from the
//! previous state, a solution with few free points, at most 1024 unknowns: the largest set of
//! candidate points) makes a dense active-set method with nalgebra's Cholesky exact and cheap, while the
//! quadratic-programming crates (interior-point or ADMM) end at a tolerance on the
//! complementarity, which is exactly where the projected conjugate gradient of
//! [`crate::BemSolver::solve_load_plastic`] stalls on contacts of a few pixels.

use nalgebra::{Cholesky, DMatrix, DVector, Dyn};

use crate::grid::{block_sum, block_sum2};

/// Steps of the Newton iteration for the scale of the mean (it ends in a few).
const MAX_SCALE_STEPS: usize = 100;

/// How the mean pressure is restored after a step ([`restore_mean`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum MeanFix {
    /// Points below the cap scaled by `f` (clamped at the cap), points at the cap kept.
    Scale(f64),
    /// Points in contact shifted by `lambda` (Pa) and clamped to `[0, cap]`: when the points at
    /// the cap alone carry more than the target (a step that saturated too many).
    Shift(f64),
    /// Every point shifted by `lambda` (Pa) and clamped to `[0, cap]` (the Euclidean projection
    /// on `{0 <= x <= cap, mean(x) = target}`): when the contact points, all at the cap, carry
    /// less than the target (a step that saturated and released too many near full plasticity).
    Lift(f64),
}

impl MeanFix {
    pub(crate) fn apply(self, v: f64, cap: f64) -> f64 {
        match self {
            MeanFix::Scale(f) => {
                if v < cap {
                    (v * f).min(cap)
                } else {
                    cap
                }
            }
            MeanFix::Shift(l) => {
                if v > 0.0 {
                    (v + l).clamp(0.0, cap)
                } else {
                    0.0
                }
            }
            MeanFix::Lift(l) => (v + l).clamp(0.0, cap),
        }
    }
}

/// Bisection steps for the shift (to the last bit of a value below the cap).
const SHIFT_STEPS: usize = 80;

/// The fix that makes `mean(fix(x)) = target` (x in `[0, cap]`, `0 < target < cap`): the scale
/// `f` of the points below the cap by Newton's method from below (the mean of `min(f x, cap)`
/// is concave and piecewise linear in `f`); when the points at the cap alone carry more than the
/// target, the shift of the contact points by bisection. Deterministic block sums.
pub(crate) fn restore_mean(x: &[f64], cap: f64, target: f64) -> Option<MeanFix> {
    let n = x.len() as f64;
    let (free_sum, capped) = block_sum2(x.len(), |rg| {
        rg.fold((0.0, 0.0), |a, i| if x[i] < cap { (a.0 + x[i], a.1) } else { (a.0, a.1 + cap) })
    });
    if !(free_sum + capped).is_finite() || free_sum + capped <= 0.0 {
        return None;
    }
    if capped >= target * n || free_sum <= 0.0 {
        // The contact points alone reach the target when they are all at the cap; if they do
        // not (the free ones are none and the capped ones too few), every point is lifted.
        let kind: fn(f64) -> MeanFix =
            if capped >= target * n || free_sum > 0.0 { MeanFix::Shift } else { MeanFix::Lift };
        let mean_at = |l: f64| block_sum(x.len(), |rg| rg.map(|i| kind(l).apply(x[i], cap)).sum()) / n;
        let (mut lo, mut hi) = (-cap, cap);
        for _ in 0..SHIFT_STEPS {
            let mid = 0.5 * (lo + hi);
            if mean_at(mid) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return Some(kind(0.5 * (lo + hi)));
    }
    let mut f = (target * n - capped) / free_sum;
    for _ in 0..MAX_SCALE_STEPS {
        let (value, slope) = block_sum2(x.len(), |rg| {
            rg.fold((0.0, 0.0), |a, i| {
                let v = x[i];
                if v >= cap || f * v >= cap { (a.0 + cap, a.1) } else { (a.0 + f * v, a.1 + v) }
            })
        });
        if slope <= 0.0 {
            break;
        }
        let step = (target * n - value) / slope;
        if step <= f * 1e-15 {
            break;
        }
        f += step;
    }
    Some(MeanFix::Scale(f))
}

/// The terms of the capped problem's residual for the pressure `x` (Pa) in `[0, cap]` and the
/// complementary field `r` (m): `sum x` and
/// `sum_F x |r| + target sum_{x=0} max(-r, 0) + cap sum_{x=cap} max(r, 0)`; the residual is the
/// second over the first times the heights' scale (deterministic block sums).
pub(crate) fn capped_violation(x: &[f64], r: &[f64], cap: f64, target: f64) -> (f64, f64) {
    block_sum2(x.len(), |rg| {
        rg.fold((0.0, 0.0), |a, i| {
            let (xi, ri) = (x[i], r[i]);
            if xi <= 0.0 {
                (a.0, a.1 + (-ri).max(0.0) * target)
            } else if xi >= cap {
                (a.0 + xi, a.1 + ri.max(0.0) * cap)
            } else {
                (a.0 + xi, a.1 + xi * ri.abs())
            }
        })
    })
}

/// Where a point of the set is: free, or held at a bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Bound {
    Free,
    Zero,
    Cap,
}

/// A solution of the capped problem on the set.
#[derive(Clone, Debug)]
pub(crate) struct CappedSet {
    /// The gap `g = K x - b - lambda` at every point of the set (m): 0 to rounding on the free
    /// points, `>= -tol` at zero, `<= tol` at the cap.
    pub(crate) gap: Vec<f64>,
    /// The multiplier of the sum, `lambda` (m).
    pub(crate) multiplier: f64,
    /// Active-set steps taken.
    pub(crate) steps: usize,
}

/// Why the active-set method gave up (the caller then solves on the whole grid).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum GiveUp {
    /// The start is not feasible (`T` not within `[0, c m]`, a value out of bounds).
    Infeasible,
    /// More free points than [`MAX_FREE`].
    TooManyFree,
    /// `K_FF` was not numerically positive definite.
    NotDefinite,
    /// `max_steps` taken.
    Steps,
}

/// Most free points of an equality-constrained step (its factor holds `|F|^2` values): the
/// largest set of candidate points.
pub(crate) const MAX_FREE: usize = 1024;

/// `sum_j K_ij x_j - b_i` over the nonzero `x_j` (in ascending `j`), for every `i` of the set.
fn field(matrix: &[f64], m: usize, b: &[f64], x: &[f64]) -> Vec<f64> {
    let mut r: Vec<f64> = b.iter().map(|b| -b).collect();
    for (j, &xj) in x.iter().enumerate() {
        if xj != 0.0 {
            let col = &matrix[j * m..(j + 1) * m];
            r.iter_mut().zip(col).for_each(|(r, k)| *r += xj * k);
        }
    }
    r
}

/// The feasible start with the fewest free points: the total poured on the highest points
/// (largest `b`, ties by index) at the cap, the remainder on the next one.
pub(crate) fn fill_highest(b: &[f64], total: f64, cap: f64) -> Vec<f64> {
    let mut order: Vec<usize> = (0..b.len()).collect();
    order.sort_by(|&i, &j| b[j].total_cmp(&b[i]).then(i.cmp(&j)));
    let mut x = vec![0.0; b.len()];
    let mut left = total;
    for i in order {
        if left <= 0.0 {
            break;
        }
        x[i] = left.min(cap);
        left -= x[i];
    }
    x
}

/// Refactorise `K_FF` from scratch after this many updates of the factor (rounding drift).
const REFACTOR_EVERY: usize = 64;

/// The Cholesky factor of `K_FF` for the sorted free points `free`.
fn factor(matrix: &[f64], m: usize, free: &[usize]) -> Result<Cholesky<f64, Dyn>, GiveUp> {
    let k = free.len();
    DMatrix::from_fn(k, k, |a, c| matrix[free[a] * m + free[c]]).cholesky().ok_or(GiveUp::NotDefinite)
}

/// Solves the capped problem (module docs) on a set of `m` points with the row-major symmetric
/// influence matrix `matrix` (m/Pa), heights `b` (m), the cap `cap` (Pa) and the total
/// `total = sum x` (Pa), from the feasible start in `x` (`0 <= x_i <= cap`, `sum x = total` to
/// rounding), overwriting `x` with the solution. A held point is released when its gap violates
/// its sign by more than `tol_m` (m). At most `max_steps` steps. The factor of `K_FF` is updated
/// as a point joins or leaves `F` (a column inserted or removed, `O(|F|^2)`), and refactorised
/// every [`REFACTOR_EVERY`] updates.
pub(crate) fn solve_capped(
    matrix: &[f64],
    b: &[f64],
    x: &mut [f64],
    total: f64,
    cap: f64,
    tol_m: f64,
    max_steps: usize,
) -> Result<CappedSet, GiveUp> {
    let m = b.len();
    if matrix.len() != m * m
        || x.len() != m
        || !(total > 0.0 && total <= cap * m as f64)
        || x.iter().any(|&v| !(0.0..=cap).contains(&v))
    {
        return Err(GiveUp::Infeasible);
    }
    let mut bound: Vec<Bound> = x
        .iter()
        .map(|&v| {
            if v <= 0.0 {
                Bound::Zero
            } else if v >= cap {
                Bound::Cap
            } else {
                Bound::Free
            }
        })
        .collect();
    // With no free point the sum cannot move: free the first point with load.
    if !bound.contains(&Bound::Free) {
        let first = (0..m).find(|&i| x[i] > 0.0).ok_or(GiveUp::Infeasible)?;
        bound[first] = Bound::Free;
    }
    let mut free: Vec<usize> = (0..m).filter(|&i| bound[i] == Bound::Free).collect();
    if free.len() > MAX_FREE {
        return Err(GiveUp::TooManyFree);
    }
    let mut chol = factor(matrix, m, &free)?;
    let mut updates = 0;
    for step in 1..=max_steps {
        let k = free.len();
        let capped: Vec<usize> = (0..m).filter(|&i| bound[i] == Bound::Cap).collect();
        let rhs = DVector::from_iterator(
            k,
            free.iter().map(|&i| b[i] - cap * capped.iter().map(|&j| matrix[i * m + j]).sum::<f64>()),
        );
        let z1 = chol.solve(&rhs);
        let z2 = chol.solve(&DVector::from_element(k, 1.0));
        let (s1, s2) = (z1.sum(), z2.sum());
        if !(s2 > 0.0 && s1.is_finite()) {
            return Err(GiveUp::NotDefinite);
        }
        let lambda = (total - cap * capped.len() as f64 - s1) / s2;
        let y: Vec<f64> = (0..k).map(|a| z1[a] + lambda * z2[a]).collect();
        // The longest step toward y within the bounds, and the point that blocks it (never the
        // last free point, whose value the sum fixes: it is only clamped).
        let mut alpha = 1.0;
        let mut blocking = None;
        for (a, &i) in free.iter().enumerate() {
            let (from, to) = (x[i], y[a]);
            let (limit, kind) = if to < 0.0 {
                (from / (from - to), Bound::Zero)
            } else if to > cap {
                ((cap - from) / (to - from), Bound::Cap)
            } else {
                continue;
            };
            if limit < alpha && k > 1 {
                alpha = limit.max(0.0);
                blocking = Some((a, kind));
            }
        }
        for (a, &i) in free.iter().enumerate() {
            x[i] = (x[i] + alpha * (y[a] - x[i])).clamp(0.0, cap);
        }
        updates += 1;
        if let Some((a, kind)) = blocking {
            let i = free.remove(a);
            x[i] = if kind == Bound::Zero { 0.0 } else { cap };
            bound[i] = kind;
            chol = if updates % REFACTOR_EVERY == 0 { factor(matrix, m, &free)? } else { chol.remove_column(a) };
            continue;
        }
        // At the minimum on this working set: the gaps of the held points.
        let mut gap = field(matrix, m, b, x);
        gap.iter_mut().for_each(|g| *g -= lambda);
        let worst = (0..m)
            .filter_map(|i| match bound[i] {
                Bound::Zero if gap[i] < -tol_m => Some((i, -gap[i])),
                Bound::Cap if gap[i] > tol_m => Some((i, gap[i])),
                _ => None,
            })
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
        let Some((i, _)) = worst else {
            return Ok(CappedSet { gap, multiplier: lambda, steps: step });
        };
        if k + 1 > MAX_FREE {
            return Err(GiveUp::TooManyFree);
        }
        bound[i] = Bound::Free;
        let pos = free.partition_point(|&f| f < i);
        free.insert(pos, i);
        chol = if updates % REFACTOR_EVERY == 0 {
            factor(matrix, m, &free)?
        } else {
            let col = DVector::from_iterator(k + 1, free.iter().map(|&f| matrix[f * m + i]));
            // The new diagonal must be positive (K_FF positive definite), else a rounding
            // breakdown: refactorise, which fails cleanly if the matrix is not definite.
            let next = chol.insert_column(pos, col);
            let d = next.l_dirty()[(pos, pos)];
            if d.is_finite() && d > 0.0 { next } else { factor(matrix, m, &free)? }
        };
    }
    Err(GiveUp::Steps)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1-D chain of `m` points with the kernel `K_ij = 1 / (1 + |i - j|)` (positive definite:
    /// a Hilbert-like Toeplitz matrix of a decreasing convex sequence, Polya's criterion).
    fn chain(m: usize) -> Vec<f64> {
        let mut k = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                k[i * m + j] = 1.0 / (1.0 + i.abs_diff(j) as f64);
            }
        }
        k
    }

    /// The optimality conditions of the capped problem (module docs), to `tol` relative.
    fn assert_kkt(k: &[f64], b: &[f64], x: &[f64], total: f64, cap: f64, out: &CappedSet) {
        let m = b.len();
        let sum: f64 = x.iter().sum();
        assert!((sum - total).abs() <= 1e-12 * total, "sum {sum} against {total}");
        let g = field(k, m, b, x);
        for i in 0..m {
            let gi = g[i] - out.multiplier;
            assert!((gi - out.gap[i]).abs() < 1e-12, "reported gap {i}");
            if x[i] <= 0.0 {
                assert!(gi >= -1e-12, "point {i} out of contact with a negative gap {gi}");
            } else if x[i] >= cap {
                assert!(gi <= 1e-12, "point {i} at the cap with a positive gap {gi}");
            } else {
                assert!(gi.abs() < 1e-12, "free point {i} with a gap {gi}");
            }
            assert!((0.0..=cap).contains(&x[i]));
        }
    }

    /// Without a binding cap, on heights `b = K x*` of a positive `x*` summing to the total, the
    /// solution is `x*` itself with `lambda = 0` (the unconstrained minimum is feasible).
    #[test]
    fn an_interior_minimum_is_found_exactly() {
        let m = 12;
        let k = chain(m);
        let star: Vec<f64> = (0..m).map(|i| 1.0 + (i as f64 * 0.7).sin() * 0.5).collect();
        let total: f64 = star.iter().sum();
        let b = field(&k, m, &vec![0.0; m], &star);
        let mut x = vec![total / m as f64; m];
        let out = solve_capped(&k, &b, &mut x, total, 10.0, 1e-14, 200).unwrap();
        for (a, s) in x.iter().zip(&star) {
            assert!((a - s).abs() < 1e-10, "{a} against {s}");
        }
        assert!(out.multiplier.abs() < 1e-10);
        assert_kkt(&k, &b, &x, total, 10.0, &out);
    }

    /// A single summit in the middle (the heights fall off away from it) with a cap so low that
    /// the load needs at least `total / cap` points: the rigid-plastic bound. Every point the
    /// method reports at the cap carries the cap, the others `0 <= x < cap`, and the conditions
    /// hold; a cap above the elastic peak leaves no point at the cap.
    #[test]
    fn a_low_cap_spreads_the_load_over_at_least_total_over_cap_points() {
        let m = 40;
        let k = chain(m);
        let b: Vec<f64> = (0..m).map(|i| 5.0 - 0.5 * (i as f64 - 19.5).abs()).collect();
        let (total, cap) = (7.3, 1.0);
        let mut x = vec![total / m as f64; m];
        let out = solve_capped(&k, &b, &mut x, total, cap, 1e-13, 1000).unwrap();
        assert_kkt(&k, &b, &x, total, cap, &out);
        let at_cap = x.iter().filter(|&&v| v >= cap).count();
        let loaded = x.iter().filter(|&&v| v > 0.0).count();
        assert!(at_cap <= 7 && loaded >= 8, "at the cap {at_cap}, loaded {loaded}");
        // The elastic solution (a cap far above it) has no point at the cap.
        let mut e = vec![total / m as f64; m];
        let out_e = solve_capped(&k, &b, &mut e, total, 1e6, 1e-13, 1000).unwrap();
        assert_kkt(&k, &b, &e, total, 1e6, &out_e);
        let peak = e.iter().cloned().fold(0.0, f64::max);
        assert!(peak > cap, "the elastic peak {peak} must exceed the low cap for the test to mean anything");
    }

    /// Infeasible requests give up instead of returning a state.
    #[test]
    fn infeasible_starts_give_up() {
        let k = chain(3);
        let b = [1.0, 2.0, 1.0];
        assert_eq!(solve_capped(&k, &b, &mut [1.0, 1.0, 1.0], 4.0, 1.0, 1e-12, 10).unwrap_err(), GiveUp::Infeasible);
        assert_eq!(solve_capped(&k, &b, &mut [2.0, 0.0, 0.0], 2.0, 1.0, 1e-12, 10).unwrap_err(), GiveUp::Infeasible);
    }
}
