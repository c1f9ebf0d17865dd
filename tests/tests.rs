//! End-to-end tests: run the `stiction` binary on the shipped scenarios and on broken inputs, as a
//! user would. One test binary with modules (as in ripgrep); data in tests/data/.

mod util;

mod bad_inputs;
mod bem;
mod figures;
mod fit_hardening;
mod hardening;
mod height_map_models;
mod models;
mod outputs;
mod scenarios;
mod standalone;
mod study;
mod topography;
