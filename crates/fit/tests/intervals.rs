//! Honest intervals of `stiction fit`: coverage of the weighted eq. 10 interval of mu_e,a and of
//! the noise interval of s under Gaussian noise on V_pull, the calibration interval of s against
//! its closed form, and nulls with reasons where the data determine nothing.

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde_json::Value;
use stiction_fit::{
    Eq10Point, FitOptions, FitReport, ModelContext, ModelKind, analyse, calibration_sources, eq10::fit_eq10,
    parse_measured_voltages, synth,
};
use stiction_scenario::Scenario;

mod common;

fn scenario(name: &str) -> (Scenario, Value, PathBuf) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios").join(name);
    let s = Scenario::load(&path, &[]).unwrap();
    let j = Scenario::load_json(&path, &[]).unwrap();
    (s, j, path.parent().unwrap().to_path_buf())
}

/// The paper's 13 clamp voltages, 23-29 V.
fn volts() -> Vec<f64> {
    (0..13).map(|k| 23.0 + 0.5 * k as f64).collect()
}

fn fit_rows(rows: &[stiction_fit::Row], sc: &(Scenario, Value, PathBuf), opts: &FitOptions) -> FitReport {
    let csv = synth::to_csv(rows, "synthetic").unwrap();
    let data = parse_measured_voltages(csv.as_bytes(), "synthetic.csv").unwrap();
    analyse(&data, &sc.0, &sc.1, &sc.2, opts).unwrap()
}

/// Acceptance band for a 95 % interval's coverage over 200 data sets: 183 to 197 covered
/// (91.5-98.5 %). Exact binomial at p = 0.95, n = 200: P(X <= 182) = 1.2 %, P(X >= 198) = 0.2 %,
/// so a correct interval fails this test with probability 1.4 % (the seeds are fixed, so the test
/// is deterministic); an interval that covers 91 % (182 of 200, ordinary least squares on these
/// data in one measurement) fails it.
const COVERED: std::ops::RangeInclusive<usize> = 183..=197;
const SETS: usize = 200;

/// Coverage of the eq. 10 interval of mu_e,a: 200 data sets on the line of the paper's device
/// (mu_e,a = 0.74, F_a0 = 2.3 uN with a_clamp 1.4e-8, a_pull 3.8e-9 N/V^2, F_spring 7 uN, the
/// paper's section 5), 3 repeats at 13 clamp voltages, Gaussian noise of SD 0.5 V on V_pull. The
/// noise of V_pull^2 grows with V_pull (2 V_pull sd), which the weighted fit takes into account.
#[test]
fn eq10_interval_of_mu_covers_the_truth_95_percent_of_the_time() {
    let sc = scenario("tas2000.json");
    let ctx = ModelContext::new(&sc.0, &sc.2).unwrap();
    let red = ctx.device;
    let sources = calibration_sources(&sc.1, &red).unwrap();
    let (mu, fa0) = (0.74, 2.3e-6);
    let k = red.a_pull_n_per_v2 / red.a_clamp_n_per_v2;
    let beta = mu / k;
    let alpha = beta * (fa0 - red.spring_force_n) / red.a_clamp_n_per_v2;
    let mut rng = ChaCha8Rng::seed_from_u64(2100);
    let mut covered = 0;
    let sets: usize = std::env::var("STICTION_COVERAGE_SETS").ok().and_then(|s| s.parse().ok()).unwrap_or(SETS);
    for _ in 0..sets {
        let mut pts = Vec::new();
        for v in volts() {
            let v_pull = (alpha + beta * v * v).sqrt();
            for _ in 0..3 {
                let z: f64 = StandardNormal.sample(&mut rng);
                pts.push(Eq10Point { v_clamp_v: v, v_pull_v: v_pull + 0.5 * z, v_pull_sd_v: None });
            }
        }
        let f = fit_eq10(&pts, &red, &sources, 0, 1).unwrap();
        let [lo, hi] = f.mu_apparent.ci95.unwrap();
        covered += (lo <= mu && mu <= hi) as usize;
    }
    eprintln!("mu_e,a: {covered} of {sets} intervals cover the truth");
    if sets != SETS {
        return;
    }
    assert!(COVERED.contains(&covered), "mu_e,a interval covers {covered} of {SETS}");
}

/// Coverage of the noise interval of s: 200 data sets from the discrete N = 3 model at
/// s = 1.4 GPa (the paper's value), 3 repeats at 13 clamp voltages, 0.5 V Gaussian noise on V_pull.
#[test]
fn noise_interval_of_s_covers_the_truth_95_percent_of_the_time() {
    let sc = scenario("tas2000-discrete.json");
    let ctx = ModelContext::new(&sc.0, &sc.2).unwrap();
    let s_true = 1.4e9;
    let opts = FitOptions { models: vec![ModelKind::Discrete(3)], calibration_draws: 10, ..FitOptions::default() };
    let mut rng = ChaCha8Rng::seed_from_u64(2101);
    let mut covered = 0;
    for _ in 0..SETS {
        let rows = synth::from_model(&ctx, ModelKind::Discrete(3), s_true, &volts(), 3, 0.5, &mut rng).unwrap();
        let r = fit_rows(&rows, &sc, &opts);
        let s = &r.models[0].shear_strength_pa;
        assert!(s.ci95_meaning.starts_with("noise only"), "{}", s.ci95_meaning);
        let [lo, hi] = s.ci95.unwrap();
        covered += (lo <= s_true && s_true <= hi) as usize;
    }
    eprintln!("s: {covered} of {SETS} noise intervals cover the truth");
    assert!(COVERED.contains(&covered), "s noise interval covers {covered} of {SETS}");
}

/// The calibration interval of s against its closed form. With the shear-area criterion the model
/// predicts V_pull^2 = s A_r(L) / a_pull, so with a_clamp and F_spring exact and no noise, s is
/// proportional to a_pull: its 95 % interval is s (1 -/+ 1.96 x 0.8 / 3.8) for the scenario's
/// normal a_pull of 3.8e-9 +/- 0.8e-9 N/V^2 = s x [0.587, 1.413], and a_pull carries all of its
/// variance. Tolerance 3 % of s on each end (4000 draws: the 2.5 % percentile's standard error is
/// about 0.8 % of s).
#[test]
fn calibration_interval_of_s_scales_with_a_pull() {
    let mut sc = scenario("tas2000-discrete.json");
    sc.1["actuators"]["clamp"]["conversion_factor"] = Value::String("1.4e-8 N/V^2".into());
    sc.1["meter"]["spring_force"] = Value::String("7 uN".into());
    let ctx = ModelContext::new(&sc.0, &sc.2).unwrap();
    let rows =
        synth::from_model(&ctx, ModelKind::Discrete(3), 1.4e9, &volts(), 1, 0.0, &mut ChaCha8Rng::seed_from_u64(1))
            .unwrap();
    // A whisker of noise so the noise interval exists (residual noise level > 0).
    let mut rows = rows;
    for (i, r) in rows.iter_mut().enumerate() {
        r.v_pull_v += if i % 2 == 0 { 1e-4 } else { -1e-4 };
    }
    let opts = FitOptions { models: vec![ModelKind::Discrete(3)], calibration_draws: 4000, ..FitOptions::default() };
    let r = fit_rows(&rows, &sc, &opts);
    let s = &r.models[0].shear_strength_pa;
    let [lo, hi] = s.ci95_with_calibration.unwrap();
    let half = 1.959_964 * 0.8 / 3.8;
    eprintln!("s {:.4e}, with calibration [{lo:.4e}, {hi:.4e}], shares {:?}", s.value, s.variance_shares);
    assert!((lo / s.value - (1.0 - half)).abs() < 0.03, "low end {}", lo / s.value);
    assert!((hi / s.value - (1.0 + half)).abs() < 0.03, "high end {}", hi / s.value);
    assert!(s.variance_shares["a_pull"] > 0.99, "{:?}", s.variance_shares);
    assert!(s.ci95_with_calibration_note.contains("noise and calibration"), "{}", s.ci95_with_calibration_note);
}

/// A file whose pull voltages are all equal carries no load dependence: mu_e,a and F_a0 are null
/// with the reason (not 0 and inf), and no model is fitted or ranked.
#[test]
fn equal_pull_voltages_give_nulls_with_reasons_and_no_ranking() {
    let sc = scenario("tas2000-discrete.json");
    let mut text = String::from("v_clamp_v,v_pull_v\n");
    for v in volts() {
        text.push_str(&format!("{v},30\n"));
    }
    let data = parse_measured_voltages(text.as_bytes(), "flat.csv").unwrap();
    let opts = FitOptions { models: vec![ModelKind::Discrete(1), ModelKind::Gw], ..FitOptions::default() };
    let r = analyse(&data, &sc.0, &sc.1, &sc.2, &opts).unwrap();
    assert!(r.mu_apparent.value.is_none() && r.apparent_adhesion_force_n.value.is_none());
    assert!(r.mu_apparent.value_note.as_deref().unwrap().contains("same pull voltage"));
    assert!(r.apparent_adhesion_force_n.value_note.as_deref().unwrap().contains("same pull voltage"));
    assert!(r.models.is_empty(), "{:?}", r.models.iter().map(|m| &m.name).collect::<Vec<_>>());
    assert_eq!(r.models_failed.len(), 2);
    assert!(r.models_failed.iter().all(|f| f.reason.contains("not ranked")));
    assert!(r.model_selection.is_empty());
    assert_eq!(common::non_finite_in_debug(&format!("{r:?}")), None);
}

/// `--surfaces 0` is a setting error, not a fit with a failed row.
#[test]
fn zero_surfaces_is_an_error() {
    let sc = scenario("tas2000-discrete.json");
    let rows = synth::from_meter(&sc.0, &sc.2, &volts(), 1, 0.3, 1).unwrap();
    let data = parse_measured_voltages(synth::to_csv(&rows, "x").unwrap().as_bytes(), "x.csv").unwrap();
    for surfaces in [0, stiction_fit::models::MAX_SURFACES + 1] {
        let opts = FitOptions { models: vec![ModelKind::Discrete(3)], surfaces, ..FitOptions::default() };
        let e = analyse(&data, &sc.0, &sc.1, &sc.2, &opts).unwrap_err().to_string();
        assert!(e.contains("--surfaces") && e.contains("expected 1 to"), "{e}");
    }
}

/// The weights: the noise of V_pull^2 is 2 V_pull sd, so on a sweep whose pull voltage runs from
/// 5 to 30 V (the paper's device with the intercept lowered to -1419 V^2) the weighted slope
/// scatters less than the unweighted one (Gauss-Markov: the inverse-variance weights give the
/// smallest variance of all linear unbiased estimates), and the reported standard error matches
/// the scatter. 1000 data sets, 0.5 V noise, 3 repeats at 13 clamp voltages. Tolerances: the
/// weighted SD at most 0.85 of the unweighted one (measured 0.76; the ratio's sampling error with
/// 1000 sets is about 3 %), and the mean standard error within 6 % of the scatter (the SD of an SD
/// over 1000 sets is 2.2 %).
#[test]
fn weights_follow_the_noise_of_v_pull_squared() {
    let sc = scenario("tas2000.json");
    let ctx = ModelContext::new(&sc.0, &sc.2).unwrap();
    let red = ctx.device;
    let sources = calibration_sources(&sc.1, &red).unwrap();
    let k = red.a_pull_n_per_v2 / red.a_clamp_n_per_v2;
    let beta = 0.74 / k;
    let alpha = -1419.0;
    let mut rng = ChaCha8Rng::seed_from_u64(2103);
    let (mut weighted, mut plain, mut se) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..1000 {
        let mut pts = Vec::new();
        for v in volts() {
            let v_pull = (alpha + beta * v * v).sqrt();
            for _ in 0..3 {
                let z: f64 = StandardNormal.sample(&mut rng);
                pts.push(Eq10Point { v_clamp_v: v, v_pull_v: v_pull + 0.5 * z, v_pull_sd_v: None });
            }
        }
        let f = fit_eq10(&pts, &red, &sources, 0, 1).unwrap();
        weighted.push(f.mu_apparent.value.unwrap());
        se.push(f.mu_apparent.stderr.unwrap());
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.v_clamp_v.powi(2), p.v_pull_v.powi(2))).collect();
        plain.push(k * stiction_fit::stats::fit_line(&xy).unwrap().slope);
    }
    let sd = |v: &[f64]| stiction_fit::stats::mean_sd(v).unwrap().1;
    let mean_se = se.iter().sum::<f64>() / se.len() as f64;
    let (sw, sp) = (sd(&weighted), sd(&plain));
    eprintln!("SD of mu: weighted {sw:.5}, unweighted {sp:.5} (ratio {:.3}); mean se {mean_se:.5}", sw / sp);
    assert!(sw < 0.85 * sp, "weighted {sw} vs unweighted {sp}");
    assert!((mean_se / sw - 1.0).abs() < 0.06, "mean se {mean_se} vs scatter {sw}");
}
