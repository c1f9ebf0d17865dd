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
    for f in ["fields.csv", "curve.csv", "pressure.png", "gap.png", "load_area.png", "load_gap.png", "area_ratio.png"] {
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
