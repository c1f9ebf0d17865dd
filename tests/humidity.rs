//! `stiction plot humidity` and a study that draws the relative humidity (issue 22): the sweep is
//! the friction meter of `run` at each humidity (same numbers, dry point first), a humidity
//! without an eq. 10 line is an explicit null with its reason, and a study of the humid scenario
//! lists `environment.relative_humidity` among its drawn inputs.

use crate::util::{num, stiction_json, temp_dir};

/// Each point of the sweep is `stiction run` of the scenario at that humidity (`--set
/// environment.relative_humidity=RH`): mu_e,a, F_a0 and the capillary share (capillary over
/// adhesive load summed over the points in contact, recomputed here from run's `points`) to 1e-12
/// relative; the grid gets its dry point first.
#[test]
fn each_humidity_is_the_meter_of_run_at_that_humidity_dry_first() {
    let v =
        stiction_json(&["plot", "humidity", "--scenario", "scenarios/tas2000-humid.json", "--rh", "0.2,0.5", "--json"]);
    let points = v["points"].as_array().unwrap();
    let rhs: Vec<f64> = points.iter().map(|p| num(p, "relative_humidity")).collect();
    assert_eq!(rhs, [0.0, 0.2, 0.5]);
    for p in points {
        let rh = num(p, "relative_humidity");
        let set = format!("environment.relative_humidity={rh}");
        let r = stiction_json(&["run", "scenarios/tas2000-humid.json", "--set", &set, "--json"]);
        for key in ["mu_apparent", "apparent_adhesion_force_n"] {
            let (a, b) = (num(p, key), num(&r, key));
            assert!((a / b - 1.0).abs() < 1e-12, "RH {rh}: {key} {a} vs run {b}");
        }
        let (adh, cap) = r["points"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|q| q["in_contact"] == true && q["error"].is_null())
            .fold((0.0, 0.0), |(a, c), q| {
                (a + num(q, "adhesive_load_n"), c + q["capillary_load_n"].as_f64().unwrap_or(0.0))
            });
        let share = num(p, "capillary_share");
        assert!(
            (share - cap / adh).abs() <= 1e-12 * (cap / adh).max(1e-300),
            "RH {rh}: share {share} vs {}",
            cap / adh
        );
        // The meniscus of this humidity (the Kelvin radius grows with RH): run's at the same RH.
        assert_eq!(p["meniscus_height_m"], r["environment"]["meniscus_height_m"], "RH {rh}");
        if rh == 0.0 {
            assert_eq!(share, 0.0, "dry: no capillary load");
            assert!(p["meniscus_height_m"].is_null(), "{p}");
        } else {
            assert!(share > 0.0 && share < 1.0, "RH {rh}: share {share}");
            assert!(p["meniscus_height_m"].as_f64().unwrap() > 0.0, "{p}");
        }
        assert!(p["reason"].is_null(), "{p}");
    }
    // The reference is the scenario's, at the humidity and sd its `environment` states.
    let r = &v["reference"];
    assert!(
        (num(r, "relative_humidity") - 0.35).abs() < 1e-12 && (num(r, "relative_humidity_sd") - 0.05).abs() < 1e-12
    );
    assert_eq!(num(r, "mu_apparent"), 0.7);
}

/// With two clamp voltages the meter has no eq. 10 line at any humidity: every point is there,
/// with null mu_e,a and F_a0 and the meter's reason, in the JSON and in humidity.csv (empty cells).
#[test]
fn a_humidity_without_an_eq10_line_is_a_null_with_its_reason() {
    let dir = temp_dir("humidity-null");
    let out = dir.join("out");
    let v = stiction_json(&[
        "plot",
        "humidity",
        "--scenario",
        "scenarios/tas2000-humid.json",
        "--set",
        "meter.clamp_voltages.steps=2",
        "--rh",
        "0:0.6:3",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 3);
    for p in points {
        assert!(p["mu_apparent"].is_null() && p["apparent_adhesion_force_n"].is_null(), "{p}");
        let reason = p["reason"].as_str().unwrap_or_else(|| panic!("no reason: {p}"));
        assert!(reason.contains("at least 3 distinct loads"), "{reason}");
    }
    let text = std::fs::read_to_string(out.join("humidity.csv")).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header = reader.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("{name}: {header:?}"));
    let rows: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 3, "{text}");
    for row in &rows {
        assert!(row[col("mu_apparent")].is_empty() && row[col("apparent_adhesion_force_n")].is_empty(), "{row:?}");
        assert!(row[col("reason")].contains("at least 3 distinct loads"), "{row:?}");
    }
    // The figures name the humidities without a line.
    let note = std::fs::read_to_string(out.join("humidity-mu.svg")).unwrap();
    assert!(note.contains("no eq. 10 line at RH = 0, 30, 60 %"), "humidity-mu.svg lacks the note");
}

/// A study of the humid scenario draws the relative humidity (35 +/- 5 %): it is one of the inputs
/// of the sensitivity table (JSON and sensitivity.csv) and a column of samples.csv named by its
/// path, whose drawn values scatter about 0.35 with sd 0.05 (mean within 4 standard errors, sample
/// sd within 35 %: 48 draws). The dry scenario has no such input.
#[test]
fn a_humid_study_draws_the_relative_humidity() {
    let dir = temp_dir("humidity-study");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let v = stiction_json(&[
        "study",
        "scenarios/tas2000-humid.json",
        "--samples",
        "48",
        "--seed",
        "5",
        "--quiet",
        "--json",
        "--out",
        o,
    ]);
    let inputs: Vec<&str> =
        v["sensitivity"]["inputs"].as_array().unwrap().iter().map(|r| r["input"].as_str().unwrap()).collect();
    assert!(inputs.contains(&"environment.relative_humidity"), "{inputs:?}");
    let table = std::fs::read_to_string(out.join("sensitivity.csv")).unwrap();
    assert!(table.lines().any(|l| l.starts_with("environment.relative_humidity,")), "{table}");
    let csv = std::fs::read_to_string(out.join("samples.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let c = header.iter().position(|h| *h == "environment.relative_humidity").unwrap_or_else(|| panic!("{header:?}"));
    let rh: Vec<f64> = lines.map(|l| l.split(',').nth(c).unwrap().parse().unwrap()).collect();
    assert_eq!(rh.len(), 48);
    let n = rh.len() as f64;
    let mean = rh.iter().sum::<f64>() / n;
    let sd = (rh.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    assert!((mean - 0.35).abs() < 4.0 * 0.05 / n.sqrt(), "mean RH {mean}");
    assert!((sd / 0.05 - 1.0).abs() < 0.35, "sd of RH {sd}");

    let dry = stiction_json(&["study", "scenarios/tas2000.json", "--samples", "8", "--seed", "5", "--quiet", "--json"]);
    let dry_inputs = dry["sensitivity"]["inputs"].as_array().unwrap();
    assert!(dry_inputs.iter().all(|r| r["input"] != "environment.relative_humidity"), "{dry_inputs:?}");
}

/// `environment.min_kelvin_radius` (the dry regime: no meniscus below a molecular Kelvin radius).
/// At RH 0.1 (r_K = 0.228 nm for water at 25 C, below 0.28 nm) the run is the dry run bit for bit
/// (points, eq. 10 line, fit) and says so; at RH 0.35 (r_K = 0.500 nm) the cut-off changes nothing.
/// `bem --rh` likewise: below the cut-off only the van der Waals law acts (its RH 0 value), above
/// it the adhesion energy is the one without the cut-off. A cut-off that is not a positive length
/// is refused naming the field.
#[test]
fn below_the_min_kelvin_radius_no_meniscus_condenses() {
    let cut = "environment.min_kelvin_radius=0.28 nm";
    let dry = stiction_json(&["run", "scenarios/tas2000.json", "--json"]);
    let below = ["run", "scenarios/tas2000.json", "--set", "environment.relative_humidity=0.1", "--set", cut];
    let low = stiction_json(&[&below[..], &["--json"]].concat());
    // (A humid run adds `capillary_load_n` to each point: 0 here; the rest is the dry point.)
    let mut low_points = low["points"].clone();
    for p in low_points.as_array_mut().unwrap() {
        let cap = p.as_object_mut().unwrap().remove("capillary_load_n");
        assert_eq!(cap, Some(serde_json::json!(0.0)), "RH 0.1 below the cut-off: a capillary load");
    }
    assert!(low_points == dry["points"], "RH 0.1 below the cut-off: the points are not the dry ones");
    for key in ["mu_apparent", "apparent_adhesion_force_n", "fit"] {
        assert!(low[key] == dry[key], "RH 0.1 below the cut-off: {key} {} is not the dry {}", low[key], dry[key]);
    }
    let env = &low["environment"];
    assert!((num(env, "kelvin_radius_m") - 0.228e-9).abs() < 0.001e-9, "{env}");
    assert!(env["meniscus_height_m"].is_null() && (num(env, "min_kelvin_radius_m") - 0.28e-9).abs() < 1e-24, "{env}");
    let out = crate::util::stiction(&below);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("below environment.min_kelvin_radius") && text.contains("dry"), "{text}");
    let humid = ["run", "scenarios/tas2000.json", "--set", "environment.relative_humidity=0.35", "--json"];
    let plain = stiction_json(&humid);
    let mut with_cut: Vec<&str> = humid.to_vec();
    with_cut.extend_from_slice(&["--set", cut]);
    let cut_above = stiction_json(&with_cut);
    for key in ["points", "mu_apparent", "apparent_adhesion_force_n", "fit"] {
        assert!(cut_above[key] == plain[key], "RH 0.35 above the cut-off: {key} changed");
    }
    assert!(plain["points"] != dry["points"], "RH 0.35 must differ from dry");

    let bem = |extra: &[&str]| {
        let mut a =
            vec!["bem", "--size", "0.5um", "--grid", "32", "--rms-height", "2nm", "--work-of-adhesion", "0.1 J/m^2"];
        a.extend_from_slice(&["--range", "0.4 nm", "--rh", "0,0.1,0.35", "--json"]);
        a.extend_from_slice(extra);
        let v = stiction_json(&a);
        v["points"].as_array().unwrap().iter().map(|p| num(p, "adhesion_energy_j_per_m2")).collect::<Vec<f64>>()
    };
    let (plain, cut) = (bem(&[]), bem(&["--min-kelvin-radius", "0.28 nm"]));
    assert_eq!(cut[1], cut[0], "RH 0.1 below the cut-off: the van der Waals value");
    assert!(plain[1] > plain[0], "without the cut-off RH 0.1 condenses: {plain:?}");
    assert_eq!(cut[2], plain[2], "RH 0.35 above the cut-off");

    for bad in ["environment.min_kelvin_radius=-1 nm", "environment.min_kelvin_radius=0.3 V"] {
        let out = crate::util::stiction(&[
            "run",
            "scenarios/tas2000.json",
            "--set",
            "environment.relative_humidity=0.1",
            "--set",
            bad,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("min_kelvin_radius"), "{bad}: {err}");
    }
}
