//! `scenario`: a scenario checked as the commands read it.

// The scenario and its reference section (the paper's measured values), which front ends print.
pub use stiction_scenario::{ReferenceSpec, Scenario};

use crate::Error;
use crate::scenario_source::ScenarioSource;

/// The checks of `stiction scenario`: the scenario `source` parsed and validated, and a height-map
/// sidewall checked as `run` reads it: the map is read and prepared (cut-offs no longer than the
/// map, a map at least as large as the shoe or `tile`), so a scenario that passes here does not
/// fail there. The parsed scenario comes back.
pub fn check(source: &ScenarioSource) -> Result<Scenario, Error> {
    let scenario = source.parse(&[])?;
    if let Ok(surface) = scenario.require_surface()
        && surface.source == stiction_surface::SurfaceSource::HeightMap
    {
        stiction_surface::height_map_patch(surface, &source.base).map_err(|e| format!("{}: {e}", source.name()))?;
    }
    Ok(scenario)
}

/// The JSON Schema of a scenario file (`stiction scenario --schema`), generated from the types
/// that parse it.
pub fn schema() -> serde_json::Value {
    Scenario::json_schema()
}

/// The table of every scenario quantity's physical domain, as Markdown (`stiction scenario
/// --domains`; docs/reliability.md holds the same table).
pub fn domains_table() -> String {
    stiction_scenario::domain::markdown_table()
}

/// The scenario as an input file with every default written out and its file paths absolute
/// (from `base`), so that the printed scenario runs from wherever it is saved.
pub fn input_json(scenario: &Scenario, base: &std::path::Path) -> serde_json::Value {
    let mut printed = scenario.to_input_json();
    stiction_scenario::absolutize_file_paths(&mut printed, base);
    printed
}
