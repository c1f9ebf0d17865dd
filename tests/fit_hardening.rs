//! `stiction fit` as a hostile or careless user meets it: zero surfaces, equal pull voltages,
//! semicolon files, too many distinct clamp voltages.

use crate::util::{stiction, stiction_json, temp_dir};

const SCENARIO: &str = "scenarios/tas2000-discrete.json";

/// `--surfaces 0` is an error with status 2, not a success with a "failed" row.
#[test]
fn zero_surfaces_exits_2() {
    let out =
        stiction(&["fit", "data/measured-voltages-synthetic/voltages.csv", "--scenario", SCENARIO, "--surfaces", "0"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--surfaces 0") && err.contains("expected 1 to"), "{err}");
}

/// All pull voltages equal: mu_e,a and F_a0 are null with the reason in JSON and text, no model
/// is ranked, and nothing prints `inf` or `NaN`.
#[test]
fn equal_pull_voltages_are_nulls_with_reasons() {
    let dir = temp_dir("fit-flat");
    let file = dir.join("flat.csv");
    let mut text = String::from("v_clamp_v,v_pull_v\n");
    for k in 0..13 {
        text.push_str(&format!("{},30\n", 23.0 + 0.5 * k as f64));
    }
    std::fs::write(&file, text).unwrap();
    let f = file.to_str().unwrap();
    let v = stiction_json(&["fit", f, "--scenario", SCENARIO, "--models", "discrete-n1,gw-dmt", "--json"]);
    assert!(v["mu_apparent"]["value"].is_null() && v["apparent_adhesion_force_n"]["value"].is_null(), "{v}");
    assert!(v["mu_apparent"]["value_note"].as_str().unwrap().contains("same pull voltage"));
    assert_eq!(v["models"].as_array().unwrap().len(), 0);
    assert_eq!(v["models_failed"].as_array().unwrap().len(), 2);
    let out = stiction(&["fit", f, "--scenario", SCENARIO, "--models", "discrete-n1,gw-dmt"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for bad in ["inf", "NaN", "fits best"] {
        assert!(!text.contains(bad), "`{bad}` in:\n{text}");
    }
    assert!(text.contains("mu_e,a = n/a: all 13 rows"), "{text}");
}

/// A semicolon-separated file (a spreadsheet export) gives the same fit as the comma file.
#[test]
fn semicolon_files_fit_like_comma_files() {
    let dir = temp_dir("fit-semicolon");
    let comma =
        std::fs::read_to_string(crate::util::root().join("data/measured-voltages-synthetic/voltages.csv")).unwrap();
    let file = dir.join("semi.csv");
    std::fs::write(&file, comma.replace(',', ";")).unwrap();
    let args = |d: &str| {
        stiction_json(&["fit", d, "--scenario", SCENARIO, "--models", "discrete-n3", "--draws", "100", "--json"])
    };
    let a = args("data/measured-voltages-synthetic/voltages.csv");
    let b = args(file.to_str().unwrap());
    assert_eq!(a["mu_apparent"], b["mu_apparent"]);
    assert_eq!(a["models"][0]["shear_strength_pa"], b["models"][0]["shear_strength_pa"]);
}

/// The text names both intervals of s: the noise-only one and the one with the calibration.
#[test]
fn both_intervals_of_s_are_printed_and_labelled() {
    let out = stiction(&[
        "fit",
        "data/measured-voltages-synthetic/voltages.csv",
        "--scenario",
        SCENARIO,
        "--models",
        "discrete-n3",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("95 % noise only (GPa)") && text.contains("95 % with calibration (GPa)"), "{text}");
    assert!(text.contains("variance shares of s: a_clamp"), "{text}");
    let v = stiction_json(&[
        "fit",
        "data/measured-voltages-synthetic/voltages.csv",
        "--scenario",
        SCENARIO,
        "--models",
        "discrete-n3",
        "--json",
    ]);
    let s = &v["models"][0]["shear_strength_pa"];
    assert!(s["ci95_meaning"].as_str().unwrap().starts_with("noise only"), "{s}");
    let [lo, hi] = [s["ci95_with_calibration"][0].as_f64().unwrap(), s["ci95_with_calibration"][1].as_f64().unwrap()];
    let [nlo, nhi] = [s["ci95"][0].as_f64().unwrap(), s["ci95"][1].as_f64().unwrap()];
    assert!(lo < nlo && hi > nhi, "calibration interval [{lo}, {hi}] inside the noise one [{nlo}, {nhi}]");
    let shares: f64 = s["variance_shares"].as_object().unwrap().values().map(|x| x.as_f64().unwrap()).sum();
    assert!((shares - 1.0).abs() < 1e-9, "{s}");
}

/// More distinct clamp voltages than the documented limit: a clear error, at once.
#[test]
fn too_many_distinct_clamp_voltages_is_refused() {
    let dir = temp_dir("fit-distinct");
    let file = dir.join("distinct.csv");
    let mut text = String::from("v_clamp_v,v_pull_v\n");
    for k in 0..6000 {
        let v = 23.0 + 6.0 * k as f64 / 6000.0;
        text.push_str(&format!("{v:.6},{:.3}\n", 20.0 + 0.5 * v));
    }
    std::fs::write(&file, text).unwrap();
    let out = stiction(&["fit", file.to_str().unwrap(), "--scenario", SCENARIO]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("6000 distinct clamp voltages") && err.contains("at most 5000"), "{err}");
}

/// `stiction fit` with a `structure` scenario: a threshold file's bad cell exits 2 naming the line
/// and column, contact-model flags and `--synthesize` are refused naming them, a file whose
/// columns do not fit the parts is refused naming both, a row past the normal comb's side pull-in
/// is listed with its reason instead of a load, and `--out` writes the report and its figure.
#[test]
fn structure_thresholds_are_fitted_or_refused_by_name() {
    let dir = temp_dir("fit-structure");
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "v_normal_v,displacement_m\n0.9,2e-7\n1.1,x\n").unwrap();
    let plate = "scenarios/plate-released-spring.json";
    let out = stiction(&["fit", bad.to_str().unwrap(), "--scenario", plate]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("line 3") && err.contains("`displacement_m`"), "{err}");
    let good = dir.join("comb.csv");
    std::fs::write(&good, "v_normal_v,v_tangential_v\n30,20\n40,25\n50,29.5\n60,33\n85,40\n").unwrap();
    let g = good.to_str().unwrap();
    for flags in [&["--models", "gw-dmt"][..], &["--free", "s,R"], &["--surfaces", "3"]] {
        let mut args = vec!["fit", g, "--scenario", "scenarios/comb-sidewall.json"];
        args.extend_from_slice(flags);
        let out = stiction(&args);
        assert_eq!(out.status.code(), Some(2), "{flags:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(flags[0]), "{flags:?}");
    }
    let out = stiction(&["fit", g, "--scenario", plate]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("v_tangential_v"));
    let out = stiction(&["fit", "--scenario", plate, "--synthesize", dir.join("s.csv").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--synthesize"));
    let v = stiction_json(&["fit", g, "--scenario", "scenarios/comb-sidewall.json", "--json"]);
    assert_eq!(v["rows_used"], 4, "{v}");
    let side = &v["rows_rejected"][0];
    assert!(side["line"] == 6 && side["reason"].as_str().unwrap().contains("side pull-in"), "{v}");
    assert!(v["points"].as_array().unwrap().iter().all(|p| p["line"] != 6));
    let out_dir = dir.join("out");
    let out = stiction(&["fit", g, "--scenario", "scenarios/comb-sidewall.json", "--out", out_dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for f in ["report.json", "fit-friction-load.svg", "fit-friction-load.png", "fit-friction-load.csv"] {
        assert!(out_dir.join(f).is_file(), "{f}");
    }
}
