//! `stiction bem`: a small non-adhesive sweep with the asperity comparison and all outputs, an
//! adhesive mean-gap cycle, and bad flags (exit status 2, a message naming the flag).

use crate::util::{stiction, stiction_json, temp_dir};

#[test]
fn bem_sweep_writes_fields_curves_and_figures() {
    let dir = temp_dir("bem-out");
    let v = stiction_json(&[
        "bem",
        "--grid",
        "64",
        "--sweep",
        "50MPa:1GPa:3",
        "--shear-strength",
        "100 MPa",
        "--compare-asperity",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 3);
    // Area grows with load; friction is s A_r exactly.
    let a: Vec<f64> = pts.iter().map(|p| p["contact_area_m2"].as_f64().unwrap()).collect();
    assert!(a[0] < a[1] && a[1] < a[2], "{a:?}");
    for p in pts {
        let f = p["friction_n"].as_f64().unwrap();
        assert!((f / (1e8 * p["contact_area_m2"].as_f64().unwrap()) - 1.0).abs() < 1e-12);
        assert!(p["area_ratio_bem_over_asperity"].as_f64().unwrap() > 0.0);
    }
    for f in [
        "results.json",
        "manifest.json",
        "fields.csv",
        "curve.csv",
        "height.png",
        "pressure.png",
        "gap.png",
        "load_area.png",
        "load_area.csv",
        "load_gap.png",
        "area_ratio.png",
        "area_ratio.csv",
    ] {
        let meta = std::fs::metadata(dir.join(f)).unwrap_or_else(|_| panic!("{f} missing"));
        assert!(meta.len() > 100, "{f} is nearly empty");
    }
    let fields = std::fs::read_to_string(dir.join("fields.csv")).unwrap();
    assert!(fields.starts_with("x_m,y_m,height_m,pressure_pa,gap_m,contact"));
    assert_eq!(fields.lines().count(), 64 * 64 + 1);
}

#[test]
fn bem_adhesive_cycle_reports_pull_off() {
    let v = stiction_json(&[
        "bem",
        "--grid",
        "32",
        "--rms-height",
        "20 nm",
        "--gap-sweep",
        "60nm:30nm:4",
        "--gap-back",
        "--work-of-adhesion",
        "0.1 J/m^2",
        "--range",
        "2 nm",
        "--json",
    ]);
    assert_eq!(v["points"].as_array().unwrap().len(), 7);
    assert!(v["pull_off_n"].as_f64().unwrap() <= 0.0);
}

#[test]
fn bem_bad_flags_exit_2() {
    for (args, needle) in [
        (vec!["bem", "--grid", "1", "--pressure", "1MPa"], "--grid"),
        (vec!["bem", "--grid", "100000", "--pressure", "1MPa"], "--grid"),
        (vec!["bem", "--work-of-adhesion", "0.1", "--range", "1nm", "--pressure", "1MPa"], "--gap-sweep"),
        (vec!["bem", "--sweep", "1MPa:2MPa:0"], "STEPS"),
        (vec!["bem", "--tolerance", "2", "--pressure", "1MPa"], "--tolerance"),
        (vec!["bem", "--hurst", "1.5", "--pressure", "1MPa"], "hurst"),
    ] {
        let out = stiction(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A measured map (the bundled 640 x 200 gsf, non-square) is the periodic cell: the grid, pixel
/// and rms height are those `stiction topography` reports for it (levelled plane).
#[test]
fn bem_on_a_measured_height_map() {
    let v = stiction_json(&["bem", "--map", "data/topography-example/wall.gsf", "--pressure", "20 MPa", "--json"]);
    assert_eq!(v["grid"]["nx"].as_u64(), Some(640));
    assert_eq!(v["grid"]["ny"].as_u64(), Some(200));
    assert!((v["grid"]["dx_m"].as_f64().unwrap() / 40e-9 - 1.0).abs() < 1e-9);
    assert_eq!(v["surface"]["source"], "height_map");
    let topo = stiction_json(&["topography", "data/topography-example/wall.gsf", "--json"]);
    let (a, b) = (v["rms_height_m"].as_f64().unwrap(), topo["rms_height_m"].as_f64().unwrap());
    assert!((a / b - 1.0).abs() < 1e-9, "{a} vs {b}");
    let p = &v["points"][0];
    assert!((p["mean_pressure_pa"].as_f64().unwrap() / 20e6 - 1.0).abs() < 1e-9);
    assert!(p["contact_fraction"].as_f64().unwrap() > 0.0);
    // A generator flag with a map is refused.
    let out = stiction(&["bem", "--map", "data/topography-example/wall.gsf", "--grid", "64", "--pressure", "1MPa"]);
    assert_eq!(out.status.code(), Some(2));
}

/// A scenario's height-map face under the shoe: 20 um x 5 um at 40 nm = 500 x 125 points, E* from
/// the material (3/(4D), D = 9.1e-12 1/Pa); the output folder is an OutputSet (manifest, --force).
#[test]
fn bem_on_a_scenario_patch_with_output_set() {
    let dir = temp_dir("bem-scenario");
    let out_dir = dir.join("out");
    let args = |extra: &[&str]| {
        let mut a = vec![
            "bem",
            "--scenario",
            "scenarios/tas2000-height-map.json",
            "--sweep",
            "0.01MPa:1MPa:3",
            "--json",
            "--out",
            out_dir.to_str().unwrap(),
        ];
        a.extend_from_slice(extra);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        stiction(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let out = run(&[]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!((v["grid"]["nx"].as_u64(), v["grid"]["ny"].as_u64()), (Some(500), Some(125)));
    assert!((v["e_star_pa"].as_f64().unwrap() * 9.1e-12 / 0.75 - 1.0).abs() < 1e-12);
    assert_eq!(v["surface"]["source"], "scenario");
    let manifest = std::fs::read_to_string(out_dir.join("manifest.json")).unwrap();
    assert!(manifest.contains("\"command\": \"bem\"") && manifest.contains("fields.csv"), "{manifest}");
    // A second run replaces the folder; a foreign file makes it refuse without --force.
    assert!(run(&[]).status.success());
    std::fs::write(out_dir.join("notes.txt"), "mine").unwrap();
    let refused = run(&[]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--force"));
    assert!(run(&["--force"]).status.success());
    assert_eq!(std::fs::read_to_string(out_dir.join("notes.txt")).unwrap(), "mine");
}
