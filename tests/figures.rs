//! Every figure has its data beside it: the CSV next to `run`'s Fig. 5 holds exactly the numbers of
//! results.json that the figure plots (issue 14).

use crate::util::{stiction, temp_dir};

#[test]
fn fig5_data_csv_holds_the_plotted_points_of_results_json() {
    let dir = temp_dir("fig5-data");
    let out = stiction(&["run", "scenarios/tas2000.json", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let points: Vec<(f64, f64)> = results["points"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["v_pull_sq_v2"].is_number())
        .map(|p| (p["v_clamp_sq_v2"].as_f64().unwrap(), p["v_pull_sq_v2"].as_f64().unwrap()))
        .collect();
    assert!(points.len() >= 3, "too few points in results.json: {}", points.len());
    let text = std::fs::read_to_string(dir.join("fig5.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    assert!(header.starts_with("series,style,v_clamp_squared_v2,v_pull_squared_v2"), "{header}");
    let plotted: Vec<(f64, f64)> = lines
        .filter(|l| l.starts_with("virtual measurement,markers,"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[2].parse().unwrap(), f[3].parse().unwrap())
        })
        .collect();
    // The CSV is written with Rust's shortest round-trip format; the figure squares the voltages
    // itself, so the two agree to rounding (1e-12 relative).
    assert_eq!(plotted.len(), points.len());
    for (p, q) in plotted.iter().zip(&points) {
        assert!((p.0 - q.0).abs() <= 1e-12 * q.0.abs() && (p.1 - q.1).abs() <= 1e-12 * q.1.abs(), "{p:?} vs {q:?}");
    }
    // and the manifest lists it
    let manifest = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
    assert!(manifest.contains("fig5.csv") && manifest.contains("fig7.csv"), "{manifest}");
}
