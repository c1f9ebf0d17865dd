//! The physical-domain fuzzer: extreme but parseable values of every quantity field of every
//! bundled scenario (the paper's meter and the structures built from parts), through the code the binary runs (`Scenario::from_str_with_sets` with a
//! `--set`, `Meter::from_scenario`, `Meter::run`), checked for what the numbers mean, not only for
//! crashes:
//!
//! * a value outside its domain (`stiction_scenario::domain`) is refused naming the field;
//! * a value inside it either runs or is refused with a message (a field, or the inputs of a
//!   broken invariant), never a panic;
//! * a result that runs holds its invariants: every point's real area within the apparent area,
//!   contacts within the summits, the capillary load within the adhesive load, a friction only
//!   with a slip; mu_e,a present exactly when `fit_note` is absent, and then finite and positive
//!   with a finite F_a0; the whole result serialises with every number finite and every null
//!   with a reason (`stiction_units::finite::check_finite`).
//!
//! Short mode (the default, 400 cases) runs in CI; `STICTION_FUZZ_CASES=20000` for the long run
//! (docs/reliability.md gives its counts).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

use serde_json::Value;
use stiction_meter::Meter;
use stiction_scenario::{Scenario, domain};

mod common;
use common::{Rng, root};

fn cases() -> usize {
    common::cases(400)
}

/// The bundled scenarios with a meter, kept small: six clamp voltages (18 to 30 V), a summit budget of
/// 20 000, no slip dynamics (the fuzzer checks meaning, not how long a large request takes).
fn scenarios() -> Vec<(String, Value)> {
    let mut out = Vec::new();
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join("scenarios"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    for p in paths {
        let mut v: Value = serde_json::from_str(&std::fs::read_to_string(&p).unwrap()).unwrap();
        if let Some(meter) = v.get_mut("meter").and_then(Value::as_object_mut) {
            meter.insert("clamp_voltages".into(), serde_json::json!({"from": "18 V", "to": "30 V", "steps": 6}));
            meter.remove("slip_dynamics");
        } else if let Some(structure) = v.get_mut("structure").and_then(Value::as_object_mut) {
            // A structure built from parts: its own normal voltages, three of them.
            if let Some(Value::Object(r)) = structure.get_mut("normal_voltages") {
                r.insert("steps".into(), Value::from(3));
            }
        } else {
            continue;
        }
        if let Some(s) = v.get_mut("surface").and_then(Value::as_object_mut) {
            s.insert("max_summits".into(), Value::from(20_000));
        }
        if v.pointer("/contact/model").and_then(Value::as_str) == Some("bem") {
            continue; // the boundary-element model has its own fuzzing (crates/bem)
        }
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        // A humid scenario once more with a liquid given by its properties (ethanol, CRC values at
        // 25 C), so that the liquid's fields are fuzzed like the others.
        if v.get("environment").is_some() {
            let mut given = v.clone();
            given["environment"]["liquid"] = serde_json::json!({
                "name": "ethanol", "surface_tension": "21.97 mN/m", "molar_volume": "58.68 cm^3/mol",
                "saturation_pressure": "7.87 kPa", "contact_angle": "10 deg", "source": "CRC Handbook, 25 C"
            });
            if let Some(m) = given.get_mut("material").and_then(Value::as_object_mut) {
                m.remove("contact_angle");
                m.remove("counter_face_contact_angle");
            }
            out.push((format!("{name} + ethanol"), given));
        }
        // The comb tester once more with the lowered-normal protocol, so that every protocol of a
        // structure is fuzzed (ramp and release are the bundled ones').
        if name == "comb-sidewall.json" {
            let mut lowered = v.clone();
            lowered["structure"]["protocol"] =
                serde_json::json!({"kind": "lower_normal", "tangential_voltages": ["20 V", "30 V"]});
            out.push((format!("{name} + lower_normal"), lowered));
        }
        out.push((name, v));
    }
    out
}

/// The dotted paths of the numeric leaves (outside lists) of a typed scenario that have a domain.
fn quantity_paths(typed: &Value, prefix: &str, out: &mut Vec<String>) {
    if let Value::Object(map) = typed {
        for (k, v) in map {
            let p = if prefix.is_empty() { k.clone() } else { format!("{prefix}.{k}") };
            match v {
                Value::Number(_) if domain::lookup(&p).is_some() => out.push(p),
                Value::Object(_) => quantity_paths(v, &p, out),
                _ => {}
            }
        }
    }
}

/// A value for `d`: its bounds, just outside them, its usual range's ends, a log-uniform draw
/// inside it or a wild power of ten.
fn value_for(d: &domain::Domain, rng: &mut Rng) -> f64 {
    let inside = |rng: &mut Rng| {
        let lo = if d.min > 0.0 { d.min } else { (d.max * 1e-12).max(1e-30) };
        (lo.ln() + rng.unit() * (d.max.ln() - lo.ln())).exp()
    };
    match rng.below(9) {
        0 => d.min,
        1 => d.max,
        2 => d.min - d.min.abs().max(1e-300) * 1e-6,
        3 => d.max * (1.0 + 1e-6),
        4 => d.usual.0,
        5 => d.usual.1,
        6 => 10f64.powi(rng.below(80) as i32 - 40),
        _ => inside(rng),
    }
}

#[derive(Default, Debug)]
struct Counts {
    refused_outside: usize,
    refused_inside: usize,
    ran: usize,
    no_fit: usize,
    meter_errors: usize,
    invariant_errors: usize,
}

/// Checks the invariants of a result; `Err` says which broke.
fn check_result(r: &stiction_meter::MeterResult, apparent_area_m2: f64) -> Result<(), String> {
    for (i, p) in r.points.iter().enumerate() {
        if p.real_area_m2 > apparent_area_m2 * (1.0 + 1e-9) || p.real_area_m2 < 0.0 {
            return Err(format!("point {i}: A_r {} beyond A_a {apparent_area_m2}", p.real_area_m2));
        }
        if let Some(c) = p.capillary_load_n
            && (c < -1e-18 || c > p.adhesive_load_n * (1.0 + 1e-9) + 1e-18)
        {
            return Err(format!("point {i}: capillary {c} outside [0, {}]", p.adhesive_load_n));
        }
        // A friction with a slip: a pull (tangential) voltage, or a released spring's displacement.
        if p.friction_n.is_some() != (p.v_pull.is_some() || p.displacement_m.is_some()) {
            return Err(format!("point {i}: a friction without a slip or the reverse"));
        }
        if p.friction_n.is_none() && p.reason.is_none() {
            return Err(format!("point {i}: no friction and no reason"));
        }
    }
    match (r.mu_apparent, &r.fit_note) {
        (Some(mu), None) => {
            let fa0 = r.apparent_adhesion_force_n.ok_or("mu without F_a0")?;
            if !(mu.is_finite() && mu > 0.0 && fa0.is_finite()) {
                return Err(format!("mu {mu}, F_a0 {fa0}"));
            }
        }
        (None, Some(note)) if !note.trim().is_empty() => {}
        (mu, note) => return Err(format!("mu {mu:?} with note {note:?}: one exactly")),
    }
    stiction_units::finite::check_finite(r).map_err(|e| e.to_string())
}

#[test]
fn extreme_values_of_every_field_are_refused_or_give_results_that_hold_their_invariants() {
    let all = scenarios();
    assert!(all.len() >= 8, "{}", all.len());
    let mut rng = Rng(common::seed(33));
    let mut counts = Counts::default();
    let base = root().join("scenarios");
    let prepared: Vec<(String, String, Vec<String>)> = all
        .iter()
        .map(|(name, v)| {
            let text = serde_json::to_string(v).unwrap();
            let typed =
                serde_json::to_value(Scenario::from_str_with_sets(&text, Path::new(name), &[]).unwrap()).unwrap();
            let mut paths = Vec::new();
            quantity_paths(&typed, "", &mut paths);
            paths.retain(|p| !p.ends_with("max_summits"));
            (name.clone(), text, paths)
        })
        .collect();
    for case in 0..cases() {
        let (name, text, paths) = &prepared[rng.below(prepared.len())];
        let path = &paths[rng.below(paths.len())];
        let d = domain::lookup(path).unwrap();
        let value = value_for(d, &mut rng);
        let set = format!("{path}={value:e}");
        let label = format!("case {case}: {name} --set {set}");
        let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<(), String> {
            let parsed = Scenario::from_str_with_sets(text, Path::new(name), std::slice::from_ref(&set));
            let s = match parsed {
                Err(e) => {
                    let msg = e.to_string();
                    if !msg.contains("at `") && !msg.contains("--set") {
                        return Err(format!("error names no field: {msg}"));
                    }
                    if d.contains(value) {
                        counts.refused_inside += 1;
                    } else {
                        if !msg.contains(path.as_str()) {
                            return Err(format!("outside its domain but the error does not name it: {msg}"));
                        }
                        counts.refused_outside += 1;
                    }
                    return Ok(());
                }
                Ok(s) => s,
            };
            if !d.contains(value) {
                return Err(format!("{value:e} is outside {} and was accepted", d.range_text()));
            }
            let surface = s.surface.as_ref().ok_or("no surface")?;
            let a_a = surface.apparent_length * surface.apparent_width;
            let mut m = match Meter::from_scenario(&s, &base) {
                Ok(m) => m,
                Err(_) => {
                    counts.meter_errors += 1;
                    return Ok(());
                }
            };
            match m.run(&mut |_, _| {}) {
                Ok(r) => {
                    check_result(&r, a_a)?;
                    counts.ran += 1;
                    if r.mu_apparent.is_none() {
                        counts.no_fit += 1;
                    }
                }
                Err(e) => {
                    let msg = e.to_string();
                    if msg.trim().is_empty() {
                        return Err("an empty error".into());
                    }
                    if msg.contains("breaks a physical invariant") {
                        counts.invariant_errors += 1;
                    }
                    counts.meter_errors += 1;
                }
            }
            Ok(())
        }));
        match outcome {
            Ok(Ok(())) => {}
            Ok(Err(e)) => panic!("{label}: {e}"),
            Err(_) => panic!("{label}: panicked"),
        }
    }
    println!("domain fuzz: {} cases, {counts:?}", cases());
    assert!(counts.ran > 0 && counts.refused_outside > 0, "{counts:?}");
}
