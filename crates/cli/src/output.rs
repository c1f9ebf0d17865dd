//! Shared helpers of the subcommands: quantity flags, JSON and table printing, output folders.

use std::path::Path;

use stiction_units::{Constraint, Dimension, parse_quantity_checked};

/// The result of a subcommand.
pub type CliResult = Result<(), Box<dyn std::error::Error>>;

/// A clap value parser for a quantity of `dim` (bare SI number or number with a unit).
pub fn quantity(
    dim: Dimension,
    constraint: Constraint,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| parse_quantity_checked(s, dim, constraint).map_err(|e| e.to_string())
}

/// Prints a value as pretty JSON on stdout.
pub fn print_json<T: serde::Serialize>(value: &T) -> CliResult {
    println!("{}", serde_json::to_string_pretty(value)?);
    Ok(())
}

/// Prints a two-column table of (name, value with unit).
pub fn print_table(title: &str, rows: &[(&str, String)]) {
    println!("{title}");
    let width = rows.iter().map(|(n, _)| n.len()).max().unwrap_or(0);
    for (name, value) in rows {
        println!("  {name:<width$}  {value}");
    }
}

/// Creates an output folder (and its parents).
pub fn ensure_dir(dir: &Path) -> CliResult {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create output folder {}: {e}", dir.display()))?;
    Ok(())
}

/// Formats an SI value with a prefix and unit.
pub fn q(value: f64, dim: Dimension) -> String {
    stiction_units::format_quantity(value, dim)
}
