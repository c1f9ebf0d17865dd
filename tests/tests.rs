//! End-to-end tests: run the `stiction` binary on the shipped scenarios and on broken inputs, as a
//! user would. One test binary with modules (as in ripgrep); data in tests/data/.

mod util;

mod bad_inputs;
mod bem;
mod design;
mod figure_data;
mod figure_layout;
mod figures;
mod fit_hardening;
mod hardening;
mod hardening_inputs;
mod hardening_outputs;
mod height_map_models;
mod humidity;
mod models;
mod npy;
mod null_reasons;
mod outputs;
mod own_device;
mod scenarios;
mod slurm;
mod standalone;
mod study;
mod topography;
