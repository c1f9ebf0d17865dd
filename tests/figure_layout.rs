//! Every figure every command draws, at the journal preset (85 mm x 60 mm, 8 pt) and at
//! 400 x 280 px, checked from its drawn elements: the program writes each figure's layout (every
//! text box, the plot area, the legend and the drawn data positions) as JSON into the folder named
//! by `STICTION_LAYOUT_DIR`, and this test checks the boxes itself (not through the plot crate's
//! `Layout::problems`, so that it does not trust the code it tests):
//!
//! - every text lies inside the canvas (0.5 px of tolerance);
//! - the tick labels of an axis do not overlap one another;
//! - the legend covers no drawn data point; a legend outside the axes does not overlap them;
//! - titles, captions, axis labels and tick labels overlap neither each other, nor the plot area,
//!   nor a legend outside the axes;
//! - the font is at least 0.85 of the size asked for (the legibility floor: 6.8 pt at 8 pt).
//!
//! One line of [`CASES`] adds a command.

use std::path::Path;

use crate::util::{root, temp_dir};

/// A command line whose figures are checked. `{dir}` in an argument is the case's own folder;
/// `setup` runs first (e.g. the shards `merge` combines), without layouts recorded; `figures` is
/// the least number of figure files the command must draw.
struct Case {
    name: &'static str,
    setup: &'static [&'static [&'static str]],
    args: &'static [&'static str],
    figures: usize,
}

const fn case(name: &'static str, args: &'static [&'static str], figures: usize) -> Case {
    Case { name, setup: &[], args, figures }
}

/// Every command that draws, with the figures it draws (SVG and PNG count separately).
const CASES: &[Case] = &[
    case("run", &["run", "scenarios/tas2000.json", "--out", "{dir}/out"], 4),
    case("run-measured", &["run", "scenarios/tas2000-fit-synthetic.json", "--out", "{dir}/out"], 4),
    case("plot-fig2", &["plot", "fig2", "--out", "{dir}/fig2.png"], 1),
    case("plot-fig3", &["plot", "fig3", "--out", "{dir}/fig3.png"], 1),
    case("plot-fig7", &["plot", "fig7", "--out", "{dir}/fig7.png"], 1),
    case(
        "plot-fig7-scenario",
        &["plot", "fig7", "--scenario", "scenarios/tas2000-maugis-dugdale.json", "--out", "{dir}/fig7.png"],
        1,
    ),
    case("plot-actuator", &["plot", "actuator", "--scenario", "scenarios/tas2000.json", "--out", "{dir}/a.png"], 1),
    case(
        "plot-actuator-pull",
        &["plot", "actuator", "--scenario", "scenarios/tas2000.json", "--array", "pull", "--out", "{dir}/a.png"],
        1,
    ),
    case(
        "plot-humidity",
        &[
            "plot",
            "humidity",
            "--scenario",
            "scenarios/tas2000-humid.json",
            "--rh",
            "0.2,0.5,0.9",
            "--out",
            "{dir}/out",
        ],
        6,
    ),
    case("study", &["study", "scenarios/tas2000.json", "--samples", "40", "--quiet", "--out", "{dir}/out"], 6),
    case(
        "design",
        &[
            "study",
            "scenarios/tas2000.json",
            "--samples",
            "24",
            "--quiet",
            "--vary",
            "actuators.pull.spring.stiffness=1 N/m,3 N/m",
            "--out",
            "{dir}/out",
        ],
        2,
    ),
    case(
        "fit",
        &[
            "fit",
            "--scenario",
            "scenarios/tas2000-fit-synthetic.json",
            "--surfaces",
            "4",
            "--draws",
            "200",
            "--out",
            "{dir}/out",
        ],
        6,
    ),
    case(
        "actuator-validation",
        &[
            "actuator",
            "scenarios/gca-rauf2022.json",
            "--validate",
            "data/gca-pullin-release/measured.csv",
            "--out",
            "{dir}/out",
        ],
        4,
    ),
    case(
        "actuator-transients",
        &[
            "actuator",
            "scenarios/gca-rauf2022.json",
            "--transients",
            "data/gca-transients/measured_times.csv",
            "--out",
            "{dir}/out",
        ],
        2,
    ),
    case("topography", &["topography", "data/topography-example/wall.gsf", "--out", "{dir}/out"], 8),
    case(
        "bem",
        &[
            "bem",
            "--map",
            "data/topography-example/wall.gsf",
            "--e-star",
            "82.4 GPa",
            "--sweep",
            "2MPa:2GPa:4",
            "--compare-asperity",
            "--out",
            "{dir}/out",
        ],
        12,
    ),
    Case {
        name: "merge",
        setup: &[
            &["study", "scenarios/tas2000.json", "--samples", "40", "--quiet", "--shard", "0/2", "--out", "{dir}/s0"],
            &["study", "scenarios/tas2000.json", "--samples", "40", "--quiet", "--shard", "1/2", "--out", "{dir}/s1"],
        ],
        args: &["merge", "{dir}/s0", "{dir}/s1", "--out", "{dir}/out"],
        figures: 6,
    },
];

/// The two sizes every figure must survive.
const SIZES: [(&str, &[&str]); 2] =
    [("single-column", &["--preset", "single-column"]), ("400x280", &["--width", "400", "--height", "280"])];

/// The legibility floor: the smallest fraction of the requested font a layout may use.
const FONT_FLOOR: f64 = 0.85;

type Boxes = Vec<(String, [f64; 4])>;

fn rect(v: &serde_json::Value) -> [f64; 4] {
    let a = v.as_array().unwrap_or_else(|| panic!("not a box: {v}"));
    [0, 1, 2, 3].map(|i| a[i].as_f64().unwrap_or_else(|| panic!("not a number in {v}")))
}

fn texts(l: &serde_json::Value, key: &str) -> Boxes {
    l[key]
        .as_array()
        .unwrap_or_else(|| panic!("layout without {key}"))
        .iter()
        .map(|t| (t["text"].as_str().unwrap_or_default().to_string(), rect(&t["box"])))
        .collect()
}

fn overlap(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// What is wrong with one figure's layout, one line each.
fn layout_faults(l: &serde_json::Value) -> Vec<String> {
    let mut out = Vec::new();
    let (w, h) = (l["width_px"].as_f64().unwrap(), l["height_px"].as_f64().unwrap());
    let plot = rect(&l["plot"]);
    let (font, asked) = (l["font_px"].as_f64().unwrap(), l["requested_font_px"].as_f64().unwrap());
    if font < FONT_FLOOR * asked - 1e-9 {
        out.push(format!("font {font:.2} px is below {FONT_FLOOR} of the {asked:.2} px asked for"));
    }
    let keys = ["title", "caption", "x_label", "y_label", "x_ticks", "y_ticks", "legend_entries"];
    for key in keys {
        for (t, r) in texts(l, key) {
            if r[0] < -0.5 || r[1] < -0.5 || r[2] > w + 0.5 || r[3] > h + 0.5 {
                out.push(format!("{key} {t:?} at {r:?} leaves the {w:.0} x {h:.0} canvas"));
            }
        }
    }
    for key in ["x_ticks", "y_ticks"] {
        let ticks = texts(l, key);
        for (i, a) in ticks.iter().enumerate() {
            for b in &ticks[i + 1..] {
                if overlap(&a.1, &b.1) {
                    out.push(format!("{key} {:?} and {:?} overlap", a.0, b.0));
                }
            }
        }
    }
    let legend = (!l["legend"].is_null()).then(|| rect(&l["legend"]));
    let inside = l["legend_inside"].as_bool().unwrap_or(false);
    if let Some(g) = legend {
        for p in l["points"].as_array().unwrap() {
            let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            if x >= g[0] && x <= g[2] && y >= g[1] && y <= g[3] {
                out.push(format!("the legend {g:?} covers the data point ({x:.1}, {y:.1})"));
                break;
            }
        }
        if !inside && overlap(&g, &plot) {
            out.push(format!("the legend {g:?} outside the axes overlaps the plot {plot:?}"));
        }
    }
    let outer: Boxes =
        ["title", "caption", "x_label", "y_label", "x_ticks", "y_ticks"].iter().flat_map(|k| texts(l, k)).collect();
    let inner_plot = [plot[0] + 0.5, plot[1] + 0.5, plot[2] - 0.5, plot[3] - 0.5];
    for (i, a) in outer.iter().enumerate() {
        if overlap(&a.1, &inner_plot) {
            out.push(format!("{:?} lies over the plot", a.0));
        }
        for b in &outer[i + 1..] {
            if overlap(&a.1, &b.1) {
                out.push(format!("{:?} and {:?} overlap", a.0, b.0));
            }
        }
        if let Some(g) = legend.filter(|_| !inside)
            && overlap(&a.1, &g)
        {
            out.push(format!("{:?} lies under the legend", a.0));
        }
    }
    out
}

fn run_in(dir: &Path, args: &[&str], layouts: Option<&Path>) -> std::process::Output {
    let d = dir.to_str().unwrap();
    let args: Vec<String> = args.iter().map(|a| a.replace("{dir}", d)).collect();
    let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_stiction"));
    cmd.args(&args).current_dir(root());
    if let Some(l) = layouts {
        cmd.env("STICTION_LAYOUT_DIR", l);
    }
    let out = cmd.output().expect("run stiction");
    assert!(out.status.success(), "stiction {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    out
}

/// The faults of every figure a case draws at one size, each line naming the figure.
fn case_faults(c: &Case, size: &str, size_args: &[&str]) -> Vec<String> {
    let dir = temp_dir(&format!("layout-{}-{size}", c.name));
    for s in c.setup {
        run_in(&dir, s, None);
    }
    let layouts = dir.join("layouts");
    let mut args = c.args.to_vec();
    args.extend(size_args);
    run_in(&dir, &args, Some(&layouts));
    let mut files: Vec<_> =
        std::fs::read_dir(&layouts).map(|d| d.flatten().map(|e| e.path()).collect()).unwrap_or_default();
    files.sort();
    let mut faults = Vec::new();
    if files.len() < c.figures {
        faults.push(format!("{} at {size}: {} figure layouts, expected at least {}", c.name, files.len(), c.figures));
    }
    for f in files {
        let l: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&f).unwrap()).unwrap();
        let name = f.file_name().unwrap().to_string_lossy().replace(".layout.json", "");
        faults.extend(layout_faults(&l).into_iter().map(|p| format!("{} {name} at {size}: {p}", c.name)));
    }
    faults.extend(data_faults(&dir).into_iter().map(|p| format!("{} at {size}: {p}", c.name)));
    let _ = std::fs::remove_dir_all(&dir);
    faults
}

/// Every figure (`*.svg`, `*.png`) under `dir` has its data CSV beside it in the documented shape
/// (docs/figures.md, "Data CSV"): a chart's `series,style[,label],X,Y,X_err,Y_err,Y_upper,X_upper`,
/// a map's `x_um,y_um,VALUE_UNIT`, the x and y columns each followed by their `_err` and `_upper`
/// columns in that order; every number Rust's shortest decimal of an f64 (it prints
/// back to the same text), no NaN or infinity.
fn data_faults(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                if !p.ends_with("layouts") {
                    stack.push(p);
                }
                continue;
            }
            if !matches!(p.extension().and_then(|e| e.to_str()), Some("svg" | "png")) {
                continue;
            }
            let csv = p.with_extension("csv");
            let Ok(text) = std::fs::read_to_string(&csv) else {
                out.push(format!("{} has no data CSV beside it", p.display()));
                continue;
            };
            let mut lines = text.lines();
            let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
            let chart = header.starts_with(&["series", "style"]);
            let map = header.len() == 3 && header[0] == "x_um" && header[1] == "y_um";
            let first = if chart { if header.get(2) == Some(&"label") { 3 } else { 2 } } else { 0 };
            // (Column names carry their unit, `load_un`, but a dimensionless one has none,
            // `theta`: the unit is not checked here.)
            let cols = if chart { 6 } else { 3 };
            if !(chart || map) || header.len() != first + cols || header[first..].iter().any(|k| k.is_empty()) {
                out.push(format!("{}: header {header:?} is not the documented shape", csv.display()));
                continue;
            }
            if chart {
                let (x, y) = (header[first], header[first + 1]);
                let want = [format!("{x}_err"), format!("{y}_err"), format!("{y}_upper"), format!("{x}_upper")];
                if header[first + 2..] != want.iter().map(String::as_str).collect::<Vec<_>>()[..] {
                    out.push(format!("{}: header {header:?} is not the documented shape", csv.display()));
                    continue;
                }
            }
            let mut rows = csv_rows(&text);
            rows.remove(0);
            for (i, row) in rows.iter().enumerate() {
                for cell in &row[first.min(row.len())..] {
                    if cell.is_empty() {
                        continue;
                    }
                    match cell.parse::<f64>() {
                        Ok(v) if v.is_finite() && format!("{v}") == *cell => {}
                        _ => {
                            out.push(format!(
                                "{} line {}: {cell:?} is not a shortest finite decimal",
                                csv.display(),
                                i + 2
                            ));
                            break;
                        }
                    }
                }
            }
        }
    }
    out
}

/// The records of a CSV text (quoted fields may hold commas).
fn csv_rows(text: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for line in text.lines() {
        let (mut row, mut cell, mut quoted) = (Vec::new(), String::new(), false);
        let mut chars = line.chars().peekable();
        while let Some(c) = chars.next() {
            match c {
                '"' if quoted && chars.peek() == Some(&'"') => {
                    cell.push('"');
                    chars.next();
                }
                '"' => quoted = !quoted,
                ',' if !quoted => row.push(std::mem::take(&mut cell)),
                _ => cell.push(c),
            }
        }
        row.push(cell);
        rows.push(row);
    }
    rows
}

#[test]
fn every_figure_of_every_command_fits_a_journal_column_and_a_small_preview() {
    let faults: Vec<String> =
        CASES.iter().flat_map(|c| SIZES.iter().flat_map(move |(size, a)| case_faults(c, size, a))).collect();
    assert!(faults.is_empty(), "{} layout faults:\n{}", faults.len(), faults.join("\n"));
}

/// The checker finds what it is meant to find: a tick label moved onto its neighbour, a text
/// pushed off the canvas, a legend moved onto a data point and a font under the floor are each
/// reported (a layout the program drew, then broken by hand).
#[test]
fn the_layout_checker_catches_broken_layouts() {
    let dir = temp_dir("layout-checker");
    let layouts = dir.join("layouts");
    run_in(&dir, &["plot", "fig7", "--out", "{dir}/fig7.png", "--preset", "single-column"], Some(&layouts));
    let text = std::fs::read_to_string(layouts.join("fig7.png.layout.json")).unwrap();
    let good: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(layout_faults(&good), Vec::<String>::new());
    let mut bad = good.clone();
    let first = bad["x_ticks"][0]["box"].clone();
    bad["x_ticks"][1]["box"] = first;
    assert!(layout_faults(&bad).iter().any(|f| f.contains("x_ticks") && f.contains("overlap")), "tick overlap");
    let mut bad = good.clone();
    bad["title"][0]["box"][2] = serde_json::json!(good["width_px"].as_f64().unwrap() + 3.0);
    assert!(layout_faults(&bad).iter().any(|f| f.contains("leaves the")), "text off the canvas");
    let mut bad = good.clone();
    let p = bad["points"][0].clone();
    let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
    bad["legend"] = serde_json::json!([x - 1.0, y - 1.0, x + 1.0, y + 1.0]);
    bad["legend_inside"] = serde_json::json!(true);
    assert!(layout_faults(&bad).iter().any(|f| f.contains("covers the data point")), "legend over data");
    let mut bad = good;
    bad["font_px"] = serde_json::json!(0.8 * bad["requested_font_px"].as_f64().unwrap());
    assert!(layout_faults(&bad).iter().any(|f| f.contains("below 0.85")), "font under the floor");
    let _ = std::fs::remove_dir_all(&dir);
}
