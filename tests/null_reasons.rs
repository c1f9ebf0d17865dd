//! Outputs whose nulls once had no reason beside them: the result check (every null beside its
//! reason, `stiction_units::finite::check_finite`) stopped these commands with an internal error,
//! exit 2, instead of printing. Each case here failed that way before its fix (seen failing: the
//! three commands exited 2 with "internal error: ... is null without a reason").

use crate::util::{root, stiction, stiction_json};

/// The JSON Schema is a specification whose `default: null` is JSON Schema's keyword, not a
/// result: `scenario --schema` prints it, and it is the schema shipped in docs/.
#[test]
fn scenario_schema_prints_the_shipped_schema() {
    let out = stiction(&["scenario", "--schema"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let printed: serde_json::Value = serde_json::from_slice(&out.stdout).expect("schema is JSON");
    let shipped: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join("docs/scenario.schema.json")).unwrap()).unwrap();
    assert_eq!(printed, shipped, "docs/scenario.schema.json differs from `stiction scenario --schema`");
}

/// An array without a stop has no release voltage and no hysteresis: both null, with the reason.
#[test]
fn actuator_without_release_says_why() {
    for array in ["clamp", "pull"] {
        let v = stiction_json(&["actuator", "scenarios/tas2000.json", "--array", array, "--json"]);
        if v["release_voltage_v"].is_null() {
            assert!(v["hysteresis_v"].is_null(), "{array}: {v}");
            let note = v["release_note"].as_str().unwrap_or_else(|| panic!("{array}: no release_note in {v}"));
            assert!(note.contains("stop"), "{array}: {note}");
        } else {
            // With a release voltage: below pull-in (hysteresis > 0) and no note.
            let hysteresis = v["hysteresis_v"].as_f64().expect("hysteresis");
            assert!(hysteresis > 0.0, "{array}: {v}");
            assert!(v.get("release_note").is_none(), "{array}: {v}");
        }
    }
}

/// A scenario without a measured reference of its device: `reference` null, with the reason.
#[test]
fn humidity_without_reference_says_why() {
    let v =
        stiction_json(&["plot", "humidity", "--scenario", "scenarios/tas2000-rough.json", "--rh", "0.3,0.6", "--json"]);
    assert!(v["reference"].is_null(), "tas2000-rough.json has no reference of its device: {}", v["reference"]);
    assert!(v["reference_note"].as_str().is_some_and(|n| n.contains("reference")), "{}", v["reference_note"]);
    // With a reference (the paper's scenario), no note.
    let v = stiction_json(&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "0.3", "--json"]);
    assert!(v["reference"].is_object() && v.get("reference_note").is_none(), "{}", v["reference"]);
}
