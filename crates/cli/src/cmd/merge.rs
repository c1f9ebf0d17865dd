//! `stiction merge`: combine the folders of a study's shards into the folder one run would have written.

use std::path::PathBuf;

use stiction_study::log;

use crate::output::{CliResult, ensure_dir};

/// Combine the output folders of a study's shards (`stiction study ... --shard K/M --out DIR`, one
/// folder per shard, in any order) into exactly the samples.log, study.json, samples.csv,
/// sensitivity table and figures one unsharded run would have written. Refuses folders of
/// different studies (scenario, seed, sample count, flags), missing or repeated shards, and
/// unfinished shards.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shards' output folders.
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// The folder to write the merged study to (must not hold a study yet).
    #[arg(long)]
    pub out: PathBuf,
    /// Print study.json instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Figure size and font.
    #[command(flatten)]
    pub fig: crate::figargs::FigureArgs,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    ensure_dir(&args.out)?;
    let header = log::merge(&args.dirs, &args.out)?;
    let summary = crate::cmd::study::finish_folder(&args.out, &args.fig)?;
    crate::cmd::study::report(&summary, args.json, std::path::Path::new(&header.scenario))
}
