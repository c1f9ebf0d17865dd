//! `stiction scenario`: check a scenario file, print it as it is run, explain where each quantity
//! the meter uses comes from, or print the format's JSON Schema.

use std::path::PathBuf;

use crate::output::{CliResult, TextTable, print_json};
use stiction_engine::ScenarioSource;

/// Check a scenario (with overrides) and print it as it is run (readable as input: the file's
/// units and uncertainties, and every default filled in), explain its quantities, or print the
/// JSON Schema.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file (omit with --schema).
    #[arg(required_unless_present_any = ["schema", "domains"])]
    pub scenario: Option<PathBuf>,
    /// Override a field: --set surface.summit_sd="40 nm" (repeatable; PATH=null removes a field).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// For each quantity the meter uses: its value, uncertainty and origin (given, derived from
    /// which fields, calibrated), with disagreements flagged, and the device fingerprint.
    #[arg(long)]
    pub explain: bool,
    /// With --explain: one JSON object instead of the table.
    #[arg(long, requires = "explain")]
    pub json: bool,
    /// Print the JSON Schema of the scenario format instead.
    #[arg(long)]
    pub schema: bool,
    /// Print the physical domain of every quantity (the range outside which an input is refused,
    /// the usual range outside which it runs with a warning, and why) as a Markdown table.
    #[arg(long, conflicts_with_all = ["schema", "explain"])]
    pub domains: bool,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    if args.schema {
        // The JSON Schema is a specification, not a result: its `default: null` entries are JSON
        // Schema's own keyword (a field that defaults to absent), so the result rule (every null
        // beside its reason) does not apply to it. It is a `serde_json` value: no float in it can
        // be a NaN or an infinity.
        let schema = serde_json::to_string_pretty(&stiction_engine::scenario::schema())?;
        crate::outln!("{schema}");
        return Ok(());
    }
    if args.domains {
        crate::outln!("{}", stiction_engine::scenario::domains_table().trim_end());
        return Ok(());
    }
    let path = args.scenario.ok_or("a scenario file is needed")?;
    let source = ScenarioSource::file(&path, &args.sets)?;
    let scenario = stiction_engine::scenario::check(&source)?;
    if !args.explain {
        for n in &scenario.notes {
            crate::errln!("note [{}]: {}", n.code, n.message);
        }
        // File paths absolute, so that the printed scenario runs from wherever it is saved.
        return print_json(&stiction_engine::scenario::input_json(&scenario, &source.base));
    }
    let e = scenario.explain();
    if args.json {
        return print_json(&e);
    }
    crate::outln!("stiction scenario {} --explain", path.display());
    crate::outln!("  device fingerprint: {}", e.device);
    crate::outln!();
    let mut t = TextTable::new(&["quantity", "value", "uncertainty (sd)", "origin"]);
    for q in &e.quantities {
        t.row(vec![q.name.clone(), q.value_text(), q.uncertainty_text(), q.origin.clone()]);
    }
    t.print("  ");
    if !e.warnings.is_empty() {
        crate::outln!();
    }
    for w in &e.warnings {
        crate::outln!("  warning [{}]: {}", w.code, w.message);
    }
    Ok(())
}
