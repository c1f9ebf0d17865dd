//! `stiction topography` on the bundled example map, and the friction meter on a height-map scenario.

use crate::util::{assert_fit_of_points, num, stiction, stiction_json, temp_dir};

#[test]
fn topography_reports_the_contract_keys_beside_nayak() {
    let v = stiction_json(&[
        "topography",
        "data/topography-example/wall.gsf",
        "--scenario",
        "scenarios/tas2000.json",
        "--json",
    ]);
    for key in [
        "summit_count",
        "summit_density_per_m2",
        "summit_height_sd_m",
        "summit_radius_mean_m",
        "rms_height_m",
        "rms_slope",
    ] {
        assert!(v.get(key).is_some_and(|x| x.is_number()), "no `{key}` in {v}");
    }
    let nayak = &v["nayak"];
    // The map was generated with a 0.2 um Gaussian correlation length at 40 nm pixels (README):
    // Nayak's density 4.6e12 m^-2; counted and predicted agree within 10 % (5 pixels per length).
    let (count, pred) = (num(&v, "summit_density_per_m2"), num(nayak, "summit_density_per_m2"));
    assert!((count / pred - 1.0).abs() < 0.1, "{count} vs Nayak {pred}");
    assert!((pred / 4.6e12 - 1.0).abs() < 0.15, "{pred}");
    assert!((num(&v, "rms_height_m") / 20e-9 - 1.0).abs() < 0.1);
    assert!(num(&v["gw"], "adhesion_parameter_theta") > 0.0);
}

#[test]
fn topography_writes_summits_figures_and_their_data() {
    let dir = temp_dir("topography");
    let csv = dir.join("s.csv");
    let out = stiction(&[
        "topography",
        "data/topography-example/wall.gsf",
        "--cutoff",
        "80 nm",
        "--summits",
        csv.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("x_m,y_m,height_m,radius_m\n") && text.lines().count() > 100);
    for f in [
        "height_map.png",
        "height_map.csv",
        "psd.png",
        "psd.csv",
        "summit_heights.png",
        "summit_heights.csv",
        "summit_radii.png",
        "summit_radii.csv",
        "statistics.json",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("0.0800 um"), "the cut-off is stated: {stdout}");
}

#[test]
fn a_npy_without_pixel_size_says_what_is_missing() {
    let dir = temp_dir("topography-npy");
    let p = dir.join("m.npy");
    let mut b = b"\x93NUMPY\x01\x00".to_vec();
    let mut h = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }".to_string();
    while !(10 + h.len() + 1).is_multiple_of(64) {
        h.push(' ');
    }
    h.push('\n');
    b.extend_from_slice(&(h.len() as u16).to_le_bytes());
    b.extend_from_slice(h.as_bytes());
    for k in 0..9 {
        b.extend_from_slice(&f64::from(k).to_le_bytes());
    }
    std::fs::write(&p, b).unwrap();
    let out = stiction(&["topography", p.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("missing metadata") && err.contains("--pixel-size"), "{err}");
}

#[test]
fn the_meter_runs_on_a_height_map_scenario() {
    // No independent reference pins mu_e,a on the measured map (explicit DMT contacts on the map's
    // summits have no closed form); what is checked is that every number the run reports follows
    // from the meter's protocol and the paper's relations, recomputed here from the printed points:
    // - each point's reported friction is the first pull step above the friction capacity s A_r
    //   (eq. 1, s = 1.4 GPa): a_pull V^2 >= s A_r > a_pull (V - 0.05 V)^2 (a_pull = 3.8e-9 N/V^2);
    // - loads are a_clamp V_clamp^2 - F_spring (a_clamp = 1.4e-8 N/V^2, F_spring = 7 uN);
    // - mu_e,a and F_a0 are the least-squares line F = mu (L + F_a0) through those points.
    // Tolerances: 1e-12 relative for f64 arithmetic on the same numbers; 1e-9 for the fit.
    let v = stiction_json(&["run", "scenarios/tas2000-height-map.json", "--json"]);
    assert_eq!(v["contact_model"], "explicit");
    let (a_clamp, a_pull, f_spring, s, step) = (1.4e-8, 3.8e-9, 7e-6, 1.4e9, 0.05);
    let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * b.abs();
    let mut in_contact = 0;
    for p in v["points"].as_array().unwrap().iter().filter(|p| p["in_contact"] == true) {
        let (vc, vp) = (num(p, "v_clamp_v"), num(p, "v_pull_v"));
        let load = num(p, "load_n");
        assert!(close(load, a_clamp * vc * vc - f_spring, 1e-12), "{p}");
        let capacity = num(p, "friction_capacity_n");
        assert!(close(capacity, s * num(p, "real_area_m2"), 1e-12), "{p}");
        let friction = num(p, "friction_n");
        assert!(close(friction, a_pull * vp * vp, 1e-12), "{p}");
        assert!(friction >= capacity && a_pull * (vp - step).powi(2) < capacity, "not the first step above s A_r: {p}");
        assert!(num(p, "contacts") >= 1.0, "{p}");
        in_contact += 1;
    }
    assert_eq!(in_contact, 13, "every clamp voltage of the scenario is in contact");
    assert_fit_of_points(&v);
    let mu = num(&v, "mu_apparent");
    // Another seed cuts another patch of the map: other contacts, another mu.
    let other = stiction_json(&["run", "scenarios/tas2000-height-map.json", "--set", "surface.seed=7", "--json"]);
    assert_ne!(num(&other, "mu_apparent"), mu);
}

/// A scenario's surface may be a grid generated in the scenario (`height_map.generated`). With the
/// seed and parameters that made the bundled map, it gives the same summits as the map file: the
/// same count, and heights and radii equal to the file's float32 rounding (relative 1e-6). Another
/// seed gives another wall.
#[test]
fn a_generated_grid_in_a_scenario_matches_the_bundled_map_it_reproduces() {
    let file = stiction_json(&["surface", "scenarios/tas2000-height-map.json", "--json"]);
    let generated = stiction_json(&["surface", "scenarios/tas2000-generated-grid.json", "--json"]);
    assert_eq!(file["stats"]["count"], generated["stats"]["count"]);
    assert!(generated["stats"]["count"].as_u64().unwrap() > 100);
    for key in ["height_mean_m", "height_sd_m", "radius_mean_m", "radius_sd_m"] {
        let (a, b) = (num(&file["stats"], key), num(&generated["stats"], key));
        assert!((a - b).abs() <= 1e-6 * a.abs(), "{key}: file {a} vs generated {b}");
    }
    let other =
        stiction_json(&["surface", "scenarios/tas2000-generated-grid.json", "--set", "surface.seed=7", "--json"]);
    assert_ne!(other["stats"]["height_mean_m"], generated["stats"]["height_mean_m"]);
}

#[test]
fn a_height_map_needs_exactly_one_of_file_and_generated() {
    for (set, expect) in [
        ("surface.height_map.file=\"../data/topography-example/wall.gsf\"", "not both"),
        ("surface.height_map.generated.hurst=0.8", "not both"),
    ] {
        let out = stiction(&["surface", "scenarios/tas2000-generated-grid.json", "--set", set]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{set}: {err}");
        assert!(err.contains(expect), "{set}: {err}");
    }
}

#[test]
fn an_instrument_file_lists_its_channels_and_states_the_one_read() {
    // --channels: index, name, grid, size, unit; exit 0.
    let out = stiction(&["topography", "data/topography-formats/di-1.di", "--channels"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
    for s in ["nanoscope", "0 Height (default)", "2 Phase", "3 AmplitudeError", "512 x 512 pixels", "0.500000 um", "nm"]
    {
        assert!(text.contains(s), "`{s}` not in:\n{text}");
    }
    let v = stiction_json(&["topography", "data/topography-formats/spot_1-1000nm.ibw", "--channels", "--json"]);
    assert_eq!(v["format"], "ibw");
    assert_eq!(v["default_channel"], 0);
    assert_eq!(v["channels"].as_array().unwrap().len(), 8);
    assert_eq!(v["channels"][1]["name"], "HeightRetrace");
    // The default channel, stated in the JSON and the table; --channel picks another.
    let v = stiction_json(&["topography", "data/topography-formats/di-1.di", "--json"]);
    assert_eq!(v["format"], "nanoscope");
    assert_eq!(v["read"]["channel"]["name"], "Height");
    assert_eq!(v["read"]["channel"]["chosen"], "default");
    let v = stiction_json(&["topography", "data/topography-formats/spot_1-1000nm.ibw", "--channel", "1", "--json"]);
    assert_eq!(v["read"]["channel"]["name"], "HeightRetrace");
    assert_eq!(v["read"]["channel"]["chosen"], "given");
    let out = stiction(&["topography", "data/topography-formats/sdf-1.sdf"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("0 `Default` of 1") && text.contains("from the file, from the file"), "{text}");
}

#[test]
fn instrument_files_refuse_what_they_cannot_give() {
    // A phase channel is not a height map; a wave without units asks for them; a contradicting flag
    // is refused naming the file's value. Each exits 2 naming the file.
    for (args, needle) in [
        (vec!["data/topography-formats/di-1.di", "--channel", "Phase"], "not heights"),
        (vec!["data/topography-formats/di-1.di", "--channel", "7"], "no channel 7"),
        (vec!["data/topography-formats/10x10-one_channel_without_name.ibw"], "--pixel-size"),
        (vec!["data/topography-formats/10x10-one_channel_without_name.ibw", "--pixel-size", "1 um"], "--height-unit"),
        (vec!["data/topography-formats/di-1.di", "--pixel-size", "2 nm"], "the value in"),
        (vec!["data/topography-formats/sdf-1.sdf", "--format", "ibw"], "--format says ibw"),
    ] {
        let mut a = vec!["topography"];
        a.extend(&args);
        let out = stiction(&a);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle) && err.contains("data/topography-formats/"), "{args:?}: {err}");
    }
    let out = stiction(&[
        "topography",
        "data/topography-formats/10x10-one_channel_without_name.ibw",
        "--pixel-size",
        "1 um",
        "--height-unit",
        "nm",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stderr));
}
