//! End-to-end tests: run the `stiction` binary on the shipped scenarios and on broken inputs, as a
//! user would. One test binary with modules (as in ripgrep); data in tests/data/.

mod util;

mod bad_inputs;
mod bem;
mod figures;
mod hardening;
mod hardening_inputs;
mod models;
mod outputs;
mod scenarios;
mod standalone;
mod study;
mod topography;
