//! The subcommands' results as JSON values, for front ends other than the command line (the
//! Python module): each function returns what the matching subcommand prints with `--json`, from
//! the same code.

pub use crate::cmd::contact::{Args as ContactArgs, Mode as ContactMode, Model as ContactModelKind, contact_json};
pub use crate::cmd::discrete::{Args as DiscreteArgs, Law, discrete_json};
pub use crate::cmd::run::{Experiment, experiment, run_json};
pub use crate::cmd::scenario::check as check_scenario;
pub use crate::cmd::study::{study_json, study_json_of, study_pool, with_lab_intervals};
pub use crate::cmd::topography::topography_json;

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

/// `value` as a JSON value after [`stiction_units::finite::check_finite`]: a NaN or an infinity is
/// refused with its key path (`points[3].friction_n`) as the command line refuses it when it
/// prints, instead of the silent null of `serde_json::to_value`.
pub fn finite_value<T: serde::Serialize + ?Sized>(
    value: &T,
) -> Result<serde_json::Value, stiction_units::finite::NonFinite> {
    stiction_units::finite::check_finite(value)?;
    serde_json::to_value(value).map_err(|e| stiction_units::finite::NonFinite(format!("internal error: {e}")))
}
pub use crate::cmd::bem::{Args as BemArgs, BemSurface, bem_json, check_rh_values};
pub use crate::cmd::fit::{Args as FitArgs, fit_json};
pub use crate::cmd::humidity::{DEFAULT_RH, rh_grid, rh_grid_of};

/// A subcommand's arguments parsed from flags as the command line parses them (`["--pressure",
/// "20 MPa"]`), so that a front end's keyword arguments meet the same checks and the same messages
/// (clap's, without its `error: ` prefix and usage hint).
pub fn parse_args<A: clap::Args + clap::FromArgMatches>(command: &'static str, flags: &[String]) -> Result<A, String> {
    let cmd = A::augment_args(clap::Command::new(command).no_binary_name(true));
    let message = |e: clap::Error| {
        let text = e.render().to_string();
        let text = text.strip_prefix("error: ").unwrap_or(&text);
        let text = text.split("\n\nUsage:").next().unwrap_or(text);
        text.split("\n\nFor more information").next().unwrap_or(text).trim().to_string()
    };
    let matches = cmd.try_get_matches_from(flags).map_err(message)?;
    A::from_arg_matches(&matches).map_err(message)
}

/// The JSON object `stiction plot humidity --scenario S [--set ...] --rh RH --json` prints for
/// the scenario `source` (a file or a tree built in memory): the friction meter at each relative
/// humidity of `rhs` ([`rh_grid`] of the `--rh` text, or [`rh_grid_of`] of numbers; the dry point
/// first), `progress(done, total)` after each humidity; every number checked finite.
pub fn humidity_json(
    source: &ScenarioSource,
    rhs: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let sweep = crate::cmd::humidity::sweep(source, rhs, progress)?;
    Ok(finite_value(&sweep)?)
}

#[cfg(test)]
mod tests {
    /// A NaN never reaches a front end as a silent null: `serde_json::to_value` writes one as
    /// null, `finite_value` refuses it naming its key path (the rule of the command line's
    /// printed JSON, `stiction_units::finite`).
    #[test]
    fn finite_value_refuses_a_nan_that_to_value_would_null() {
        #[derive(serde::Serialize)]
        struct Point {
            load_n: f64,
            friction_n: Option<f64>,
        }
        let points =
            vec![Point { load_n: 1.0, friction_n: Some(2.0) }, Point { load_n: 2.0, friction_n: Some(f64::NAN) }];
        assert_eq!(serde_json::to_value(&points).unwrap()[1]["friction_n"], serde_json::Value::Null);
        let e = super::finite_value(&points).unwrap_err().to_string();
        assert!(e.contains("[1].friction_n"), "{e}");
        let ok = vec![Point { load_n: 1.0, friction_n: None }];
        assert_eq!(super::finite_value(&ok).unwrap(), serde_json::json!([{"load_n": 1.0, "friction_n": null}]));
    }
}
