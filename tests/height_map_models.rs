//! Height maps wherever a summit model goes: the statistical models (GW, discrete) on a
//! height-map scenario take the summit statistics counted on the map, the same numbers
//! `stiction topography` prints, and say so; a map smaller than the shoe is refused in plain
//! units naming `tile`, and with `tile` it is used as a periodic cell and the output says so.

use crate::util::{stiction, stiction_json, temp_dir};

/// `stiction fit` on scenarios/tas2000-height-map.json with gw-dmt and discrete-n3: its summit
/// statistics are exactly (bit for bit) those `stiction topography` prints for the map with the
/// scenario's preparation (level plane, no filters), and the report names the map.
#[test]
fn statistical_models_use_the_maps_summit_statistics() {
    let topo = stiction_json(&["topography", "data/topography-example/wall.gsf", "--level", "plane", "--json"]);
    let fit = stiction_json(&[
        "fit",
        "data/measured-voltages-synthetic/voltages.csv",
        "--scenario",
        "scenarios/tas2000-height-map.json",
        "--models",
        "gw-dmt,discrete-n3",
        "--draws",
        "50",
        "--json",
    ]);
    let st = &fit["summit_statistics"];
    assert_eq!(st["summit_density_per_m2"], topo["summit_density_per_m2"], "{st}");
    assert_eq!(st["summit_sd_m"], topo["summit_height_sd_m"], "{st}");
    assert_eq!(st["summit_radius_m"], topo["summit_radius_mean_m"], "{st}");
    assert_eq!(st["summit_count"], topo["summit_count"], "{st}");
    assert!(st["source"].as_str().unwrap().contains("wall.gsf"), "{st}");
    let notes = fit["surface_notes"].to_string();
    assert!(notes.contains("gw-dmt and discrete-nN use the summit statistics counted on the height map"), "{notes}");
    let names: Vec<&str> = fit["models"].as_array().unwrap().iter().map(|m| m["name"].as_str().unwrap()).collect();
    assert!(names.contains(&"gw-dmt") && names.contains(&"discrete-n3"), "{names:?}; failed: {}", fit["models_failed"]);
    // `run` with the GW model on the height-map scenario runs too, and says in a warning that its
    // statistics are the map's, with topography's numbers (printed to 4 significant digits).
    let out = stiction(&["run", "scenarios/tas2000-height-map.json", "--set", "contact.model=\"gw\""]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let run = stiction_json(&["run", "scenarios/tas2000-height-map.json", "--set", "contact.model=\"gw\"", "--json"]);
    let w = run["warnings"].as_array().unwrap().iter().find(|w| w["code"] == "statistics_from_map");
    let msg = w.unwrap_or_else(|| panic!("no statistics_from_map warning: {}", run["warnings"]))["message"].to_string();
    let eta_per_um2 = topo["summit_density_per_m2"].as_f64().unwrap() * 1e-12;
    let sd_nm = topo["summit_height_sd_m"].as_f64().unwrap() * 1e9;
    let r_um = topo["summit_radius_mean_m"].as_f64().unwrap() * 1e6;
    for needle in [
        format!("{} summits", topo["summit_count"]),
        format!("eta = {eta_per_um2:.3} 1/um^2"),
        format!("sigma_s = {sd_nm:.3} nm"),
        format!("R = {r_um:.3} um"),
        "wall.gsf".to_string(),
    ] {
        assert!(msg.contains(&needle), "missing `{needle}` in {msg}");
    }
}

/// A 2 um x 2 um map (200 x 200 pixels of 10 nm, a sum of sines) under the 20 um x 5 um shoe:
/// without `tile` an error in um naming `surface.height_map.tile`; with it, the explicit model
/// runs on the tiled map and `fit` states the tiling (10 x 2.5 periodic cells).
#[test]
fn a_map_smaller_than_the_shoe_is_tiled_only_when_asked() {
    let dir = temp_dir("small-map");
    let mut text = String::new();
    for iy in 0..200 {
        let row: Vec<String> = (0..200)
            .map(|ix| {
                let (x, y) = (ix as f64 / 200.0, iy as f64 / 200.0);
                let z =
                    10.0 * (2.0 * std::f64::consts::PI * 7.0 * x).sin() * (2.0 * std::f64::consts::PI * 5.0 * y).cos()
                        + 4.0 * (2.0 * std::f64::consts::PI * 13.0 * (x + y)).sin();
                format!("{z:.4}")
            })
            .collect();
        text.push_str(&row.join(" "));
        text.push('\n');
    }
    let map = dir.join("small.txt");
    std::fs::write(&map, text).unwrap();
    let file_set = format!("surface.height_map.file={}", serde_json::to_string(&map.to_string_lossy()).unwrap());
    let common = [
        "--set",
        file_set.as_str(),
        "--set",
        "surface.height_map.pixel_size=\"10 nm\"",
        "--set",
        "surface.height_map.height_unit=\"nm\"",
    ];
    let mut args = vec!["run", "scenarios/tas2000-height-map.json"];
    args.extend(common);
    let out = stiction(&args);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stdout));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("20 um x 5 um") && err.contains("2 um x 2 um"), "{err}");
    assert!(err.contains("surface.height_map.tile"), "{err}");
    assert!(!err.contains("0.0000"), "{err}");

    args.extend(["--set", "surface.height_map.tile=true"]);
    let out = stiction(&args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));

    let mut fit = vec![
        "fit",
        "data/measured-voltages-synthetic/voltages.csv",
        "--scenario",
        "scenarios/tas2000-height-map.json",
        "--models",
        "discrete-n3,explicit",
        "--draws",
        "50",
        "--json",
        "--set",
        "surface.height_map.tile=true",
    ];
    fit.extend(common);
    let v = stiction_json(&fit);
    let notes = v["surface_notes"].to_string();
    assert!(notes.contains("periodic cell, tiled 10.00 x 2.50 times"), "{notes}");
}
