//! Bounded work of the meter's `bem` contact model for any input: the bundled boundary-element
//! scenario (scenarios/tas2000-bem.json, kept small: six clamp voltages, no slip dynamics, the
//! patch coarsened to at most 4000 points) with each of its quantity fields at the ends of its
//! physical domain and beyond them, on the finite patch (default) and the periodic cell, flat and
//! tilting, and with the hardness cap (`contact.bem.plastic`, the hardness `material.hardness`):
//!
//! * a value outside its domain is refused naming the field (a generated rms height of 1e30 m and
//!   a clamp thickness of 9e18 m are two of them: before the domains, they kept the meter busy
//!   for minutes);
//! * a value inside runs to a result that holds its invariants (real area within the apparent
//!   area, a friction or a reason at every point, every number finite) or is refused with a
//!   message; every solve is bounded by the solver's caps (conjugate-gradient iterations,
//!   cohesive-zone updates, pose solves of the tilting shoe), each of which ends in an explicit
//!   non-convergence error. Reaching the end of this test is the bound; its time is printed, not
//!   asserted.

use std::path::Path;

use stiction_meter::Meter;
use stiction_scenario::{Scenario, domain};

mod common;
use common::root;

fn base_text() -> String {
    let mut v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root().join("scenarios/tas2000-bem.json")).unwrap()).unwrap();
    let meter = v.get_mut("meter").and_then(serde_json::Value::as_object_mut).unwrap();
    meter.insert("clamp_voltages".into(), serde_json::json!({"from": "18 V", "to": "30 V", "steps": 6}));
    meter.remove("slip_dynamics");
    v["contact"]["bem"]["points"] = serde_json::json!(4000);
    serde_json::to_string(&v).unwrap()
}

/// Runs one case; `Ok(true)` when it ran, `Ok(false)` when refused with a message.
fn run(text: &str, sets: &[String]) -> Result<bool, String> {
    let s = match Scenario::from_str_with_sets(text, Path::new("tas2000-bem.json"), sets) {
        Ok(s) => s,
        Err(e) => return if e.to_string().trim().is_empty() { Err("empty error".into()) } else { Ok(false) },
    };
    let surface = s.surface.as_ref().ok_or("no surface")?;
    let a_a = surface.apparent_length * surface.apparent_width;
    let mut m = match Meter::from_scenario(&s, &root().join("scenarios")) {
        Ok(m) => m,
        Err(e) => return if e.to_string().trim().is_empty() { Err("empty error".into()) } else { Ok(false) },
    };
    let r = match m.run(&mut |_, _| {}) {
        Ok(r) => r,
        Err(e) => return if e.to_string().trim().is_empty() { Err("empty error".into()) } else { Ok(false) },
    };
    for (i, p) in r.points.iter().enumerate() {
        if p.real_area_m2 > a_a * (1.0 + 1e-9) || p.real_area_m2 < 0.0 {
            return Err(format!("point {i}: A_r {} beyond A_a {a_a}", p.real_area_m2));
        }
        if p.friction_n.is_none() && p.reason.is_none() {
            return Err(format!("point {i}: no friction and no reason"));
        }
    }
    stiction_units::finite::check_finite(&r).map_err(|e| e.to_string())?;
    Ok(true)
}

#[test]
fn every_bem_input_is_refused_or_runs_to_a_bounded_result() {
    let text = base_text();
    let start = std::time::Instant::now();
    // The two inputs of the report, outside their domains: refused naming the field.
    for (set, field) in [
        ("surface.height_map.generated.rms_height=1e30 m", "surface.height_map.generated.rms_height"),
        ("actuators.clamp.thickness=9e18 m", "actuators.clamp.thickness"),
    ] {
        let e = Scenario::from_str_with_sets(&text, Path::new("x.json"), &[set.to_string()]).unwrap_err().to_string();
        assert!(e.contains(field), "{set}: {e}");
    }
    let fields = [
        "surface.height_map.generated.rms_height",
        "surface.height_map.generated.correlation_length",
        "material.compliance",
        "material.work_of_adhesion",
        "material.equilibrium_spacing",
        "contact.bem.tolerance",
        "contact.bem.range",
        "actuators.clamp.thickness",
    ];
    let shoes: [&[&str]; 3] = [&[], &["contact.bem.boundary=\"periodic\""], &["contact.bem.tilt=true"]];
    let (mut ran, mut refused) = (0, 0);
    for field in fields {
        let d = domain::lookup(field).unwrap_or_else(|| panic!("{field}: no domain"));
        let lo = if d.min_inclusive {
            d.min
        } else if d.min == 0.0 {
            d.max * 1e-12
        } else {
            d.min * (1.0 + 1e-9)
        };
        let hi = d.max;
        for (value, inside) in [(lo, true), (hi, true), (hi * 10.0 + 1.0, false)] {
            for shoe in shoes {
                let mut sets: Vec<String> = shoe.iter().map(|s| s.to_string()).collect();
                sets.push(format!("{field}={value:e}"));
                let t = std::time::Instant::now();
                let outcome = run(&text, &sets).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
                eprintln!(
                    "{sets:?}: {} in {:.2} s",
                    if outcome { "ran" } else { "refused" },
                    t.elapsed().as_secs_f64()
                );
                if !inside {
                    assert!(!outcome, "{sets:?}: outside the domain and ran");
                }
                if outcome { ran += 1 } else { refused += 1 }
            }
        }
    }
    // A tilting shoe on the periodic cell is refused naming the field (when the scenario is read).
    let sets = vec!["contact.bem.boundary=\"periodic\"".to_string(), "contact.bem.tilt=true".to_string()];
    let e = Scenario::from_str_with_sets(&text, Path::new("x.json"), &sets).unwrap_err().to_string();
    assert!(e.contains("contact.bem.tilt"), "{e}");
    // The hardness cap: the hardness at the ends of its domain and beyond, a hardness below every
    // mean pressure (each point a null with its reason), with and without adhesion;
    // beside a tilting shoe, below.
    let d = domain::lookup("material.hardness").unwrap();
    for (value, inside) in [(d.max * 1e-12, true), (1.0, true), (d.max, true), (d.max * 10.0, false), (-1.0, false)] {
        for law in ["contact.law=\"hertz\"", "contact.law=\"dmt\""] {
            let sets: Vec<String> = [law.to_string(), "contact.bem.plastic=true".to_string()]
                .into_iter()
                .chain([format!("material.hardness={value:e} Pa")])
                .collect();
            let outcome = run(&text, &sets).unwrap_or_else(|e| panic!("{sets:?}: {e}"));
            eprintln!("{sets:?}: {}", if outcome { "ran" } else { "refused" });
            assert_eq!(outcome, inside, "{sets:?}");
        }
    }
    // The cap beside a tilting shoe, at the ends of the hardness's domain: it runs (each pose
    // capped; a pose the set solve cannot take is a null with its reason).
    for value in [d.max * 1e-12, d.max] {
        let sets: Vec<String> = ["contact.law=\"dmt\"", "contact.bem.plastic=true", "contact.bem.tilt=true"]
            .iter()
            .map(|s| s.to_string())
            .chain([format!("material.hardness={value:e} Pa")])
            .collect();
        assert_eq!(run(&text, &sets), Ok(true), "{sets:?}");
    }
    eprintln!("{ran} ran, {refused} refused, {:.1} s in all", start.elapsed().as_secs_f64());
    assert!(ran > 10, "{ran}");
}
