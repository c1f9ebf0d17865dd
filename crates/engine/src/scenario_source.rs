//! A scenario as the commands read it, from a file or built in memory.

// The error of reading, overriding and parsing a scenario, which the constructors return.
pub use stiction_scenario::ScenarioError;

/// A scenario as the commands read it: its JSON tree as written (before any override), the
/// `--set PATH=VALUE` overrides in order, the name errors and results give it (the file's path,
/// or "<scenario>" for one built in memory) and the folder its relative paths (surface CSVs,
/// height maps, measured voltages) are read from (the file's folder). A command parses it with
/// its own overrides added, so a scenario from a file and the same tree built in memory give the
/// same numbers and the same messages.
#[derive(Clone, Debug)]
pub struct ScenarioSource {
    /// The JSON tree as written.
    pub value: serde_json::Value,
    /// The name in errors (a path, or "<scenario>").
    pub origin: std::path::PathBuf,
    /// The folder of the relative paths in the scenario.
    pub base: std::path::PathBuf,
    /// `--set PATH=VALUE` overrides, in order.
    pub sets: Vec<String>,
}

impl ScenarioSource {
    /// A scenario file (read now, at most the scenario size limit) with `sets`; its relative
    /// paths are read from its folder.
    pub fn file(path: &std::path::Path, sets: &[String]) -> Result<ScenarioSource, stiction_scenario::ScenarioError> {
        Ok(ScenarioSource {
            value: stiction_scenario::Scenario::load_json(path, &[])?,
            origin: path.to_path_buf(),
            base: path.parent().map(std::path::PathBuf::from).unwrap_or_default(),
            sets: sets.to_vec(),
        })
    }

    /// Scenario JSON text held in memory, named `origin` in errors, its relative paths read from
    /// `base`.
    pub fn text(
        text: &str,
        origin: &std::path::Path,
        base: &std::path::Path,
        sets: &[String],
    ) -> Result<ScenarioSource, stiction_scenario::ScenarioError> {
        Ok(ScenarioSource {
            value: stiction_scenario::Scenario::json_with_sets(text, origin, &[])?,
            origin: origin.to_path_buf(),
            base: base.to_path_buf(),
            sets: sets.to_vec(),
        })
    }

    /// The name in errors and in results' `scenario`/`file` fields.
    pub fn name(&self) -> String {
        self.origin.display().to_string()
    }

    /// The overrides and then `extra` (a command's own, such as `contact.mode="flat"`).
    fn all_sets(&self, extra: &[String]) -> Vec<String> {
        self.sets.iter().chain(extra).cloned().collect()
    }

    /// The JSON tree with the overrides and `extra` applied (what a study draws from).
    pub fn json(&self, extra: &[String]) -> Result<serde_json::Value, stiction_scenario::ScenarioError> {
        let mut value = self.value.clone();
        for set in self.all_sets(extra) {
            stiction_scenario::apply_set(&mut value, &set)?;
        }
        Ok(value)
    }

    /// The scenario parsed and validated with the overrides and `extra` applied, as
    /// `Scenario::load(path, sets + extra)` gives it for a file.
    pub fn parse(&self, extra: &[String]) -> Result<stiction_scenario::Scenario, stiction_scenario::ScenarioError> {
        stiction_scenario::Scenario::from_value_with_sets(self.json(extra)?, &self.origin, &self.all_sets(extra))
    }
}
