//! stiction-study: Monte Carlo studies of the friction meter over the uncertain parameters of a
//! scenario.
//!
//! Every quantity of a scenario that is written with an uncertainty
//! (`{"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"}`) is drawn anew for each
//! sample, and (by default) each sample gets its own rough surface (a new generator seed). The
//! meter runs on each realisation and the study collects the distribution of the quantities the
//! lab reports: the apparent friction coefficient mu_e,a and zero-load adhesion force F_a0 of
//! eq. 10. This is how stiction answers "why do measured static friction coefficients scatter so
//! widely": which part of the scatter comes from the roughness realisation of one small shoe
//! face, and which from the uncertain calibration of the actuators.
//!
//! # Determinism
//! Sample `i` draws from `ChaCha8Rng::seed_from_u64(seed)` on stream `i` (`set_stream(i)`), so
//! its values depend only on (`seed`, `i`), never on the thread that runs it, the number of
//! threads or the shard. Results are kept in sample order. Same seed, same bytes.

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::Serialize;
use serde_json::Value;
use stiction_meter::{Meter, Reduction};
use stiction_scenario::Scenario;

mod sample;
pub use sample::{Draw, draw, sample_tree};

/// Why a study failed.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// An uncertain parameter could not be drawn.
    #[error("at `{path}`: {message}")]
    Sample {
        /// JSON path of the parameter.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// The scenario file could not be read or parsed.
    #[error(transparent)]
    Scenario(#[from] stiction_scenario::ScenarioError),
    /// A study setting is wrong.
    #[error("{0}")]
    Setting(String),
}

/// How the virtual lab turns each sample's voltages into forces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Calibration {
    /// The nominal conversion factors and spring force of the file, as the paper did (default).
    #[default]
    Nominal,
    /// Each device's clamp and pull arrays are calibrated from their own pull-in voltages
    /// ([`stiction_actuator::calibrate_from_pull_in`]: the gap is inferred, the rest of the array
    /// model is the nominal one); the spring force stays nominal.
    PullIn,
}

/// Settings of a Monte Carlo study.
#[derive(Debug, Clone, Serialize)]
pub struct StudyConfig {
    /// Number of samples in the whole study.
    pub samples: usize,
    /// Base seed of the draws.
    pub seed: u64,
    /// Give each sample its own surface (surface.seed = seed + i); false keeps the file's surface.
    pub vary_surface: bool,
    /// Run only the samples with `i % shard_count == shard_index`.
    pub shard_index: usize,
    /// Number of shards.
    pub shard_count: usize,
    /// How each sample's voltages are reduced to forces.
    pub calibration: Calibration,
}

/// The outcome of one sample.
#[derive(Debug, Clone, Serialize)]
pub struct SampleResult {
    /// Sample index.
    pub index: usize,
    /// The drawn parameters.
    pub draws: Vec<Draw>,
    /// mu_e,a of eq. 10 (None: fewer than two slip points with L > 0).
    pub mu_apparent: Option<f64>,
    /// F_a0 of eq. 10, N.
    pub apparent_adhesion_force_n: Option<f64>,
    /// Mean number of contacts over the clamp voltages in contact.
    pub mean_contacts: Option<f64>,
    /// Why the sample failed, if it did (kept, never skipped silently).
    pub error: Option<String>,
}

/// Summary statistics of one reported quantity over the samples that gave it.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Spread {
    /// Number of samples with a value.
    pub count: usize,
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation.
    pub sd: f64,
    /// 5th percentile.
    pub p05: f64,
    /// Median.
    pub median: f64,
    /// 95th percentile.
    pub p95: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Spread {
    /// Statistics of `values` (None when empty). Percentiles by linear interpolation.
    pub fn of(values: &[f64]) -> Option<Spread> {
        if values.is_empty() {
            return None;
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let mean = v.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 { (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt() } else { 0.0 };
        let pct = |p: f64| {
            let r = p * (n - 1) as f64;
            let (lo, hi) = (r.floor() as usize, r.ceil() as usize);
            v[lo] + (v[hi] - v[lo]) * (r - lo as f64)
        };
        Some(Spread { count: n, mean, sd, p05: pct(0.05), median: pct(0.5), p95: pct(0.95), min: v[0], max: v[n - 1] })
    }
}

/// A whole study.
#[derive(Debug, Clone, Serialize)]
pub struct StudyResult {
    /// The settings.
    pub config: StudyConfig,
    /// The scenario file.
    pub scenario: PathBuf,
    /// Per-sample results, in index order.
    pub samples: Vec<SampleResult>,
    /// Spread of mu_e,a.
    pub mu_apparent: Option<Spread>,
    /// Spread of F_a0, N.
    pub apparent_adhesion_force_n: Option<Spread>,
    /// Samples that failed (their errors are in `samples`).
    pub failed: usize,
    /// Samples that ran but had fewer than two slip points with L > 0, so no eq. 10 fit (the
    /// clamp voltages did not bring that device into contact often enough).
    pub without_fit: usize,
    /// The nominal conversion every sample's voltages were reduced with.
    pub reduction: Reduction,
}

/// Runs a study on the scenario at `path` with `sets` applied before drawing.
pub fn run_study(
    path: &Path,
    sets: &[String],
    config: &StudyConfig,
    progress: &(dyn Fn() + Sync),
) -> Result<StudyResult, StudyError> {
    if config.samples == 0 {
        return Err(StudyError::Setting("--samples must be at least 1".into()));
    }
    if config.shard_count == 0 || config.shard_index >= config.shard_count {
        return Err(StudyError::Setting(format!(
            "shard {}/{} is not valid: expected K/M with 0 <= K < M",
            config.shard_index, config.shard_count
        )));
    }
    let base = Scenario::load_json(path, sets)?;
    // The nominal scenario must be valid before any sample is drawn; its conversion factors and
    // spring force are what the lab reduces every measurement with.
    let nominal = Scenario::from_value(base.clone(), path)?;
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let reduction = Meter::from_scenario(&nominal, &base_dir)
        .and_then(|m| m.device_reduction())
        .map_err(|e| StudyError::Setting(format!("the nominal scenario cannot run: {e}")))?;
    let indices: Vec<usize> = (0..config.samples).filter(|i| i % config.shard_count == config.shard_index).collect();
    let samples: Vec<SampleResult> = indices
        .par_iter()
        .map(|&i| {
            let r = run_sample(&base, path, &base_dir, config, &nominal, reduction, i);
            progress();
            r
        })
        .collect();
    let mus: Vec<f64> = samples.iter().filter_map(|s| s.mu_apparent).collect();
    let fas: Vec<f64> = samples.iter().filter_map(|s| s.apparent_adhesion_force_n).collect();
    Ok(StudyResult {
        config: config.clone(),
        scenario: path.to_path_buf(),
        failed: samples.iter().filter(|s| s.error.is_some()).count(),
        without_fit: samples.iter().filter(|s| s.error.is_none() && s.mu_apparent.is_none()).count(),
        reduction,
        mu_apparent: Spread::of(&mus),
        apparent_adhesion_force_n: Spread::of(&fas),
        samples,
    })
}

/// Runs sample `i`: draw, parse, assemble, run.
fn run_sample(
    base: &Value,
    path: &Path,
    base_dir: &Path,
    config: &StudyConfig,
    nominal: &Scenario,
    reduction: Reduction,
    i: usize,
) -> SampleResult {
    let mut out = SampleResult {
        index: i,
        draws: Vec::new(),
        mu_apparent: None,
        apparent_adhesion_force_n: None,
        mean_contacts: None,
        error: None,
    };
    let mut rng = ChaCha8Rng::seed_from_u64(config.seed);
    rng.set_stream(i as u64);
    let mut value = base.clone();
    match sample_tree(&mut value, &mut rng) {
        Ok(d) => out.draws = d,
        Err(e) => {
            out.error = Some(e.to_string());
            return out;
        }
    }
    if config.vary_surface
        && let Some(surface) = value.get_mut("surface").and_then(Value::as_object_mut)
    {
        surface.insert("seed".into(), Value::from(config.seed.wrapping_add(i as u64)));
    }
    let result = Scenario::from_value(value, path).map_err(|e| e.to_string()).and_then(|s| {
        let reduction = match config.calibration {
            Calibration::Nominal => reduction,
            Calibration::PullIn => calibrated_reduction(nominal, &s, reduction)?,
        };
        let mut m = Meter::from_scenario(&s, base_dir).map_err(|e| e.to_string())?;
        m.set_reduction(reduction);
        m.run(&mut |_, _| {}).map_err(|e| e.to_string())
    });
    match result {
        Ok(r) => {
            out.mu_apparent = r.mu_apparent;
            out.apparent_adhesion_force_n = r.apparent_adhesion_force_n;
            let c: Vec<f64> = r.points.iter().filter(|p| p.in_contact).map(|p| p.contacts).collect();
            out.mean_contacts = (!c.is_empty()).then(|| c.iter().sum::<f64>() / c.len() as f64);
        }
        Err(e) => out.error = Some(e),
    }
    out
}

/// The lab's conversion for one device calibrated from its arrays' pull-in voltages: the device
/// (`sample`) pulls in at V_pi; the nominal array model, with the gap that reproduces V_pi, gives
/// the conversion factor. The spring force stays nominal.
fn calibrated_reduction(
    nominal: &Scenario,
    sample: &Scenario,
    nominal_reduction: Reduction,
) -> Result<Reduction, String> {
    let calibrate = |name: &str| -> Result<f64, String> {
        let device = sample.actuators[name].to_model().map_err(|e| format!("actuator `{name}`: {e}"))?;
        let v_pi = device.pull_in().map_err(|e| format!("actuator `{name}`: {e}"))?.voltage_v;
        stiction_actuator::calibrate_from_pull_in(&nominal.actuators[name], v_pi)
            .map(|c| c.conversion_factor_n_per_v2)
            .map_err(|e| format!("calibrating `{name}` from its pull-in at {v_pi:.3} V: {e}"))
    };
    Ok(Reduction { a_clamp_n_per_v2: calibrate("clamp")?, a_pull_n_per_v2: calibrate("pull")?, ..nominal_reduction })
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
    }
}
