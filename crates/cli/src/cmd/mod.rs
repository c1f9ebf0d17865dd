//! One module per subcommand.

pub mod actuator;
pub mod bem;
pub mod contact;
pub mod design;
pub mod discrete;
pub mod fit;
pub mod gw;
pub mod humidity;
pub mod map_args;
pub mod merge;
pub mod plot;
pub mod run;
pub mod scenario;
pub mod study;
pub mod study_common;
pub mod surface;
pub mod topography;
