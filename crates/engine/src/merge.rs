//! `merge`: the folders of a study's shards combined into the folder one unsharded run would have
//! written (samples.log, study.json, samples.csv, sensitivity.csv and the figures). A folder
//! operation: the sample logs are merged by `stiction_study::log::merge` and the folder finished
//! like a study's ([`crate::study_folder::finish_folder`]); every file is written through
//! `stiction_units::io`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use stiction_study::StudySummary;
use stiction_study::log::{self, LOG_NAME};

use crate::Error;
use crate::study_folder::{FolderHooks, finish_folder};

/// A merge of shard folders.
pub struct MergeRequest<'a> {
    /// The shards' study folders, in any order.
    pub dirs: &'a [PathBuf],
}

/// A merged study.
pub struct Merged {
    /// The scenario file of the study (from the logs' header).
    pub scenario: PathBuf,
    /// The summary of the merged log (what study.json holds).
    pub summary: StudySummary,
    /// The files written into the output folder: the log, then those of [`finish_folder`].
    pub files: Vec<String>,
}

/// The stages of a merge, reported to `progress`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MergeStage {
    /// The shards' logs are being read and merged into one.
    Logs,
    /// The merged log is being summarised and its files and figures written.
    Folder,
}

impl MergeRequest<'_> {
    /// Checks the inputs before anything is written: a design study's folder (which holds one
    /// study folder per design, not a log) is refused with how to merge it, and every shard's
    /// log is declared an input, so that no output may replace it.
    pub fn check(&self) -> Result<(), Error> {
        for d in self.dirs {
            if !d.join(LOG_NAME).exists() && crate::design::is_design_study(d) {
                return Err(format!(
                    "{} is a design study's folder (designs.json, design-NNN): merge each design's shard folders on \
                     their own (stiction merge A/design-000 B/design-000 --out M/design-000, and so on), then run the \
                     design study with --out M --resume for its table",
                    d.display()
                )
                .into());
            }
        }
        for d in self.dirs {
            stiction_units::io::declare_input(&d.join(LOG_NAME));
        }
        Ok(())
    }
}

/// Merges the shards' logs into `out_dir` (an empty folder) and writes the merged study's files
/// there (figures through `hooks`). [`MergeRequest::check`] first. `progress` is told each stage
/// as it starts; an `interrupt` set before a stage stops the merge there (None; the caller
/// removes `out_dir`).
pub fn merge(
    req: &MergeRequest,
    out_dir: &Path,
    hooks: &dyn FolderHooks,
    progress: &dyn Fn(MergeStage),
    interrupt: &AtomicBool,
) -> Result<Option<Merged>, Error> {
    if interrupt.load(Ordering::Relaxed) {
        return Ok(None);
    }
    progress(MergeStage::Logs);
    let header = log::merge(req.dirs, out_dir)?;
    if interrupt.load(Ordering::Relaxed) {
        return Ok(None);
    }
    progress(MergeStage::Folder);
    let (summary, written) = finish_folder(out_dir, hooks)?;
    let mut files = vec![LOG_NAME.to_string()];
    files.extend(written);
    Ok(Some(Merged { scenario: PathBuf::from(&header.scenario), summary, files }))
}
