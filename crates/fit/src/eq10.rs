//! Eq. 10 as the paper did it, `F_f = mu_e,a (F_a0 + L)` with `F_f = a_pull V_pull^2` and
//! `L = a_clamp V_clamp^2 - F_spring`, with two kinds of uncertainty kept apart.
//!
//! * **Regression.** The line is fitted in the measured variables, `Y = alpha + beta X` with
//!   `X = V_clamp^2`, `Y = V_pull^2` (over the rows with `L > 0`, weighted by the noise of
//!   `V_pull^2`, which grows with `V_pull`: see [`eq10_line`]), keeping
//!   the covariance of `alpha` and `beta`. Then `mu_e,a = (a_pull / a_clamp) beta` and
//!   `F_a0 = a_clamp alpha / beta + F_spring`, exactly the slope and intercept / slope of the line in
//!   (L, F_f). The interval of `mu_e,a` is `t_{n-2}` times its standard error; the interval of `F_a0`
//!   is Fieller's interval of the ratio `alpha / beta` (exact for normal errors, and honest when
//!   the slope is poorly known: then it is unbounded and reported as null with the reason); its
//!   standard error is the delta method's.
//! * **Calibration.** `a_clamp`, `a_pull` and `F_spring` are not measured with the voltages: the
//!   scenario gives each as a value with an uncertainty. A seeded Monte Carlo draws them (the same
//!   distributions and draw rules as `stiction study`), reduces the voltages with the drawn values
//!   and refits over the same rows (those with `L > 0` under the nominal values: they slipped, so
//!   they were in contact whatever the true factors), `draws` times: the calibration
//!   spread. Drawing also the regression's slope and intercept from their normal distribution in
//!   each draw gives `ci95_with_calibration` (2.5 and 97.5 percentiles).
//! * **Variance shares.** Each calibration source is drawn alone (the others at nominal), and its
//!   variance is set beside the regression variance; the shares are those variances over their
//!   sum (first order: interactions are left out; the joint Monte Carlo's spread is reported too).
//!   All Monte Carlo spreads are robust SDs (half the 15.9-84.1 percentile range): the quantities
//!   are proportional to `1 / a_clamp`, and a normal `a_clamp` of 1.4 +/- 0.5 gives `1 / a_clamp`
//!   a tail so long that the plain variance is dominated by a handful of draws near zero.
//!
//! The line is fitted once (the rows are those of the nominal reduction in every draw), so each
//! draw costs O(1) whatever the number of rows, and the whole fit is linear in the rows.
//!
//! When every row in the line has the same pull voltage the data show no load dependence: then
//! `mu_e,a` and `F_a0` are null with the reason, and so are they (and `F_a0` alone) when the slope
//! is not positive; nothing is divided by a zero slope.

use std::collections::BTreeMap;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::Serialize;
use stiction_meter::Reduction;
use stiction_units::UncertainInput;

use crate::error::FitError;
use crate::stats::{Line, fieller, percentile, robust_sd, t975, weighted_line};

/// One uncertain quantity of the reduction.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrationSource {
    /// `a_clamp`, `a_pull` or `spring_force`.
    pub name: String,
    /// Where it comes from in the scenario (JSON path).
    pub path: String,
    /// Nominal value in SI units (N/V^2 for a conversion factor, N for the spring force; the unit
    /// is in `unit`).
    #[serde(rename = "nominal_si")]
    pub nominal: f64,
    /// The SI unit of `nominal_si`: "N/V^2" or "N".
    pub unit: &'static str,
    /// Its uncertainty as written (None: the scenario gives no uncertainty, the value is exact).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uncertainty: Option<UncertainInput>,
}

/// A quantity with its intervals.
#[derive(Debug, Clone, Serialize)]
pub struct Estimate {
    /// Best estimate (nominal reduction); null when the data do not determine it (reason in
    /// `value_note`).
    pub value: Option<f64>,
    /// Why `value` is null, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub value_note: Option<String>,
    /// Standard error from the regression alone.
    pub stderr: Option<f64>,
    /// 95 % interval from the regression alone.
    pub ci95: Option<[f64; 2]>,
    /// Why `ci95` is null, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95_note: Option<String>,
    /// 95 % interval from the regression and the calibration together (Monte Carlo percentiles).
    pub ci95_with_calibration: Option<[f64; 2]>,
    /// Why `ci95_with_calibration` is null, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95_with_calibration_note: Option<String>,
    /// Standard deviation from the calibration alone (Monte Carlo; robust: half the 15.9-84.1
    /// percentile range, since mu_e,a is proportional to 1 / a_clamp, whose normal draw has a
    /// long tail towards small a_clamp that would make the plain SD meaningless).
    pub sd_calibration: Option<f64>,
}

/// Eq. 10 of one data set.
#[derive(Debug, Clone, Serialize)]
pub struct Eq10Fit {
    /// Apparent friction coefficient mu_e,a.
    pub mu_apparent: Estimate,
    /// Apparent zero-load adhesion force F_a0, N.
    pub apparent_adhesion_force_n: Estimate,
    /// Intercept of F_f against L, mu_e,a F_a0, N.
    pub intercept_n: Option<f64>,
    /// Covariance of the slope mu_e,a and the intercept (N), from the regression.
    pub slope_intercept_covariance_n: Option<f64>,
    /// Rows in the line.
    pub points: usize,
    /// Degrees of freedom of the line, n - 2.
    pub dof: usize,
    /// Coefficient of determination (weighted).
    pub r_squared: f64,
    /// How the line is weighted ([`WEIGHTING`]).
    pub weighting: String,
    /// Share of the variance of each quantity by source (`regression`, `a_clamp`, `a_pull`,
    /// `spring_force`), summing to 1.
    pub variance_shares: VarianceShares,
    /// The Monte Carlo behind the calibration numbers.
    pub calibration: CalibrationRun,
}

/// Variance shares of the two eq. 10 quantities.
#[derive(Debug, Clone, Serialize, Default)]
pub struct VarianceShares {
    /// Of mu_e,a.
    pub mu_apparent: BTreeMap<String, f64>,
    /// Of F_a0.
    pub apparent_adhesion_force_n: BTreeMap<String, f64>,
}

/// The calibration Monte Carlo.
#[derive(Debug, Clone, Serialize)]
pub struct CalibrationRun {
    /// Draws.
    pub draws: usize,
    /// Seed (ChaCha8; stream 0 joint, streams 1-3 one source at a time).
    pub seed: u64,
    /// The sources.
    pub sources: Vec<CalibrationSource>,
    /// Draws with fewer than three rows at L > 0 or a non-positive slope (left out, counted here).
    pub failed_draws: usize,
    /// Standard deviation of mu_e,a over the joint draws (calibration and regression).
    pub mu_sd_total: Option<f64>,
    /// Standard deviation of F_a0 over the joint draws, N.
    pub adhesion_force_sd_total_n: Option<f64>,
    /// Why there was no Monte Carlo, when there was none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// One measured slip entering eq. 10.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eq10Point {
    /// Clamp voltage, V.
    pub v_clamp_v: f64,
    /// Pull voltage at slip, V.
    pub v_pull_v: f64,
    /// The row's pull-voltage SD, V (the file's `v_pull_sd_v`), when the file gives it.
    pub v_pull_sd_v: Option<f64>,
}

/// How the eq. 10 line is weighted, in words (the report's `eq10.weighting`).
pub const WEIGHTING: &str = "weighted least squares in (V_clamp^2, V_pull^2) with weights 1 / Var(V_pull^2), Var(V_pull^2) = (2 V_pull sd)^2 to first order: V_pull from the line's own prediction (three reweighting passes from the unweighted line), sd the row's v_pull_sd_v or one common value; the scale of the variances comes from the weighted residuals (t with n - 2 degrees of freedom)";

/// Reweighting passes of the eq. 10 line.
const REWEIGHT_PASSES: usize = 3;

/// The eq. 10 line `Y = alpha + beta X` through `(X, Y, sd)` = (V_clamp^2, V_pull^2, pull-voltage
/// SD): the noise of `Y = V_pull^2` is `2 V_pull sd` to first order, so it grows with `V_pull`;
/// ordinary least squares ignores that and its interval of the slope undercovers. Weights
/// `w = 1 / (Yhat sd^2)` (the constant 4 cancels against the residual scale) with `Yhat` the line's
/// prediction, from the unweighted line and [`REWEIGHT_PASSES`] passes (the prediction, not the
/// measured `Y`, so that a high measurement is not down-weighted for being high). `Yhat` is kept
/// at least a quarter of the smallest measured `Y`.
pub fn eq10_line(points: &[(f64, f64, f64)]) -> Option<Line> {
    let y_floor = 0.25 * points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
    let mut w: Vec<(f64, f64, f64)> = points.iter().map(|&(x, y, sd)| (x, y, 1.0 / (sd * sd))).collect();
    let mut line = weighted_line(&w)?;
    for _ in 0..REWEIGHT_PASSES {
        for (q, &(x, _, sd)) in w.iter_mut().zip(points) {
            let y_hat = (line.intercept + line.slope * x).max(y_floor);
            q.2 = 1.0 / (y_hat * sd * sd);
        }
        line = weighted_line(&w)?;
    }
    Some(line)
}

/// mu_e,a and F_a0 from a line in (V_clamp^2, V_pull^2) and a reduction.
fn reduce(beta: f64, alpha: f64, r: &Reduction) -> (f64, f64) {
    (r.a_pull_n_per_v2 / r.a_clamp_n_per_v2 * beta, r.a_clamp_n_per_v2 * alpha / beta + r.spring_force_n)
}

/// Draws one value of a source (its nominal when it has no uncertainty).
pub(crate) fn draw(src: &CalibrationSource, rng: &mut ChaCha8Rng) -> Result<f64, FitError> {
    match &src.uncertainty {
        Some(u) => stiction_study::draw(u, &src.path, rng).map_err(|e| FitError::Setting(e.to_string())),
        None => Ok(src.nominal),
    }
}

/// Rows of the line: `(V_clamp^2, V_pull^2, pull-voltage SD)`.
type LineRows = Vec<(f64, f64, f64)>;

/// The rows of the line, `(V_clamp^2, V_pull^2, sd)`: those with V_pull > 0 and L > 0 under the
/// nominal reduction, and the line through them ([`eq10_line`]).
fn nominal_line(points: &[Eq10Point], nominal: &Reduction) -> Result<(LineRows, Line), FitError> {
    let cut = nominal.spring_force_n / nominal.a_clamp_n_per_v2;
    let pts: Vec<(f64, f64, f64)> = points
        .iter()
        .filter(|p| p.v_pull_v > 0.0 && p.v_clamp_v * p.v_clamp_v > cut)
        .map(|p| (p.v_clamp_v * p.v_clamp_v, p.v_pull_v * p.v_pull_v, p.v_pull_sd_v.unwrap_or(1.0)))
        .collect();
    let line = eq10_line(&pts).ok_or_else(|| {
        FitError::TooFewRows("eq. 10 needs at least three rows with L > 0 and two different clamp voltages".into())
    })?;
    Ok((pts, line))
}

/// The widths (upper minus lower end) of eq. 10's 95 % intervals, without and with the
/// calibration uncertainty; None where [`fit_eq10`] gives no interval.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IntervalWidths {
    /// mu_e,a, regression alone: `2 t_0.975(n-2) se(mu_e,a)`.
    pub mu: Option<f64>,
    /// mu_e,a with the calibration: 2.5-97.5 percentile range of the joint draws.
    pub mu_with_calibration: Option<f64>,
    /// F_a0, regression alone (Fieller), N.
    pub fa0_n: Option<f64>,
    /// F_a0 with the calibration, N.
    pub fa0_with_calibration_n: Option<f64>,
}

/// The widths of [`fit_eq10`]'s four 95 % intervals, and nothing else, for studies that need
/// them for every virtual experiment. The calibrated widths come from the same joint Monte Carlo
/// as `fit_eq10`'s `ci95_with_calibration` (stream 0 of `seed`: a_clamp, a_pull, F_spring drawn
/// from their stated distributions and the line's slope and intercept from their normal
/// distribution, 2.5 and 97.5 percentiles by linear interpolation between order statistics), so
/// with the same `draws` and `seed` the widths are those of `fit_eq10`'s intervals to the bit.
/// What makes it cheap enough for thousands of draws per experiment: the distributions are parsed
/// once ([`stiction_study::Sampler`]), the per-source and calibration-only runs that give
/// `fit_eq10` its variance shares are skipped, and the two percentiles are selected, not sorted.
///
/// Why thousands: the percentile range of the long-tailed mu_e,a (proportional to `1 / a_clamp`,
/// a normal of 1.4 +/- 0.5 on the paper's device) read from few draws is biased narrow: the mean
/// width over many seeds from 50 draws is about 10 % below the limit of many draws on an experiment
/// of the paper's device; from [`LAB_WIDTH_DRAWS`] draws it is within 0.3 % (test
/// `calibrated_width_is_unbiased_against_20000_draws` in `crates/fit/tests/eq10_widths.rs`).
pub fn interval_widths(
    points: &[Eq10Point],
    nominal: &Reduction,
    sources: &[CalibrationSource; 3],
    draws: usize,
    seed: u64,
) -> Result<IntervalWidths, FitError> {
    let (pts, line) = nominal_line(points, nominal)?;
    let flat = pts.iter().all(|p| p.1 == pts[0].1);
    let slope_ok = line.slope > 0.0 && !flat;
    if !slope_ok {
        return Ok(IntervalWidths::default());
    }
    let (a, b) = (line.intercept, line.slope);
    let k = nominal.a_pull_n_per_v2 / nominal.a_clamp_n_per_v2;
    let t = t975(line.dof as f64);
    let finite = |x: f64| x.is_finite().then_some(x);
    // The regression's widths computed as fit_eq10 computes the ends (the same bits).
    let mu_value = reduce(b, a, nominal).0;
    let mu_se = k * line.var_slope.sqrt();
    let mu = t.and_then(|t| finite((mu_value + t * mu_se) - (mu_value - t * mu_se)));
    let fa0_n = t.and_then(|t| fieller(a, b, line.var_intercept, line.var_slope, line.cov, t)).and_then(|[lo, hi]| {
        let end = |x: f64| nominal.a_clamp_n_per_v2 * x + nominal.spring_force_n;
        finite(end(hi) - end(lo))
    });
    if draws == 0 {
        return Ok(IntervalWidths { mu, fa0_n, ..IntervalWidths::default() });
    }
    let (mut ms, mut fs, _) = joint_draws(&line, sources, draws, seed)?;
    Ok(IntervalWidths {
        mu,
        mu_with_calibration: percentile_width(&mut ms).and_then(finite),
        fa0_n,
        fa0_with_calibration_n: percentile_width(&mut fs).and_then(finite),
    })
}

/// The joint calibration Monte Carlo of [`fit_eq10`] and [`interval_widths`]: `draws` draws from
/// stream 0 of `seed`, each of a_clamp, a_pull and F_spring from its stated distribution (parsed
/// once, [`stiction_study::Sampler`]; the nominal without one) and of the line's slope and
/// intercept from their joint normal distribution (`beta = b + sd_b z1` and
/// `alpha = a + (cov/sd_b) z1 + sqrt(var_a - cov^2/var_b) z2`), reduced to mu_e,a and F_a0 (N).
/// Returns those of the finite draws and the number of draws that were not finite.
fn joint_draws(
    line: &Line,
    sources: &[CalibrationSource; 3],
    draws: usize,
    seed: u64,
) -> Result<(Vec<f64>, Vec<f64>, usize), FitError> {
    let samplers = sources
        .iter()
        .map(|s| match &s.uncertainty {
            Some(u) => stiction_study::Sampler::new(u, &s.path).map(Some),
            None => Ok(None),
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| FitError::Setting(e.to_string()))?;
    let one = |i: usize, rng: &mut ChaCha8Rng| -> Result<f64, FitError> {
        match &samplers[i] {
            Some(s) => s.sample(&sources[i].path, rng).map_err(|e| FitError::Setting(e.to_string())),
            None => Ok(sources[i].nominal),
        }
    };
    let (a, b) = (line.intercept, line.slope);
    let sb = line.var_slope.sqrt();
    let (cz, rest) = if sb > 0.0 {
        (line.cov / sb, (line.var_intercept - line.cov * line.cov / line.var_slope).max(0.0).sqrt())
    } else {
        (0.0, line.var_intercept.max(0.0).sqrt())
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(0);
    let (mut ms, mut fs, mut failed) = (Vec::with_capacity(draws), Vec::with_capacity(draws), 0);
    for _ in 0..draws {
        let r = Reduction {
            a_clamp_n_per_v2: one(0, &mut rng)?,
            a_pull_n_per_v2: one(1, &mut rng)?,
            spring_force_n: one(2, &mut rng)?,
        };
        let (z1, z2): (f64, f64) = (StandardNormal.sample(&mut rng), StandardNormal.sample(&mut rng));
        let (m, f) = reduce(b + sb * z1, a + cz * z1 + rest * z2, &r);
        if m.is_finite() && f.is_finite() {
            ms.push(m);
            fs.push(f);
        } else {
            failed += 1;
        }
    }
    Ok((ms, fs, failed))
}

/// The 2.5-97.5 percentile range of `v` (reordered), exactly [`percentile`] of the sorted values
/// at 0.025 and 0.975, by selection in O(n).
fn percentile_width(v: &mut [f64]) -> Option<f64> {
    let at = |v: &mut [f64], p: f64| -> Option<f64> {
        if v.is_empty() {
            return None;
        }
        let h = p * (v.len() - 1) as f64;
        let (i, f) = (h.floor() as usize, h - h.floor());
        let (_, &mut lo, right) = v.select_nth_unstable_by(i, f64::total_cmp);
        let hi = if f > 0.0 { right.iter().copied().min_by(f64::total_cmp).unwrap_or(lo) } else { lo };
        Some(lo + f * (hi - lo))
    };
    Some(at(v, 0.975)? - at(v, 0.025)?)
}

/// Calibration draws per virtual experiment behind a study's calibrated interval widths
/// ([`interval_widths`]).
pub const LAB_WIDTH_DRAWS: usize = 2000;

/// Eq. 10 on measured rows (those with V_pull > 0 and L > 0 under the nominal reduction enter the
/// line), weighted by the noise of V_pull^2 ([`eq10_line`]), with `draws` calibration draws from
/// `seed` (0: no calibration Monte Carlo, the regression intervals only, with the reason in
/// `calibration.note`). `sources` are a_clamp, a_pull, spring_force in this order.
pub fn fit_eq10(
    points: &[Eq10Point],
    nominal: &Reduction,
    sources: &[CalibrationSource; 3],
    draws: usize,
    seed: u64,
) -> Result<Eq10Fit, FitError> {
    let (pts, line) = nominal_line(points, nominal)?;
    let flat = pts.iter().all(|p| p.1 == pts[0].1);
    let slope_ok = line.slope > 0.0 && !flat;
    let (mu, fa0) = reduce(line.slope, line.intercept, nominal);
    let t = t975(line.dof as f64);
    let k = nominal.a_pull_n_per_v2 / nominal.a_clamp_n_per_v2;
    let mu_se = k * line.var_slope.sqrt();
    // F_a0 = a_c (alpha / beta) + F_spring; delta method for the ratio.
    let (a, b) = (line.intercept, line.slope);
    let ratio_var =
        (line.var_intercept / (b * b) - 2.0 * a * line.cov / b.powi(3) + a * a * line.var_slope / b.powi(4)).max(0.0);
    let fa0_se = nominal.a_clamp_n_per_v2 * ratio_var.sqrt();
    let flat_note = || {
        format!(
            "all {} rows in the line have the same pull voltage ({} V): the data show no change of friction with load, so eq. 10 has no slope to fit",
            pts.len(),
            pts[0].1.sqrt()
        )
    };
    let fa0_ci = t
        .filter(|_| slope_ok)
        .and_then(|t| fieller(a, b, line.var_intercept, line.var_slope, line.cov, t))
        .map(|[lo, hi]| {
            [
                nominal.a_clamp_n_per_v2 * lo + nominal.spring_force_n,
                nominal.a_clamp_n_per_v2 * hi + nominal.spring_force_n,
            ]
        });
    let mu_ci = t.filter(|_| slope_ok).map(|t| [mu - t * mu_se, mu + t * mu_se]);

    // The calibration Monte Carlo: stream 0 joint (with regression draws), streams 1-3 one source,
    // stream 4 all sources without the regression. The rows and the line stay those of the
    // nominal reduction (they slipped, so they were in contact whatever the true factors).
    let (mut joint_mu, mut joint_fa0, mut failed) = (Vec::new(), Vec::new(), 0usize);
    let mut one_at_a_time = [(0.0, 0.0); 3];
    let mut cal_only_mu = Vec::new();
    let mut cal_only_fa0 = Vec::new();
    let mc_note = if !slope_ok {
        Some(if flat { flat_note() } else { "the fitted slope is not positive: no calibration Monte Carlo".into() })
    } else if draws == 0 {
        Some("no calibration draws asked for: the intervals are the regression's alone".into())
    } else {
        None
    };
    if mc_note.is_none() {
        (joint_mu, joint_fa0, failed) = joint_draws(&line, sources, draws, seed)?;
        for (which, slot) in one_at_a_time.iter_mut().enumerate() {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            rng.set_stream(which as u64 + 1);
            let (mut ms, mut fs) = (Vec::with_capacity(draws), Vec::with_capacity(draws));
            for _ in 0..draws {
                let mut r = *nominal;
                let x = draw(&sources[which], &mut rng)?;
                match which {
                    0 => r.a_clamp_n_per_v2 = x,
                    1 => r.a_pull_n_per_v2 = x,
                    _ => r.spring_force_n = x,
                }
                let (m, f) = reduce(line.slope, line.intercept, &r);
                if m.is_finite() && f.is_finite() {
                    ms.push(m);
                    fs.push(f);
                }
            }
            *slot = (robust_sd(&ms).map_or(0.0, |v| v * v), robust_sd(&fs).map_or(0.0, |v| v * v));
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(4);
        for _ in 0..draws {
            let r = Reduction {
                a_clamp_n_per_v2: draw(&sources[0], &mut rng)?,
                a_pull_n_per_v2: draw(&sources[1], &mut rng)?,
                spring_force_n: draw(&sources[2], &mut rng)?,
            };
            let (m, f) = reduce(line.slope, line.intercept, &r);
            if m.is_finite() && f.is_finite() {
                cal_only_mu.push(m);
                cal_only_fa0.push(f);
            }
        }
    }
    let shares = |reg: f64, parts: [f64; 3]| {
        let total = reg + parts.iter().sum::<f64>();
        let mut m = BTreeMap::new();
        if total > 0.0 && total.is_finite() {
            for (name, v) in
                [("regression", reg), ("a_clamp", parts[0]), ("a_pull", parts[1]), ("spring_force", parts[2])]
            {
                m.insert(name.to_string(), v / total);
            }
        }
        m
    };
    let variance_shares = if mc_note.is_none() {
        VarianceShares {
            mu_apparent: shares(mu_se * mu_se, one_at_a_time.map(|v| v.0)),
            apparent_adhesion_force_n: shares(fa0_se * fa0_se, one_at_a_time.map(|v| v.1)),
        }
    } else {
        VarianceShares::default()
    };
    let interval = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        Some([percentile(v, 0.025)?, percentile(v, 0.975)?])
    };
    let fa0_note = if !slope_ok {
        Some(if flat {
            flat_note()
        } else {
            format!(
                "F_a0 = a_clamp intercept / slope + F_spring needs a positive slope; the fitted slope is {:.4} (V^2/V^2)",
                line.slope
            )
        })
    } else {
        fa0_ci.is_none().then(|| {
            "Fieller's interval of F_a0 = intercept / slope is unbounded: the slope is not significantly above zero at 95 %"
                .to_string()
        })
    };
    let mu_note = if flat {
        Some(flat_note())
    } else if !slope_ok {
        Some("the fitted slope is not positive".to_string())
    } else {
        t.is_none().then(|| "no interval: too few degrees of freedom".to_string())
    };
    let finite = |x: f64| x.is_finite().then_some(x);
    Ok(Eq10Fit {
        mu_apparent: Estimate {
            value: if flat { None } else { finite(mu) },
            value_note: flat.then(flat_note),
            stderr: if flat { None } else { finite(mu_se) },
            ci95: mu_ci,
            ci95_note: mu_note,
            ci95_with_calibration: interval(&mut joint_mu.clone()),
            ci95_with_calibration_note: mc_note.clone(),
            sd_calibration: robust_sd(&cal_only_mu),
        },
        apparent_adhesion_force_n: Estimate {
            value: if slope_ok { finite(fa0) } else { None },
            value_note: (!slope_ok).then(|| fa0_note.clone().unwrap_or_default()),
            stderr: if slope_ok { finite(fa0_se) } else { None },
            ci95: fa0_ci,
            ci95_note: fa0_note,
            ci95_with_calibration: interval(&mut joint_fa0.clone()),
            ci95_with_calibration_note: mc_note.clone(),
            sd_calibration: robust_sd(&cal_only_fa0),
        },
        intercept_n: finite(nominal.a_pull_n_per_v2 * line.intercept + mu * nominal.spring_force_n),
        slope_intercept_covariance_n: finite(
            k * nominal.a_pull_n_per_v2
                * (line.cov + line.var_slope * nominal.spring_force_n / nominal.a_clamp_n_per_v2),
        ),
        points: line.points,
        dof: line.dof,
        r_squared: line.r_squared,
        weighting: WEIGHTING.into(),
        variance_shares,
        calibration: CalibrationRun {
            draws,
            seed,
            sources: sources.to_vec(),
            failed_draws: failed,
            mu_sd_total: robust_sd(&joint_mu),
            adhesion_force_sd_total_n: robust_sd(&joint_fa0),
            note: mc_note,
        },
    })
}
