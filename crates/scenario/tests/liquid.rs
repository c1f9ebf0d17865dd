//! The condensing liquid of `environment.liquid`: water (the default, unchanged), 1-pentanol
//! (handbook values) and a liquid given by its properties; the Kelvin radius follows the Kelvin
//! equation `r_K = gamma V_m / (R T ln(p_sat/p))` in each case.

use std::path::PathBuf;

use serde_json::{Value, json};
use stiction_contact::capillary::{GAS_CONSTANT_J_PER_MOL_K, Liquid};
use stiction_scenario::Scenario;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The paper's meter in humid air (scenarios/tas2000-humid.json) with `environment` replaced.
fn humid_with(environment: Value, contact_angle: Option<&str>) -> Result<Scenario, String> {
    let path = root().join("scenarios/tas2000-humid.json");
    let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    v["environment"] = environment;
    match contact_angle {
        Some(a) => v["material"]["contact_angle"] = json!(a),
        None => {
            v["material"].as_object_mut().unwrap().remove("contact_angle");
        }
    }
    Scenario::from_value(v, &path).map_err(|e| e.to_string())
}

/// `"liquid": "water"` is the default: the same capillarity to the bit as no `liquid`.
/// Deliberate bug caught: water's Kelvin length taken from another liquid.
#[test]
fn water_by_name_is_the_default_to_the_bit() {
    let none = humid_with(json!({"relative_humidity": "35 %", "temperature": "25 C"}), Some("0 deg")).unwrap();
    let named =
        humid_with(json!({"relative_humidity": "35 %", "temperature": "25 C", "liquid": "water"}), Some("0 deg"))
            .unwrap();
    let a = none.capillarity().unwrap().unwrap();
    let b = named.capillarity().unwrap().unwrap();
    assert_eq!(a, b);
    assert_eq!(a.kelvin_radius_m.to_bits(), Liquid::water(298.15).kelvin_radius_m(298.15, 0.35).to_bits());
}

/// 1-pentanol at 95 % of its saturation pressure, 25 C, fully wetting (the vapour-phase
/// lubrication experiment's highest pressure): r_K = 1.1120 nm / ln(1/0.95) = 21.68 nm (handbook
/// gamma 25.36 mN/m, V_m 108.72 cm^3/mol; to 0.2 %), and h_m = 2 r_K. At 20 % of saturation
/// r_K = 0.691 nm. Deliberate bug caught: water's correlations for every liquid (r_K = 10.2 nm).
#[test]
fn pentanol_kelvin_radius_at_the_experiments_pressures() {
    for (x, want) in [(0.95, 21.68e-9), (0.2, 0.6909e-9)] {
        let s =
            humid_with(json!({"relative_humidity": x, "temperature": "25 C", "liquid": "1-pentanol"}), None).unwrap();
        let c = s.capillarity().unwrap().unwrap();
        assert!((c.kelvin_radius_m - want).abs() < 2e-3 * want, "{x}: {}", c.kelvin_radius_m);
        assert!((c.meniscus_height_m() - 2.0 * c.kelvin_radius_m).abs() < 1e-15 * want);
        assert!((c.surface_tension_n_per_m - 25.36e-3).abs() < 0.01e-3);
    }
}

/// A liquid given by its properties: the Kelvin radius is the Kelvin equation of the given
/// numbers (closed form, to 1e-12), its own contact angle is used, and the explanation lists its
/// properties and the partial pressure p = (p/p_sat) p_sat. Ethanol at 25 C (CRC Handbook:
/// gamma 21.97 mN/m, V_m 58.68 cm^3/mol, p_sat 7.87 kPa).
#[test]
fn a_given_liquid_follows_the_kelvin_equation() {
    let env = json!({
        "relative_humidity": 0.5,
        "temperature": "25 C",
        "liquid": {
            "name": "ethanol",
            "surface_tension": "21.97 mN/m",
            "molar_volume": "58.68 cm^3/mol",
            "saturation_pressure": "7.87 kPa",
            "contact_angle": "20 deg",
            "source": "CRC Handbook of Chemistry and Physics (surface tension, density, vapour pressure at 25 C)"
        }
    });
    let s = humid_with(env.clone(), None).unwrap();
    let c = s.capillarity().unwrap().unwrap();
    let want = 21.97e-3 * 58.68e-6 / (GAS_CONSTANT_J_PER_MOL_K * 298.15 * (1.0f64 / 0.5).ln());
    assert!((c.kelvin_radius_m - want).abs() <= 1e-12 * want, "{} vs {want}", c.kelvin_radius_m);
    assert!((c.cos_angle_sum - 2.0 * 20f64.to_radians().cos()).abs() < 1e-12);
    let e = s.explain();
    let q = |k: &str| e.quantities.iter().find(|q| q.key == k).unwrap_or_else(|| panic!("no {k}")).value;
    assert!((q("partial_pressure") - 3935.0).abs() < 1e-9);
    assert!((q("molar_volume") - 58.68e-6).abs() < 1e-18);
    // a surface tension is a force per length: printed in N/m (it is numerically J/m^2)
    let tension = e.quantities.iter().find(|q| q.key == "surface_tension").unwrap();
    assert_eq!(tension.value_text(), "0.02197 N/m");
    // the contact angle in two places is refused, naming the liquid's field
    let err = humid_with(env, Some("0 deg")).unwrap_err();
    assert!(err.contains("environment.liquid.contact_angle"), "{err}");
}

/// Bad liquids are refused with the field named: an unknown name, a missing source, a molar volume
/// in the wrong unit, 1-pentanol outside the temperatures of its correlations.
#[test]
fn bad_liquids_are_refused_naming_the_field() {
    let err = humid_with(json!({"relative_humidity": 0.5, "liquid": "pentanol"}), None).unwrap_err();
    assert!(err.contains("unknown liquid") && err.contains("1-pentanol"), "{err}");
    let err = humid_with(
        json!({"relative_humidity": 0.5, "liquid": {"name": "x", "surface_tension": "22 mN/m",
               "molar_volume": "58 cm^3/mol", "saturation_pressure": "7 kPa"}}),
        None,
    )
    .unwrap_err();
    assert!(err.contains("source"), "{err}");
    let err = humid_with(
        json!({"relative_humidity": 0.5, "liquid": {"name": "x", "surface_tension": "22 mN/m",
               "molar_volume": "58 cm^3", "saturation_pressure": "7 kPa", "source": "s"}}),
        None,
    )
    .unwrap_err();
    assert!(err.contains("molar volume"), "{err}");
    let err =
        humid_with(json!({"relative_humidity": 0.5, "temperature": "60 C", "liquid": "1-pentanol"}), None).unwrap_err();
    assert!(err.contains("environment.temperature") && err.contains("1-pentanol"), "{err}");
}

/// The published experiments (scenarios/published/, docs/published.md) are valid against the
/// schema, load, and state their source: a description and a reference with a source, a device
/// fingerprint that is their own, and a measured value (mu or an adhesion force).
#[test]
fn published_scenarios_are_valid_and_state_their_source() {
    let schema = Scenario::json_schema();
    let validator = jsonschema::validator_for(&schema).expect("the schema compiles");
    let mut count = 0;
    for entry in std::fs::read_dir(root().join("scenarios/published")).unwrap() {
        let path = entry.unwrap().path();
        let value: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let errors: Vec<String> =
            validator.iter_errors(&value).map(|e| format!("{e} at {}", e.instance_path())).collect();
        assert!(errors.is_empty(), "{}: {errors:#?}", path.display());
        let s = Scenario::load(&path, &[]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            value["description"].as_str().is_some_and(|d| d.contains("read") || d.contains("full text")),
            "{}",
            path.display()
        );
        let r = s.reference.as_ref().unwrap_or_else(|| panic!("{}: no reference kept", path.display()));
        assert!(!r.source.is_empty());
        assert!(r.mu_apparent.is_some() || r.apparent_adhesion_force.is_some(), "{}", path.display());
        count += 1;
    }
    assert!(count >= 6, "{count}");
}
