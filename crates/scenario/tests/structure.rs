//! The `structure` section: the bundled structure scenarios load; a protocol that does not fit its
//! tangential part, a structure beside the paper's meter, dimples without the discrete model and a
//! released spring given twice are refused naming the field.

use std::path::{Path, PathBuf};

use serde_json::Value;
use stiction_scenario::Scenario;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn load(name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(root().join("scenarios").join(name)).unwrap()).unwrap()
}

fn refuse(v: Value) -> String {
    match Scenario::from_value(v, Path::new("s.json")) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bundled_structures_load() {
    for name in ["comb-sidewall.json", "plate-released-spring.json", "pad-uniform-pressure.json"] {
        let s = Scenario::from_value(load(name), Path::new(name)).unwrap();
        assert!(s.structure.is_some() && s.meter.is_none(), "{name}");
        // The parts are part of the device fingerprint.
        let mut other = load(name);
        if name == "comb-sidewall.json" {
            other["structure"]["normal"]["contact_travel"] = Value::from("3 um");
        } else {
            other["structure"]["normal"]["stiffness"] = Value::from(3.0);
        }
        let o = Scenario::from_value(other, Path::new(name)).unwrap();
        assert_ne!(s.device_fingerprint(), o.device_fingerprint(), "{name}");
    }
}

#[test]
fn misfits_are_refused_naming_the_field() {
    let mut v = load("plate-released-spring.json");
    v["structure"]["protocol"] = serde_json::json!({"kind": "ramp"});
    let e = refuse(v);
    assert!(e.contains("structure.protocol.kind"), "{e}");

    let mut v = load("comb-sidewall.json");
    v["meter"] = load("tas2000.json")["meter"].clone();
    v["actuators"] = load("tas2000.json")["actuators"].clone();
    let e = refuse(v);
    assert!(e.contains("at `actuators`") && e.contains("beside `structure`") && e.contains("one device"), "{e}");

    let mut v = load("pad-uniform-pressure.json");
    v["structure"]["geometry"] = serde_json::json!({"kind": "dimples", "count": 3, "radius": "2 um"});
    let e = refuse(v);
    assert!(e.contains("structure.geometry.kind") && e.contains("discrete"), "{e}");

    let mut v = load("plate-released-spring.json");
    v["structure"]["tangential"]["stiffness"] = Value::from("10 N/m");
    let e = refuse(v);
    assert!(e.contains("structure.tangential") && e.contains("not both"), "{e}");

    let mut v = load("plate-released-spring.json");
    v["structure"]["normal"]["dielectric"][0]["relative_permittivity"] = Value::from(0.5);
    let e = refuse(v);
    assert!(e.contains("relative_permittivity"), "{e}");

    let mut v = load("comb-sidewall.json");
    v["structure"]["normal"]["comb"]["bogus"] = Value::from(1);
    let e = refuse(v);
    assert!(e.contains("bogus"), "{e}");
}
