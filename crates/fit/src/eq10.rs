//! Eq. 10 as the paper did it, `F_f = mu_e,a (F_a0 + L)` with `F_f = a_pull V_pull^2` and
//! `L = a_clamp V_clamp^2 - F_spring`, with two kinds of uncertainty kept apart.
//!
//! * **Regression.** The line is fitted in the measured variables, `Y = alpha + beta X` with
//!   `X = V_clamp^2`, `Y = V_pull^2` (ordinary least squares over the rows with `L > 0`), keeping
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
//! Line fits in the Monte Carlo use running sums over the rows sorted by `V_clamp^2`, so each draw
//! costs O(log n) whatever the number of rows.

use std::collections::BTreeMap;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::Serialize;
use stiction_meter::Reduction;
use stiction_units::UncertainInput;

use crate::FitError;
use crate::stats::{Line, Sums, fieller, percentile, robust_sd, t975};

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
    /// Best estimate (nominal reduction).
    pub value: f64,
    /// Standard error from the regression alone.
    pub stderr: Option<f64>,
    /// 95 % interval from the regression alone.
    pub ci95: Option<[f64; 2]>,
    /// Why `ci95` is null, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95_note: Option<String>,
    /// 95 % interval from the regression and the calibration together (Monte Carlo percentiles).
    pub ci95_with_calibration: Option<[f64; 2]>,
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
    pub intercept_n: f64,
    /// Covariance of the slope mu_e,a and the intercept (N), from the regression.
    pub slope_intercept_covariance_n: f64,
    /// Rows in the line.
    pub points: usize,
    /// Degrees of freedom of the line, n - 2.
    pub dof: usize,
    /// Coefficient of determination.
    pub r_squared: f64,
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
}

/// The measured voltages behind eq. 10, sorted by V_clamp^2 with running sums.
struct Prepared {
    /// Sorted X = V_clamp^2 (V^2).
    xs: Vec<f64>,
    /// Running sums of centred (X, Y); prefix[k] covers rows 0..k.
    prefix: Vec<Sums>,
    mx: f64,
    my: f64,
}

impl Prepared {
    fn new(pairs: &[(f64, f64)]) -> Prepared {
        let mut p: Vec<(f64, f64)> = pairs.to_vec();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        let n = p.len().max(1) as f64;
        let mx = p.iter().map(|q| q.0).sum::<f64>() / n;
        let my = p.iter().map(|q| q.1).sum::<f64>() / n;
        let mut prefix = Vec::with_capacity(p.len() + 1);
        let mut s = Sums::default();
        prefix.push(s);
        for q in &p {
            s.add(q.0 - mx, q.1 - my);
            prefix.push(s);
        }
        Prepared { xs: p.iter().map(|q| q.0).collect(), prefix, mx, my }
    }

    /// The line Y = alpha + beta X over the rows with X > x_min, in uncentred coordinates.
    fn line_above(&self, x_min: f64) -> Option<Line> {
        let k = self.xs.partition_point(|&x| x <= x_min);
        let all = self.prefix[self.prefix.len() - 1];
        let sums = all.minus(&self.prefix[k]);
        let mut l = sums.line()?;
        let (mx, my) = (self.mx, self.my);
        let (a_c, var_c, cov_c) = (l.intercept, l.var_intercept, l.cov);
        l.intercept = a_c + my - l.slope * mx;
        l.var_intercept = var_c + mx * mx * l.var_slope - 2.0 * mx * cov_c;
        l.cov = cov_c - mx * l.var_slope;
        Some(l)
    }
}

/// mu_e,a and F_a0 from a line in (V_clamp^2, V_pull^2) and a reduction.
fn reduce(beta: f64, alpha: f64, r: &Reduction) -> (f64, f64) {
    (r.a_pull_n_per_v2 / r.a_clamp_n_per_v2 * beta, r.a_clamp_n_per_v2 * alpha / beta + r.spring_force_n)
}

/// Draws one value of a source (its nominal when it has no uncertainty).
fn draw(src: &CalibrationSource, rng: &mut ChaCha8Rng) -> Result<f64, FitError> {
    match &src.uncertainty {
        Some(u) => stiction_study::draw(u, &src.path, rng).map_err(|e| FitError::Setting(e.to_string())),
        None => Ok(src.nominal),
    }
}

/// Eq. 10 on measured (V_clamp, V_pull) pairs (all readable rows with V_pull > 0; the rows with
/// L > 0 under the nominal reduction enter the line), with `draws` calibration draws from `seed`.
/// `sources` are a_clamp, a_pull, spring_force in this order.
pub fn fit_eq10(
    voltages: &[(f64, f64)],
    nominal: &Reduction,
    sources: &[CalibrationSource; 3],
    draws: usize,
    seed: u64,
) -> Result<Eq10Fit, FitError> {
    let pairs: Vec<(f64, f64)> = voltages.iter().map(|&(c, p)| (c * c, p * p)).collect();
    let prep = Prepared::new(&pairs);
    let cut = |r: &Reduction| r.spring_force_n / r.a_clamp_n_per_v2;
    let line = prep.line_above(cut(nominal)).ok_or_else(|| {
        FitError::TooFewRows("eq. 10 needs at least three rows with L > 0 and two different clamp voltages".into())
    })?;
    let (mu, fa0) = reduce(line.slope, line.intercept, nominal);
    let t = t975(line.dof as f64).unwrap_or(f64::NAN);
    let k = nominal.a_pull_n_per_v2 / nominal.a_clamp_n_per_v2;
    let mu_se = k * line.var_slope.sqrt();
    // F_a0 = a_c (alpha / beta) + F_spring; delta method for the ratio.
    let (a, b) = (line.intercept, line.slope);
    let ratio_var =
        (line.var_intercept / (b * b) - 2.0 * a * line.cov / b.powi(3) + a * a * line.var_slope / b.powi(4)).max(0.0);
    let fa0_se = nominal.a_clamp_n_per_v2 * ratio_var.sqrt();
    let fa0_ci = fieller(a, b, line.var_intercept, line.var_slope, line.cov, t).map(|[lo, hi]| {
        [nominal.a_clamp_n_per_v2 * lo + nominal.spring_force_n, nominal.a_clamp_n_per_v2 * hi + nominal.spring_force_n]
    });
    let mu_ci = (mu > 0.0).then_some([mu - t * mu_se, mu + t * mu_se]);

    // The calibration Monte Carlo: stream 0 joint (with regression draws), streams 1-3 one source.
    let mut joint_mu = Vec::with_capacity(draws);
    let mut joint_fa0 = Vec::with_capacity(draws);
    let mut failed = 0usize;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(0);
    for _ in 0..draws {
        let r = Reduction {
            a_clamp_n_per_v2: draw(&sources[0], &mut rng)?,
            a_pull_n_per_v2: draw(&sources[1], &mut rng)?,
            spring_force_n: draw(&sources[2], &mut rng)?,
        };
        let (z1, z2): (f64, f64) = (StandardNormal.sample(&mut rng), StandardNormal.sample(&mut rng));
        match prep.line_above(cut(nominal)) {
            Some(l) if l.slope > 0.0 => {
                let sb = l.var_slope.sqrt();
                let beta = l.slope + sb * z1;
                let alpha = l.intercept
                    + if sb > 0.0 { l.cov / sb * z1 } else { 0.0 }
                    + (l.var_intercept - if sb > 0.0 { l.cov * l.cov / l.var_slope } else { 0.0 }).max(0.0).sqrt() * z2;
                let (m, f) = reduce(beta, alpha, &r);
                if m.is_finite() && f.is_finite() {
                    joint_mu.push(m);
                    joint_fa0.push(f);
                } else {
                    failed += 1;
                }
            }
            _ => failed += 1,
        }
    }
    let mut one_at_a_time = [(0.0, 0.0); 3];
    let mut cal_only_mu = Vec::new();
    let mut cal_only_fa0 = Vec::new();
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
            if let Some(l) = prep.line_above(cut(nominal)).filter(|l| l.slope > 0.0) {
                let (m, f) = reduce(l.slope, l.intercept, &r);
                ms.push(m);
                fs.push(f);
            }
        }
        *slot = (robust_sd(&ms).map_or(0.0, |v| v * v), robust_sd(&fs).map_or(0.0, |v| v * v));
    }
    // Calibration alone (all three sources, no regression draw), stream 4.
    {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(4);
        for _ in 0..draws {
            let r = Reduction {
                a_clamp_n_per_v2: draw(&sources[0], &mut rng)?,
                a_pull_n_per_v2: draw(&sources[1], &mut rng)?,
                spring_force_n: draw(&sources[2], &mut rng)?,
            };
            if let Some(l) = prep.line_above(cut(nominal)).filter(|l| l.slope > 0.0) {
                let (m, f) = reduce(l.slope, l.intercept, &r);
                cal_only_mu.push(m);
                cal_only_fa0.push(f);
            }
        }
    }
    let shares = |reg: f64, parts: [f64; 3]| {
        let total = reg + parts.iter().sum::<f64>();
        let mut m = BTreeMap::new();
        for (name, v) in [("regression", reg), ("a_clamp", parts[0]), ("a_pull", parts[1]), ("spring_force", parts[2])]
        {
            m.insert(name.to_string(), if total > 0.0 { v / total } else { 0.0 });
        }
        m
    };
    let variance_shares = VarianceShares {
        mu_apparent: shares(mu_se * mu_se, one_at_a_time.map(|v| v.0)),
        apparent_adhesion_force_n: shares(fa0_se * fa0_se, one_at_a_time.map(|v| v.1)),
    };
    let interval = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        Some([percentile(v, 0.025)?, percentile(v, 0.975)?])
    };
    let fa0_note = fa0_ci.is_none().then(|| {
        "Fieller's interval of F_a0 = intercept / slope is unbounded: the slope is not significantly above zero at 95 %"
            .to_string()
    });
    Ok(Eq10Fit {
        mu_apparent: Estimate {
            value: mu,
            stderr: Some(mu_se),
            ci95: mu_ci,
            ci95_note: mu_ci.is_none().then(|| "the fitted slope is not positive".to_string()),
            ci95_with_calibration: interval(&mut joint_mu.clone()),
            sd_calibration: robust_sd(&cal_only_mu),
        },
        apparent_adhesion_force_n: Estimate {
            value: fa0,
            stderr: Some(fa0_se),
            ci95: fa0_ci,
            ci95_note: fa0_note,
            ci95_with_calibration: interval(&mut joint_fa0.clone()),
            sd_calibration: robust_sd(&cal_only_fa0),
        },
        intercept_n: mu * fa0,
        slope_intercept_covariance_n: k
            * nominal.a_pull_n_per_v2
            * (line.cov + line.var_slope * nominal.spring_force_n / nominal.a_clamp_n_per_v2),
        points: line.points,
        dof: line.dof,
        r_squared: line.r_squared,
        variance_shares,
        calibration: CalibrationRun {
            draws,
            seed,
            sources: sources.to_vec(),
            failed_draws: failed,
            mu_sd_total: robust_sd(&joint_mu),
            adhesion_force_sd_total_n: robust_sd(&joint_fa0),
        },
    })
}
