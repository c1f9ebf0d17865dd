//! The subcommands' results as JSON values, for front ends other than the command line (the
//! Python module): each function returns what the matching subcommand prints with `--json`, from
//! the same code.

pub use crate::cmd::contact::{Args as ContactArgs, Mode as ContactMode, Model as ContactModelKind, contact_json};
pub use crate::cmd::discrete::{Args as DiscreteArgs, Law, discrete_json};
pub use crate::cmd::run::{Experiment, experiment, run_json};
pub use crate::cmd::scenario::check as check_scenario;
pub use crate::cmd::study::{study_json, study_json_of, study_pool, with_lab_intervals};
pub use crate::cmd::topography::topography_json;

pub use crate::json_value::finite_value;
pub use crate::scenario_source::ScenarioSource;

pub use crate::cmd::bem::{Args as BemArgs, BemSurface, bem_json};
pub use crate::cmd::fit::{Args as FitArgs, fit_json};
pub use crate::cmd::humidity::{DEFAULT_RH, rh_grid, rh_grid_of};
pub use crate::rh::check_rh_values;

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

/// The command line's limits on counts and lengths, for a front end that takes the same
/// quantities as arrays or integers (the Python module checks its arguments against these before
/// any work, and names its own argument in the message).
pub mod limits {
    /// Most loads of one `stiction contact` sweep by default (`--max-sweep-steps`).
    pub use crate::cmd::contact::DEFAULT_MAX_SWEEP_STEPS;
    /// Most calibration draws of `stiction fit --draws`.
    pub use stiction_fit::MAX_DRAWS;
    /// Most data rows of `stiction fit`.
    pub use stiction_fit::MAX_FIT_ROWS;
    /// Most surface realisations of `stiction fit --surfaces`.
    pub use stiction_fit::models::MAX_SURFACES;
    /// Most worker threads of `stiction study --threads`.
    pub use stiction_study::MAX_THREADS;
    /// The sample limit of `stiction study --samples` in force (`STICTION_MAX_SAMPLES` raises it).
    pub use stiction_study::max_samples;

    /// Most steps of a `stiction bem --sweep` or `--gap-sweep` path (FROM:TO:STEPS), so also most
    /// pressures of a front end's vector of pressures. The check is `bem`'s own (`parse_path`);
    /// the test `bem_limits_are_the_commands` fails if the two ever differ.
    pub const BEM_MAX_PATH_STEPS: usize = 10_000;
    /// Most grid points per side of `stiction bem --grid` (checked by `bem` itself; same test).
    pub const BEM_MAX_GRID_SIDE: usize = 4096;
    /// Most relative humidities of `--rh` (`stiction bem`, `stiction plot humidity`), checked by
    /// [`super::check_rh_values`] (same test).
    pub const MAX_RH: usize = 1000;

    /// A front end's vector of `len` loads for one sweep (Python's `contact(load=[...])`, named
    /// `name`), checked against `max` before any load is solved: the limit and the reason of
    /// `--sweep STEPS` (`parse_sweep`), with the front end's `advice` ("raise it with
    /// max_sweep_steps=N if you mean it").
    pub fn check_sweep_len(name: &str, len: usize, max: usize, advice: &str) -> Result<(), String> {
        if len == 0 {
            return Err(format!("{name}: expected at least one load"));
        }
        if len > max {
            return Err(format!(
                "{name}: {len} loads, more than the limit of {max} loads of a sweep (one equilibrium solve and about \
                 100 bytes of output each: {:.1e} bytes); {advice}",
                len as f64 * 100.0
            ));
        }
        Ok(())
    }

    /// A front end's vector of `len` mean pressures for `stiction bem` (named `name`): 1 to
    /// [`BEM_MAX_PATH_STEPS`], the limit of `--sweep FROM:TO:STEPS`.
    pub fn check_pressures_len(name: &str, len: usize) -> Result<(), String> {
        if len == 0 || len > BEM_MAX_PATH_STEPS {
            return Err(format!(
                "{name}: {len} pressures; expected 1 to {BEM_MAX_PATH_STEPS} mean pressures (the limit of bem's sweep \
                 FROM:TO:STEPS)"
            ));
        }
        Ok(())
    }

    /// A BEM grid of `nx` x `ny` points from an array named `name`, checked against the solver's
    /// grid limit (`stiction bem --map`'s check, [`stiction_bem::Grid::new`]) before the array is
    /// read or copied.
    pub fn check_bem_grid(name: &str, nx: usize, ny: usize) -> Result<(), String> {
        stiction_bem::Grid::new(nx, ny, 1.0, 1.0).map(|_| ()).map_err(|e| format!("{name}: {e} (the BEM grid limit)"))
    }
}

#[cfg(test)]
mod tests {
    /// A NaN never reaches a front end as a silent null: `serde_json::to_value` writes one as
    /// null, `finite_value` refuses it naming its key path (the rule of the command line's
    /// printed JSON, `stiction_units::finite`).
    /// The limits `api::limits` states are those the commands check: one past each is refused by
    /// the command's own parser with a message that names it, the limit itself is taken.
    #[test]
    fn bem_limits_are_the_commands() {
        use super::limits::*;
        let bem = |flags: &[&str]| {
            let flags: Vec<String> = flags.iter().map(|s| s.to_string()).collect();
            let args: super::BemArgs = super::parse_args("bem", &flags).unwrap();
            super::bem_json(&args, super::BemSurface::Generated, None).map(|_| ()).map_err(|e| e.to_string())
        };
        let over = format!("--sweep=1MPa:2MPa:{}", BEM_MAX_PATH_STEPS + 1);
        let e = bem(&["--grid=32", &over]).unwrap_err();
        assert!(e.contains(&format!("1..={BEM_MAX_PATH_STEPS}")), "{e}");
        let e = bem(&["--grid=32", &over.replace("--sweep", "--gap-sweep").replace("MPa", "um")]).unwrap_err();
        assert!(e.contains(&format!("1..={BEM_MAX_PATH_STEPS}")), "{e}");
        let grid = format!("--grid={}", BEM_MAX_GRID_SIDE + 1);
        let e = bem(&[&grid, "--pressure=1MPa"]).unwrap_err();
        assert!(e.contains(&format!("2..={BEM_MAX_GRID_SIDE}")), "{e}");
        let e = super::check_rh_values(&[0.5; MAX_RH + 1]).unwrap_err();
        assert!(e.contains(&format!("1 to {MAX_RH}")), "{e}");
        super::check_rh_values(&[0.5; MAX_RH]).unwrap();
        let e = super::rh_grid(Some(&format!("0:0.5:{}", MAX_RH + 1))).unwrap_err();
        assert!(e.contains(&format!("1..={MAX_RH}")), "{e}");
        assert!(check_bem_grid("heights", 4096, 4097).unwrap_err().starts_with("heights: "));
        check_bem_grid("heights", 4096, 4096).unwrap();
        check_pressures_len("pressure", BEM_MAX_PATH_STEPS).unwrap();
        assert!(check_pressures_len("pressure", BEM_MAX_PATH_STEPS + 1).unwrap_err().starts_with("pressure: "));
    }

    /// The sweep limit of a front end's vector of loads is `--sweep`'s: the same count refused
    /// by `parse_sweep` is refused here, one less taken.
    #[test]
    fn the_sweep_limit_of_a_vector_is_the_sweeps() {
        use super::limits::*;
        let max = 10;
        assert!(crate::cmd::contact::parse_sweep("0uN:1uN:11", max).is_err());
        assert!(crate::cmd::contact::parse_sweep("0uN:1uN:10", max).is_ok());
        let e = check_sweep_len("load", 11, max, "raise it with max_sweep_steps=N").unwrap_err();
        assert!(e.starts_with("load: 11 loads") && e.contains("max_sweep_steps="), "{e}");
        check_sweep_len("load", 10, max, "").unwrap();
        assert!(check_sweep_len("load", 0, max, "").is_err());
        assert_eq!(DEFAULT_MAX_SWEEP_STEPS, 1_000_000);
    }
}
