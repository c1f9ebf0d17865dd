//! Nothing a user can write in a scenario makes stiction panic: a scenario with one field changed
//! to a random value of a random type either runs or fails with an error, and a scenario with a
//! numeric field scaled by a random factor (or negated) does the same through the whole meter.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use proptest::prelude::*;
use serde_json::Value;
use stiction_meter::Meter;
use stiction_scenario::Scenario;

fn paper() -> Value {
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json")).unwrap();
    let mut v: Value = serde_json::from_str(&text).unwrap();
    // Keep each case fast: no shuttle dynamics, three clamp voltages.
    v["meter"].as_object_mut().unwrap().remove("slip_dynamics");
    v["meter"]["clamp_voltages"] = serde_json::json!(["23 V", "26 V", "29 V"]);
    v
}

/// JSON paths of every leaf (number or string) of the tree, in a fixed order.
fn leaves(v: &Value, path: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    match v {
        Value::Object(m) => {
            for (k, c) in m {
                path.push(k.clone());
                leaves(c, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, c) in a.iter().enumerate() {
                path.push(i.to_string());
                leaves(c, path, out);
                path.pop();
            }
        }
        Value::Number(_) | Value::String(_) | Value::Bool(_) => out.push(path.clone()),
        Value::Null => {}
    }
}

fn slot<'a>(v: &'a mut Value, path: &[String]) -> &'a mut Value {
    path.iter().fold(v, |node, seg| match node {
        Value::Array(a) => &mut a[seg.parse::<usize>().unwrap()],
        other => &mut other[seg.as_str()],
    })
}

/// Largest surface a case may generate: the test looks for panics, not for how long a user's
/// legitimately huge request (up to the surface crate's own limit of 2^31 summits) takes.
const TEST_BUDGET_SUMMITS: f64 = 1e6;

/// Parses and, when valid, runs the meter; panics are what the test looks for.
fn parse_and_run(v: Value) -> Result<(), String> {
    let s = Scenario::from_value(v, Path::new("fuzz.json")).map_err(|e| e.to_string())?;
    if let Some(surface) = &s.surface {
        let expected = surface.summit_density.unwrap_or(0.0) * surface.apparent_length * surface.apparent_width;
        if expected > TEST_BUDGET_SUMMITS {
            return Err(format!("{expected:e} summits: beyond the test's budget"));
        }
    }
    let mut m = Meter::from_scenario(&s, Path::new(".")).map_err(|e| e.to_string())?;
    m.run(&mut |_, _| {}).map(|_| ()).map_err(|e| e.to_string())
}

fn random_value() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<f64>().prop_map(|x| serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)),
        any::<i64>().prop_map(Value::from),
        "[ -~]{0,12}".prop_map(Value::String),
        Just(Value::String("1e308 um".into())),
        Just(Value::String("-0 V".into())),
        Just(Value::Bool(true)),
        Just(Value::Null),
        Just(serde_json::json!([])),
        Just(serde_json::json!({})),
        Just(serde_json::json!({"value": "1 um", "sd": "-1 um"})),
    ]
}

proptest! {
    // A fixed seed: the same 400 cases on every run, so CI is reproducible.
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20_001),
        ..ProptestConfig::default()
    })]

    #[test]
    fn any_value_in_any_field_gives_a_result_or_an_error(pick in any::<prop::sample::Index>(), value in random_value()) {
        let mut v = paper();
        let mut all = Vec::new();
        leaves(&v, &mut Vec::new(), &mut all);
        let path = &all[pick.index(all.len())];
        *slot(&mut v, path) = value;
        let outcome = catch_unwind(AssertUnwindSafe(|| parse_and_run(v)));
        prop_assert!(outcome.is_ok(), "panic with {} changed", path.join("."));
    }

    #[test]
    fn scaled_numbers_run_or_fail_cleanly(pick in any::<prop::sample::Index>(), log_factor in -3.0f64..3.0, negate in any::<bool>()) {
        let mut v = paper();
        let mut all = Vec::new();
        leaves(&v, &mut Vec::new(), &mut all);
        let numeric: Vec<&Vec<String>> = all.iter().filter(|p| {
            let mut w = paper();
            let s = slot(&mut w, p);
            s.is_number() || s.as_str().is_some_and(|t| t.trim_start().starts_with(|c: char| c.is_ascii_digit()))
        }).collect();
        let path = numeric[pick.index(numeric.len())];
        let factor = 10f64.powf(log_factor) * if negate { -1.0 } else { 1.0 };
        let target = slot(&mut v, path);
        let scaled = match target.clone() {
            Value::Number(n) => Value::from(n.as_f64().unwrap() * factor),
            Value::String(t) => {
                let split = t.find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == '-' || c == '+')).unwrap_or(t.len());
                let x: f64 = t[..split].parse().unwrap_or(1.0);
                Value::String(format!("{}{}", x * factor, &t[split..]))
            }
            other => other,
        };
        *target = scaled;
        let outcome = catch_unwind(AssertUnwindSafe(|| parse_and_run(v)));
        prop_assert!(outcome.is_ok(), "panic with {} scaled by {factor}", path.join("."));
    }
}
