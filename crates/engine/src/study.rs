//! `study`: Monte Carlo over a scenario's uncertain parameters and surface realisations, the
//! spread of mu_e,a and F_a0 (eq. 10). The one study loop (a sample log in a folder, resumable)
//! shared by the command line's study and design studies and by Python.

use std::path::{Path, PathBuf};

use stiction_fit::with_lab_intervals;
use stiction_study::log::LogWriter;

// The study's types that a front end names or prints: the lab's options, the configuration, the
// summary (the result: what `study --json` prints) and its parts, the sample log's name, and the
// digits rule of the summary's printed values.
pub use stiction_meter::SlipPath;
pub use stiction_study::log::LOG_NAME;
pub use stiction_study::sensitivity::InputShare;
pub use stiction_study::summary::{FigureData, REASONS, digits, usable_se};
pub use stiction_study::{Calibration, MAX_THREADS, Spread, Study, StudyConfig, StudySummary};

use crate::Error;
use crate::check::Names;

/// A study of a scenario: samples, seed, shard and the lab's options.
#[derive(Clone, Debug)]
pub struct StudyRequest {
    /// Number of samples of the whole study (at most `stiction_study::max_samples()`).
    pub samples: usize,
    /// Base seed.
    pub seed: u64,
    /// Keep the scenario's surface for every sample (vary only the uncertain parameters).
    pub fixed_surface: bool,
    /// Run only shard `shard.0` of `shard.1` (samples with index % M == K); (0, 1) for all.
    pub shard: (usize, usize),
    /// How the virtual lab converts voltages to forces.
    pub calibration: Calibration,
    /// How the pull shuttle is followed after each slip.
    pub slip_path: SlipPath,
    /// Worker threads, 1 to [`MAX_THREADS`] (None: one per core).
    pub threads: Option<usize>,
}

impl Default for StudyRequest {
    fn default() -> Self {
        StudyRequest {
            samples: 100,
            seed: 1,
            fixed_surface: false,
            shard: (0, 1),
            calibration: Calibration::Nominal,
            slip_path: SlipPath::Light,
            threads: None,
        }
    }
}

impl StudyRequest {
    /// The study's configuration, checked (counts first: nothing is read or started before they
    /// are known to be sane).
    pub fn config(&self) -> Result<StudyConfig, Error> {
        let config = StudyConfig {
            calibration: self.calibration,
            slip_path: self.slip_path,
            samples: self.samples,
            seed: self.seed,
            vary_surface: !self.fixed_surface,
            shard_index: self.shard.0,
            shard_count: self.shard.1,
        };
        config.validate()?;
        Ok(config)
    }
}

/// Parses a shard "K/M" (0 <= K < M), named `--shard` in errors.
pub fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let (k, m) = s.split_once('/').ok_or_else(|| format!("--shard {s:?}: expected K/M, like 0/4"))?;
    let k: usize = k.trim().parse().map_err(|_| format!("--shard {s:?}: K is not a whole number"))?;
    let m: usize = m.trim().parse().map_err(|_| format!("--shard {s:?}: M is not a whole number"))?;
    if m == 0 || k >= m {
        return Err(format!("--shard {s:?}: expected 0 <= K < M"));
    }
    Ok((k, m))
}

/// The worker pool of `threads` (default: all cores), 1 to [`MAX_THREADS`]; `names` names the
/// field `threads` in a refusal.
pub fn thread_pool(threads: Option<usize>, names: &Names) -> Result<rayon::ThreadPool, Error> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if t == 0 || t > MAX_THREADS {
            return Err(format!(
                "{} {t}: expected 1 to {MAX_THREADS} (this machine has {} cores; more threads than cores do \
                 not make a study faster)",
                names("threads"),
                std::thread::available_parallelism().map_or(1, |n| n.get())
            )
            .into());
        }
        pool = pool.num_threads(t);
    }
    Ok(pool.build()?)
}

/// [`Study::prepare`] of a scenario file with its overrides, with the lab's eq. 10 intervals of
/// every experiment ([`stiction_fit::with_lab_intervals`]).
pub fn prepare_study(
    scenario: &Path,
    sets: &[String],
    config: &StudyConfig,
) -> Result<Study, stiction_study::StudyError> {
    with_lab_intervals(Study::prepare(scenario, sets, config)?)
}

/// [`Study::prepare_value`] of a scenario held as a source (a file or a tree built in memory),
/// with the lab's intervals.
pub fn prepare_source(source: &crate::ScenarioSource, config: &StudyConfig) -> Result<Study, Error> {
    let value = source.json(&[])?;
    Ok(Study::prepare_value(value, &source.origin, &source.base, config).and_then(with_lab_intervals)?)
}

/// How [`run_log`] ended.
pub enum LogOutcome {
    /// Every sample of the shard is in the log.
    Complete,
    /// Stopped by `interrupt`: this many samples of the shard are in the log.
    Interrupted {
        /// Samples of the shard in the log.
        logged: usize,
    },
}

/// The one study loop: opens (or with `resume` reopens) the sample log in `dir`, tells `opened`
/// how many samples the log already holds (an error of `opened` stops here), runs the shard's
/// remaining samples on `pool` into the log (`progress(n)`: samples of the shard in the log).
/// An `interrupt` stops it early with what it logged.
pub fn run_log(
    study: &Study,
    dir: &Path,
    resume: bool,
    pool: &rayon::ThreadPool,
    opened: &dyn Fn(usize, &Path) -> Result<(), Error>,
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
) -> Result<LogOutcome, Error> {
    let header = study.header();
    let (mut log, done) = if resume { LogWriter::resume(dir, &header)? } else { (LogWriter::create(dir, &header)?, 0) };
    opened(done, log.path())?;
    let logged = pool.install(|| study.run_into_until(&mut log, done, progress, interrupt))?;
    drop(log);
    if logged < study.config.shard_len() {
        return Ok(LogOutcome::Interrupted { logged });
    }
    Ok(LogOutcome::Complete)
}

/// A fresh folder name for the log of a study without an output folder (one per call, so that
/// studies running at once in one process do not meet).
pub fn temporary_log_dir() -> PathBuf {
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("stiction-study-{}-{call}", std::process::id()))
}

/// Runs a prepared study on `pool` in a temporary folder and summarises it: the summary and,
/// with `samples_csv`, the samples as the CSV of a study folder (samples.csv: one line per
/// sample, columns named in the first line). None when `interrupt` was set before the end (the
/// samples in flight finish; nothing is kept).
pub fn run_temporary(
    study: &Study,
    pool: &rayon::ThreadPool,
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
    samples_csv: Option<&mut Vec<u8>>,
) -> Result<Option<StudySummary>, Error> {
    let dir = temporary_log_dir();
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create output folder {}: {e}", dir.display()))?;
    let ran = run_log(study, &dir, false, pool, &|_, _| Ok(()), progress, interrupt);
    let out = match ran {
        Ok(LogOutcome::Complete) => {
            stiction_study::summary::summarize(&dir.join(stiction_study::log::LOG_NAME), samples_csv)
                .map(|(s, _)| Some(s))
                .map_err(Error::from)
        }
        Ok(LogOutcome::Interrupted { .. }) => Ok(None),
        Err(e) => Err(e),
    };
    let _ = std::fs::remove_dir_all(&dir);
    out
}

/// The summary as a JSON value (what `study SCENARIO --json` prints) of [`run_temporary`].
pub fn study_json_of(
    study: &Study,
    pool: &rayon::ThreadPool,
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
    samples_csv: Option<&mut Vec<u8>>,
) -> Result<Option<serde_json::Value>, Error> {
    match run_temporary(study, pool, progress, interrupt, samples_csv)? {
        Some(summary) => Ok(Some(crate::json::finite_value(&summary)?)),
        None => Ok(None),
    }
}
