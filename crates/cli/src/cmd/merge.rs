//! `stiction merge`: combine the folders of a study's shards into the folder one run would have
//! written. The merge is the engine's (`stiction_engine::merge`); here: the flags, the staged
//! output folder, the figures and the printed summary.

use std::path::PathBuf;

use stiction_engine::merge::{MergeRequest, merge};

use crate::cmd::study_common::StudyFolder;
use crate::output::{CliResult, OutputSet};

/// Combine the output folders of a study's shards (`stiction study ... --shard K/M --out DIR`, one
/// folder per shard, in any order) into exactly the samples.log, study.json, samples.csv,
/// sensitivity table and figures one unsharded run would have written. Refuses folders of
/// different studies (scenario, seed, sample count, flags), missing or repeated shards, and
/// unfinished shards. The merged folder is staged and swapped in whole, with a manifest.json, like
/// every --out folder.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shards' output folders.
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// The folder to write the merged study to (replaced as a whole; one of the shards' folders is
    /// refused).
    #[arg(long)]
    pub out: PathBuf,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are
    /// left alone; the earlier run's files are replaced or removed).
    #[arg(long)]
    pub force: bool,
    /// Print study.json instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Figure size and font.
    #[command(flatten)]
    pub fig: crate::figargs::FigureArgs,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let req = MergeRequest { dirs: &args.dirs };
    // A design study's folder is refused (with how to merge it), and the shards' logs become
    // this command's inputs (no output may replace them), before the output folder is touched.
    req.check()?;
    let mut set = OutputSet::begin(&args.out, "merge", args.force)?;
    // The staged folder's manifest is the output set's; Ctrl-C removes the staging folder.
    let hooks = StudyFolder { fig: &args.fig, manifest: false };
    let Some(merged) = merge(&req, set.staging_dir(), &hooks, &|_| {}, &crate::output::INTERRUPT)? else {
        return Err(Box::new(crate::output::Interrupted("interrupted: nothing was merged".into())));
    };
    set.adopt_staged()?;
    let files = set.file_names();
    set.commit()?;
    crate::cmd::study_common::report(&merged.summary, args.json, &merged.scenario)?;
    if !args.json {
        crate::outln!("\nwrote {}/{}, {}", args.out.display(), files.join(", "), crate::output::MANIFEST);
    }
    Ok(())
}
