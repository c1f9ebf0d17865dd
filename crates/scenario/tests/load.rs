//! Scenario loading: the shipped files parse, overrides apply, and bad input names path and value.

use std::path::{Path, PathBuf};

use stiction_scenario::{Scenario, ScenarioError};

fn scenarios_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

fn load_str(text: &str, sets: &[&str]) -> Result<Scenario, ScenarioError> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::from_str_with_sets(text, Path::new("test.json"), &sets)
}

#[test]
fn every_shipped_scenario_loads() {
    let mut count = 0;
    for entry in std::fs::read_dir(scenarios_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            Scenario::load(&path, &[]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            count += 1;
        }
    }
    assert!(count >= 1, "no scenario found in {}", scenarios_dir().display());
}

#[test]
fn the_paper_scenario_holds_table_1_in_si() {
    // Table 1 of the paper: eta = 4e12 m^-2, R = 0.5 um, dgamma = 0.1 J/m^2, sigma = 0.04 um, D = 9.1e-12 1/Pa.
    let s = Scenario::load(&scenarios_dir().join("tas2000.json"), &[]).unwrap();
    let surface = s.surface.as_ref().unwrap();
    assert_eq!(surface.summit_density, Some(4e12));
    assert_eq!(surface.summit_sd, Some(0.04e-6));
    assert_eq!(surface.summit_radius, Some(0.5e-6));
    let m = s.material.as_ref().unwrap();
    assert_eq!(m.compliance_per_pa(), 9.1e-12);
    assert_eq!(m.work_of_adhesion, 0.1);
    assert_eq!(m.shear_strength, 1.4e9);
    assert_eq!(s.actuators["clamp"].plate_count, 30);
    assert_eq!(s.actuators["pull"].plate_count, 15);
}

#[test]
fn set_overrides_a_field_with_units() {
    let text = std::fs::read_to_string(scenarios_dir().join("tas2000.json")).unwrap();
    let s = load_str(&text, &["surface.summit_sd=20 nm", "contact.law=\"jkr\""]).unwrap();
    assert_eq!(s.surface.unwrap().summit_sd, Some(20e-9));
    assert_eq!(s.contact.unwrap().law, stiction_contact::single::AdhesionLaw::Jkr);
}

#[test]
fn set_with_a_wrong_path_lists_near_names() {
    let text = std::fs::read_to_string(scenarios_dir().join("tas2000.json")).unwrap();
    let err = load_str(&text, &["surface.sumit_sd=20 nm"]).unwrap_err().to_string();
    assert!(err.contains("sumit_sd") && err.contains("nearest: `summit_sd`"), "{err}");
    let err = load_str(&text, &["materail.hardness=9 GPa"]).unwrap_err().to_string();
    assert!(err.contains("nearest: `material`"), "{err}");
}

#[test]
fn errors_name_the_json_path_the_value_and_the_expectation() {
    let base = r#"{"format_version": 1, "material": {"compliance": "9.1e-12 1/Pa", "work_of_adhesion": "0.1 J/m^2", "shear_strength": "1.4 GPa"}}"#;
    assert!(load_str(base, &[]).is_ok());
    let cases: &[(&str, &[&str])] = &[
        ("material.shear_strength=\"1.4 um\"", &["material.shear_strength", "1.4 um", "expected a positive pressure"]),
        ("material.hardness=\"-9 GPa\"", &["material.hardness", "negative"]),
        ("material.compliance=\"NaN\"", &["material.compliance", "NaN"]),
        ("material.work_of_adhesion=true", &["material.work_of_adhesion", "neither a number nor a string"]),
        ("format_version=2", &["format_version", "2 is not supported"]),
    ];
    for (set, needles) in cases {
        let err = load_str(base, &[set]).unwrap_err().to_string();
        for n in *needles {
            assert!(err.contains(n), "--set {set}: `{err}` lacks `{n}`");
        }
    }
    let unknown = r#"{"format_version": 1, "materials": {}}"#;
    let err = load_str(unknown, &[]).unwrap_err().to_string();
    assert!(err.contains("unknown field `materials`") && err.contains("`material`"), "{err}");
    let syntax = "{\"format_version\": 1,\n \"material\": }";
    let err = load_str(syntax, &[]).unwrap_err().to_string();
    assert!(err.contains("line 2"), "{err}");
}

#[test]
fn the_schema_describes_every_top_level_section() {
    let schema = Scenario::json_schema();
    let props = schema["properties"].as_object().unwrap();
    for key in ["format_version", "surface", "material", "contact", "actuators", "meter"] {
        assert!(props.contains_key(key), "schema lacks {key}");
    }
}

/// The `reference` section (issue 14): the paper scenarios carry the paper's measured values in SI;
/// a scenario without it has none; bad sections are refused with the path.
#[test]
fn reference_values_come_from_the_scenario_and_only_from_it() {
    // Tas et al. 2000, section 5: mu_e,a = 0.7 +/- 0.3, F_a0 = 2.0 +/- 1.3 uN.
    let s = Scenario::load(&scenarios_dir().join("tas2000.json"), &[]).unwrap();
    let r = s.reference.expect("the paper scenario carries the paper's measurement");
    assert_eq!((r.mu_apparent, r.mu_apparent_uncertainty), (Some(0.7), Some(0.3)));
    assert!((r.apparent_adhesion_force.unwrap() - 2.0e-6).abs() < 1e-18);
    assert!((r.apparent_adhesion_force_uncertainty.unwrap() - 1.3e-6).abs() < 1e-18);
    assert_eq!(r.adhesion_text().unwrap(), "2 +/- 1.3 uN");
    assert_eq!(r.mu_text().unwrap(), "0.7 +/- 0.3");
    assert!(r.source.contains("Tas") && !r.uncertainty_meaning.is_empty());
    // Written back with units in the values (study.json, a study's log header), and read again exactly.
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["apparent_adhesion_force"], "2e-6 N");
    assert_eq!(json["apparent_adhesion_force_uncertainty"], "1.3e-6 N");
    let back: stiction_scenario::ReferenceSpec = serde_json::from_value(json).unwrap();
    assert_eq!(back, r);
    // A device of one's own (the synthetic-data scenario) has no reference.
    let s = Scenario::load(&scenarios_dir().join("tas2000-fit-synthetic.json"), &[]).unwrap();
    assert!(s.reference.is_none());
    // --set can add one, in units.
    let text = std::fs::read_to_string(scenarios_dir().join("tas2000-fit-synthetic.json")).unwrap();
    let s = load_str(&text, &[r#"reference={"source": "my lab", "apparent_adhesion_force": "3 uN"}"#]).unwrap();
    assert_eq!(s.reference.unwrap().apparent_adhesion_force, Some(3e-6));
    // Refused: no source, no value, an uncertainty without meaning or value, an uncertain object.
    let base = r#"{"format_version": 1, "reference": REF}"#;
    for (reference, path, what) in [
        (r#"{"source": "", "mu_apparent": 0.7}"#, "reference.source", "missing"),
        (r#"{"source": "x"}"#, "reference.mu_apparent", "missing"),
        (
            r#"{"source": "x", "mu_apparent": 0.7, "mu_apparent_uncertainty": 0.3}"#,
            "reference.uncertainty_meaning",
            "+/-",
        ),
        (
            r#"{"source": "x", "mu_apparent": 0.7, "apparent_adhesion_force_uncertainty": "1 uN", "uncertainty_meaning": "sd"}"#,
            "reference.apparent_adhesion_force_uncertainty",
            "without",
        ),
        (
            r#"{"source": "x", "apparent_adhesion_force": {"value": "2 uN", "sd": "1 uN"}}"#,
            "reference.apparent_adhesion_force",
            "plain value",
        ),
        (r#"{"source": "x", "apparent_adhesion_force": "2 V"}"#, "reference.apparent_adhesion_force", "V"),
        (r#"{"source": "x", "mu_apparent": -0.7}"#, "reference.mu_apparent", "-0.7"),
    ] {
        let err = load_str(&base.replace("REF", reference), &[]).unwrap_err().to_string();
        assert!(err.contains(path) && err.contains(what), "{reference}: {err}");
    }
}
