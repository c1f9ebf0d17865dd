//! Which uncertain input explains how much of the spread: first-order Sobol indices estimated
//! from the study's own samples, and Spearman rank correlations beside them.
//!
//! **First-order index** of input `X_i` for output `Y`: `S_i = Var(E[Y | X_i]) / Var(Y)`, the
//! share of the variance of `Y` that `X_i` alone explains (Sobol 1993; Saltelli et al., *Global
//! Sensitivity Analysis: The Primer*, 2008, ch. 4). Estimated from given data (no special design):
//! the samples are sorted by `X_i` and cut into `B = round(sqrt(n))` bins of equal count;
//! `Var(E[Y|X_i])` is the count-weighted variance of the bin means (Plischke, Reliability Eng.
//! Syst. Safety 95, 2010). With no dependence the raw ratio is about `(B - 1)/(n - 1)`; that bias
//! is removed: `S = (S_raw - b) / (1 - b)`, `b = (B - 1)/(n - 1)`, clipped to `[0, 1]`.
//!
//! The surface realisation is an input too, but it is not a number: each sample has its own
//! surface (seed + i), independent of the drawn parameters. Its first-order share and the
//! interactions are what the drawn parameters leave: `1 - sum_i S_i` (an upper bound on the
//! surface's own first-order index).
//!
//! **Total-order index** `ST_i = E[Var(Y | X_~i)] / Var(Y)`: the share of the variance that
//! involves `X_i` at all, alone or in interaction (Homma & Saltelli 1996). From given data by
//! Jansen's difference formula (Jansen 1999) on nearest neighbours: for each sample `j`, `j'` is
//! the sample nearest to it in the space of the other inputs `X_~i` (each input rank-transformed to
//! [0, 1]), so the pair differs mainly in `X_i`, and `E[Var(Y|X_~i)] ~ mean((y_j - y_j')^2) / 2`
//! over the distinct pairs.
//! When each sample has its own surface (an input without a number, independent of the drawn
//! ones) the pair differs in its surface too, and that term holds the surface's share as well;
//! the same sum over nearest neighbours in the space of all drawn inputs, which estimates
//! `E[Var(Y | X)]` (the surface's total share), is subtracted. What remains is the share of the
//! terms that involve `X_i` and not the surface (interactions with the surface cannot be told
//! apart from the surface itself with one sample per surface). The nearest-neighbour distance
//! biases both terms upward on steep responses; at most [`MAX_TOTAL_ORDER_SAMPLES`] samples are
//! used.
//!
//! **Intervals.** Every index has a 95 % percentile-bootstrap interval: `BOOTSTRAP_REPS`
//! resamples (with replacement) of the samples, the index recomputed on each, the 2.5 % and
//! 97.5 % quantiles of the results (Efron & Tibshirani 1993, ch. 13). For the first-order index
//! the interval is shifted by the bootstrap's own offset (repeated samples in a resample inflate
//! the binned estimate), so it is centred on the estimate; for the total-order index the
//! distinct neighbour pairs are kept and their terms resampled. The resampling uses a fixed seed,
//! so the same samples give the same bytes; it is done on the first
//! [`MAX_BOOTSTRAP_SAMPLES`] samples (with more, the interval is that of a study of that size:
//! wider than the study's own, on the safe side).
//!
//! **Spearman's rho**: the correlation of the ranks of `X_i` and `Y`, in [-1, 1]; its sign says
//! whether `Y` grows or falls with `X_i`, its square is roughly the share a monotone relation
//! explains.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Bootstrap resamples per interval.
pub const BOOTSTRAP_REPS: usize = 200;
/// Samples used for the bootstrap intervals (the first ones).
pub const MAX_BOOTSTRAP_SAMPLES: usize = 20_000;
/// Samples used for the total-order indices (the first ones; nearest neighbours cost more).
pub const MAX_TOTAL_ORDER_SAMPLES: usize = 20_000;
/// Seed of the bootstrap resampling (fixed: same samples, same bytes).
const BOOTSTRAP_SEED: u64 = 0x5eed_b007;

/// First-order Sobol index of `x` for `y` (same length) by the binned given-data estimator above.
/// None with fewer than 20 samples or without variance in `y`.
pub fn first_order_index(x: &[f64], y: &[f64]) -> Option<f64> {
    let n = x.len();
    if n < 20 || y.len() != n {
        return None;
    }
    let mean = y.iter().sum::<f64>() / n as f64;
    let total: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    if total.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]).then(a.cmp(&b)));
    let bins = ((n as f64).sqrt().round() as usize).max(2);
    let mut between = 0.0;
    for b in 0..bins {
        let (lo, hi) = (b * n / bins, (b + 1) * n / bins);
        if hi > lo {
            let m = order[lo..hi].iter().map(|&k| y[k]).sum::<f64>() / (hi - lo) as f64;
            between += (hi - lo) as f64 * (m - mean).powi(2);
        }
    }
    let raw = between / total;
    let bias = (bins - 1) as f64 / (n - 1) as f64;
    Some(((raw - bias) / (1.0 - bias)).clamp(0.0, 1.0))
}

/// 95 % percentile-bootstrap interval of `estimate(x, y)` over resamples of the pairs `(x_j, y_j)`
/// (the first [`MAX_BOOTSTRAP_SAMPLES`]); None when fewer than 20 resamples give a value.
pub fn bootstrap_first_order(x: &[f64], y: &[f64]) -> Option<[f64; 2]> {
    let n = x.len().min(y.len()).min(MAX_BOOTSTRAP_SAMPLES);
    if n < 20 {
        return None;
    }
    // Sorted once by x; a resample is a count per sample, walked in x order (no sort per resample).
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]).then(a.cmp(&b)));
    let mut rng = ChaCha8Rng::seed_from_u64(BOOTSTRAP_SEED);
    let mut counts = vec![0u32; n];
    let mut by = Vec::with_capacity(n);
    let mut got = Vec::with_capacity(BOOTSTRAP_REPS);
    for _ in 0..BOOTSTRAP_REPS {
        counts.iter_mut().for_each(|c| *c = 0);
        for _ in 0..n {
            counts[rng.random_range(0..n)] += 1;
        }
        by.clear();
        for &k in &order {
            for _ in 0..counts[k] {
                by.push(y[k]);
            }
        }
        if let Some(s) = binned_index_of_sorted(&by) {
            got.push(s);
        }
    }
    // A resample repeats samples, which the binned estimator sees as extra between-bin variance:
    // the resampled indices sit about one standard error above the estimate (on the Ishigami
    // function, 0.02 at n = 1000). The bootstrap is used for the spread only: its percentile
    // interval is shifted by that offset (mean of the resampled indices minus the estimate).
    let s = first_order_index(&x[..n], &y[..n])?;
    let offset = got.iter().sum::<f64>() / got.len().max(1) as f64 - s;
    percentile_interval(&mut got).map(|[a, b]| [(a - offset).clamp(0.0, 1.0), (b - offset).clamp(0.0, 1.0)])
}

/// The binned first-order index of `y` already in the order of its input (as
/// [`first_order_index`] after its sort).
fn binned_index_of_sorted(y: &[f64]) -> Option<f64> {
    let n = y.len();
    if n < 20 {
        return None;
    }
    let mean = y.iter().sum::<f64>() / n as f64;
    let total: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    if total.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let bins = ((n as f64).sqrt().round() as usize).max(2);
    let mut between = 0.0;
    for b in 0..bins {
        let (lo, hi) = (b * n / bins, (b + 1) * n / bins);
        if hi > lo {
            let m = y[lo..hi].iter().sum::<f64>() / (hi - lo) as f64;
            between += (hi - lo) as f64 * (m - mean).powi(2);
        }
    }
    let bias = (bins - 1) as f64 / (n - 1) as f64;
    Some(((between / total - bias) / (1.0 - bias)).clamp(0.0, 1.0))
}

fn percentile_interval(v: &mut [f64]) -> Option<[f64; 2]> {
    if v.len() < 20 {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let at = |p: f64| {
        let r = p * (v.len() - 1) as f64;
        let (lo, hi) = (r.floor() as usize, r.ceil() as usize);
        v[lo] + (v[hi] - v[lo]) * (r - lo as f64)
    };
    Some([at(0.025), at(0.975)])
}

/// Each column of `x` (rows are samples) as ranks scaled to [0, 1].
fn unit_ranks(x: &[Vec<f64>], d: usize) -> Vec<Vec<f64>> {
    let n = x.len();
    let cols: Vec<Vec<f64>> = (0..d)
        .map(|k| {
            let c: Vec<f64> = x.iter().map(|r| r[k]).collect();
            ranks(&c).into_iter().map(|r| (r - 1.0) / (n.max(2) - 1) as f64).collect()
        })
        .collect();
    (0..n).map(|j| cols.iter().map(|c| c[j]).collect()).collect()
}

/// For each point, the index of its nearest other point (Euclidean, over the coordinates in
/// `dims`). A sweep along the first coordinate: exact, fast in few dimensions. With no
/// coordinates every other point is as near: the next one (cyclically).
fn nearest_neighbours(pts: &[Vec<f64>], dims: &[usize]) -> Vec<usize> {
    let n = pts.len();
    if dims.is_empty() {
        return (0..n).map(|j| (j + 1) % n).collect();
    }
    let first = dims[0];
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| pts[a][first].total_cmp(&pts[b][first]).then(a.cmp(&b)));
    let dist = |a: usize, b: usize| dims.iter().map(|&k| (pts[a][k] - pts[b][k]).powi(2)).sum::<f64>();
    let mut out = vec![0; n];
    for (pos, &j) in order.iter().enumerate() {
        let (mut best, mut best_d) = (usize::MAX, f64::INFINITY);
        let visit = |k: usize, best: &mut usize, best_d: &mut f64| {
            let d = dist(j, k);
            if d < *best_d || (d == *best_d && k < *best) {
                *best_d = d;
                *best = k;
            }
        };
        for &k in &order[pos + 1..] {
            if (pts[k][first] - pts[j][first]).powi(2) > best_d {
                break;
            }
            visit(k, &mut best, &mut best_d);
        }
        for &k in order[..pos].iter().rev() {
            if (pts[k][first] - pts[j][first]).powi(2) > best_d {
                break;
            }
            visit(k, &mut best, &mut best_d);
        }
        out[j] = best;
    }
    out
}

/// Total-order indices of every input (columns of `x`) for `y`, with 95 % bootstrap intervals,
/// by the nearest-neighbour Jansen estimator above; `noisy`: each sample also has an input
/// without a number (its own surface), whose share is subtracted. None per input with fewer than
/// 20 samples or without variance in `y`. Uses the first [`MAX_TOTAL_ORDER_SAMPLES`] samples.
pub fn total_order_indices(x: &[Vec<f64>], y: &[f64], noisy: bool) -> Vec<Option<(f64, [f64; 2])>> {
    let d = x.first().map_or(0, Vec::len);
    let n = x.len().min(y.len()).min(MAX_TOTAL_ORDER_SAMPLES);
    let none = vec![None; d];
    if n < 20 {
        return none;
    }
    let y = &y[..n];
    let mean = y.iter().sum::<f64>() / n as f64;
    let var = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n as f64;
    if var.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return none;
    }
    let u = unit_ranks(&x[..n], d);
    // Jansen's half squared difference over the distinct neighbour pairs {j, nn(j)} (a pair of
    // mutual neighbours counted once, so that the terms are nearly independent for the bootstrap).
    let pair_terms = |nn: &[usize]| -> Vec<f64> {
        let mut pairs: Vec<(usize, usize)> = (0..n).map(|j| (j.min(nn[j]), j.max(nn[j]))).collect();
        pairs.sort_unstable();
        pairs.dedup();
        pairs.into_iter().map(|(a, b)| 0.5 * (y[a] - y[b]).powi(2)).collect()
    };
    let mean = |t: &[f64]| t.iter().sum::<f64>() / t.len().max(1) as f64;
    let all: Vec<usize> = (0..d).collect();
    let full = noisy.then(|| pair_terms(&nearest_neighbours(&u, &all)));
    let resample_mean = |t: &[f64], rng: &mut ChaCha8Rng| -> f64 {
        let m = t.len().min(MAX_BOOTSTRAP_SAMPLES);
        (0..m).map(|_| t[rng.random_range(0..m)]).sum::<f64>() / m as f64
    };
    use rayon::prelude::*;
    (0..d)
        .into_par_iter()
        .map(|i| {
            let others: Vec<usize> = (0..d).filter(|&k| k != i).collect();
            let terms = pair_terms(&nearest_neighbours(&u, &others));
            let noise = full.as_deref().map_or(0.0, mean);
            let value = ((mean(&terms) - noise) / var).clamp(0.0, 1.0);
            let mut rng = ChaCha8Rng::seed_from_u64(BOOTSTRAP_SEED ^ i as u64);
            // The two sums are resampled independently (they share samples and are positively
            // correlated, so the interval of their difference is on the wide side).
            let mut reps: Vec<f64> = (0..BOOTSTRAP_REPS)
                .map(|_| {
                    let t = resample_mean(&terms, &mut rng);
                    let z = full.as_deref().map_or(0.0, |f| resample_mean(f, &mut rng));
                    ((t - z) / var).clamp(0.0, 1.0)
                })
                .collect();
            percentile_interval(&mut reps).map(|ci| (value, ci))
        })
        .collect()
}

/// Ranks (1-based, ties get their mean rank).
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        let mean_rank = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            r[k] = mean_rank;
        }
        i = j + 1;
    }
    r
}

/// Spearman's rank correlation of `x` and `y`; None when either is constant or too short.
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() < 3 || x.len() != y.len() {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let n = rx.len() as f64;
    let (mx, my) = (rx.iter().sum::<f64>() / n, ry.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx).powi(2);
        syy += (b - my).powi(2);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

/// One input's share of the spread of mu_e,a and F_a0.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct InputShare {
    /// The input: a parameter's JSON path, or the surface realisation and interactions.
    pub input: String,
    /// First-order Sobol index for mu_e,a.
    pub mu_first_order: Option<f64>,
    /// First-order Sobol index for F_a0.
    pub fa0_first_order: Option<f64>,
    /// 95 % bootstrap interval of the first-order index for mu_e,a.
    pub mu_first_order_ci: Option<[f64; 2]>,
    /// 95 % bootstrap interval of the first-order index for F_a0.
    pub fa0_first_order_ci: Option<[f64; 2]>,
    /// Total-order index for mu_e,a (terms with the surface excluded when it varies).
    pub mu_total_order: Option<f64>,
    /// Its 95 % bootstrap interval.
    pub mu_total_order_ci: Option<[f64; 2]>,
    /// Total-order index for F_a0.
    pub fa0_total_order: Option<f64>,
    /// Its 95 % bootstrap interval.
    pub fa0_total_order_ci: Option<[f64; 2]>,
    /// Spearman's rho with mu_e,a (None for the remainder row).
    pub mu_spearman: Option<f64>,
    /// Spearman's rho with F_a0.
    pub fa0_spearman: Option<f64>,
    /// Why an index or interval of this row is null.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The sensitivity table of a study.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Sensitivity {
    /// What the numbers mean.
    pub method: String,
    /// Samples with a fit the table is made of.
    pub samples: usize,
    /// One row per drawn parameter, then the remainder (surface realisation and interactions).
    pub inputs: Vec<InputShare>,
}

/// The table from the samples with a fit: `x[j]` is the draws of sample j (in `names` order),
/// `mu[j]`, `fa0[j]` its outputs. `vary_surface`: whether the remainder row is the surface.
pub fn table(names: &[String], x: &[Vec<f64>], mu: &[f64], fa0: &[f64], vary_surface: bool) -> Sensitivity {
    let mut inputs = Vec::new();
    let (mut sum_mu, mut sum_fa) = (0.0, 0.0);
    // Rows with an undrawn (NaN) parameter cannot have a neighbour distance.
    let finite = x.iter().all(|r| r.iter().all(|v| v.is_finite()));
    let ((t_mu, t_fa), first): (_, Vec<_>) = rayon::join(
        || {
            if finite && !names.is_empty() {
                rayon::join(|| total_order_indices(x, mu, vary_surface), || total_order_indices(x, fa0, vary_surface))
            } else {
                (vec![None; names.len()], vec![None; names.len()])
            }
        },
        || {
            use rayon::prelude::*;
            // Each input's first-order indices and their bootstrap intervals, in parallel (the
            // results are collected in input order: same bytes whatever the threads).
            (0..names.len())
                .into_par_iter()
                .map(|k| {
                    let xk: Vec<f64> = x.iter().map(|d| d[k]).collect();
                    let (s_mu, s_fa) = (first_order_index(&xk, mu), first_order_index(&xk, fa0));
                    let (ci_mu, ci_fa) = rayon::join(
                        || s_mu.and_then(|_| bootstrap_first_order(&xk, mu)),
                        || s_fa.and_then(|_| bootstrap_first_order(&xk, fa0)),
                    );
                    (xk, s_mu, s_fa, ci_mu, ci_fa)
                })
                .collect()
        },
    );
    for (k, (name, (xk, s_mu, s_fa, ci_mu, ci_fa))) in names.iter().zip(first).enumerate() {
        sum_mu += s_mu.unwrap_or(0.0);
        sum_fa += s_fa.unwrap_or(0.0);
        let (tm, tf) = (t_mu.get(k).copied().flatten(), t_fa.get(k).copied().flatten());
        inputs.push(InputShare {
            input: name.clone(),
            mu_first_order: s_mu,
            fa0_first_order: s_fa,
            mu_first_order_ci: ci_mu,
            fa0_first_order_ci: ci_fa,
            mu_total_order: tm.map(|t| t.0),
            mu_total_order_ci: tm.map(|t| t.1),
            fa0_total_order: tf.map(|t| t.0),
            fa0_total_order_ci: tf.map(|t| t.1),
            mu_spearman: spearman(&xk, mu),
            fa0_spearman: spearman(&xk, fa0),
            note: None,
        });
        let row = inputs.last_mut().expect("just pushed");
        let nulls = [
            row.mu_first_order,
            row.fa0_first_order,
            row.mu_total_order,
            row.fa0_total_order,
            row.mu_spearman,
            row.fa0_spearman,
        ]
        .iter()
        .any(Option::is_none)
            || [row.mu_first_order_ci, row.fa0_first_order_ci, row.mu_total_order_ci, row.fa0_total_order_ci]
                .iter()
                .any(Option::is_none);
        if nulls {
            row.note = Some(format!(
                "null where the {} samples with a fit cannot estimate it: fewer than 20 samples, no spread of the \
                 input or the output, or an undrawn parameter",
                mu.len()
            ));
        }
    }
    let enough = mu.len() >= 20;
    inputs.push(InputShare {
        input: if vary_surface {
            "surface realisation and interactions (1 - sum)".into()
        } else {
            "interactions (1 - sum; the surface is fixed)".into()
        },
        mu_first_order: enough.then(|| (1.0 - sum_mu).max(0.0)),
        fa0_first_order: enough.then(|| (1.0 - sum_fa).max(0.0)),
        mu_first_order_ci: None,
        fa0_first_order_ci: None,
        mu_total_order: None,
        mu_total_order_ci: None,
        fa0_total_order: None,
        fa0_total_order_ci: None,
        mu_spearman: None,
        fa0_spearman: None,
        note: Some(
            "the remainder row has first-order shares only (1 - the sum of the inputs' indices), from 20 samples \
             with a fit on; no intervals, total orders or rank correlations"
                .into(),
        ),
    });
    Sensitivity {
        method: "first-order Sobol index S_i = Var(E[Y|X_i]) / Var(Y), binned given-data estimator (sqrt(n) bins, \
                 bias-corrected); total-order index ST_i = E[Var(Y|X_~i)] / Var(Y), Jansen's formula on nearest \
                 neighbours in the other inputs' ranks (with a varying surface: minus the same over all inputs, so \
                 the terms with the surface are left out); 95 % percentile-bootstrap intervals (200 resamples, \
                 fixed seed); Spearman rank correlation beside it; the last row is 1 - sum S_i"
            .into(),
        samples: mu.len(),
        inputs,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The additive test function Y = X1 + 2 X2 + 3 X3 + Z, X_i and Z independent U(0, 1):
    /// Var(Y) = (1 + 4 + 9 + 1)/12, so S_1 = 1/15, S_2 = 4/15, S_3 = 9/15 and the non-numeric
    /// input Z (standing for the surface realisation) leaves 1 - sum = 1/15. Tolerance 0.02 for
    /// 20000 samples (the estimator's standard error is ~0.007).
    #[test]
    fn an_additive_function_gives_its_known_indices() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let n = 20_000;
        let x: Vec<Vec<f64>> = (0..n).map(|_| (0..3).map(|_| rng.random::<f64>()).collect()).collect();
        let y: Vec<f64> = x.iter().map(|v| v[0] + 2.0 * v[1] + 3.0 * v[2] + rng.random::<f64>()).collect();
        let names: Vec<String> = ["x1", "x2", "x3"].iter().map(|s| s.to_string()).collect();
        let t = table(&names, &x, &y, &y, true);
        for (row, want) in t.inputs.iter().zip([1.0 / 15.0, 4.0 / 15.0, 9.0 / 15.0, 1.0 / 15.0]) {
            let s = row.mu_first_order.unwrap();
            assert!((s - want).abs() < 0.02, "{}: {s} vs {want}", row.input);
        }
        // Monotone increasing in every input: positive rank correlations, largest for x3.
        let rho: Vec<f64> = t.inputs[..3].iter().map(|r| r.mu_spearman.unwrap()).collect();
        assert!(rho[0] > 0.0 && rho[0] < rho[1] && rho[1] < rho[2], "{rho:?}");
    }

    #[test]
    fn an_input_without_influence_gets_zero_and_ties_are_ranked_fairly() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let x: Vec<f64> = (0..5000).map(|_| rng.random::<f64>()).collect();
        let y: Vec<f64> = (0..5000).map(|_| rng.random::<f64>()).collect();
        assert!(first_order_index(&x, &y).unwrap() < 0.02);
        assert_eq!(ranks(&[3.0, 1.0, 3.0, 2.0]), vec![3.5, 1.0, 3.5, 2.0]);
        assert!((spearman(&[1.0, 2.0, 3.0, 4.0], &[10.0, 20.0, 25.0, 100.0]).unwrap() - 1.0).abs() < 1e-15);
        assert!(first_order_index(&x[..10], &y[..10]).is_none());
    }
}
