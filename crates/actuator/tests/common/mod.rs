//! Helpers shared by the integration tests that run the Rauf et al. (JMEMS 2022) gap-closing
//! actuator of scenarios/gca-rauf2022.json. Each test binary uses some of them only.
#![allow(dead_code)]

use std::path::PathBuf;

use stiction_actuator::ArraySpec;

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `gca` array of scenarios/gca-rauf2022.json (format version 1).
pub fn gca_spec() -> ArraySpec {
    let text = std::fs::read_to_string(root().join("scenarios/gca-rauf2022.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["format_version"], 1);
    serde_json::from_value(v["actuators"]["gca"].clone()).unwrap()
}

/// The same array with the drawn finger overlap length `drawn_length_m` \[m\].
pub fn at_length(spec: &ArraySpec, drawn_length_m: f64) -> ArraySpec {
    let mut s = spec.clone();
    s.overlap_length = drawn_length_m;
    s
}
