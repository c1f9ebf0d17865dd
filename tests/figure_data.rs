//! Every figure command drawn at a small size (400 x 280 px), and every figure's data CSV in the one
//! shape of the plot crate: `series,style,` then x and y with their units in the names, the series
//! named as in the figure's legend (the SVG's text), values in the units the axes show. Beside it,
//! what each figure must show: the pull-in marker on the drawn hysteresis curve, the validation
//! model as a curve over the measured range, the CDF as the i/n staircase, one residual series per
//! model, the topography CSVs in nm and um, not SI.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::util::{stiction, temp_dir};

const SIZE: [&str; 4] = ["--width", "400", "--height", "280"];

/// Runs `stiction ARGS --width 400 --height 280` and asserts success.
fn draw(args: &[&str]) {
    let mut all: Vec<&str> = args.to_vec();
    all.extend(SIZE);
    let out = stiction(&all);
    assert!(out.status.success(), "stiction {all:?}:\n{}", String::from_utf8_lossy(&out.stderr));
}

/// One data CSV: its header and its rows as (series, style, fields by column).
struct Data {
    header: Vec<String>,
    rows: Vec<(String, String, BTreeMap<String, f64>)>,
}

impl Data {
    fn read(path: &Path) -> Data {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
        let rows = r
            .records()
            .map(|rec| {
                let rec = rec.unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                let fields = header
                    .iter()
                    .zip(rec.iter())
                    .skip(2)
                    .filter(|(k, v)| !v.is_empty() && *k != "label")
                    .map(|(k, v)| {
                        (k.clone(), v.parse::<f64>().unwrap_or_else(|e| panic!("{}: {v}: {e}", path.display())))
                    })
                    .collect();
                (rec[0].to_string(), rec[1].to_string(), fields)
            })
            .collect();
        Data { header, rows }
    }
    /// Where x is: after `series`, `style` and (when points are named) `label`.
    fn first(&self) -> usize {
        if self.header[2] == "label" { 3 } else { 2 }
    }
    fn x(&self) -> &str {
        &self.header[self.first()]
    }
    fn y(&self) -> &str {
        &self.header[self.first() + 1]
    }
    /// The points of the series whose name starts with `name`.
    fn series(&self, name: &str) -> Vec<(f64, f64)> {
        let (x, y) = (self.x(), self.y());
        self.rows
            .iter()
            .filter(|r| r.0.starts_with(name))
            .map(|r| (r.2.get(x).copied().unwrap_or(f64::NAN), r.2.get(y).copied().unwrap_or(f64::NAN)))
            .collect()
    }
    fn names(&self) -> BTreeSet<String> {
        self.rows.iter().map(|r| r.0.clone()).filter(|n| !n.is_empty()).collect()
    }
}

/// The text drawn in an SVG (XML entities decoded), one string per `<text>` element.
fn svg_texts(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..t.find("</text>")?];
            // Sub- and superscripts are tspans inside the text: read the characters only.
            let mut plain = String::new();
            let mut in_tag = false;
            for c in body.chars() {
                match c {
                    '<' => in_tag = true,
                    '>' => in_tag = false,
                    c if !in_tag => plain.push(c),
                    _ => {}
                }
            }
            Some(
                plain
                    .trim()
                    .replace("&lt;", "<")
                    .replace("&gt;", ">")
                    .replace("&quot;", "\"")
                    .replace("&#39;", "'")
                    .replace("&apos;", "'")
                    .replace("&amp;", "&"),
            )
        })
        .collect()
}

/// Column names that are pure numbers (no unit to state).
const DIMENSIONLESS: [&str; 11] = [
    "theta",
    "n_star",
    "l_star",
    "a_star",
    "mu_apparent",
    "cumulative_fraction",
    "contact_fraction",
    "area_ratio",
    "sobol_index",
    "input_number",
    "summits_per_bin",
];

/// Unit endings of a column name (`load_un`, `v_clamp_squared_v2`, `psd_m4`, ...).
const UNITS: [&str; 15] =
    ["_v", "_v2", "_un", "_um", "_nm", "_mpa", "_gpa", "_m4", "_us", "_per_um", "_n", "_m", "_pa", "_s", "_percent"];

/// The shape every figure's data CSV has, and its series named as in the legend of the SVG drawn
/// beside it (`figure` without extension).
fn check_shape(figure: &Path) {
    let csv = figure.with_extension("csv");
    let data = Data::read(&csv);
    let what = csv.display().to_string();
    assert_eq!(data.header[..2], ["series", "style"], "{what}");
    for key in [data.x(), data.y()] {
        assert!(
            DIMENSIONLESS.contains(&key) || UNITS.iter().any(|u| key.ends_with(u)),
            "{what}: column `{key}` names no unit"
        );
        assert!(key.is_ascii() && !key.contains("__"), "{what}: column `{key}`");
    }
    assert!(!data.rows.is_empty(), "{what}: no data");
    let svg = figure.with_extension("svg");
    if svg.is_file() {
        // A long legend entry wraps over several text lines: compare the text without spaces.
        let squeeze = |t: &str| t.chars().filter(|c| !c.is_whitespace()).collect::<String>();
        let texts = squeeze(&svg_texts(&svg).concat());
        for name in data.names() {
            let drawn = squeeze(&stiction_plot::text::plain(&name));
            assert!(texts.contains(&drawn), "{what}: series `{name}` is not a legend entry of {}", svg.display());
        }
    }
    for name in data.names() {
        assert!(!name.contains('`'), "{what}: Markdown in `{name}`");
    }
}

fn png_size(path: &Path) -> (u32, u32) {
    let b = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&b[..8], b"\x89PNG\r\n\x1a\n", "{}", path.display());
    (u32::from_be_bytes([b[16], b[17], b[18], b[19]]), u32::from_be_bytes([b[20], b[21], b[22], b[23]]))
}

/// Every figure (`.svg` with a `.csv` beside it) in `dir`, checked; returns their stems.
fn check_folder(dir: &Path) -> Vec<String> {
    let mut stems = Vec::new();
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for p in entries {
        if p.extension().is_some_and(|e| e == "svg") && p.with_extension("csv").is_file() {
            let csv = std::fs::read_to_string(p.with_extension("csv")).unwrap();
            let header: Vec<&str> = csv.lines().next().unwrap_or_default().split(',').collect();
            if header[..2] == ["x_um", "y_um"] {
                // A map: cell centres in um and the value in the colour bar's unit.
                assert_eq!(header.len(), 3, "{}: {header:?}", p.display());
                assert!(UNITS.iter().any(|u| header[2].ends_with(u)), "{}: {header:?}", p.display());
            } else {
                check_shape(&p);
            }
            let png = p.with_extension("png");
            if png.is_file() {
                assert_eq!(png_size(&png), (400, 280), "{}", png.display());
            }
            stems.push(p.file_stem().unwrap().to_string_lossy().into_owned());
        }
    }
    stems
}

#[test]
fn run_and_plot_figures_have_one_data_shape_and_fig5_has_the_eq10_line() {
    let dir = temp_dir("figdata-run");
    let d = |s: &str| dir.join(s).to_string_lossy().into_owned();
    draw(&["run", "scenarios/tas2000-fit-synthetic.json", "--out", &d("run")]);
    assert_eq!(check_folder(&dir.join("run")), ["fig5", "fig7"]);
    // Fig. 5: the eq. 10 line of the virtual meter (eq. 10 in voltages) beside the measured one.
    let fig5 = Data::read(&dir.join("run/fig5.csv"));
    let names = fig5.names();
    for want in ["eq. 10 fit of the virtual meter", "eq. 10 fit of the measured slips", "virtual meter", "measured"] {
        assert!(names.iter().any(|n| n.starts_with(want)), "fig5: no `{want}` in {names:?}");
    }
    // Fig. 7: both eq. 10 lines, distinguishable (their own styles), the virtual meter's drawn last.
    let fig7 = Data::read(&dir.join("run/fig7.csv"));
    let style = |name: &str| fig7.rows.iter().find(|r| r.0.starts_with(name)).map(|r| r.1.clone()).unwrap();
    assert_ne!(style("eq. 10 fit of the virtual meter"), style("eq. 10 fit of the measured slips"));
    let order: Vec<&str> = fig7.rows.iter().map(|r| r.0.as_str()).collect();
    let last = |p: &str| order.iter().rposition(|n| n.starts_with(p)).unwrap();
    assert!(last("eq. 10 fit of the virtual meter") > last("eq. 10 fit of the measured"), "{order:?}");

    for fig in ["fig2", "fig3", "fig7"] {
        draw(&["plot", fig, "--out", &d(&format!("{fig}.svg"))]);
    }
    draw(&["plot", "actuator", "--scenario", "scenarios/tas2000.json", "--array", "pull", "--out", &d("pull.svg")]);
    assert_eq!(check_folder(&dir), ["fig2", "fig3", "fig7", "pull"]);
    // Fig. 3's axis says what it is: sign(L*) log10(1 + |L*|/1e-6), not "linear within".
    let fig3: String = svg_texts(&dir.join("fig3.svg")).concat().chars().filter(|c| !c.is_whitespace()).collect();
    assert!(fig3.contains("log₁₀(1+|L*|/10⁻⁶)"), "{fig3}");
    // The pull-in marker lies on the drawn loading curve (the array has a stop).
    pull_in_on_curve(&dir.join("pull.csv"));
}

/// `plot humidity`: three figures in the one data shape; the model's points at the grid's
/// humidities (dry first) are results.json's; the measured reference is a point with its error
/// bars at the humidity of the experiment (35 +/- 5 %, tas2000-humid.json) or, where the scenario
/// states no humidity (tas2000.json), a band of its interval over the whole grid.
#[test]
fn humidity_figures_draw_the_model_and_the_reference_at_the_experiments_humidity() {
    let dir = temp_dir("figdata-humidity");
    let d = |s: &str| dir.join(s).to_string_lossy().into_owned();
    draw(&["plot", "humidity", "--scenario", "scenarios/tas2000-humid.json", "--rh", "0.2,0.5", "--out", &d("humid")]);
    assert_eq!(check_folder(&dir.join("humid")), ["humidity-fa0", "humidity-mu", "humidity-share"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("humid/results.json")).unwrap()).unwrap();
    let mu = Data::read(&dir.join("humid/humidity-mu.csv"));
    let model = mu.series("virtual meter");
    assert_eq!(model.iter().map(|p| p.0).collect::<Vec<f64>>(), [0.0, 20.0, 50.0]);
    for (p, r) in model.iter().zip(report["points"].as_array().unwrap()) {
        assert_eq!(p.1, r["mu_apparent"].as_f64().unwrap());
    }
    let measured = mu.rows.iter().find(|r| r.0.starts_with("measured")).unwrap();
    assert_eq!(measured.1, "markers");
    let f = &measured.2;
    assert_eq!(
        [f["relative_humidity_percent"], f["mu_apparent"], f["relative_humidity_percent_err"], f["mu_apparent_err"]],
        [35.0, 0.7, 5.0, 0.3]
    );
    let fa0 = Data::read(&dir.join("humid/humidity-fa0.csv"));
    let measured = &fa0.rows.iter().find(|r| r.0.starts_with("measured")).unwrap().2;
    assert_eq!([measured["apparent_adhesion_force_un"], measured["apparent_adhesion_force_un_err"]], [2.0, 1.3]);
    let share = Data::read(&dir.join("humid/humidity-share.csv")).series("virtual meter");
    assert_eq!(share[0], (0.0, 0.0), "dry: no capillary share");
    assert!(share[1..].iter().all(|p| p.1 > 0.0 && p.1 < 100.0), "{share:?}");

    // results.json holds each figure's series under `figures` (the same names as its CSV).
    for stem in ["humidity-mu", "humidity-fa0", "humidity-share"] {
        let json: BTreeSet<String> = report["figures"][stem]["series"]
            .as_array()
            .unwrap_or_else(|| panic!("no figures.{stem}"))
            .iter()
            .map(|s| s["name"].as_str().unwrap().to_string())
            .collect();
        assert_eq!(json, Data::read(&dir.join(format!("humid/{stem}.csv"))).names(), "{stem}");
    }
    // The journal size: --preset single-column is 85 mm x 60 mm, 1004 x 709 px at 300 dpi.
    let out = stiction(&[
        "plot",
        "humidity",
        "--scenario",
        "scenarios/tas2000-humid.json",
        "--rh",
        "0.3",
        "--preset",
        "single-column",
        "--out",
        &d("column"),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for stem in ["humidity-mu", "humidity-fa0", "humidity-share"] {
        assert_eq!(png_size(&dir.join(format!("column/{stem}.png"))), (1004, 709), "{stem}");
    }

    draw(&["plot", "humidity", "--scenario", "scenarios/tas2000.json", "--rh", "0.3", "--out", &d("dry")]);
    assert_eq!(check_folder(&dir.join("dry")), ["humidity-fa0", "humidity-mu", "humidity-share"]);
    let mu = Data::read(&dir.join("dry/humidity-mu.csv"));
    let band = mu.rows.iter().find(|r| r.0.starts_with("measured")).unwrap();
    assert_eq!(band.1, "y-range");
    assert!(band.0.contains("humidity not stated"), "{}", band.0);
    assert_eq!([band.2["mu_apparent"], band.2["mu_apparent_upper"]], [0.7 - 0.3, 0.7 + 0.3]);
}

/// The pull-in point is a point of the drawn loading curve, where it jumps to the stop.
fn pull_in_on_curve(csv: &Path) {
    let data = Data::read(csv);
    let pull_in = data.series("pull-in");
    assert_eq!(pull_in.len(), 1, "{}", csv.display());
    let (v, x) = pull_in[0];
    let loading = data.series("loading");
    let k = loading
        .iter()
        .position(|p| (p.0 - v).abs() <= 1e-9 * v && (p.1 - x).abs() <= 1e-9 * x)
        .unwrap_or_else(|| panic!("{}: pull-in ({v}, {x}) is not on the loading curve", csv.display()));
    // Next: the jump at the same voltage to the stop.
    let next = *loading.get(k + 1).unwrap_or_else(|| panic!("{}: the loading curve ends at pull-in", csv.display()));
    assert!(next.0 == v && next.1 > x, "{}: no jump at V_pi after the pull-in point: {next:?}", csv.display());
    // Below it the curve rises with the voltage (the stable branch).
    assert!(loading[..=k].windows(2).all(|w| w[1].0 >= w[0].0 && w[1].1 >= w[0].1), "{}", csv.display());
}

#[test]
fn actuator_figures_put_the_pull_in_on_the_curve_and_draw_the_model_over_the_whole_range() {
    let dir = temp_dir("figdata-actuator");
    let out = dir.to_string_lossy().into_owned();
    draw(&[
        "actuator",
        "scenarios/gca-rauf2022.json",
        "--validate",
        "data/gca-pullin-release/measured.csv",
        "--out",
        &out,
    ]);
    assert_eq!(check_folder(&dir), ["hysteresis", "validation"]);
    // The GCA has a stop: the curve ended at 1.386 um, 18.01 V and the marker sat at 1.607 um.
    pull_in_on_curve(&dir.join("hysteresis.csv"));
    let title = &svg_texts(&dir.join("hysteresis.svg"))[0];
    assert!(!title.contains('`'), "{title}");
    let v = Data::read(&dir.join("validation.csv"));
    let measured = v.series("pull-in, measured");
    let model = v.series("pull-in, model");
    // A curve: more finger lengths than measured, from the shortest measured length to the longest.
    assert!(model.len() > 2 * measured.len(), "{} model points for {} measured", model.len(), measured.len());
    let (lo, hi) = measured.iter().fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    assert!((model[0].0 - lo).abs() < 1e-9 && (model[model.len() - 1].0 - hi).abs() < 1e-9, "{model:?}");
    // At the measured lengths the curve is the model of the report (results.json), not a chord.
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("results.json")).unwrap()).unwrap();
    let at_lo = report["points"][0]["pull_in_model_v"].as_f64().unwrap();
    assert!((model[0].1 - at_lo).abs() <= 1e-9 * at_lo, "{} vs {at_lo}", model[0].1);

    let tr = dir.join("transients");
    let out = tr.to_string_lossy().into_owned();
    draw(&[
        "actuator",
        "scenarios/gca-rauf2022.json",
        "--transients",
        "data/gca-transients/measured_times.csv",
        "--out",
        &out,
    ]);
    let stems = check_folder(&tr);
    assert!(stems.iter().filter(|s| s.starts_with("transients_L")).count() >= 2, "{stems:?}");
    // The model as a curve over the measured voltages, not segments between them.
    let t = Data::read(&tr.join("transients_L38.25um.csv"));
    let (model, measured) = (t.series("pull-in, model"), t.series("pull-in, measured"));
    assert!(model.len() > measured.len() + 5, "{} model points for {} measured", model.len(), measured.len());
}

#[test]
fn study_fit_topography_and_bem_figures_have_one_data_shape() {
    let dir = temp_dir("figdata-rest");
    let d = |s: &str| dir.join(s).to_string_lossy().into_owned();

    draw(&["study", "scenarios/tas2000.json", "--samples", "40", "--quiet", "--out", &d("study")]);
    assert_eq!(check_folder(&dir.join("study")), ["mu_cdf", "mu_vs_fa0", "sensitivity_indices"]);
    // The CDF is i/n: from 0 up to 1 in steps of 1/n at the sorted values.
    let cdf = Data::read(&dir.join("study/mu_cdf.csv")).series("virtual meters");
    let n = cdf.len() - 1;
    assert_eq!(cdf[0].1, 0.0);
    for (i, p) in cdf.iter().enumerate().skip(1) {
        assert!((p.1 - i as f64 / n as f64).abs() < 1e-12, "CDF point {i}: {p:?} of n = {n}");
        assert!(p.0 >= cdf[i - 1].0);
    }
    // Sobol: first and total order, each with its interval segments (low to high) around the estimate.
    let s = Data::read(&dir.join("study/sensitivity_indices.csv"));
    let names = s.names();
    for want in ["first order", "total order"] {
        assert!(names.iter().filter(|n| n.ends_with(want)).count() == 2, "{want}: {names:?}");
    }
    // The interval segments are `line` rows of the series of their estimates (named as in the
    // legend), two rows each.
    let segments: Vec<(String, f64, f64)> =
        s.rows.iter().filter(|r| r.1 == "line").map(|r| (r.0.clone(), r.2[s.x()], r.2[s.y()])).collect();
    assert!(!segments.is_empty() && segments.len().is_multiple_of(2));
    for pair in segments.chunks(2) {
        assert!(pair[0].0 == pair[1].0 && pair[0].1 == pair[1].1 && pair[0].2 <= pair[1].2, "{pair:?}");
        let marks: Vec<f64> = s
            .rows
            .iter()
            .filter(|r| r.1 == "markers" && r.0 == pair[0].0 && r.2[s.x()] == pair[0].1)
            .map(|r| r.2[s.y()])
            .collect();
        assert_eq!(marks.len(), 1, "one estimate of {} per interval at x = {}", pair[0].0, pair[0].1);
    }
    // Every point names its input by its path in the scenario (the `label` column).
    let text = std::fs::read_to_string(dir.join("study/sensitivity_indices.csv")).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    assert_eq!(r.headers().unwrap().get(2), Some("label"));
    let labels: Vec<String> = r.records().map(|rec| rec.unwrap()[2].to_string()).collect();
    assert!(labels.iter().any(|l| l == "actuators.clamp.conversion_factor"), "{labels:?}");
    assert!(labels.iter().all(|l| !l.is_empty()), "{labels:?}");

    draw(&[
        "fit",
        "--scenario",
        "scenarios/tas2000-fit-synthetic.json",
        "--models",
        "discrete-n3,gw-dmt,explicit-ensemble",
        "--surfaces",
        "4",
        "--draws",
        "100",
        "--out",
        &d("fit"),
    ]);
    assert_eq!(check_folder(&dir.join("fit")), ["fit-friction-load", "fit-residuals", "fit-vpull2"]);
    // One residual series per model (and the zero line), not one per point.
    let res = Data::read(&dir.join("fit/fit-residuals.csv"));
    assert_eq!(res.names(), ["discrete-n3", "explicit-ensemble", "gw-dmt", "zero"].map(String::from).into());
    // The band says how many surfaces it comes from; the measured points come last (on top).
    let vp = Data::read(&dir.join("fit/fit-vpull2.csv"));
    assert!(vp.names().iter().any(|n| n.contains("roughness band") && n.ends_with(" surfaces")), "{:?}", vp.names());
    assert!(vp.rows.last().unwrap().0.starts_with("measured"));

    draw(&["topography", "data/topography-example/wall.gsf", "--out", &d("topo")]);
    assert_eq!(check_folder(&dir.join("topo")), ["height_map", "psd", "summit_heights", "summit_radii"]);
    // In the axes' units: heights in nm (tens), radii in um (tenths), frequencies in 1/um.
    let h = Data::read(&dir.join("topo/summit_heights.csv")).series("map");
    let top = h.iter().map(|p| p.0.abs()).fold(0.0, f64::max);
    assert!((1.0..1e4).contains(&top), "summit heights in nm, not m: {top}");
    let r = Data::read(&dir.join("topo/summit_radii.csv")).series("map");
    let top = r.iter().map(|p| p.0).fold(0.0, f64::max);
    assert!((0.01..1e3).contains(&top), "summit radii in um, not m: {top}");
    // The summit heights beside Nayak's prediction from the same map.
    assert!(Data::read(&dir.join("topo/summit_heights.csv")).names().iter().any(|n| n.starts_with("Nayak")));

    draw(&[
        "bem",
        "--map",
        "data/topography-example/wall.gsf",
        "--e-star",
        "82.4 GPa",
        "--sweep",
        "2MPa:2GPa:3",
        "--out",
        &d("bem"),
    ]);
    assert_eq!(check_folder(&dir.join("bem")), ["gap", "height", "load_area", "load_gap", "pressure"]);
    // Maps at full resolution: one CSV row per grid cell (640 x 200), pressures in GPa.
    let p = std::fs::read_to_string(dir.join("bem/pressure.csv")).unwrap();
    assert!(p.starts_with("x_um,y_um,pressure_gpa\n"), "{}", &p[..40]);
    assert_eq!(p.lines().count(), 1 + 640 * 200);
}
