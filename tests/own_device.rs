//! A researcher's own device, end to end (docs/own-device.md): the tutorial's steps, and each trap
//! of a copied-and-edited scenario giving the right physics or a clear error.

use crate::util::{num, stiction, stiction_json, temp_dir};

/// Vacuum permittivity, F/m (CODATA 2018).
const EPS0: f64 = 8.854_187_812_8e-12;

fn text(args: &[&str]) -> (i32, String, String) {
    let out = stiction(args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn codes(v: &serde_json::Value) -> Vec<String> {
    v["warnings"]
        .as_array()
        .map(|w| w.iter().map(|x| x["code"].as_str().unwrap_or("").to_string()).collect())
        .unwrap_or_default()
}

/// Trap 1: a copy of the paper's scenario with 50 clamp plates. The conversion factor was
/// calibrated on 30 plates (`calibrated_on`): the as-built gap it implies is kept and a_clamp
/// scales with the plate count. Closed form (parallel plates, fringing off, no back electrode):
/// F = n eps0 l t V^2 / (2 (g - x)^2), so at the same gap a_50 / a_30 = 50 / 30 exactly (to
/// rounding, 1e-12). Before: the calibration silently overrode the geometry and mu_e,a stayed
/// 0.74247. Deliberate bug caught: ignoring `calibrated_on` in ArraySpec::plates.
#[test]
fn fifty_plates_scale_the_clamp_force_by_the_plate_ratio() {
    let paper = stiction_json(&["run", "scenarios/tas2000.json", "--json"]);
    let v = stiction_json(&["run", "scenarios/tas2000.json", "--json", "--set", "actuators.clamp.plate_count=50"]);
    let a30 = num(&paper["reduction"], "a_clamp_n_per_v2");
    let a50 = num(&v["reduction"], "a_clamp_n_per_v2");
    assert!((a50 / a30 - 50.0 / 30.0).abs() < 1e-12, "a_clamp ratio {}", a50 / a30);
    // Every load is the parallel-plate force at 50 plates minus the same spring force.
    let f_spring = num(&v, "spring_force_n");
    for p in v["points"].as_array().unwrap() {
        let vc = num(p, "v_clamp_v");
        let expected = a30 * 50.0 / 30.0 * vc * vc - f_spring;
        assert!((num(p, "true_load_n") - expected).abs() < 1e-12 * a50 * vc * vc, "{p}");
    }
    // A larger clamp force loads the same concave A_r(L) further up: the secant slope mu_e,a falls.
    let (mu30, mu50) = (num(&paper, "mu_apparent"), num(&v, "mu_apparent"));
    assert!(mu50 < mu30 - 0.05, "mu_e,a 50 plates {mu50} vs 30 plates {mu30}");
    let c = codes(&v);
    assert!(c.contains(&"calibration_rederived".to_string()) && c.contains(&"reference_dropped".to_string()), "{c:?}");
    // The paper's own numbers keep no warnings at all.
    assert!(paper.get("warnings").is_none(), "{}", paper["warnings"]);
}

/// Trap 2: a stiffer clamp spring (12 N/m) with the paper's measured F_spring = 7 +/- 2 uN:
/// k x_c = 12 N/m x 0.9 um = 10.8 uN disagrees by 3.8 uN > 2 uN, so the run is refused with an
/// error naming both fields and the way out; without the given value F_spring = k x_c exactly.
/// Before: F_spring = 7.000 uN silently. Deliberate bug caught: skipping
/// `spring_force_conflict` in `run`.
#[test]
fn a_stiffer_spring_is_refused_until_the_spring_force_is_restated() {
    let (code, _, err) = text(&["run", "scenarios/tas2000.json", "--set", "actuators.clamp.spring.stiffness=12 N/m"]);
    assert_eq!(code, 2, "{err}");
    for needle in ["meter.spring_force", "actuators.clamp.spring", "10.8 uN", "--set meter.spring_force=null"] {
        assert!(err.contains(needle), "missing `{needle}` in: {err}");
    }
    let v = stiction_json(&[
        "run",
        "scenarios/tas2000.json",
        "--json",
        "--set",
        "actuators.clamp.spring.stiffness=12 N/m",
        "--set",
        "meter.spring_force=null",
    ]);
    let f = num(&v, "spring_force_n");
    assert!((f - 12.0 * 0.9e-6).abs() < 1e-12 * 10.8e-6, "F_spring = {f}");
    // The paper's own 7 +/- 2 uN against 7.8 N/m x 0.9 um = 7.02 uN agrees: it runs.
    assert_eq!(text(&["run", "scenarios/tas2000.json", "--json"]).0, 0);
    // `fit` reads the same device and refuses the same contradiction (deliberate bug caught:
    // skipping `spring_force_conflict` in `fit`, which then fits with the stale 7 uN).
    let (code, _, err) = text(&[
        "fit",
        "data/measured-voltages-synthetic/voltages.csv",
        "--scenario",
        "scenarios/tas2000.json",
        "--set",
        "actuators.clamp.spring.stiffness=12 N/m",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("meter.spring_force") && err.contains("10.8 uN"), "{err}");
}

/// Trap 3: a device that never reaches the wall over its clamp voltages. Closed form of the
/// voltage at which the clamp's equilibrium reaches the wall: a(x_c) V^2 = k x_c with
/// a(x_c) = n eps0 l t / (2 (g - x_c)^2) (tests/data/own_device.json: n = 50, l = 100 um,
/// t = 5 um, g = 3 um, x_c = 0.9 um, k = 12 N/m): V_c = 20.74 V. Each row says so; no fit, with
/// the reason. Before: "no contact" without a reason. Deliberate bug caught: not setting
/// `reason` on a point without contact.
#[test]
fn a_device_that_never_reaches_the_wall_says_why() {
    let a = 50.0 * EPS0 * 100e-6 * 5e-6 / (2.0 * (2.1e-6f64).powi(2));
    let v_c = (12.0 * 0.9e-6 / a).sqrt();
    let v = stiction_json(&[
        "run",
        "tests/data/own_device.json",
        "--json",
        "--set",
        r#"meter.clamp_voltages={"from": "16 V", "to": "20 V", "steps": 5}"#,
    ]);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    for p in points {
        assert_eq!(p["in_contact"], false, "{p}");
        let reason = p["reason"].as_str().unwrap_or_else(|| panic!("no reason: {p}"));
        assert!(reason.contains("no contact") && reason.contains(&format!("{v_c:.2} V")), "{reason} vs {v_c}");
    }
    assert!(v["mu_apparent"].is_null() && v["fit_note"].is_string(), "{v}");
    let (_, out, _) =
        text(&["run", "tests/data/own_device.json", "--set", "meter.clamp_voltages=[\"19 V\", \"20 V\"]"]);
    assert!(out.contains(&format!("V_clamp is below {v_c:.2} V")), "{out}");
}

/// Trap 4: a short clamp range, and a clamp range mostly without contact. A fit over 3 points
/// (one degree of freedom) and a fit over 3 of 13 clamp voltages warn, in text and JSON.
/// Before: "fit over 3 points ... R^2 = 0.9999" without a warning. Deliberate bug caught:
/// `eq10_warnings` returning nothing.
#[test]
fn a_short_clamp_range_warns() {
    let v = stiction_json(&[
        "run",
        "scenarios/tas2000.json",
        "--json",
        "--set",
        r#"meter.clamp_voltages={"from": "28 V", "to": "29 V", "steps": 3}"#,
    ]);
    assert_eq!(num(&v["fit"], "points"), 3.0);
    assert_eq!(codes(&v).iter().filter(|c| c.as_str() == "few_points").count(), 1, "{}", v["warnings"]);
    // 12 N/m and F_spring = k x_c: the clamp reaches the wall at 27.77 V, 3 of 13 voltages remain.
    let sets = ["--set", "actuators.clamp.spring.stiffness=12 N/m", "--set", "meter.spring_force=null"];
    let mut args = vec!["run", "scenarios/tas2000.json", "--json"];
    args.extend(sets);
    let v = stiction_json(&args);
    let c = codes(&v);
    assert!(c.contains(&"few_points".to_string()) && c.contains(&"partial_clamp_range".to_string()), "{c:?}");
    let no_contact = v["points"].as_array().unwrap().iter().filter(|p| p["in_contact"] == false).count();
    assert_eq!(no_contact, 10);
    let mut args = vec!["run", "scenarios/tas2000.json"];
    args.extend(sets);
    let (_, out, _) = text(&args);
    assert!(out.contains("warning [few_points]") && out.contains("warning [partial_clamp_range]"), "{out}");
}

/// The paper's reference belongs to the paper's device: shown for scenarios/tas2000.json, dropped
/// with a note for an edited copy (here 50 clamp plates), in text and JSON. Deliberate bug caught:
/// not comparing `reference.device` with the scenario's fingerprint.
#[test]
fn the_reference_is_shown_only_for_its_own_device() {
    let (_, out, _) = text(&["run", "scenarios/tas2000.json"]);
    assert!(out.contains("reference, measured (Tas et al., MEMS 2000"), "{out}");
    let (_, out, _) = text(&["run", "scenarios/tas2000.json", "--set", "actuators.clamp.plate_count=50"]);
    assert!(!out.contains("reference, measured"), "{out}");
    assert!(out.contains("warning [reference_dropped]"), "{out}");
    // The model variants of the paper's device (other surfaces, contact models) share its fingerprint.
    let fp = |f: &str| stiction_json(&["scenario", f, "--explain", "--json"])["device"].as_str().unwrap().to_string();
    let paper = fp("scenarios/tas2000.json");
    for f in ["scenarios/tas2000-gw.json", "scenarios/tas2000-two-faces.json", "scenarios/tas2000-discrete.json"] {
        assert_eq!(fp(f), paper, "{f}");
    }
}

/// `stiction scenario FILE` prints the file as it is run, uncertainties and units kept; what it
/// prints loads again and gives the same run. Deliberate bug caught: printing the typed scenario
/// (SI nominal values only) instead of `to_input_json`.
#[test]
fn the_printed_scenario_keeps_its_uncertainties_and_runs_the_same() {
    let dir = temp_dir("own-device-roundtrip");
    let printed = stiction_json(&["scenario", "scenarios/tas2000.json"]);
    assert_eq!(printed["meter"]["spring_force"]["sd"], "2 uN");
    assert_eq!(printed["surface"]["apparent_length"], "20 um");
    assert_eq!(printed["actuators"]["clamp"]["conversion_factor"]["sd"], "0.5e-8 N/V^2");
    let copy = dir.join("copy.json");
    std::fs::write(&copy, serde_json::to_string_pretty(&printed).unwrap()).unwrap();
    let copy = copy.to_string_lossy().to_string();
    let mut a = stiction_json(&["run", "scenarios/tas2000.json", "--json"]);
    let mut b = stiction_json(&["run", &copy, "--json"]);
    a["scenario"] = serde_json::Value::Null;
    b["scenario"] = serde_json::Value::Null;
    assert_eq!(a, b);
}

/// A bad `--set` value names `--set` and the argument, not the scenario file; the humidity gets
/// the same message with `--set` as in a file. Deliberate bug caught: from_value ignoring `sets`.
#[test]
fn set_errors_name_the_set() {
    let (code, _, err) = text(&["run", "scenarios/tas2000.json", "--set", "surface.summit_radius=-1 um"]);
    assert_eq!(code, 2);
    assert!(err.contains("--set surface.summit_radius=-1 um") && !err.contains("tas2000.json: at"), "{err}");
    let (code, _, err) = text(&["run", "scenarios/tas2000.json", "--set", "material.relative_humidity=0.4"]);
    assert_eq!(code, 2);
    assert!(err.contains("--set material.relative_humidity") && err.contains("environment.relative_humidity"), "{err}");
}

/// The tutorial (docs/own-device.md), step by step: the numbers the doc shows.
#[test]
fn the_tutorial_reproduces() {
    // Step 1: --explain. a_clamp from the geometry (closed form above: 2.510e-8 N/V^2), its sd
    // from the gap's 0.1 um; F_spring = k x_c = 10.8 uN derived.
    let (code, out, _) = text(&["scenario", "tests/data/own_device.json", "--explain"]);
    assert_eq!(code, 0);
    for line in [
        "2.510e-8 N/V^2  2.401e-9 N/V^2",
        "derived from actuators.clamp plate geometry and front_gap (sd propagated from front_gap's sd)",
        "10.8 uN         -                 derived: actuators.clamp.spring x contact travel (k x_c)",
        "3.800e-9 N/V^2  8.000e-10 N/V^2   calibrated: actuators.pull.conversion_factor",
    ] {
        assert!(out.contains(line), "missing `{line}` in:\n{out}");
    }
    // Step 2: the run; 3 rows below the contact voltage, mu_e,a with regression and calibration.
    let (code, out, _) = text(&["run", "tests/data/own_device.json"]);
    assert_eq!(code, 0);
    for line in [
        "no contact: V_clamp is below 20.74 V",
        "apparent friction coefficient mu_e,a = 0.609 +/- 0.021",
        "with the conversion factors' sd (+/- 23.1 % on mu_e,a): mu_e,a = 0.609 +/- 0.143",
        "fit over 10 points with L > 0",
    ] {
        assert!(out.contains(line), "missing `{line}` in:\n{out}");
    }
    // The 23.1 %: sqrt((0.8/3.8)^2 + (u(a_clamp)/a_clamp)^2), u(a_clamp)/a_clamp = 2.401/25.10.
    let rel = (0.8f64 / 3.8).hypot(2.401 / 25.10);
    assert!((rel - 0.231).abs() < 5e-4, "{rel}");
    assert!(!out.contains("warning"), "{out}");
}
