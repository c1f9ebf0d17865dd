//! The subcommands' results as JSON values, for front ends other than the command line (the
//! Python module): each function returns what the matching subcommand prints with `--json`, from
//! the same code.

pub use crate::cmd::contact::{Args as ContactArgs, Mode as ContactMode, Model as ContactModelKind};
pub use crate::cmd::discrete::{Args as DiscreteArgs, Law};
pub use crate::cmd::study::{study_pool, with_lab_intervals};
pub use stiction_engine::run::{Experiment, experiment, run_json};
pub use stiction_engine::scenario::check as check_scenario;
pub use stiction_engine::study::study_json_of;
pub use stiction_engine::topography::topography_json;

pub use stiction_engine::ScenarioSource;
pub use stiction_engine::json::finite_value;

pub use crate::cmd::bem::Args as BemArgs;
pub use crate::cmd::fit::Args as FitArgs;
pub use stiction_engine::bem::{BemSurface, bem_json};
pub use stiction_engine::humidity::{DEFAULT_RH, humidity_json, rh_grid, rh_grid_of};
pub use stiction_engine::rh::check_rh_values;

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

/// The limits of the commands (the engine's).
pub use stiction_engine::limits;

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
            super::bem_json(&args.request(), super::BemSurface::Generated, None).map(|_| ()).map_err(|e| e.to_string())
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
        assert!(stiction_engine::contact::parse_sweep("0uN:1uN:11", max).is_err());
        assert!(stiction_engine::contact::parse_sweep("0uN:1uN:10", max).is_ok());
        let e = check_sweep_len("load", 11, max, "raise it with max_sweep_steps=N").unwrap_err();
        assert!(e.starts_with("load: 11 loads") && e.contains("max_sweep_steps="), "{e}");
        check_sweep_len("load", 10, max, "").unwrap();
        assert!(check_sweep_len("load", 0, max, "").is_err());
        assert_eq!(DEFAULT_MAX_SWEEP_STEPS, 1_000_000);
    }
}
