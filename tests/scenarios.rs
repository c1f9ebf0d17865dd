//! The shipped scenarios, run as a user would.

use crate::util::{num, root, stiction, stiction_json, temp_dir};

#[test]
fn the_paper_experiment_lands_within_the_measured_values() {
    // Paper, section 5: measured mu_e,a = 0.7 +/- 0.3 and F_a0 = 2.0 +/- 1.3 uN.
    let v = stiction_json(&["run", "scenarios/tas2000.json", "--json"]);
    let mu = num(&v, "mu_apparent");
    let fa0 = num(&v, "apparent_adhesion_force_n");
    assert!((mu - 0.7).abs() <= 0.3, "mu_e,a = {mu}");
    assert!((fa0 - 2.0e-6).abs() <= 1.3e-6, "F_a0 = {fa0}");
    let points = v["points"].as_array().expect("points");
    assert!(points.len() >= 5);
    for p in points {
        for key in ["v_clamp_v", "v_pull_v", "load_n", "friction_n", "real_area_m2", "contacts"] {
            assert!(p.get(key).is_some(), "point lacks `{key}`: {p}");
        }
    }
    // The pull force at slip is at least the friction capacity and less than one voltage step above it.
    for p in points.iter().filter(|p| !p["v_pull_v"].is_null()) {
        let f = num(p, "friction_n");
        let cap = num(p, "friction_capacity_n");
        assert!(f >= cap && f < cap * 1.02 + 1e-9, "F_pull {f} vs capacity {cap}");
    }
}

#[test]
fn the_discrete_model_in_the_meter_reproduces_fig_7() {
    // Same scenario with the paper's own model (eq. 12, N = 3): the fitted slope over the clamp
    // loads stays near the paper's 0.7 (fitted at L = 3 uN) and F_a0 near 2.3 uN. Tolerance 0.15 and 0.8 uN:
    // the fit spans a range of loads on a curve whose slope falls with L.
    let v = stiction_json(&[
        "run",
        "scenarios/tas2000.json",
        "--set",
        "contact.model=\"discrete\"",
        "--set",
        "contact.contacts=3",
        "--json",
    ]);
    let mu = num(&v, "mu_apparent");
    let fa0 = num(&v, "apparent_adhesion_force_n");
    assert!((mu - 0.7).abs() < 0.15, "mu = {mu}");
    assert!((fa0 - 2.3e-6).abs() < 0.8e-6, "F_a0 = {fa0}");
    assert_eq!(v["contact_model"], "discrete-n3");
}

#[test]
fn run_writes_results_and_figures() {
    let dir = temp_dir("run-out");
    let out = stiction(&["run", "scenarios/tas2000.json", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for f in ["results.json", "results.csv", "fig5.svg", "fig5.png", "fig7.svg", "fig7.png"] {
        let meta = std::fs::metadata(dir.join(f)).unwrap_or_else(|_| panic!("{f} missing"));
        assert!(meta.len() > 100, "{f} is nearly empty");
    }
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert!(csv.starts_with("v_clamp_v,"));
    assert!(csv.lines().count() >= 6);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("mu_e,a"), "{stdout}");
}

#[test]
fn every_shipped_scenario_checks() {
    for entry in std::fs::read_dir(root().join("scenarios")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let out = stiction(&["scenario", path.to_str().unwrap()]);
            assert!(out.status.success(), "{}: {}", path.display(), String::from_utf8_lossy(&out.stderr));
        }
    }
}

#[test]
fn explicit_contact_command_reports_the_contract_keys() {
    let v = stiction_json(&["contact", "scenarios/tas2000.json", "--load", "3 uN", "--json"]);
    for key in [
        "load_n",
        "separation_m",
        "tilt_x_rad",
        "tilt_y_rad",
        "contacts",
        "real_area_m2",
        "adhesive_load_n",
        "friction_capacity_n",
        "max_pressure_pa",
        "force_residual_n",
    ] {
        assert!(v.get(key).is_some(), "contact --json lacks `{key}`");
    }
    // Force residual below 1e-9 of the load scale (issue 3).
    assert!(num(&v, "force_residual_n").abs() < 1e-9 * 3e-6);
    let sweep = stiction_json(&["contact", "scenarios/tas2000.json", "--sweep", "0uN:10uN:6", "--json"]);
    assert_eq!(sweep["points"].as_array().map(Vec::len), Some(6));
}

#[test]
fn the_gca_actuator_matches_measured_hardware() {
    // Issue 6 floors: mean absolute relative error <= 10 % for pull-in and for release.
    let v = stiction_json(&[
        "actuator",
        "scenarios/gca-rauf2022.json",
        "--validate",
        "data/gca-pullin-release/measured.csv",
        "--json",
    ]);
    let r = &v;
    assert!(num(r, "pull_in_mean_abs_rel_error") <= 0.10, "{r}");
    assert!(num(r, "release_mean_abs_rel_error") <= 0.10, "{r}");
    let points = r["points"].as_array().unwrap();
    assert_eq!(points.len(), 9);
    for key in ["finger_length_m", "pull_in_measured_v", "pull_in_model_v", "release_measured_v", "release_model_v"] {
        assert!(points[0].get(key).is_some(), "lacks {key}");
    }
    for key in [
        "pull_in_voltage_v",
        "pull_in_travel_m",
        "release_voltage_v",
        "conversion_factor_n_per_v2",
        "spring_stiffness_n_per_m",
    ] {
        assert!(v.get(key).is_some(), "actuator --json lacks {key}");
    }
}

#[test]
fn with_three_contacts_the_roughness_amplitude_does_not_change_the_friction() {
    // A finding of the explicit solver (docs/experiment.md): while three summits carry the shoe,
    // statics fixes their loads from their positions alone, so scaling every height (summit SD
    // 40 nm -> 80 nm, same seed, same positions and order) leaves the friction unchanged; only
    // when the wall is smooth enough that more summits touch does it change.
    let at = |sd: &str| {
        stiction_json(&["run", "scenarios/tas2000.json", "--set", &format!("surface.summit_sd={sd}"), "--json"])
    };
    let (a, b, smooth) = (at("40 nm"), at("80 nm"), at("2 nm"));
    let f = |v: &serde_json::Value| -> Vec<f64> {
        v["points"].as_array().unwrap().iter().filter_map(|p| p["friction_n"].as_f64()).collect()
    };
    assert!(a["points"].as_array().unwrap().iter().all(|p| p["contacts"] == 3.0));
    assert_eq!(f(&a), f(&b));
    let more = smooth["points"].as_array().unwrap().iter().filter(|p| p["contacts"].as_f64().unwrap() > 3.0).count();
    assert!(more > 0, "a 2 nm wall should bring more than three summits into contact");
    assert!(num(&smooth, "mu_apparent") > num(&a, "mu_apparent"));
}

#[test]
fn measured_voltages_are_reduced_and_compared() {
    // A scenario with a `measured` section: the measured (V_clamp, V_pull) pairs are reduced with
    // the nominal factors (a_clamp = 1.4e-8, a_pull = 3.8e-9 N/V^2, F_spring = 7 uN) and fitted
    // with eq. 10, and the virtual meter runs at the same clamp voltages.
    let dir = temp_dir("measured");
    std::fs::copy(root().join("scenarios/tas2000.json"), dir.join("s.json")).unwrap();
    std::fs::write(dir.join("m.csv"), "# three slips\nv_clamp_v,v_pull_v\n24,27.5\n26,32.0\n28,36.2\n").unwrap();
    let s = dir.join("s.json");
    // A path given with --set is relative to the current directory (the tests run in the
    // workspace root), so the temporary files are named by their full paths.
    let set = |f: &str| format!(r#"measured={{"voltages_csv": {:?}}}"#, dir.join(f).to_str().unwrap());
    let v = stiction_json(&["run", s.to_str().unwrap(), "--set", &set("m.csv"), "--json"]);
    let m = &v["measured"];
    let pts = m["points"].as_array().unwrap();
    assert_eq!(pts.len(), 3);
    // Hand reduction: L = 1.4e-8 V^2 - 7e-6, F = 3.8e-9 V^2; least squares on the three points.
    let data = [(24.0f64, 27.5f64), (26.0, 32.0), (28.0, 36.2)];
    let xy: Vec<(f64, f64)> = data.iter().map(|(c, p)| (1.4e-8 * c * c - 7e-6, 3.8e-9 * p * p)).collect();
    let (mx, my) = (xy.iter().map(|p| p.0).sum::<f64>() / 3.0, xy.iter().map(|p| p.1).sum::<f64>() / 3.0);
    let slope =
        xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / xy.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
    assert!((num(m, "mu_apparent_measured") - slope).abs() < 1e-9, "{m}");
    assert!(num(&pts[0], "v_pull_model_v") > 0.0);
    let residual = num(&pts[1], "v_pull_sq_residual_v2");
    assert!((residual - (num(&pts[1], "v_pull_model_v").powi(2) - 32.0f64.powi(2))).abs() < 1e-9);
    // A bad line is named.
    std::fs::write(dir.join("bad.csv"), "v_clamp_v,v_pull_v\n24,27.5\n26,x\n").unwrap();
    let out = stiction(&["run", s.to_str().unwrap(), "--set", &set("bad.csv")]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && stderr.contains("bad.csv, line 3") && stderr.contains("\"x\""), "{stderr}");
}

#[test]
fn staying_clamped_while_unloading_keeps_adhesive_contacts() {
    // JKR summits stay in contact down to their pull-off interference: a shoe that stays clamped
    // while the clamp voltage falls (meter.reclamp = false) keeps more summits, and so more
    // friction, than one that comes down anew at each voltage. On the smooth (2 nm) wall.
    let run = |reclamp: &str| {
        stiction_json(&[
            "run",
            "scenarios/tas2000-smooth.json",
            "--set",
            &format!("meter.reclamp={reclamp}"),
            "--set",
            r#"meter.clamp_voltages=["40 V","30 V","26 V","24 V","23 V","22.6 V"]"#,
            "--set",
            r#"contact.law="jkr""#,
            "--set",
            "meter.slip_dynamics=null",
            "--json",
        ])
    };
    let cap = |v: &serde_json::Value| -> Vec<f64> {
        v["points"].as_array().unwrap().iter().map(|p| p["friction_capacity_n"].as_f64().unwrap()).collect()
    };
    let (fresh, kept) = (cap(&run("true")), cap(&run("false")));
    assert_eq!(fresh[0], kept[0], "the first clamp is the same either way");
    for (f, k) in fresh.iter().zip(&kept) {
        assert!(k >= &(f * (1.0 - 1e-9)), "kept {k} below fresh {f}");
    }
    assert!(kept.last().unwrap() > &(1.2 * fresh.last().unwrap()), "{fresh:?} vs {kept:?}");
}

#[test]
fn an_exported_surface_read_back_gives_the_same_contact() {
    // `stiction surface --csv` writes the summits in SI; a scenario with "source": "csv" reads them
    // back, and the explicit solver finds the same equilibrium to the last digit.
    let dir = temp_dir("surface-csv");
    let csv = dir.join("summits.csv");
    let out = stiction(&["surface", "scenarios/tas2000.json", "--csv", csv.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let stats = stiction_json(&["surface", "scenarios/tas2000.json", "--json"]);
    // Table 1: eta = 4e12 m^-2 over 100 um^2 (Poisson: 400 +/- 20, 4 SD = 80), sigma = 40 nm (+/- 15 %).
    assert!((num(&stats["stats"], "count") - 400.0).abs() < 80.0);
    assert!((num(&stats["stats"], "height_sd_m") - 40e-9).abs() < 6e-9);
    let generated = stiction_json(&["contact", "scenarios/tas2000.json", "--load", "3 uN", "--json"]);
    let from_csv = stiction_json(&[
        "contact",
        "scenarios/tas2000.json",
        "--load",
        "3 uN",
        "--json",
        "--set",
        "surface.source=\"csv\"",
        "--set",
        &format!("surface.csv_path={:?}", csv.to_str().unwrap()),
        "--set",
        "surface.summit_density=null",
        "--set",
        "surface.summit_sd=null",
        "--set",
        "surface.summit_radius=null",
    ]);
    for key in ["friction_capacity_n", "real_area_m2", "separation_m", "tilt_x_rad", "tilt_y_rad", "contacts"] {
        assert_eq!(generated[key], from_csv[key], "{key}");
    }
}

#[test]
fn calibrating_the_actuators_from_pull_in_narrows_the_scatter() {
    // Only the calibration uncertainties vary (same surface, nominal R). Reducing each device's
    // voltages with conversion factors inferred from its own pull-in voltages instead of the
    // nominal ones must cut the scatter of mu_e,a (400 samples: sd 0.31 -> 0.15; asserted < 0.7 x).
    let study = |calibration: &str| {
        stiction_json(&[
            "study",
            "scenarios/tas2000.json",
            "--samples",
            "200",
            "--seed",
            "3",
            "--fixed-surface",
            "--set",
            "surface.summit_radius=0.5 um",
            "--set",
            "meter.slip_dynamics=null",
            "--calibration",
            calibration,
            "--json",
        ])
    };
    let (nominal, calibrated) = (study("nominal"), study("pull-in"));
    assert_eq!(calibrated["failed"], 0);
    let sd = |v: &serde_json::Value| num(&v["mu_apparent"], "sd");
    assert!(sd(&calibrated) < 0.7 * sd(&nominal), "sd {} vs {}", sd(&calibrated), sd(&nominal));
}

#[test]
fn a_point_without_equilibrium_is_reported_and_the_run_goes_on() {
    // A 40 um summit SD on a 20 um x 5 um shoe: the tilt-free shoe would tip beyond the
    // small-angle model at every load. Each point says so; the run itself still succeeds.
    let dir = temp_dir("tips-over");
    let out = stiction(&[
        "run",
        "scenarios/tas2000.json",
        "--set",
        "surface.summit_sd=40 um",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("tips over"), "{stdout}");
    let v = stiction_json(&["run", "scenarios/tas2000.json", "--set", "surface.summit_sd=40 um", "--json"]);
    let points = v["points"].as_array().unwrap();
    assert!(points.iter().all(|p| p["error"].as_str().is_some_and(|e| e.contains("tips over"))));
    assert!(v["mu_apparent"].is_null());
    let csv = std::fs::read_to_string(dir.join("results.csv")).unwrap();
    assert!(csv.lines().nth(1).unwrap().contains("tips over"));
}
