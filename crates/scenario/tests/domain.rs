//! Every quantity of the scenario format has a physical domain (crates/scenario/src/domain.rs),
//! the bundled scenarios lie inside their domains without a warning, and a value outside is
//! refused naming the field, in the file and through `--set` alike.

use std::path::PathBuf;

use serde_json::Value;
use stiction_scenario::{Scenario, ScenarioError, domain};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn bundled() -> Vec<PathBuf> {
    let mut names: Vec<_> = std::fs::read_dir(root().join("scenarios"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    names.sort();
    names
}

/// The key paths of every quantity field (a `QuantityInput`, a temperature or a plain number that
/// is not a count) in the JSON Schema, with `*` for an actuator array's name.
fn schema_quantities() -> Vec<String> {
    let schema = Scenario::json_schema();
    let defs = schema["$defs"].as_object().unwrap().clone();
    let mut out = Vec::new();
    fn resolve<'a>(v: &'a Value, defs: &'a serde_json::Map<String, Value>) -> &'a Value {
        let mut v = v;
        while let Some(r) = v.get("$ref").and_then(Value::as_str) {
            v = &defs[r.rsplit('/').next().unwrap()];
        }
        v
    }
    fn is_quantity(v: &Value) -> bool {
        let r = v.get("$ref").and_then(Value::as_str).unwrap_or("");
        r.ends_with("QuantityInput") || r.ends_with("TemperatureInput")
    }
    fn walk(v: &Value, path: &str, defs: &serde_json::Map<String, Value>, out: &mut Vec<String>, depth: usize) {
        if depth > 14 {
            return;
        }
        if is_quantity(v) {
            out.push(path.to_string());
            return;
        }
        let v = resolve(v, defs);
        for k in ["anyOf", "oneOf", "allOf"] {
            for alt in v.get(k).and_then(Value::as_array).into_iter().flatten() {
                walk(alt, path, defs, out, depth + 1);
            }
        }
        let number = |t: &Value| t == "number" || t.as_array().is_some_and(|a| a.iter().any(|x| x == "number"));
        if v.get("type").is_some_and(number) && !path.is_empty() {
            out.push(path.to_string());
        }
        if let Some(props) = v.get("properties").and_then(Value::as_object) {
            for (k, x) in props {
                let p = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                walk(x, &p, defs, out, depth + 1);
            }
        }
        if let Some(x) = v.get("additionalProperties").filter(|x| x.is_object()) {
            walk(x, &format!("{path}.*"), defs, out, depth + 1);
        }
        if let Some(x) = v.get("items").filter(|x| x.is_object()) {
            walk(x, &format!("{path}[]"), defs, out, depth + 1);
        }
    }
    walk(&schema, "", &defs, &mut out, 0);
    out.sort();
    out.dedup();
    out
}

/// Every quantity the format takes (by its JSON Schema, so a new field is found without a list
/// kept by hand) has a domain, except the fields that are not physical quantities of the device
/// (the reference's force values are checked by sign, design ranges by the design section).
/// Deliberate bug caught: the table without `material.hardness` fails here.
#[test]
fn every_quantity_of_the_schema_has_a_domain() {
    let quantities = schema_quantities();
    assert!(quantities.len() > 80, "{}", quantities.len());
    let exempt = ["reference.apparent_adhesion_force", "reference.apparent_adhesion_force_uncertainty"];
    let missing: Vec<&String> = quantities
        .iter()
        .filter(|p| !exempt.contains(&p.as_str()) && !p.starts_with("design."))
        .filter(|p| domain::lookup(&p.replace(".*.", ".x.")).is_none() && domain::lookup(p).is_none())
        .collect();
    assert!(missing.is_empty(), "quantities without a domain: {missing:?}");
}

/// docs/reliability.md lists every domain: its table is exactly `stiction scenario --domains`
/// (the table in the code), between the `domains` markers.
#[test]
fn the_documented_domains_are_the_table() {
    let doc = std::fs::read_to_string(root().join("docs/reliability.md")).unwrap();
    let start = doc.find("<!-- domains: begin -->").expect("begin marker") + "<!-- domains: begin -->\n".len();
    let end = doc.find("<!-- domains: end -->").expect("end marker");
    assert_eq!(&doc[start..end], domain::markdown_table(), "regenerate with `stiction scenario --domains`");
}

/// The bundled scenarios lie inside every domain and inside the usual ranges (no
/// `unusual_value` note): the table's bounds are not tighter than the devices they describe.
#[test]
fn bundled_scenarios_are_inside_their_domains_without_a_warning() {
    for path in bundled() {
        let s = Scenario::load(&path, &[]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let unusual: Vec<_> = s.notes.iter().filter(|n| n.code == "unusual_value").collect();
        assert!(unusual.is_empty(), "{}: {unusual:?}", path.display());
    }
}

fn load(sets: &[&str]) -> Result<Scenario, ScenarioError> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&root().join("scenarios/tas2000.json"), &sets)
}

/// The impossible inputs: refused naming the `--set`, the field, the value and the
/// domain; an unusual but valid value runs with a note naming it.
#[test]
fn impossible_values_are_refused_naming_the_field() {
    for (set, field, domain_text) in [
        ("surface.summit_radius=1 m", "surface.summit_radius", "(0, 0.001] m"),
        ("material.work_of_adhesion=1e30", "material.work_of_adhesion", "[0, 10] J/m^2"),
        ("environment={\"relative_humidity\": 0.35, \"temperature\": 186}", "environment.temperature", "273.16"),
        ("actuators.pull.thickness=3 m", "actuators.pull.thickness", "(0, 0.001] m"),
        ("material.compliance=5e-324", "material.compliance", "[1e-13, 1e-5] 1/Pa"),
        // A count is a quantity too: a billion plates printed a 40 N load before it had a domain.
        ("actuators.clamp.plate_count=1000000000", "actuators.clamp.plate_count", "[1, 100000]"),
    ] {
        let e = load(&[set]).unwrap_err().to_string();
        assert!(e.contains(&format!("--set {set}")) && e.contains(field) && e.contains(domain_text), "{set}: {e}");
        assert!(e.len() < 500, "{e}");
    }
    let e = load(&["environment={\"relative_humidity\": 0.35, \"temperature\": 25}"]).unwrap_err().to_string();
    assert!(e.contains("write \"25 C\""), "{e}");
    let e = load(&["environment.relative_humidity=35 deg"]).unwrap_err().to_string();
    assert!(e.contains("no unit but `%`"), "{e}");
    let s = load(&["material.work_of_adhesion=5 J/m^2"]).unwrap();
    assert!(s.notes.iter().any(|n| n.code == "unusual_value" && n.message.contains("material.work_of_adhesion")));
    // The comb's finger count, in a structure scenario.
    let sets = vec!["structure.normal.comb.finger_count=1000000000".to_string()];
    let e = Scenario::load(&root().join("scenarios/comb-sidewall.json"), &sets).unwrap_err().to_string();
    assert!(e.contains("structure.normal.comb.finger_count") && e.contains("[1, 100000]"), "{e}");
}

/// A humidity whose meniscus does not fit the shoe is refused naming the humidity (RH one ulp
/// below 1 gave a Kelvin radius of 2,362 km); 99 % (a 0.1 um meniscus) runs with a note.
#[test]
fn a_kelvin_radius_beyond_the_shoe_is_refused() {
    let e = load(&["environment={\"relative_humidity\": 0.9999999999999999}"]).unwrap_err().to_string();
    assert!(e.contains("environment.relative_humidity") && e.contains("floods"), "{e}");
    let s = load(&["environment={\"relative_humidity\": 0.99}"]).unwrap();
    assert!(s.notes.iter().any(|n| n.message.contains("environment.relative_humidity")), "{:?}", s.notes);
}
