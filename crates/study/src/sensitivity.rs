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
//! **Spearman's rho**: the correlation of the ranks of `X_i` and `Y`, in [-1, 1]; its sign says
//! whether `Y` grows or falls with `X_i`, its square is roughly the share a monotone relation
//! explains.

use serde::Serialize;

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
    /// Spearman's rho with mu_e,a (None for the remainder row).
    pub mu_spearman: Option<f64>,
    /// Spearman's rho with F_a0.
    pub fa0_spearman: Option<f64>,
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
    for (k, name) in names.iter().enumerate() {
        let xk: Vec<f64> = x.iter().map(|d| d[k]).collect();
        let s_mu = first_order_index(&xk, mu);
        let s_fa = first_order_index(&xk, fa0);
        sum_mu += s_mu.unwrap_or(0.0);
        sum_fa += s_fa.unwrap_or(0.0);
        inputs.push(InputShare {
            input: name.clone(),
            mu_first_order: s_mu,
            fa0_first_order: s_fa,
            mu_spearman: spearman(&xk, mu),
            fa0_spearman: spearman(&xk, fa0),
        });
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
        mu_spearman: None,
        fa0_spearman: None,
    });
    Sensitivity {
        method: "first-order Sobol index S_i = Var(E[Y|X_i]) / Var(Y), binned given-data estimator (sqrt(n) bins, \
                 bias-corrected); Spearman rank correlation beside it; the last row is 1 - sum S_i"
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
