//! Every figure has its data beside it: the CSV next to `run`'s Fig. 5 holds exactly the numbers of
//! results.json that the figure plots (issue 14); results.json holds every plotted curve; reference
//! values are drawn and printed only when the scenario has them; `plot` follows `--scenario` and
//! `--set`; `--width`, `--height` and `--font-size` size the figures.

use crate::util::{stiction, temp_dir};

/// The rows of a figure's data CSV: (series, style, fields by column name).
fn read_data_csv(path: &std::path::Path) -> Vec<(String, String, std::collections::BTreeMap<String, f64>)> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            let fields = header
                .iter()
                .zip(rec.iter())
                .skip(2)
                .filter(|(_, v)| !v.is_empty())
                .map(|(k, v)| (k.clone(), v.parse::<f64>().unwrap()))
                .collect();
            (rec[0].to_string(), rec[1].to_string(), fields)
        })
        .collect()
}

fn png_size(path: &std::path::Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap();
    assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n");
    (u32::from_be_bytes([b[16], b[17], b[18], b[19]]), u32::from_be_bytes([b[20], b[21], b[22], b[23]]))
}

#[test]
fn results_json_holds_every_plotted_curve_and_equals_the_figure_csvs() {
    let dir = temp_dir("fig-json");
    let out = stiction(&["run", "scenarios/tas2000-fit-synthetic.json", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    for fig in ["fig5", "fig7"] {
        let json = &results["figures"][fig]["series"];
        let rows = read_data_csv(&dir.join(format!("{fig}.csv")));
        let series = json.as_array().unwrap_or_else(|| panic!("no figures.{fig}.series in results.json"));
        // Every CSV row is the same number in the JSON series of that name, under the same key.
        let mut index = std::collections::BTreeMap::<String, usize>::new();
        for (name, style, fields) in &rows {
            let s = series.iter().find(|s| s["name"] == name.as_str()).unwrap_or_else(|| panic!("{fig}: {name}"));
            assert_eq!(s["style"], style.as_str());
            let i = index.entry(name.clone()).or_default();
            for (key, v) in fields {
                let j = s[key][*i].as_f64().unwrap_or_else(|| panic!("{fig} {name} {key}[{i}]"));
                assert!((j - v).abs() <= 1e-12 * v.abs(), "{fig} {name} {key}: {j} vs {v}");
            }
            *i += 1;
        }
        // and nothing in the JSON is missing from the CSV
        let total: usize = series
            .iter()
            .map(|s| s.as_object().unwrap().values().filter_map(|v| v.as_array()).map(Vec::len).max().unwrap_or(0))
            .sum();
        assert_eq!(total, rows.len(), "{fig}");
    }
    // Fig. 7 holds the model curves and both eq. 10 lines, with units in the keys.
    let names: Vec<&str> =
        results["figures"]["fig7"]["series"].as_array().unwrap().iter().map(|s| s["name"].as_str().unwrap()).collect();
    for want in
        ["explicit solver", "discrete model N = 3", "eq. 10 fit of the virtual meter", "eq. 10 fit of the measured"]
    {
        assert!(names.iter().any(|n| n.starts_with(want)), "{want} not in {names:?}");
    }
    let line = results["figures"]["fig7"]["series"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"].as_str().unwrap().starts_with("eq. 10 fit of the measured"))
        .unwrap();
    // The measured eq. 10 line meets F_f = 0 at L = -F_a0 of the measured fit.
    let fa0 = results["measured"]["apparent_adhesion_force_measured_n"].as_f64().unwrap() * 1e6;
    assert!((line["load_un"][0].as_f64().unwrap() + fa0).abs() < 1e-9, "{line}");
    assert_eq!(line["friction_un"][0].as_f64().unwrap(), 0.0);
    // The title says what the data are.
    let svg = std::fs::read_to_string(dir.join("fig7.svg")).unwrap();
    assert!(svg.contains("measured (voltages.csv)") && !svg.contains("(virtual)"), "Fig. 7 title");
}

/// The paper's measured values are printed and drawn only for a scenario with a `reference`
/// section (tas2000.json), not for one without (the synthetic-data device), also with --set.
#[test]
fn reference_values_are_shown_only_when_the_scenario_has_them() {
    let with = temp_dir("ref-with");
    let out = stiction(&["run", "scenarios/tas2000.json", "--out", with.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    // Every printed +/- says what it is.
    assert!(text.contains("reference, measured (Tas et al., MEMS 2000, section 5): mu_e,a = 0.7 +/- 0.3, F_a0 = 2 +/- 1.3 uN; +/- is the uncertainty stated by the paper"), "{text}");
    assert!(text.contains("+/- is the regression's standard error only"), "{text}");
    let band: Vec<_> = read_data_csv(&with.join("fig7.csv")).into_iter().filter(|r| r.1 == "x-range").collect();
    assert_eq!(band.len(), 1, "one F_a0 band in Fig. 7");
    // the band is -F_a0 = -(2.0 +/- 1.3) uN
    assert!((band[0].2["load_un"] + 3.3).abs() < 1e-9 && (band[0].2["load_un_upper"] + 0.7).abs() < 1e-9, "{band:?}");
    assert!(band[0].0.contains("2 ± 1.3 µN"), "{band:?}");

    let without = temp_dir("ref-without");
    let out = stiction(&["run", "scenarios/tas2000-fit-synthetic.json", "--out", without.to_str().unwrap()]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(!text.contains("reference") && !text.contains("0.7 +/- 0.3") && !text.contains("2.0 +/- 1.3"), "{text}");
    assert!(read_data_csv(&without.join("fig7.csv")).iter().all(|r| r.1 != "x-range"));
    // A reference added with --set is shown, with its own source.
    let out = stiction(&[
        "run",
        "scenarios/tas2000-fit-synthetic.json",
        "--set",
        r#"reference={"source": "my lab, 2025", "mu_apparent": 0.8, "mu_apparent_uncertainty": 0.1, "uncertainty_meaning": "SD of 5 devices"}"#,
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("reference, measured (my lab, 2025): mu_e,a = 0.8 +/- 0.1; +/- is the SD of 5 devices"),
        "{text}"
    );

    // The study: the CDF is a step with the reference band; the scatter has the point with both error bars.
    for (scenario, has) in [("scenarios/tas2000.json", true), ("scenarios/tas2000-fit-synthetic.json", false)] {
        let dir = temp_dir(if has { "ref-study-with" } else { "ref-study-without" });
        let out = stiction(&["study", scenario, "--samples", "24", "--quiet", "--out", dir.to_str().unwrap()]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        assert_eq!(String::from_utf8_lossy(&out.stdout).contains("reference, measured"), has);
        let cdf = read_data_csv(&dir.join("mu_cdf.csv"));
        assert!(cdf.iter().any(|r| r.1 == "step"), "the CDF is a step");
        assert_eq!(cdf.iter().any(|r| r.1 == "x-range"), has);
        let scatter = read_data_csv(&dir.join("mu_vs_fa0.csv"));
        let point = scatter.iter().find(|r| r.0.starts_with("measured"));
        assert_eq!(point.is_some(), has);
        if let Some((_, _, f)) = point {
            assert_eq!((f["fa0_un"], f["mu_apparent"]), (2.0, 0.7));
            assert_eq!((f["fa0_un_err"], f["mu_apparent_err"]), (1.3, 0.3));
        }
        let study: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("study.json")).unwrap()).unwrap();
        assert_eq!(study.get("reference").is_some(), has);
    }
}

/// `plot fig7 --scenario S --set material.shear_strength=...` changes the curve (F_f = s A_r: in
/// proportion to s, eq. 1 and 12) and its title and note.
#[test]
fn plot_follows_the_scenario_and_set() {
    let dir = temp_dir("plot-set");
    let base = dir.join("base.svg");
    let set = dir.join("set.svg");
    for (path, extra) in [(&base, None), (&set, Some("material.shear_strength=2.8 GPa"))] {
        let mut args = vec!["plot", "fig7", "--scenario", "scenarios/tas2000.json", "--out", path.to_str().unwrap()];
        if let Some(e) = extra {
            args.extend(["--set", e]);
        }
        let out = stiction(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let curve = |p: &std::path::Path| -> Vec<(f64, f64)> {
        read_data_csv(&p.with_extension("csv"))
            .into_iter()
            // F_f = s A_r, however its symbols are typeset.
            .filter(|r| r.0.contains(" = s A") && r.1 == "line")
            .map(|r| (r.2["load_un"], r.2["friction_un"]))
            .collect()
    };
    let (a, b) = (curve(&base), curve(&set));
    assert!(a.len() >= 100 && a.len() == b.len());
    for (p, q) in a.iter().zip(&b) {
        assert_eq!(p.0, q.0);
        assert!((q.1 - 2.0 * p.1).abs() <= 1e-9 * p.1.abs().max(1e-9), "{p:?} {q:?}");
    }
    let svg = std::fs::read_to_string(&set).unwrap();
    assert!(svg.contains("s = 2.8 GPa") && !svg.contains("s = 1.4 GPa"), "the legend names the override");
    // The scenario's law and contacts: Maugis-Dugdale in the title.
    let out = stiction(&[
        "plot",
        "fig7",
        "--scenario",
        "scenarios/tas2000-maugis-dugdale.json",
        "--out",
        base.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read_to_string(&base).unwrap().contains("Maugis-Dugdale"));
    // --set without --scenario is refused naming both flags.
    let out = stiction(&["plot", "fig7", "--set", "material.shear_strength=2 GPa", "--out", base.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--set") && err.contains("--scenario"), "{err}");
    // fig2 with a scenario: its theta (eq. 9, about 1.2e4 for Table 1) in the note.
    let out = stiction(&["plot", "fig2", "--scenario", "scenarios/tas2000.json", "--out", base.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(std::fs::read_to_string(&base).unwrap().contains("this scenario: θ = 12400"));
}

/// Fig. 3 shows the adhesive branches: its load axis reaches theta = 10's pull-off at L* = -0.024
/// and theta = 30's near -2e-5, and each curve has points below zero load.
#[test]
fn fig3_shows_the_pull_off_loads() {
    let dir = temp_dir("fig3");
    let path = dir.join("fig3.svg");
    let out = stiction(&["plot", "fig3", "--out", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let rows = read_data_csv(&dir.join("fig3.csv"));
    let pull_offs: Vec<f64> = rows.iter().filter(|r| r.0.starts_with("pull-off")).map(|r| r.2["l_star"]).collect();
    assert_eq!(pull_offs.len(), 3);
    // Paper Fig. 3 (GW + DMT): pull-off L* about -0.024 (theta 10) ... -2e-5 (theta 30).
    assert!((pull_offs[0] + 0.024).abs() < 0.003 && pull_offs[2] < -1e-5 && pull_offs[2] > -4e-5, "{pull_offs:?}");
    for name in ["(1)", "(2)", "(3)"] {
        let below = rows.iter().filter(|r| r.0.starts_with(name) && r.2["l_star"] < 0.0).count();
        assert!(below >= 40, "{name}: {below} points on the adhesive side");
    }
    assert!(std::fs::read_to_string(&path).unwrap().contains("−10⁻²"), "symmetric-log ticks");
}

#[test]
fn width_height_and_font_size_set_the_figure() {
    let dir = temp_dir("fig-size");
    let png = dir.join("f.png");
    let out = stiction(&[
        "plot",
        "fig7",
        "--width",
        "640",
        "--height",
        "480",
        "--font-size",
        "9",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(png_size(&png), (640, 480));
    let run = dir.join("run");
    let out = stiction(&["run", "scenarios/tas2000.json", "--width", "1000", "--out", run.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(png_size(&run.join("fig7.png")), (1000, 700));
    let svg = std::fs::read_to_string(run.join("fig7.svg")).unwrap();
    assert!(svg.contains(r#"width="1000""#) && svg.contains(r#"height="700""#));
    for (flag, value) in [("--width", "100"), ("--height", "9000"), ("--font-size", "80"), ("--font-size", "big")] {
        let out = stiction(&["plot", "fig2", flag, value, "--out", png.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(flag) && err.contains(value), "{flag} {value}: {err}");
    }
}

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
        .filter(|l| l.starts_with("virtual meter,markers,"))
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

/// The gallery page shows every image of docs/figures/gallery and links no missing one; the script
/// that makes them writes exactly those (issue 14: one page, regenerated by one command).
#[test]
fn the_gallery_page_and_its_images_agree() {
    let root = crate::util::root();
    let page = std::fs::read_to_string(root.join("docs/figures.md")).unwrap();
    let linked: std::collections::BTreeSet<String> =
        page.split("](figures/gallery/").skip(1).map(|rest| rest.split(')').next().unwrap().to_string()).collect();
    let on_disk: std::collections::BTreeSet<String> = std::fs::read_dir(root.join("docs/figures/gallery"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png"))
        .collect();
    assert_eq!(linked, on_disk, "docs/figures.md and docs/figures/gallery/ differ");
    let script = std::fs::read_to_string(root.join("scripts/gallery.sh")).unwrap();
    for name in &on_disk {
        let stem = name.trim_end_matches(".png");
        // bem figures are copied by a loop with a bem- prefix
        assert!(
            script.contains(name)
                || script.contains(stem)
                || name.starts_with("bem-")
                || name.starts_with("topography-"),
            "{name} not made by scripts/gallery.sh"
        );
    }
}
