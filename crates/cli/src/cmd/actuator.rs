//! `stiction actuator` (being written).

use crate::output::CliResult;

/// Arguments.
#[derive(clap::Args, Debug)]
pub struct Args {}

/// Runs the subcommand.
pub fn run(_args: Args) -> CliResult {
    Err("not yet available".into())
}
