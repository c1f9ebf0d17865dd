//! `stiction scenario`: check a scenario file or print the format's JSON Schema.

use std::path::PathBuf;

use stiction_scenario::Scenario;

use crate::output::{CliResult, print_json};

/// Check a scenario (with overrides) and print it with every quantity in SI, or print the JSON Schema.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file (omit with --schema).
    #[arg(required_unless_present = "schema")]
    pub scenario: Option<PathBuf>,
    /// Override a field: --set surface.summit_sd="40 nm" (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Print the JSON Schema of the scenario format instead.
    #[arg(long)]
    pub schema: bool,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    if args.schema {
        return print_json(&Scenario::json_schema());
    }
    let path = args.scenario.ok_or("a scenario file is needed")?;
    let scenario = Scenario::load(&path, &args.sets)?;
    print_json(&scenario)
}
