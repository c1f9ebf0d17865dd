//! stiction's engine: every command of the friction meter as a typed request, its
//! orchestration, and a typed result whose JSON serialisation is what `stiction COMMAND --json`
//! prints.
//!
//! The engine sits between the physics crates (units, topography, surface, contact, bem,
//! actuator, scenario, meter, study, fit, plot) and the front ends (the `stiction` command line,
//! crates/cli; the Python package, crates/py). It holds no argument parser, prints nothing and
//! draws no progress bar: progress comes out through callbacks (`progress(done, total)`), and
//! interruption comes in through an `AtomicBool` the front end sets (the command line on
//! Ctrl-C, Python on KeyboardInterrupt). A front end turns its own inputs (flags, keyword
//! arguments) into a request, calls the engine, and presents the result (text tables, output
//! folders, Python objects).
//!
//! Requests carry SI values with the unit in the field name (`radius_m`, `load_n`) and are
//! checked against the physical domains of `stiction_scenario::domain`, naming each field as the
//! front end calls it ([`check::Names`]).

pub mod actuator;
pub mod bem;
pub mod check;
pub mod contact;
pub mod design;
pub mod discrete;
pub mod fit;
pub mod gw;
pub mod humidity;
pub mod json;
pub mod limits;
pub mod merge;
pub mod plot;
pub mod range;
pub mod rh;
pub mod run;
pub mod scenario;
pub mod scenario_source;
pub mod study;
pub mod study_folder;
pub mod surface;
pub mod topography;

pub use scenario_source::ScenarioSource;

/// The engine's error: a message for the user (naming the field or input at fault).
pub type Error = Box<dyn std::error::Error>;
