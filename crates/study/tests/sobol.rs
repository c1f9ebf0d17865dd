//! The Sobol estimators of `stiction_study::sensitivity` on functions whose indices are known.
//!
//! * Ishigami: `Y = sin X1 + a sin^2 X2 + b X3^4 sin X1`, `X_i ~ U(-pi, pi)`, a = 7, b = 0.1
//!   (Ishigami & Homma 1990; values from Saltelli et al., *Global Sensitivity Analysis: The
//!   Primer*, 2008, sec. 4.6 / Sobol' & Levitan 1999): S1 = 0.3139, S2 = 0.4424, S3 = 0,
//!   ST1 = 0.5576, ST2 = 0.4424, ST3 = 0.2437.
//! * Additive: `Y = X1 + 2 X2 + 3 X3 (+ Z)`, all U(0, 1): `S_i = ST_i = c_i^2 / sum c^2`.

#![allow(clippy::needless_range_loop)] // the indices name the inputs X1..X3 as in the formulas

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiction_study::sensitivity::{bootstrap_first_order, first_order_index, total_order_indices};

const PI: f64 = std::f64::consts::PI;
const S1: [f64; 3] = [0.3139, 0.4424, 0.0];
const ST: [f64; 3] = [0.5576, 0.4424, 0.2437];

fn ishigami(n: usize, seed: u64) -> (Vec<Vec<f64>>, Vec<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let x: Vec<Vec<f64>> = (0..n).map(|_| (0..3).map(|_| rng.random_range(-PI..PI)).collect()).collect();
    let y = x.iter().map(|v| v[0].sin() + 7.0 * v[1].sin().powi(2) + 0.1 * v[2].powi(4) * v[0].sin()).collect();
    (x, y)
}

fn column(x: &[Vec<f64>], k: usize) -> Vec<f64> {
    x.iter().map(|r| r[k]).collect()
}

/// 20000 samples: the first-order estimator's bootstrap standard error is about 0.006 here,
/// the total-order one's about 0.01; tolerance 0.03 (3-5 standard errors, plus the binning's
/// small smoothing bias).
#[test]
fn ishigami_first_and_total_order_indices() {
    let (x, y) = ishigami(20_000, 1);
    for k in 0..3 {
        let s = first_order_index(&column(&x, k), &y).unwrap();
        assert!((s - S1[k]).abs() < 0.03, "S{}: {s} vs {}", k + 1, S1[k]);
    }
    let t = total_order_indices(&x, &y, false);
    for k in 0..3 {
        let (v, ci) = t[k].unwrap();
        assert!((v - ST[k]).abs() < 0.03, "ST{}: {v} vs {}", k + 1, ST[k]);
        assert!(ci[0] <= v && v <= ci[1] && ci[1] - ci[0] < 0.1, "ST{}: {ci:?}", k + 1);
    }
}

/// Coverage: 200 independent Ishigami studies of 2000 samples; the 95 % bootstrap interval of
/// each index should hold the true value in about 190 of them. If it does, the count is
/// Binomial(200, 0.95): sd 3.1; accepted 180..=197 (exact binomial: a correct interval falls below
/// with probability 0.12 %, above with 0.23 %; an interval too wide, covering 99 %, is caught
/// above with probability 0.68). Seen: 187, 187, 193, 194. Deliberate bug caught: the bootstrap
/// interval taken from its 0.5 and 99.5 percentiles (seen failing: ST1 and ST3 198 of 200). S3 = 0 sits
/// on the estimator's clip at 0 and is left out; the total-order intervals are checked the same
/// way for ST1 and ST3 (ST2 = S2).
#[test]
fn ishigami_bootstrap_intervals_cover_about_95_percent() {
    let reps = 200;
    let mut hits = [0usize; 4];
    for r in 0..reps {
        let (x, y) = ishigami(2000, 100 + r as u64);
        for k in 0..2 {
            let ci = bootstrap_first_order(&column(&x, k), &y).unwrap();
            hits[k] += usize::from(ci[0] <= S1[k] && S1[k] <= ci[1]);
        }
        let t = total_order_indices(&x, &y, false);
        for (slot, k) in [(2, 0), (3, 2)] {
            let (_, ci) = t[k].unwrap();
            hits[slot] += usize::from(ci[0] <= ST[k] && ST[k] <= ci[1]);
        }
    }
    eprintln!("coverage of {reps}: S1, S2, ST1, ST3 = {hits:?}");
    for (name, h) in ["S1", "S2", "ST1", "ST3"].iter().zip(hits) {
        assert!((180..=197).contains(&h), "{name}: {h} of {reps} intervals hold the true value");
    }
}

/// Additive, no noise: S_i = ST_i = (1, 4, 9)/14. With an unnumbered input Z ~ U(0,1) (the
/// surface realisation's stand-in) and `noisy`, the total-order indices leave Z's share out:
/// (1, 4, 9)/15. 10000 samples, tolerance 0.03.
#[test]
fn an_additive_function_has_equal_first_and_total_indices() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let n = 10_000;
    let x: Vec<Vec<f64>> = (0..n).map(|_| (0..3).map(|_| rng.random::<f64>()).collect()).collect();
    let y: Vec<f64> = x.iter().map(|v| v[0] + 2.0 * v[1] + 3.0 * v[2]).collect();
    let t = total_order_indices(&x, &y, false);
    for (k, c) in [1.0, 4.0, 9.0].into_iter().enumerate() {
        let s = first_order_index(&column(&x, k), &y).unwrap();
        assert!((s - c / 14.0).abs() < 0.03, "S{}: {s}", k + 1);
        assert!((t[k].unwrap().0 - c / 14.0).abs() < 0.03, "ST{}: {:?}", k + 1, t[k]);
    }
    let yz: Vec<f64> = y.iter().map(|v| v + rng.random::<f64>()).collect();
    let t = total_order_indices(&x, &yz, true);
    for (k, c) in [1.0, 4.0, 9.0].into_iter().enumerate() {
        assert!((t[k].unwrap().0 - c / 15.0).abs() < 0.03, "ST{} with noise: {:?}", k + 1, t[k]);
    }
    // Without subtracting the unnumbered input's share the index would hold it too: ST1 ~ 2/15.
    let raw = total_order_indices(&x, &yz, false)[0].unwrap().0;
    assert!((raw - 2.0 / 15.0).abs() < 0.03, "{raw}");
}
