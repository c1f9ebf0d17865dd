//! The subcommands' results as JSON values, for front ends other than the command line (the
//! Python module): each function returns what the matching subcommand prints with `--json`, from
//! the same code.

pub use crate::cmd::contact::{Args as ContactArgs, Mode as ContactMode, Model as ContactModelKind, contact_json};
pub use crate::cmd::discrete::{Args as DiscreteArgs, Law, discrete_json};
pub use crate::cmd::run::{Experiment, experiment, run_json};
pub use crate::cmd::study::{study_json, study_json_of, study_pool, with_lab_intervals};
pub use crate::cmd::topography::topography_json;

/// `value` as a JSON value after [`stiction_units::finite::check_finite`]: a NaN or an infinity is
/// refused with its key path (`points[3].friction_n`) as the command line refuses it when it
/// prints, instead of the silent null of `serde_json::to_value`.
pub fn finite_value<T: serde::Serialize + ?Sized>(
    value: &T,
) -> Result<serde_json::Value, stiction_units::finite::NonFinite> {
    stiction_units::finite::check_finite(value)?;
    serde_json::to_value(value).map_err(|e| stiction_units::finite::NonFinite(format!("internal error: {e}")))
}
pub use crate::cmd::bem::{Args as BemArgs, bem_json_of_map};
pub use crate::cmd::fit::{Args as FitArgs, fit_json};

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

/// The JSON object `stiction plot humidity --scenario PATH [--set ...] --rh RH --json` prints:
/// the friction meter of the scenario at each relative humidity of `rh` (a list or FROM:TO:STEPS,
/// default 0:0.9:10; the dry point first).
pub fn humidity_json(
    path: &std::path::Path,
    sets: &[String],
    rh: Option<&str>,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    let rhs = crate::cmd::humidity::rh_grid(rh)?;
    let sweep = crate::cmd::humidity::sweep(path, sets, &rhs, &mut |_, _| {})?;
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
