//! `stiction study`: Monte Carlo over a scenario's uncertain parameters and surface realisations.

use std::path::Path;

use stiction_engine::study::{Calibration, LOG_NAME, SlipPath, StudyRequest, temporary_log_dir, thread_pool};
use stiction_engine::study_folder::{Folder, Outcome, run_study};

use crate::output::{CliResult, ensure_dir};

pub use crate::cmd::study_common::{Args, CalibrationArg, SlipPathArg};
use crate::cmd::study_common::{Progress, StudyFolder, flag, interrupted, parse_shard, prepare_study, report};

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let (shard_index, shard_count) = match &args.shard {
        Some(s) => parse_shard(s)?,
        None => (0, 1),
    };
    // Counts first: nothing is read or started before they are known to be sane.
    let config = args.request((shard_index, shard_count)).config()?;
    let section = crate::cmd::design::section(&args.scenario, &args.sets)?;
    if !args.vary.is_empty() || section.is_some() {
        return crate::cmd::design::run(args, config, section);
    }
    if args.design_points.is_some() || args.rank_by.is_some() {
        return Err("--design-points and --rank-by belong to a design study: add --vary PATH=V1,V2,... (or a \
                    `design` section in the scenario)"
            .into());
    }
    let pool = thread_pool(args.threads, &flag)?;
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
    let hooks = StudyFolder { fig: &args.fig, manifest: true };
    let folder = if temporary { Folder::Temporary(None) } else { Folder::Kept(&hooks) };
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

impl Args {
    /// The engine's request of these flags, for `shard` (K, M).
    pub fn request(&self, shard: (usize, usize)) -> StudyRequest {
        StudyRequest {
            samples: self.samples,
            seed: self.seed,
            fixed_surface: self.fixed_surface,
            shard,
            calibration: match self.calibration {
                CalibrationArg::Nominal => Calibration::Nominal,
                CalibrationArg::PullIn => Calibration::PullIn,
            },
            slip_path: match self.slip_path {
                SlipPathArg::Light => SlipPath::Light,
                SlipPathArg::RigidBody => SlipPath::RigidBody,
            },
            threads: self.threads,
        }
    }
}

/// The --out rules of a study folder, which is written in place (the log grows sample by sample):
/// files no stiction run listed are refused unless --force; a new study over a finished or
/// unfinished one needs --resume (finish it) or --force (start again: its files are removed).
fn prepare_folder(dir: &Path, args: &Args) -> CliResult {
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
