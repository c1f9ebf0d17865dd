//! A study's folder: the one study loop run into a folder (its sample log, written sample by
//! sample and resumable) and the files of a finished study (study.json, samples.csv,
//! sensitivity.csv, then the figures, which the front end draws). Shared by `study`, design
//! studies ([`crate::design::run_designs`]) and `merge` ([`crate::merge`]).

use std::path::{Path, PathBuf};

use stiction_study::log::LOG_NAME;
use stiction_study::summary::FigureData;
use stiction_study::{Study, StudySummary};

use crate::Error;
use crate::study::{LogOutcome, run_log};

/// What a front end adds to a kept study folder, which the engine writes in place.
pub trait FolderHooks {
    /// The log in `dir` is open and samples are about to run: the folder is not complete until
    /// the study ends (the command line removes its manifest here).
    fn opened(&self, _dir: &Path) -> Result<(), Error> {
        Ok(())
    }
    /// Draws the figures of the finished study into `dir` (the engine does not draw) and returns
    /// the names of the files written.
    fn figures(&self, dir: &Path, summary: &StudySummary, fig: &FigureData) -> Result<Vec<String>, Error>;
    /// The folder is complete and holds `files` (the log first): the command line writes its
    /// manifest here.
    fn finished(&self, _dir: &Path, _files: &[String]) -> Result<(), Error> {
        Ok(())
    }
}

/// Where a study's outputs go.
pub enum Folder<'a> {
    /// A temporary folder: only the log, summarised at the end (the caller removes the folder);
    /// with a buffer, the samples' CSV (samples.csv) is written into it.
    Temporary(Option<&'a mut Vec<u8>>),
    /// A kept study folder: study.json, samples.csv, sensitivity.csv and the figures (through
    /// the hooks), written when the study is complete.
    Kept(&'a dyn FolderHooks),
}

/// How [`run_study`] ended.
pub enum Outcome {
    /// Every sample of the shard is in the log: its summary and, in a kept folder, the files
    /// of the folder (the log first).
    Finished {
        /// The summary, computed from the log alone.
        summary: Box<StudySummary>,
        /// The files of the folder (empty for a temporary one).
        files: Vec<String>,
    },
    /// Stopped by `interrupt`: this many samples of the shard are in the log.
    Interrupted {
        /// Samples of the shard in the log.
        logged: usize,
    },
}

/// Creates an output folder (and its parents); errors name the folder. A symbolic link is
/// refused: outputs never go through a link.
pub fn ensure_dir(dir: &Path) -> Result<(), Error> {
    if std::fs::symlink_metadata(dir).is_ok_and(|m| m.file_type().is_symlink()) {
        return Err(
            format!("output folder {} is a symbolic link; outputs never go through a link", dir.display()).into()
        );
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create output folder {}: {e}", dir.display()))?;
    Ok(())
}

/// The one study loop into a folder, shared by `study`, design studies and the Python binding:
/// opens (or with `resume` reopens) the sample log in `dir`, tells a kept folder's hooks and
/// `opened` how many samples the log already holds, runs the shard's remaining samples on `pool`
/// into the log (`progress(n)`: samples of the shard in the log), and summarises the complete log
/// (a kept folder gets its files, [`finish_folder`], and the hooks' `finished`). An `interrupt`
/// stops it early with what it logged.
#[allow(clippy::too_many_arguments)]
pub fn run_study(
    study: &Study,
    dir: &Path,
    resume: bool,
    folder: Folder,
    pool: &rayon::ThreadPool,
    opened: &dyn Fn(usize, &Path),
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
) -> Result<Outcome, Error> {
    let on_open = |done: usize, path: &Path| -> Result<(), Error> {
        if let Folder::Kept(hooks) = &folder {
            hooks.opened(dir)?;
        }
        opened(done, path);
        Ok(())
    };
    if let LogOutcome::Interrupted { logged } = run_log(study, dir, resume, pool, &on_open, progress, interrupt)? {
        return Ok(Outcome::Interrupted { logged });
    }
    match folder {
        Folder::Temporary(csv) => {
            let (summary, _) = stiction_study::summary::summarize(&dir.join(LOG_NAME), csv)?;
            Ok(Outcome::Finished { summary: Box::new(summary), files: Vec::new() })
        }
        Folder::Kept(hooks) => {
            let (summary, written) = finish_folder(dir, hooks)?;
            let mut files = vec![LOG_NAME.to_string()];
            files.extend(written);
            hooks.finished(dir, &files)?;
            Ok(Outcome::Finished { summary: Box::new(summary), files })
        }
    }
}

/// Writes study.json, samples.csv, sensitivity.csv and (through `hooks`) the figures of the
/// study whose complete log is in `dir`. Returns the summary and the names of the files written.
pub fn finish_folder(dir: &Path, hooks: &dyn FolderHooks) -> Result<(StudySummary, Vec<String>), Error> {
    let (summary, fig) = stiction_study::summary::finalize(dir)?;
    let mut files = vec!["study.json".to_string(), "samples.csv".into()];
    stiction_units::io::write_atomic(&dir.join("sensitivity.csv"), &sensitivity_csv(&summary)?)?;
    files.push("sensitivity.csv".into());
    files.extend(hooks.figures(dir, &summary, &fig)?);
    Ok((summary, files))
}

/// The sensitivity table of a study folder (sensitivity.csv): one line per uncertain input,
/// its first- and total-order Sobol indices with their 95 % bootstrap intervals and its Spearman
/// rho, for mu_e,a and F_a0 (an empty cell where a value is not defined).
pub fn sensitivity_csv(summary: &StudySummary) -> Result<Vec<u8>, Error> {
    let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    w.write_record([
        "input",
        "mu_first_order_sobol",
        "fa0_first_order_sobol",
        "mu_spearman_rho",
        "fa0_spearman_rho",
        "mu_first_order_ci_low",
        "mu_first_order_ci_high",
        "fa0_first_order_ci_low",
        "fa0_first_order_ci_high",
        "mu_total_order_sobol",
        "mu_total_order_ci_low",
        "mu_total_order_ci_high",
        "fa0_total_order_sobol",
        "fa0_total_order_ci_low",
        "fa0_total_order_ci_high",
    ])?;
    let f = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    let lo = |c: Option<[f64; 2]>| f(c.map(|c| c[0]));
    let hi = |c: Option<[f64; 2]>| f(c.map(|c| c[1]));
    for r in &summary.sensitivity.inputs {
        w.write_record([
            r.input.clone(),
            f(r.mu_first_order),
            f(r.fa0_first_order),
            f(r.mu_spearman),
            f(r.fa0_spearman),
            lo(r.mu_first_order_ci),
            hi(r.mu_first_order_ci),
            lo(r.fa0_first_order_ci),
            hi(r.fa0_first_order_ci),
            f(r.mu_total_order),
            lo(r.mu_total_order_ci),
            hi(r.mu_total_order_ci),
            f(r.fa0_total_order),
            lo(r.fa0_total_order_ci),
            hi(r.fa0_total_order_ci),
        ])?;
    }
    Ok(w.into_inner().map_err(|e| e.to_string())?)
}

/// The path of the sample log in a study folder.
pub fn log_path(dir: &Path) -> PathBuf {
    dir.join(LOG_NAME)
}
