//! `stiction study`: Monte Carlo over a scenario's uncertain parameters and surface realisations.

use std::path::{Path, PathBuf};

use stiction_meter::SlipPath;
use stiction_study::{Calibration, MAX_THREADS, Study, StudyConfig};

use crate::output::{CliResult, ensure_dir};

pub use crate::cmd::study_common::{Args, CalibrationArg, SlipPathArg};
use crate::cmd::study_common::{Folder, Outcome, Progress, interrupted, parse_shard, prepare_study, report, run_study};

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let (shard_index, shard_count) = match &args.shard {
        Some(s) => parse_shard(s)?,
        None => (0, 1),
    };
    let config = StudyConfig {
        calibration: match args.calibration {
            CalibrationArg::Nominal => Calibration::Nominal,
            CalibrationArg::PullIn => Calibration::PullIn,
        },
        slip_path: match args.slip_path {
            SlipPathArg::Light => SlipPath::Light,
            SlipPathArg::RigidBody => SlipPath::RigidBody,
        },
        samples: args.samples,
        seed: args.seed,
        vary_surface: !args.fixed_surface,
        shard_index,
        shard_count,
    };
    // Counts first: nothing is read or started before they are known to be sane.
    config.validate()?;
    let section = crate::cmd::design::section(&args.scenario, &args.sets)?;
    if !args.vary.is_empty() || section.is_some() {
        return crate::cmd::design::run(args, config, section);
    }
    if args.design_points.is_some() || args.rank_by.is_some() {
        return Err("--design-points and --rank-by belong to a design study: add --vary PATH=V1,V2,... (or a \
                    `design` section in the scenario)"
            .into());
    }
    let pool = thread_pool(args.threads)?;
    let study = prepare_study(&args.scenario, &args.sets, &config)?;
    // Without --out the log lives in a temporary folder removed at the end.
    let (dir, temporary) = match &args.out {
        Some(d) => (d.clone(), false),
        None => (temporary_log_dir(), true),
    };
    if temporary {
        let _ = std::fs::remove_dir_all(&dir);
    }
    ensure_dir(&dir)?;
    if !temporary {
        prepare_folder(&dir, &args)?;
    }
    let total = config.shard_len();
    let progress = Progress::new(total, 0, args.quiet || args.json);
    let found = std::cell::Cell::new(0);
    crate::output::stop_cleanly();
    let folder = if temporary { Folder::Temporary(None) } else { Folder::Kept(&args.fig) };
    let opened = |done: usize, log: &Path| {
        found.set(done);
        progress.restart_at(done);
        if args.resume && !args.quiet {
            crate::errln!("resuming: {done} of {total} samples found in {}", log.display());
        }
    };
    let ran = run_study(
        &study,
        &dir,
        args.resume,
        folder,
        &pool,
        &opened,
        &|n| progress.update(n),
        &crate::output::INTERRUPT,
    );
    progress.finish(match &ran {
        Ok(Outcome::Interrupted { logged }) => *logged,
        Ok(Outcome::Finished { .. }) => total,
        Err(_) => found.get(),
    });
    if temporary {
        let _ = std::fs::remove_dir_all(&dir);
    }
    let (summary, files) = match ran? {
        Outcome::Interrupted { logged } => return Err(Box::new(interrupted(logged, total, &dir, temporary))),
        Outcome::Finished { summary, files } => (*summary, files),
    };
    if !temporary {
        report(&summary, args.json, &args.scenario)?;
        if !args.json {
            crate::outln!("\nwrote {}/{}, {}", dir.display(), files.join(", "), crate::output::MANIFEST);
        }
        return Ok(());
    }
    report(&summary, args.json, &args.scenario)
}

pub use stiction_fit::with_lab_intervals;

/// The --out rules of a study folder, which is written in place (the log grows sample by sample):
/// files no stiction run listed are refused unless --force; a new study over a finished or
/// unfinished one needs --resume (finish it) or --force (start again: its files are removed).
fn prepare_folder(dir: &Path, args: &Args) -> CliResult {
    use stiction_study::log::LOG_NAME;
    crate::output::check_foreign(dir, &[LOG_NAME], args.force)?;
    if !args.resume && args.force {
        let mut old = crate::output::listed_files(dir)?;
        old.push(LOG_NAME.into());
        old.push(crate::output::MANIFEST.into());
        for f in old {
            let p = dir.join(&f);
            if std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&p).map_err(|e| format!("cannot remove {}: {e}", p.display()))?;
            }
        }
    }
    Ok(())
}

/// The worker pool of `--threads` (default: all cores).
fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, Box<dyn std::error::Error>> {
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if t == 0 || t > MAX_THREADS {
            return Err(format!(
                "--threads {t}: expected 1 to {MAX_THREADS} (this machine has {} cores; more threads than cores do \
                 not make a study faster)",
                std::thread::available_parallelism().map_or(1, |n| n.get())
            )
            .into());
        }
        pool = pool.num_threads(t);
    }
    Ok(pool.build()?)
}

/// A fresh folder name for the log of a study without --out (one per call, so that studies
/// running at once in one process do not meet).
fn temporary_log_dir() -> PathBuf {
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    std::env::temp_dir().join(format!("stiction-study-{}-{call}", std::process::id()))
}

/// The summary `stiction study SCENARIO --json` prints (without --out, --shard or --vary): the
/// study of the scenario file with the `sets` overrides, `config`'s samples, seed and options, on
/// `threads` workers; `progress(done)` as samples finish.
pub fn study_json(
    scenario: &Path,
    sets: &[String],
    config: &StudyConfig,
    threads: Option<usize>,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    config.validate()?;
    let pool = thread_pool(threads)?;
    let study = prepare_study(scenario, sets, config)?;
    let never = std::sync::atomic::AtomicBool::new(false);
    Ok(study_json_of(&study, &pool, progress, &never, None)?.ok_or("the study was interrupted")?)
}

/// The summary of a prepared study run on `pool` (what [`study_json`] prints), and with
/// `samples_csv` the samples as the CSV of `stiction study --out` (samples.csv: one line per
/// sample, columns named in the first line). None when `interrupt` was set before the end (the
/// samples in flight finish; nothing is kept). Runs [`run_study`] in a temporary folder.
pub fn study_json_of(
    study: &Study,
    pool: &rayon::ThreadPool,
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
    samples_csv: Option<&mut Vec<u8>>,
) -> Result<Option<serde_json::Value>, Box<dyn std::error::Error>> {
    let dir = temporary_log_dir();
    let _ = std::fs::remove_dir_all(&dir);
    ensure_dir(&dir)?;
    let ran = run_study(study, &dir, false, Folder::Temporary(samples_csv), pool, &|_, _| {}, progress, interrupt);
    let _ = std::fs::remove_dir_all(&dir);
    match ran? {
        Outcome::Finished { summary, .. } => Ok(Some(stiction_engine::json::finite_value(&summary)?)),
        Outcome::Interrupted { .. } => Ok(None),
    }
}

/// A rayon pool of `threads` workers (default: one per core), as `stiction study --threads`.
pub fn study_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, Box<dyn std::error::Error>> {
    thread_pool(threads)
}
