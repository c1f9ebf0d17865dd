//! The calibration interval of a fitted shear strength s.
//!
//! A model predicts `V_pull^2 = (s g(L) + h(L)) / a_pull` with `L = a_clamp V_clamp^2 - F_spring`,
//! so s depends on all three calibrated quantities: exactly in proportion to `a_pull` (when
//! `h = 0`), and through the loads on `a_clamp` and `F_spring`. The profile interval of s
//! ([`crate::mle`]) takes them as exact (noise only). Here they are drawn from their stated
//! uncertainties (the same draws as eq. 10 and `stiction study`) and s is refitted per draw:
//!
//! * the model's threshold parts `(g, h)` are evaluated once on a grid of [`LOAD_GRID`] loads
//!   spanning every load the draws need (for the explicit ensemble: the ensemble mean on that
//!   grid) and interpolated linearly; the draw's s minus the interpolated nominal s is added to
//!   the fitted s, so the grid's interpolation error cancels to first order;
//! * per draw, `s = sum_j (g_j / a_pull) (WY_j - h_j / a_pull W_j) / sum_j W_j (g_j / a_pull)^2`
//!   over the distinct clamp voltages j (`W_j`, `WY_j`: the rows' weights and weighted V_pull^2
//!   summed per voltage), so a draw costs O(distinct voltages), not O(rows);
//! * the noise enters each joint draw as `se t_nu` (se: the noise interval's half-width over
//!   `t_0.975(nu)`); `ci95_with_calibration` is the 2.5-97.5 percentile range of the joint draws;
//! * a draw in which a used row would have no load (`L <= 0`) contradicts that row's measured slip
//!   and is left out (counted in the note);
//! * variance shares: each source drawn alone (robust SD squared) beside `se^2`, over their sum.
//!
//! The nuisance parameters stay at their fitted values; a free `F_spring` is fitted, not drawn.

use std::collections::BTreeMap;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StudentT};

use crate::eq10::{CalibrationSource, draw};
use crate::error::FitError;
use crate::mle::Free;
use crate::mle::{Ensemble, FitData, ModelFit, Noise};
use crate::models::{ModelContext, ModelKind, Parts};
use crate::stats::{percentile, robust_sd, t975};

/// Loads in the interpolation grid of the threshold parts.
pub const LOAD_GRID: usize = 64;

/// Largest number of calibration draws for s (per source and joint).
pub const MAX_S_DRAWS: usize = 4000;

/// The calibration interval and the variance shares of s.
#[derive(Debug, Clone, Default)]
pub struct Propagated {
    /// 2.5 and 97.5 percentiles of the joint draws, Pa.
    pub ci95: Option<[f64; 2]>,
    /// How it was made or why it is null.
    pub note: String,
    /// Variance shares by source.
    pub shares: BTreeMap<String, f64>,
}

fn interp(grid: &[f64], parts: &[Parts], load: f64) -> Option<(f64, f64)> {
    let k = grid.partition_point(|&l| l < load);
    let (i, j) = if k == 0 {
        (0, 1)
    } else if k >= grid.len() {
        (grid.len() - 2, grid.len() - 1)
    } else {
        (k - 1, k)
    };
    let (a, b) = (parts[i].as_ref().ok()?, parts[j].as_ref().ok()?);
    let span = grid[j] - grid[i];
    let f = if span > 0.0 { ((load - grid[i]) / span).clamp(0.0, 1.0) } else { 0.0 };
    Some((a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)))
}

/// Propagates the calibration into the fitted s of `fit` (model `kind`).
#[allow(clippy::too_many_arguments)]
pub fn propagate(
    ctx: &ModelContext,
    kind: ModelKind,
    fit: &ModelFit,
    data: &FitData,
    noise: Noise,
    sources: &[CalibrationSource; 3],
    free: Free,
    surfaces: usize,
    draws: usize,
    seed: u64,
) -> Result<Propagated, FitError> {
    let s_hat = fit.shear_strength_pa.value;
    let Some([lo, hi]) = fit.shear_strength_pa.ci95 else {
        return Ok(Propagated {
            note: "no noise interval of s, so no interval with the calibration either".into(),
            ..Propagated::default()
        });
    };
    let nu = match noise {
        Noise::Column => f64::INFINITY,
        Noise::Repeats { dof, .. } => dof as f64,
        Noise::Residuals => fit.dof as f64,
    };
    let Some(t) = t975(nu) else {
        return Ok(Propagated {
            note: "too few degrees of freedom for the noise level".into(),
            ..Propagated::default()
        });
    };
    let se = 0.5 * (hi - lo) / t;
    let draws = draws.min(MAX_S_DRAWS);
    let spring_free = free.spring && fit.spring_force_n.is_some();
    let f_fit = fit.spring_force_n.as_ref().map_or(ctx.device.spring_force_n, |p| p.value);
    let radius = fit.summit_radius_m.as_ref().map(|p| p.value);
    // Per distinct clamp voltage: summed weights and weighted V_pull^2.
    let nx = data.x_unique_v2.len();
    let (mut w_sum, mut wy_sum) = (vec![0.0; nx], vec![0.0; nx]);
    for i in 0..data.y_v2.len() {
        w_sum[data.row_unique[i]] += data.weight[i];
        wy_sum[data.row_unique[i]] += data.weight[i] * data.y_v2[i];
    }
    let nominal = [ctx.device.a_clamp_n_per_v2, ctx.device.a_pull_n_per_v2, f_fit];
    // The draws: stream 20 joint, 21-23 one source at a time.
    let mut sets: Vec<Vec<[f64; 3]>> = Vec::new();
    for stream in 20..24u64 {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(stream);
        let mut v = Vec::with_capacity(draws);
        for _ in 0..draws {
            let mut c = nominal;
            for (k, src) in sources.iter().enumerate() {
                let x = draw(src, &mut rng)?;
                let drawn = stream == 20 || stream - 21 == k as u64;
                if drawn && !(k == 2 && spring_free) {
                    c[k] = x;
                }
            }
            v.push(c);
        }
        sets.push(v);
    }
    let x_min = data.x_unique_v2.iter().copied().fold(f64::INFINITY, f64::min);
    let x_max = data.x_unique_v2.iter().copied().fold(0.0, f64::max);
    let consistent = |c: &[f64; 3]| c[0] > 0.0 && c[1] > 0.0 && c[0] * x_min - c[2] > 0.0;
    let (mut l_lo, mut l_hi) = (nominal[0] * x_min - nominal[2], nominal[0] * x_max - nominal[2]);
    for c in sets.iter().flatten().filter(|c| consistent(c)) {
        l_lo = l_lo.min(c[0] * x_min - c[2]);
        l_hi = l_hi.max(c[0] * x_max - c[2]);
    }
    if !(l_lo > 0.0 && l_hi > l_lo && l_hi.is_finite()) {
        return Ok(Propagated {
            note: "no load range to propagate the calibration over".into(),
            ..Propagated::default()
        });
    }
    let grid: Vec<f64> = (0..LOAD_GRID).map(|k| l_lo + (l_hi - l_lo) * k as f64 / (LOAD_GRID - 1) as f64).collect();
    let parts = match kind {
        ModelKind::ExplicitEnsemble => Ensemble::mean(&ctx.ensemble_parts(kind, None, surfaces, &grid)?),
        _ => {
            let mut m = ctx.build(kind, radius, None)?;
            ctx.parts(&mut m, &grid)
        }
    };
    let s_of = |c: &[f64; 3]| -> Option<f64> {
        if !consistent(c) {
            return None;
        }
        let (mut num, mut den) = (0.0, 0.0);
        for j in 0..nx {
            let (g, h) = interp(&grid, &parts, c[0] * data.x_unique_v2[j] - c[2])?;
            let x = g / c[1];
            num += x * (wy_sum[j] - h / c[1] * w_sum[j]);
            den += w_sum[j] * x * x;
        }
        let s = num / den;
        (den > 0.0 && s.is_finite()).then_some(s)
    };
    let Some(s_nominal) = s_of(&nominal) else {
        return Ok(Propagated {
            note: "the model has no contact state on part of the load range the calibration spans".into(),
            ..Propagated::default()
        });
    };
    let student = StudentT::new(if nu.is_finite() { nu } else { 1e9 })
        .map_err(|e| FitError::Setting(format!("Student t with {nu} degrees of freedom: {e}")))?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(24);
    let mut joint = Vec::with_capacity(draws);
    let mut failed = 0usize;
    for c in &sets[0] {
        let z: f64 = student.sample(&mut rng);
        match s_of(c) {
            Some(s) => joint.push(s_hat + (s - s_nominal) + se * z),
            None => failed += 1,
        }
    }
    let mut var = [se * se, 0.0, 0.0, 0.0];
    for k in 0..3 {
        let v: Vec<f64> = sets[k + 1].iter().filter_map(s_of).collect();
        var[k + 1] = robust_sd(&v).map_or(0.0, |x| x * x);
    }
    let total: f64 = var.iter().sum();
    let mut shares = BTreeMap::new();
    if total > 0.0 && total.is_finite() {
        for (name, v) in ["noise", "a_clamp", "a_pull", "spring_force"].iter().zip(var) {
            shares.insert(name.to_string(), v / total);
        }
    }
    joint.sort_by(f64::total_cmp);
    let ci = percentile(&joint, 0.025).zip(percentile(&joint, 0.975)).map(|(a, b)| [a, b]);
    let mut note = format!(
        "noise and calibration: {} joint draws of a_clamp, a_pull{} with the noise, 2.5-97.5 percentiles; the model's threshold interpolated on {LOAD_GRID} loads from {:.3} to {:.3} uN",
        joint.len(),
        if spring_free { " (F_spring is fitted, not drawn)" } else { ", F_spring" },
        l_lo * 1e6,
        l_hi * 1e6
    );
    if failed > 0 {
        note.push_str(&format!(
            "; {failed} of {draws} draws left out: in them a used row would have no load (L <= 0), contradicting its measured slip"
        ));
    }
    Ok(Propagated { ci95: ci.filter(|c| c[0].is_finite() && c[1].is_finite()), note, shares })
}
