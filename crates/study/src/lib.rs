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
//!
//! # Nothing lost, streamed
//! A study appends each finished sample, in index order, to `samples.log` ([`log`]) and flushes
//! it; every summary (study.json, samples.csv, figures, sensitivity) is computed from that log
//! alone ([`summary`]), so an uninterrupted run, a resumed one and a merge of shards give the
//! same bytes. Memory: the samples in flight plus a few numbers per sample for the percentiles
//! and the sensitivity table.

use std::path::{Path, PathBuf};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use serde_json::Value;
use stiction_meter::{Meter, Reduction, SlipPath};
use stiction_scenario::Scenario;

mod calibration;
pub mod design;
mod error;
pub mod log;
mod sample;
mod sample_result;
pub mod sensitivity;
pub mod summary;
pub use calibration::Calibration;
pub use error::StudyError;
pub use sample::{Draw, Sampler, draw, sample_tree, uncertain_parameters};
pub use sample_result::{FitIntervals, SampleResult};
pub use summary::{Spread, StudySummary};

/// Largest number of samples in one study. The summary keeps about 100 bytes per sample in
/// memory (percentiles, sensitivity) and samples.csv about 150 bytes per sample on disk and, while
/// it is written atomically, in memory: 1e7 samples need ~2.5 GB. Raise it with the environment
/// variable `STICTION_MAX_SAMPLES`.
pub const MAX_SAMPLES: usize = 10_000_000;

/// Largest thread count: more threads than cores only add overhead; this bounds the start-up
/// (each thread has its stack) far above any machine's core count.
pub const MAX_THREADS: usize = 1024;

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
    /// How the shuttle is followed after each slip (light by default; rigid body on request).
    pub slip_path: SlipPath,
}

/// The sample limit in force: [`MAX_SAMPLES`] or `STICTION_MAX_SAMPLES`.
pub fn max_samples() -> usize {
    std::env::var("STICTION_MAX_SAMPLES").ok().and_then(|s| s.trim().parse().ok()).unwrap_or(MAX_SAMPLES)
}

impl StudyConfig {
    /// Checks the counts before anything is read or allocated.
    pub fn validate(&self) -> Result<(), StudyError> {
        if self.samples == 0 {
            return Err(StudyError::Setting("--samples 0: a study needs at least 1 sample".into()));
        }
        let limit = max_samples();
        if self.samples > limit {
            return Err(StudyError::Setting(format!(
                "--samples {}: more than the limit of {limit} samples per study (the summary holds about \
                 250 bytes per sample in memory, {:.1} GB here); run several studies with different --seed, \
                 or raise the limit with the environment variable STICTION_MAX_SAMPLES",
                self.samples,
                self.samples as f64 * 250e-9
            )));
        }
        if self.shard_count == 0 || self.shard_index >= self.shard_count {
            return Err(StudyError::Setting(format!(
                "--shard {}/{}: expected K/M with 0 <= K < M",
                self.shard_index, self.shard_count
            )));
        }
        if self.shard_index >= self.samples {
            return Err(StudyError::Setting(format!(
                "--shard {}/{} with --samples {}: this shard has no samples (shard K runs the samples i with \
                 i % M == K); use at most {} shards",
                self.shard_index, self.shard_count, self.samples, self.samples
            )));
        }
        Ok(())
    }

    /// Number of samples of this shard: `#{i < n : i % M == K}`.
    pub fn shard_len(&self) -> usize {
        if self.shard_index >= self.samples { 0 } else { (self.samples - self.shard_index).div_ceil(self.shard_count) }
    }

    /// The `j`-th sample index of this shard.
    pub fn shard_index_at(&self, j: usize) -> usize {
        self.shard_index + j * self.shard_count
    }
}

/// The lab's eq. 10 intervals of one experiment: given the slips `(V_clamp, V_pull)` (V) of the
/// clamp voltages in contact, the reduction the lab used, and a seed for its calibration Monte
/// Carlo, the widths of its intervals. The study crate sits below the fit crate, so the command
/// line gives the fit crate's eq. 10 here ([`Study::with_intervals`]).
pub type IntervalFn = dyn Fn(Slips<'_>, &Reduction, u64) -> FitIntervals + Send + Sync;

/// The readings of one experiment that the lab's intervals are computed from.
#[derive(Debug, Clone, Copy)]
pub enum Slips<'a> {
    /// `(V_clamp, V_pull)` at each slip, V: the paper's meter, and a structure's normal and
    /// tangential comb voltages (ramp and lowered-normal protocols).
    Voltages(&'a [(f64, f64)]),
    /// The release protocol's `(normal voltage V, largest displacement that sticks m)` at each
    /// point of the eq. 10 fit: the lab's forces are `a_n V^2 - F_0` and `k x` with the nominal
    /// parts.
    Release(&'a [(f64, f64)]),
}

/// The interface's own friction coefficient of one device (the friction the meter sets out to
/// measure): at each clamp voltage k in contact with a true clamp load `L_k > 0`,
/// `mu_k = s A_r,k / (L_k + F_adh,k) = s / p_mean,k` (shear strength s, real contact area A_r,k,
/// adhesive load F_adh,k: the mean contact pressure is the total normal load over the real area),
/// and the coefficient is the mean of the `mu_k`. None when no clamp voltage qualifies.
/// Returns `(mean, min, max, count)`.
pub fn interface_mu(points: &[stiction_meter::MeterPoint], shear_strength_pa: f64) -> Option<(f64, f64, f64, usize)> {
    let mu: Vec<f64> = points
        .iter()
        .filter(|p| p.in_contact && p.error.is_none() && p.true_load_n > 0.0 && p.real_area_m2 > 0.0)
        .map(|p| shear_strength_pa * p.real_area_m2 / (p.true_load_n + p.adhesive_load_n))
        .filter(|m| m.is_finite())
        .collect();
    (!mu.is_empty()).then(|| {
        (
            mu.iter().sum::<f64>() / mu.len() as f64,
            mu.iter().copied().fold(f64::INFINITY, f64::min),
            mu.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            mu.len(),
        )
    })
}

/// The calibration Monte Carlo's seed of sample `i` (SplitMix64 of the study seed and the index):
/// the same in every design of a design study.
fn interval_seed(seed: u64, i: usize) -> u64 {
    let mut z = seed ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A study ready to run: the scenario read, the nominal device checked, the columns known.
pub struct Study {
    base: Value,
    path: PathBuf,
    base_dir: PathBuf,
    nominal: Scenario,
    reduction: Reduction,
    /// The settings.
    pub config: StudyConfig,
    /// The uncertain parameters `(JSON path, SI unit)`, in draw order.
    pub parameters: Vec<(String, String)>,
    /// The files the scenario points to, with the fingerprints of their contents.
    input_files: Vec<log::InputFile>,
    /// The lab's eq. 10 intervals and the number of calibration draws behind them.
    intervals: Option<(std::sync::Arc<IntervalFn>, usize)>,
}

/// The files a scenario points to (`surface.csv_path`, `surface.height_map.file`,
/// `surface.counter_height_map.file`, `measured.voltages_csv`), each read through the input layer
/// and fingerprinted (FNV-1a of its bytes), so that resume and merge refuse a study whose maps or
/// data changed.
fn input_files(scenario: &Scenario, base_dir: &Path) -> Result<Vec<log::InputFile>, StudyError> {
    let mut fields: Vec<(&str, PathBuf)> = Vec::new();
    if let Some(s) = &scenario.surface {
        if let Some(p) = &s.csv_path {
            fields.push(("surface.csv_path", p.clone()));
        }
        if let Some(f) = s.height_map.as_ref().and_then(|m| m.file.clone()) {
            fields.push(("surface.height_map.file", f));
        }
        if let Some(f) = s.counter_height_map.as_ref().and_then(|m| m.file.clone()) {
            fields.push(("surface.counter_height_map.file", f));
        }
    }
    if let Some(m) = &scenario.measured {
        fields.push(("measured.voltages_csv", m.voltages_csv.clone()));
    }
    fields
        .into_iter()
        .map(|(field, p)| {
            let full = base_dir.join(&p);
            let bytes = stiction_units::io::read_input(&full, stiction_units::io::DEFAULT_INPUT_LIMIT_BYTES)
                .map_err(|e| StudyError::Setting(format!("`{field}`: {e}")))?;
            Ok(log::InputFile {
                field: field.to_string(),
                path: p.display().to_string(),
                content_hash: format!("{:016x}", log::fnv1a(&bytes)),
            })
        })
        .collect()
}

impl Study {
    /// Reads the scenario at `path` with `sets` applied and checks the settings and the nominal
    /// device (its conversion is what the lab reduces every sample with).
    pub fn prepare(path: &Path, sets: &[String], config: &StudyConfig) -> Result<Study, StudyError> {
        config.validate()?;
        let base = Scenario::load_json(path, sets)?;
        let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Study::prepare_value(base, path, &base_dir, config)
    }

    /// [`Study::prepare`] of a scenario given as its JSON value (overrides applied): `name` names
    /// it in errors and in the log header, relative paths in it are read from `base_dir`. For a
    /// scenario built in memory (the Python module's dicts).
    pub fn prepare_value(base: Value, name: &Path, base_dir: &Path, config: &StudyConfig) -> Result<Study, StudyError> {
        config.validate()?;
        let path = name;
        let mut base = base;
        // The `design` section describes a design study, not a device: each design's study is
        // the scenario without it (the same bytes as the file without the section), once the
        // section itself has been checked.
        let design = base.as_object_mut().and_then(|m| m.remove("design"));
        let nominal = Scenario::from_value(base.clone(), path)?;
        if let Some(d) = design {
            let mut with = base.clone();
            if let Some(m) = with.as_object_mut() {
                m.insert("design".into(), d);
            }
            Scenario::from_value(with, path)?;
        }
        // The device checks `stiction run` makes (one source of truth): a given spring force that
        // contradicts the clamp spring is refused here too.
        if let Some(conflict) = nominal.spring_force_conflict() {
            return Err(StudyError::Setting(format!("{}: {conflict}", path.display())));
        }
        let base_dir = base_dir.to_path_buf();
        let reduction = Meter::from_scenario(&nominal, &base_dir)
            .and_then(|m| m.device_reduction())
            .map_err(|e| StudyError::Setting(format!("the nominal scenario cannot run: {e}")))?;
        let parameters = uncertain_parameters(&base)?;
        // A trial draw (its own stream, never a sample's) so that a parameter that can never be
        // drawn (bounds that overflow, a lognormal of a negative value) stops the study at once,
        // naming the field, instead of failing every sample.
        let mut trial = ChaCha8Rng::seed_from_u64(config.seed);
        trial.set_stream(u64::MAX);
        sample_tree(&mut base.clone(), &mut trial)?;
        let input_files = input_files(&nominal, &base_dir)?;
        Ok(Study {
            base,
            path: path.to_path_buf(),
            base_dir,
            nominal,
            reduction,
            config: config.clone(),
            parameters,
            input_files,
            intervals: None,
        })
    }

    /// Gives every sample the widths of the lab's eq. 10 intervals from `f`, which draws
    /// `calibration_draws` calibration values per sample (recorded in the log header).
    pub fn with_intervals(mut self, f: std::sync::Arc<IntervalFn>, calibration_draws: usize) -> Study {
        self.intervals = Some((f, calibration_draws));
        self
    }

    /// The scenario tree (after `--set`), with its uncertain parameters as written.
    pub fn scenario_json(&self) -> &Value {
        &self.base
    }

    /// The nominal scenario (its uncertain quantities at their values).
    pub fn nominal(&self) -> &Scenario {
        &self.nominal
    }

    /// The nominal reduction the lab uses.
    pub fn reduction(&self) -> Reduction {
        self.reduction
    }

    /// The log header that identifies this study (and shard).
    pub fn header(&self) -> log::Header {
        log::Header {
            format: log::FORMAT,
            scenario: self.path.display().to_string(),
            scenario_hash: format!(
                "{:016x}",
                log::fnv1a(serde_json::to_string(&self.base).unwrap_or_default().as_bytes())
            ),
            samples: self.config.samples,
            seed: self.config.seed,
            vary_surface: self.config.vary_surface,
            calibration: self.config.calibration,
            slip_path: self.config.slip_path,
            shard_index: self.config.shard_index,
            shard_count: self.config.shard_count,
            reduction: [
                format!("{:e}", self.reduction.a_clamp_n_per_v2),
                format!("{:e}", self.reduction.a_pull_n_per_v2),
                format!("{:e}", self.reduction.spring_force_n),
            ],
            parameters: self.parameters.clone(),
            reference: self.nominal.reference.clone(),
            program_version: env!("CARGO_PKG_VERSION").to_string(),
            input_files: self.input_files.clone(),
            calibration_draws: self.intervals.as_ref().map_or(0, |i| i.1),
        }
    }

    /// Runs sample `i`: draw, parse, assemble, run. Never fails: a failure is the sample's reason.
    pub fn run_sample(&self, i: usize) -> SampleResult {
        let mut out = SampleResult {
            index: i,
            draws: vec![f64::NAN; self.parameters.len()],
            mu_apparent: None,
            apparent_adhesion_force_n: None,
            mean_contacts: None,
            interface_mu: None,
            intervals: FitIntervals::default(),
            reason: None,
            detail: None,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(self.config.seed);
        rng.set_stream(i as u64);
        let mut value = self.base.clone();
        match sample_tree(&mut value, &mut rng) {
            Ok(d) => out.draws = d.into_iter().map(|d| d.value).collect(),
            Err(e) => {
                out.reason = Some("draw-failed".into());
                out.detail = Some(e.to_string());
                return out;
            }
        }
        if self.config.vary_surface
            && let Some(surface) = value.get_mut("surface").and_then(Value::as_object_mut)
        {
            surface.insert("seed".into(), Value::from(self.config.seed.wrapping_add(i as u64)));
        }
        let scenario = match Scenario::from_value(value, &self.path) {
            Ok(s) => s,
            Err(e) => {
                out.reason = Some("invalid-scenario".into());
                out.detail = Some(e.to_string());
                return out;
            }
        };
        let result = (|| {
            let reduction = match self.config.calibration {
                Calibration::Nominal => self.reduction,
                Calibration::PullIn => calibrated_reduction(&self.nominal, &scenario, self.reduction)?,
            };
            let mut m = Meter::from_scenario(&scenario, &self.base_dir).map_err(|e| e.to_string())?;
            m.set_reduction(reduction);
            // A structure's readings are reduced with the nominal parts, as the lab reduces them.
            if let Some(spec) = &self.nominal.structure {
                let parts = stiction_meter::structure::StructureDevice::from_spec(spec).map_err(|e| e.to_string())?;
                m.set_lab_structure(parts);
            }
            m.set_slip_path(self.config.slip_path);
            m.run(&mut |_, _| {}).map_err(|e| e.to_string()).map(|r| (r, reduction))
        })();
        let shear_strength = scenario.material.as_ref().map(|m| m.shear_strength);
        match result {
            Ok((r, reduction)) => {
                out.interface_mu = shear_strength.and_then(|s| interface_mu(&r.points, s)).map(|m| m.0);
                if r.mu_apparent.is_some()
                    && let Some((f, _)) = &self.intervals
                {
                    let release = scenario.structure.as_ref().is_some_and(|st| {
                        matches!(st.protocol, stiction_scenario::structure::ProtocolSpec::Release { .. })
                    });
                    let seed = interval_seed(self.config.seed, i);
                    let w = if release {
                        // The points of the eq. 10 fit (stiction_meter::structure::reduce).
                        let readings: Vec<(f64, f64)> = r
                            .points
                            .iter()
                            .filter(|p| p.load_n > 0.0 && p.reason.is_none())
                            .filter_map(|p| Some((p.v_clamp, p.displacement_m?)))
                            .collect();
                        f(Slips::Release(&readings), &reduction, seed)
                    } else {
                        let slips: Vec<(f64, f64)> = r
                            .points
                            .iter()
                            .filter(|p| p.in_contact)
                            .filter_map(|p| Some((p.v_clamp, p.v_pull?)))
                            .collect();
                        f(Slips::Voltages(&slips), &reduction, seed)
                    };
                    let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
                    out.intervals = FitIntervals {
                        mu_ci95_width: finite(w.mu_ci95_width),
                        mu_ci95_width_with_calibration: finite(w.mu_ci95_width_with_calibration),
                        fa0_ci95_width_n: finite(w.fa0_ci95_width_n),
                        fa0_ci95_width_with_calibration_n: finite(w.fa0_ci95_width_with_calibration_n),
                    };
                }
                // Finite or null: a non-finite result is no result, with a reason.
                let finite = |x: Option<f64>| x.filter(|v| v.is_finite());
                out.mu_apparent = finite(r.mu_apparent);
                out.apparent_adhesion_force_n = finite(r.apparent_adhesion_force_n);
                let c: Vec<f64> = r.points.iter().filter(|p| p.in_contact).map(|p| p.contacts).collect();
                out.mean_contacts = finite((!c.is_empty()).then(|| c.iter().sum::<f64>() / c.len() as f64));
                if r.mu_apparent.is_some() && (out.mu_apparent.is_none() || out.apparent_adhesion_force_n.is_none()) {
                    out.mu_apparent = None;
                    out.apparent_adhesion_force_n = None;
                    out.reason = Some("degenerate-fit".into());
                    out.detail = Some(format!(
                        "the eq. 10 line gave mu_e,a = {:?}, F_a0 = {:?} N: not finite numbers",
                        r.mu_apparent, r.apparent_adhesion_force_n
                    ));
                } else if r.mu_apparent.is_none() {
                    let in_contact = r.points.iter().filter(|p| p.in_contact).count();
                    let slips = r.points.iter().filter(|p| p.load_n > 0.0 && p.friction_n.is_some()).count();
                    let (reason, detail) = if in_contact == 0 {
                        (
                            "no-contact",
                            format!("none of the {} clamp voltages brought the shoe into contact", r.points.len()),
                        )
                    } else if slips < 2 {
                        (
                            "too-few-slips",
                            format!(
                                "{slips} slip point(s) with L > 0 ({in_contact} of {} clamp voltages in contact): the eq. 10 \
                                 line needs at least 2",
                                r.points.len()
                            ),
                        )
                    } else {
                        match &r.fit {
                            Some(l) if l.slope <= 0.0 => {
                                ("non-positive-slope", format!("the eq. 10 line has slope {:e} <= 0", l.slope))
                            }
                            _ => ("degenerate-fit", format!("{slips} slip points but no straight line through them")),
                        }
                    };
                    out.reason = Some(reason.into());
                    out.detail = Some(detail);
                }
            }
            Err(e) => {
                out.reason = Some("meter-failed".into());
                out.detail = Some(e);
            }
        }
        if out.mu_apparent.is_none() {
            out.intervals = FitIntervals::default();
        }
        out
    }
}

impl Study {
    /// Runs the shard's samples from the `done`-th on, appending each to `log` in index order as
    /// soon as it and all before it are finished. Workers take indices in order from a shared
    /// counter, so only the samples in flight (about one per thread) can be lost by a kill.
    /// `progress(n)` gets the number of samples of the shard in the log.
    pub fn run_into(
        &self,
        log: &mut log::LogWriter,
        done: usize,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<(), StudyError> {
        self.run_into_until(log, done, progress, &std::sync::atomic::AtomicBool::new(false)).map(|_| ())
    }

    /// [`Study::run_into`] that stops early when `interrupt` is set (Ctrl-C): no new sample is
    /// started, the samples in flight are finished and logged, and the number of samples of the
    /// shard in the log is returned (the shard's length when it ran to the end).
    pub fn run_into_until(
        &self,
        log: &mut log::LogWriter,
        done: usize,
        progress: &(dyn Fn(usize) + Sync),
        interrupt: &std::sync::atomic::AtomicBool,
    ) -> Result<usize, StudyError> {
        use std::collections::BTreeMap;
        use std::sync::Mutex;
        use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
        let total = self.config.shard_len();
        let next = AtomicUsize::new(done);
        let stop = AtomicBool::new(false);
        struct Pending<'a> {
            next: usize,
            lines: BTreeMap<usize, Vec<u8>>,
            log: &'a mut log::LogWriter,
            error: Option<StudyError>,
        }
        let pending = Mutex::new(Pending { next: done, lines: BTreeMap::new(), log, error: None });
        let worker = || {
            loop {
                if stop.load(Ordering::Relaxed) || interrupt.load(Ordering::Relaxed) {
                    return;
                }
                let j = next.fetch_add(1, Ordering::Relaxed);
                if j >= total {
                    return;
                }
                let line = log::row(&self.run_sample(self.config.shard_index_at(j)));
                let mut p = pending.lock().unwrap_or_else(|e| e.into_inner());
                match line {
                    Ok(l) => {
                        p.lines.insert(j, l);
                    }
                    Err(e) => {
                        p.error.get_or_insert(e);
                        stop.store(true, Ordering::Relaxed);
                        return;
                    }
                }
                let mut wrote = false;
                loop {
                    let k = p.next;
                    let Some(l) = p.lines.remove(&k) else { break };
                    if let Err(e) = p.log.append(&l) {
                        p.error.get_or_insert(e);
                        stop.store(true, Ordering::Relaxed);
                        return;
                    }
                    p.next += 1;
                    wrote = true;
                }
                if wrote {
                    progress(p.next);
                }
            }
        };
        rayon::scope(|s| {
            for _ in 0..rayon::current_num_threads() {
                s.spawn(|_| worker());
            }
        });
        let p = pending.into_inner().unwrap_or_else(|e| e.into_inner());
        match p.error {
            Some(e) => Err(e),
            None => Ok(p.next),
        }
    }
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

    fn config(samples: usize, k: usize, m: usize) -> StudyConfig {
        StudyConfig {
            samples,
            seed: 1,
            vary_surface: true,
            shard_index: k,
            shard_count: m,
            calibration: Calibration::Nominal,
            slip_path: SlipPath::Light,
        }
    }

    #[test]
    fn shard_sizes_add_up_and_empty_shards_are_refused() {
        for n in [1, 2, 3, 10, 11] {
            for m in 1..=5 {
                let total: usize = (0..m).map(|k| config(n, k, m).shard_len()).sum();
                assert_eq!(total, n, "n = {n}, m = {m}");
                for k in 0..m {
                    let c = config(n, k, m);
                    let brute = (0..n).filter(|i| i % m == k).count();
                    assert_eq!(c.shard_len(), brute);
                    assert_eq!(c.validate().is_ok(), brute > 0, "n = {n}, {k}/{m}");
                }
            }
        }
        let e = config(3, 5, 10).validate().unwrap_err().to_string();
        assert!(e.contains("--shard 5/10") && e.contains("--samples 3") && e.contains("no samples"), "{e}");
    }

    #[test]
    fn a_huge_sample_count_is_refused_before_anything_is_read() {
        let e = config(1_000_000_000_000, 0, 1).validate().unwrap_err().to_string();
        assert!(e.contains("--samples 1000000000000") && e.contains("STICTION_MAX_SAMPLES"), "{e}");
        assert!(config(0, 0, 1).validate().is_err());
    }
}
