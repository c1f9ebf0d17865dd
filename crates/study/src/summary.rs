//! The summary of a study, computed from its sample log alone (so that a run, a resumed run and a
//! merge of shards give the same bytes): spreads, counts of reasons, the sensitivity table, and
//! the files study.json and samples.csv.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;

use crate::error::StudyError;
use crate::log::{self, Header};
use crate::sensitivity::{self, Sensitivity};

/// The reason codes of a sample without a fit, and what they mean.
pub const REASONS: [(&str, &str); 7] = [
    ("no-contact", "no clamp voltage brought the shoe into contact"),
    ("too-few-slips", "fewer than 2 slip points with L > 0: no eq. 10 line"),
    ("non-positive-slope", "the eq. 10 line falls: no mu_e,a"),
    ("degenerate-fit", "the slip points admit no straight line (equal loads)"),
    ("draw-failed", "an uncertain parameter could not be drawn"),
    ("invalid-scenario", "a drawn value made the scenario invalid"),
    ("meter-failed", "the meter could not run on the drawn device"),
];

/// The summary statistics' methods, as study.json states them.
pub const STATISTICS_METHOD: &str = "over the samples that gave the quantity: mean with its standard error sd / sqrt(n); sample standard deviation sd with its standard error sqrt((m4 - sd^4) / n) / (2 sd) (m4 the fourth central moment; first order, no normality assumed); percentiles p05, median, p95 by linear interpolation between the order statistics (x at rank p (n - 1), Hyndman and Fan's type 7), each with a distribution-free 95 % interval [x_(l), x_(u)] from the binomial distribution of the number of samples below it, l = ceil(n p - 1.96 sqrt(n p (1 - p))), u = ceil(n p + 1.96 sqrt(n p (1 - p))) (Conover 1999), null when n is too small to bound the percentile; min and max";

/// Summary statistics of one reported quantity over the samples that gave it, with their Monte
/// Carlo error: the standard error of the mean `sd / sqrt(n)`, and for each percentile a
/// distribution-free 95 % interval from the binomial distribution of the order statistics
/// ([`quantile_interval`]).
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Spread {
    /// Number of samples with a value.
    pub count: usize,
    /// Mean.
    pub mean: f64,
    /// Monte Carlo standard error of the mean, `sd / sqrt(n)` (0 for one sample).
    pub mean_se: f64,
    /// Sample standard deviation.
    pub sd: f64,
    /// Monte Carlo standard error of `sd`, distribution-free to first order: `Var(s^2) = (m4 - s^4) / n`
    /// (m4 the sample's fourth central moment), so `se(s) = sqrt((m4 - s^4) / n) / (2 s)`; for a
    /// normal quantity `s / sqrt(2 n)` (0 for fewer than two samples or no spread).
    pub sd_se: f64,
    /// 5th percentile.
    pub p05: f64,
    /// 95 % interval of the 5th percentile (None: too few samples for one).
    pub p05_ci: Option<[f64; 2]>,
    /// Median.
    pub median: f64,
    /// 95 % interval of the median.
    pub median_ci: Option<[f64; 2]>,
    /// 95th percentile.
    pub p95: f64,
    /// 95 % interval of the 95th percentile.
    pub p95_ci: Option<[f64; 2]>,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Why a percentile's interval is null: too few samples to bound it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub percentile_ci_note: Option<&'static str>,
}

impl Spread {
    /// Statistics of `values` (None when empty). Percentiles by linear interpolation.
    pub fn of(values: &[f64]) -> Option<Spread> {
        if values.is_empty() {
            return None;
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        Some(Self::of_sorted(&v))
    }

    fn of_sorted(v: &[f64]) -> Spread {
        let n = v.len();
        let mean = v.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 { (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt() } else { 0.0 };
        Spread {
            count: n,
            mean,
            mean_se: sd / (n as f64).sqrt(),
            sd,
            sd_se: if n > 1 && sd > 0.0 {
                let m4 = v.iter().map(|x| (x - mean).powi(4)).sum::<f64>() / n as f64;
                ((m4 - sd.powi(4)).max(0.0) / n as f64).sqrt() / (2.0 * sd)
            } else {
                0.0
            },
            p05: percentile(v, 0.05),
            p05_ci: quantile_interval(v, 0.05),
            median: percentile(v, 0.5),
            median_ci: quantile_interval(v, 0.5),
            p95: percentile(v, 0.95),
            p95_ci: quantile_interval(v, 0.95),
            min: v[0],
            max: v[n - 1],
            percentile_ci_note: [0.05, 0.5, 0.95].iter().any(|p| quantile_interval(v, *p).is_none()).then_some(
                "too few samples for a distribution-free 95 % interval of this percentile (Conover's binomial \
                 bound needs ranks inside the sample)",
            ),
        }
    }
}

/// Distribution-free 95 % interval of the p-quantile from `n` sorted values: `[x_(l), x_(u)]`
/// (1-based order statistics) with `l = ceil(n p - 1.96 sqrt(n p (1 - p)))` and
/// `u = ceil(n p + 1.96 sqrt(n p (1 - p)))`, the normal approximation to the binomial count of
/// values below the quantile (Conover, *Practical Nonparametric Statistics*, 3rd ed., 1999,
/// sec. 3.2; its exact coverage at n = 400 is 0.949-0.950 for p = 0.05, 0.5, 0.95). None when
/// `l < 1` or `u > n`: too few samples to bound that quantile.
pub fn quantile_interval(sorted: &[f64], p: f64) -> Option<[f64; 2]> {
    let n = sorted.len() as f64;
    let half = 1.96 * (n * p * (1.0 - p)).sqrt();
    let (l, u) = ((n * p - half).ceil(), (n * p + half).ceil());
    (l >= 1.0 && u <= n).then(|| [sorted[l as usize - 1], sorted[u as usize - 1]])
}

/// The standard error `se` of `value` if it says anything: finite and above rounding level
/// (1e-12 |value|; samples that agree to their last bits, as a deterministic model gives, have no
/// spread to show).
pub fn usable_se(value: f64, se: Option<f64>) -> Option<f64> {
    se.filter(|s| s.is_finite() && *s > 1e-12 * value.abs())
}

/// `value` with only the digits its standard error `se` supports: rounded to the decimal of the
/// standard error's leading digit (0.7712 with se 0.0055 -> "0.771"), in plain notation. Without a
/// usable standard error ([`usable_se`]), 3 significant digits.
pub fn digits(value: f64, se: Option<f64>) -> String {
    match usable_se(value, se) {
        Some(s) if value.is_finite() => {
            let decimals = (-s.log10().floor()).max(0.0) as usize;
            let decimals = decimals.min(15);
            let step = 10f64.powi(s.log10().floor() as i32);
            if decimals == 0 { format!("{:.0}", (value / step).round() * step) } else { format!("{value:.decimals$}") }
        }
        _ if value == 0.0 || !value.is_finite() => format!("{value}"),
        _ => {
            let decimals = (2 - value.abs().log10().floor() as i32).max(0) as usize;
            format!("{value:.decimals$}")
        }
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let r = p * (sorted.len() - 1) as f64;
    let (lo, hi) = (r.floor() as usize, r.ceil() as usize);
    sorted[lo] + (sorted[hi] - sorted[lo]) * (r - lo as f64)
}

/// The settings as study.json reports them.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ConfigSummary {
    /// Samples of the whole study.
    pub samples: usize,
    /// Base seed.
    pub seed: u64,
    /// Each sample its own surface.
    pub vary_surface: bool,
    /// This piece: "K/M" ("0/1" for a whole study).
    pub shard: String,
    /// How voltages were reduced.
    pub calibration: crate::Calibration,
    /// How slips were followed.
    pub slip_path: stiction_meter::SlipPath,
}

/// The nominal reduction.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ReductionSummary {
    /// a_clamp, N/V^2.
    pub a_clamp_n_per_v2: f64,
    /// a_pull, N/V^2.
    pub a_pull_n_per_v2: f64,
    /// F_spring, N.
    pub spring_force_n: f64,
}

/// study.json.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct StudySummary {
    /// How the summary statistics and their Monte Carlo errors are computed ([`STATISTICS_METHOD`]).
    pub statistics_method: String,
    /// The scenario file.
    pub scenario: String,
    /// Its fingerprint (after --set).
    pub scenario_hash: String,
    /// The settings.
    pub config: ConfigSummary,
    /// Samples in the log.
    pub samples_done: usize,
    /// Samples with an eq. 10 fit.
    pub with_fit: usize,
    /// Samples that ran but gave no fit (reasons in `reasons`).
    pub without_fit: usize,
    /// Samples that failed (drawing, the scenario or the meter; reasons in `reasons`).
    pub failed: usize,
    /// Count of each reason code (see samples.csv's `reason` and `detail` columns).
    pub reasons: BTreeMap<String, usize>,
    /// The nominal conversion every sample's voltages were reduced with.
    pub reduction: ReductionSummary,
    /// Spread of mu_e,a.
    pub mu_apparent: Option<Spread>,
    /// Spread of F_a0, N.
    pub apparent_adhesion_force_n: Option<Spread>,
    /// The widths of the 95 % intervals the lab quotes for each experiment's eq. 10 fit, without
    /// and with the calibration uncertainty, over the samples with a fit.
    pub lab_intervals: LabIntervals,
    /// The interface's own coefficient `s / p_mean` of each sample's device, over the samples with
    /// a fit ([`crate::interface_mu`]).
    pub interface_mu: Option<Spread>,
    /// The bias of each experiment, `mu_e,a - s / p_mean` of the same sample, over the samples with
    /// a fit and an interface coefficient.
    pub mu_bias: Option<Spread>,
    /// Which input explains how much of the spread.
    pub sensitivity: Sensitivity,
    /// Why a spread is null: no sample gave the quantity (see `reasons`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
    /// The scenario's measured reference values (its `reference` section), if it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<stiction_scenario::ReferenceSpec>,
}

/// Spreads of the widths of the lab's 95 % intervals over the experiments with a fit.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct LabIntervals {
    /// Calibration draws per experiment behind the `with_calibration` widths (0: none computed).
    pub calibration_draws: usize,
    /// Width of mu_e,a's interval from the regression alone.
    pub mu_ci95_width: Option<Spread>,
    /// Width of mu_e,a's interval with the calibration uncertainty.
    pub mu_ci95_width_with_calibration: Option<Spread>,
    /// Width of F_a0's interval from the regression alone, N.
    pub fa0_ci95_width_n: Option<Spread>,
    /// Width of F_a0's interval with the calibration uncertainty, N.
    pub fa0_ci95_width_with_calibration_n: Option<Spread>,
    /// Why a width is null: no experiment gave that interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

/// What the figures need besides the summary.
pub struct FigureData {
    /// mu_e,a of every sample with a fit, sorted.
    pub mu_sorted: Vec<f64>,
    /// (F_a0 N, mu_e,a) of the first 20000 samples with a fit.
    pub scatter: Vec<(f64, f64)>,
}

const SCATTER_POINTS: usize = 20_000;

fn parse_exact(s: &str) -> f64 {
    s.parse().unwrap_or(f64::NAN)
}

/// Reads the log at `path` and summarises it; `csv`: also collect the samples.csv bytes.
pub fn summarize(path: &Path, mut csv: Option<&mut Vec<u8>>) -> Result<(StudySummary, FigureData), StudyError> {
    let header: Header = log::read_header(path)?;
    if let Some(c) = csv.as_deref_mut() {
        c.extend_from_slice(&log::column_line(&header)?);
    }
    let (mut mus, mut fas, mut xs, mut scatter) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut reasons: BTreeMap<String, usize> = BTreeMap::new();
    let (mut failed, mut without) = (0, 0);
    let mut widths: [Vec<f64>; 4] = Default::default();
    let (mut iface, mut bias) = (Vec::new(), Vec::new());
    let done = log::for_each_row(path, |row, line| {
        if let Some(c) = csv.as_deref_mut() {
            c.extend_from_slice(line);
        }
        match (row.mu_apparent, row.apparent_adhesion_force_n) {
            (Some(mu), Some(fa)) if row.reason.is_empty() => {
                let w = &row.intervals;
                for (v, x) in widths.iter_mut().zip([
                    w.mu_ci95_width,
                    w.mu_ci95_width_with_calibration,
                    w.fa0_ci95_width_n,
                    w.fa0_ci95_width_with_calibration_n,
                ]) {
                    v.extend(x);
                }
                if let Some(m) = row.interface_mu {
                    iface.push(m);
                    bias.push(mu - m);
                }
                mus.push(mu);
                fas.push(fa);
                xs.push(row.draws);
                if scatter.len() < SCATTER_POINTS {
                    scatter.push((fa, mu));
                }
            }
            _ => {
                let reason = if row.reason.is_empty() { "unknown".to_string() } else { row.reason };
                if ["draw-failed", "invalid-scenario", "meter-failed"].contains(&reason.as_str()) {
                    failed += 1;
                } else {
                    without += 1;
                }
                *reasons.entry(reason).or_default() += 1;
            }
        }
        Ok(())
    })?;
    let names: Vec<String> = header.parameters.iter().map(|(p, _)| p.clone()).collect();
    let sens = sensitivity::table(&names, &xs, &mus, &fas, header.vary_surface);
    drop(xs);
    let fa_spread = Spread::of(&fas);
    drop(fas);
    mus.sort_by(f64::total_cmp);
    let summary = StudySummary {
        statistics_method: STATISTICS_METHOD.into(),
        scenario: header.scenario.clone(),
        scenario_hash: header.scenario_hash.clone(),
        config: ConfigSummary {
            samples: header.samples,
            seed: header.seed,
            vary_surface: header.vary_surface,
            shard: format!("{}/{}", header.shard_index, header.shard_count),
            calibration: header.calibration,
            slip_path: header.slip_path,
        },
        samples_done: done,
        with_fit: mus.len(),
        without_fit: without,
        failed,
        reasons,
        reduction: ReductionSummary {
            a_clamp_n_per_v2: parse_exact(&header.reduction[0]),
            a_pull_n_per_v2: parse_exact(&header.reduction[1]),
            spring_force_n: parse_exact(&header.reduction[2]),
        },
        mu_apparent: (!mus.is_empty()).then(|| Spread::of_sorted(&mus)),
        apparent_adhesion_force_n: fa_spread,
        lab_intervals: LabIntervals {
            calibration_draws: header.calibration_draws,
            mu_ci95_width: Spread::of(&widths[0]),
            mu_ci95_width_with_calibration: Spread::of(&widths[1]),
            fa0_ci95_width_n: Spread::of(&widths[2]),
            fa0_ci95_width_with_calibration_n: Spread::of(&widths[3]),
            note: widths
                .iter()
                .any(|w| w.is_empty())
                .then_some("no experiment gave this interval (no fit, an unbounded interval, or no calibration draws)"),
        },
        interface_mu: Spread::of(&iface),
        mu_bias: Spread::of(&bias),
        sensitivity: sens,
        note: None,
        reference: header.reference.clone(),
    };
    let mut summary = summary;
    if summary.mu_apparent.is_none()
        || summary.apparent_adhesion_force_n.is_none()
        || summary.interface_mu.is_none()
        || summary.mu_bias.is_none()
    {
        summary.note = Some(
            "a null spread: no sample gave that quantity (no eq. 10 fit, or no interface coefficient); `reasons` \
             counts why",
        );
    }
    Ok((summary, FigureData { mu_sorted: mus, scatter }))
}

/// Summarises the log in `dir` and writes study.json and samples.csv there (atomically).
pub fn finalize(dir: &Path) -> Result<(StudySummary, FigureData), StudyError> {
    let path = dir.join(log::LOG_NAME);
    let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0);
    let mut csv = Vec::with_capacity(size as usize + 1024);
    let (summary, fig) = summarize(&path, Some(&mut csv))?;
    let json = stiction_units::finite::to_json_pretty(&summary).map_err(|e| StudyError::Log(e.to_string()))?;
    let write = |name: &str, bytes: &[u8]| {
        stiction_units::io::write_atomic(&dir.join(name), bytes).map_err(|e| StudyError::Log(e.to_string()))
    };
    write("samples.csv", &csv)?;
    drop(csv);
    write("study.json", json.as_bytes())?;
    Ok((summary, fig))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_percentiles_interpolate() {
        let s = Spread::of(&[4.0, 1.0, 3.0, 2.0, 5.0]).unwrap();
        assert_eq!((s.count, s.min, s.max, s.median), (5, 1.0, 5.0, 3.0));
        assert!((s.mean - 3.0).abs() < 1e-15);
        assert!((s.sd - 2.5f64.sqrt()).abs() < 1e-15);
        assert!((s.p05 - 1.2).abs() < 1e-12 && (s.p95 - 4.8).abs() < 1e-12);
        assert!(Spread::of(&[]).is_none());
        // Five values bound no 5th percentile; the median's interval would need l >= 1.
        assert_eq!((s.p05_ci, s.p95_ci), (None, None));
        assert!((s.mean_se - 2.5f64.sqrt() / 5f64.sqrt()).abs() < 1e-15);
    }

    #[test]
    fn sd_standard_error_matches_the_spread_of_sd_over_repeats() {
        // 500 repeats of n = 200: the spread of sd over the repeats is what se(sd) estimates.
        // Normal: se(s) = sigma / sqrt(2 n) = 0.05; exponential (kurtosis 9): sqrt(2 / n) = 0.1,
        // twice the normal formula. The spread over 500 repeats is known to about 3 % (1 / sqrt(2 x
        // 500)), the mean of se(sd) better; tolerance 10 %. Deliberate bug caught: the normal
        // formula s / sqrt(2 n) for every distribution (seen failing on the exponential: 0.05 vs 0.1).
        use rand::SeedableRng;
        use rand_distr::{Distribution, Exp, StandardNormal};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for exponential in [false, true] {
            let (mut sds, mut ses) = (Vec::new(), Vec::new());
            for _ in 0..500 {
                let v: Vec<f64> = (0..200)
                    .map(|_| {
                        if exponential {
                            Exp::new(1.0).unwrap().sample(&mut rng)
                        } else {
                            StandardNormal.sample(&mut rng)
                        }
                    })
                    .collect();
                let s = Spread::of(&v).unwrap();
                sds.push(s.sd);
                ses.push(s.sd_se);
            }
            let spread = Spread::of(&sds).unwrap().sd;
            let mean_se = ses.iter().sum::<f64>() / ses.len() as f64;
            assert!(
                (mean_se / spread - 1.0).abs() < 0.1,
                "exponential {exponential}: se(sd) {mean_se} vs spread {spread}"
            );
        }
    }

    #[test]
    fn digits_follow_the_standard_error() {
        assert_eq!(digits(0.7712, Some(0.0055)), "0.771");
        assert_eq!(digits(0.7712, Some(0.03)), "0.77");
        assert_eq!(digits(1234.5, Some(20.0)), "1230");
        assert_eq!(digits(0.7712, None), "0.771");
        // a standard error at rounding level (identical samples) is none: 3 significant digits,
        // not the 15 decimals a 1e-22 se would ask for
        assert_eq!(digits(6.046498460797e-7 * 1e6, Some(1e-19)), "0.605");
        assert_eq!(usable_se(0.605, Some(1e-19)), None);
        assert_eq!(usable_se(0.0, Some(1e-19)), Some(1e-19));
    }

    /// Coverage of the order-statistic intervals of the 5th, 50th and 95th percentiles of U(0, 1)
    /// (true values p): 1000 studies of 400 samples. The count of intervals that hold the true
    /// value is Binomial(1000, 0.95) if the method is right: mean 950, sd 6.9; accepted 930..=970
    /// (about 3 sd).
    #[test]
    fn quantile_intervals_cover_the_true_quantile_95_percent_of_the_time() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for (p, truth) in [(0.05, 0.05), (0.5, 0.5), (0.95, 0.95)] {
            let mut hit = 0;
            for _ in 0..1000 {
                let mut v: Vec<f64> = (0..400).map(|_| rng.random::<f64>()).collect();
                v.sort_by(f64::total_cmp);
                let [lo, hi] = quantile_interval(&v, p).unwrap();
                hit += usize::from(lo <= truth && truth <= hi);
            }
            assert!((930..=970).contains(&hit), "p = {p}: {hit} of 1000 intervals cover");
        }
    }
}
