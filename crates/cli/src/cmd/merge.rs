//! `stiction merge`: combine the folders of a study's shards into the folder one run would have written.

use std::path::PathBuf;

use stiction_study::log;

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
    // A design study's folder holds one study folder per design, not a log: say how to merge it.
    for d in &args.dirs {
        if !d.join(log::LOG_NAME).exists() && is_design_study(d) {
            return Err(format!(
                "{} is a design study's folder (designs.json, design-NNN): merge each design's shard folders on \
                 their own (stiction merge A/design-000 B/design-000 --out M/design-000, and so on), then run the \
                 design study with --out M --resume for its table",
                d.display()
            )
            .into());
        }
    }
    // The shards' logs are this command's inputs: no output may replace them.
    for d in &args.dirs {
        stiction_units::io::declare_input(&d.join(log::LOG_NAME));
    }
    let mut set = OutputSet::begin(&args.out, "merge", args.force)?;
    let header = log::merge(&args.dirs, set.staging_dir())?;
    let (summary, _) = crate::cmd::study_common::finish_folder(set.staging_dir(), &args.fig)?;
    set.adopt_staged()?;
    let files = set.file_names();
    set.commit()?;
    crate::cmd::study_common::report(&summary, args.json, std::path::Path::new(&header.scenario))?;
    if !args.json {
        crate::outln!("\nwrote {}/{}, {}", args.out.display(), files.join(", "), crate::output::MANIFEST);
    }
    Ok(())
}

/// Whether `dir` is a design study's --out: it holds designs.json or a `design-NNN` folder.
fn is_design_study(dir: &std::path::Path) -> bool {
    dir.join("designs.json").is_file()
        || std::fs::read_dir(dir).is_ok_and(|mut e| {
            e.any(|e| {
                e.is_ok_and(|e| {
                    let n = e.file_name().to_string_lossy().into_owned();
                    e.path().is_dir()
                        && n.strip_prefix("design-")
                            .is_some_and(|d| d.len() >= 3 && d.bytes().all(|b| b.is_ascii_digit()))
                })
            })
        })
}
