//! The subcommands' results as JSON values, for front ends other than the command line (the
//! Python module): each function returns what the matching subcommand prints with `--json`, from
//! the same code.

pub use crate::cmd::discrete::{Args as DiscreteArgs, Law, discrete_json};
pub use crate::cmd::run::{Experiment, experiment, run_json};
pub use crate::cmd::study::study_json;
pub use crate::cmd::topography::topography_json;
