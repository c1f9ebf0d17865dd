//! The JSON Schema shipped in docs/scenario.schema.json is the one the code generates, and every
//! shipped scenario is valid against it.

use std::path::{Path, PathBuf};

use stiction_scenario::Scenario;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn shipped_schema_is_current() {
    let generated = serde_json::to_string_pretty(&Scenario::json_schema()).unwrap() + "\n";
    let path = root().join("docs/scenario.schema.json");
    if std::env::var_os("STICTION_BLESS").is_some() {
        std::fs::write(&path, &generated).unwrap();
    }
    let shipped = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        shipped == generated,
        "docs/scenario.schema.json is out of date: run `STICTION_BLESS=1 cargo test -p stiction-scenario --test schema`"
    );
}

#[test]
fn every_shipped_scenario_is_valid_against_the_schema() {
    let schema = Scenario::json_schema();
    let validator = jsonschema::validator_for(&schema).expect("the schema compiles");
    let mut count = 0;
    for entry in std::fs::read_dir(root().join("scenarios")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let value: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
            let errors: Vec<String> =
                validator.iter_errors(&value).map(|e| format!("{} at {}", e, e.instance_path())).collect();
            assert!(errors.is_empty(), "{}: {errors:#?}", path.display());
            count += 1;
        }
    }
    assert!(count >= 2);
    // The schema is not vacuous: a wrong type and an unknown field fail it.
    let bad = serde_json::json!({"format_version": 1, "material": {"compliance": true, "work_of_adhesion": 0.1, "shear_strength": 1.4e9}});
    assert!(!validator.is_valid(&bad));
    let unknown = serde_json::json!({"format_version": 1, "surfce": {}});
    assert!(!validator.is_valid(&unknown));
}
