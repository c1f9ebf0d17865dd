//! Tests of charts: dodge, SVG and PNG output, formats, the data CSV, log ticks, column keys.

use std::path::PathBuf;

use super::scales::{Scale, tick_label, ticks};
use super::*;

fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stiction-plot-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sample() -> Chart {
    Chart::new("Test chart", "load L (µN)", "friction F_f (µN)")
        .with(Series::line("model", (0..10).map(|i| (i as f64, (i * i) as f64)).collect()))
        .with(Series::markers("data", vec![(1.0, 1.2), (2.0, 3.9)]).with_y_err(vec![0.3, 0.4]))
        .with(Series::y_range("measured range", 2.0, 5.0))
}

/// A dodge draws the markers (and their error bars) shifted by its fraction of the plot's
/// width, and the data CSV keeps the true x: two series at the same point stay apart.
#[test]
fn a_dodge_shifts_the_drawn_markers_not_the_data() {
    let chart = |dodge: f64| {
        let mut c = Chart::new("dodge", "x", "y")
            .with(Series::markers("a", vec![(1.0, 1.0), (2.0, 2.0)]).with_y_err(vec![0.1, 0.1]).with_dodge(dodge));
        // (Room on both sides, so that no shifted position leaves the axes.)
        c.x_range = Some((0.0, 3.0));
        c.y_range = Some((0.0, 3.0));
        c
    };
    let (plain, moved) = (chart(0.0), chart(0.05));
    let (lp, lm) = (plain.layout().unwrap(), moved.layout().unwrap());
    assert_eq!(lp.plot, lm.plot);
    let shift = 0.05 * lp.plot.width();
    // Markers and the sampled error bars: every drawn position moves by the shift, none stays.
    assert_eq!(lp.points.len(), lm.points.len());
    for (a, b) in lp.points.iter().zip(&lm.points) {
        assert!((b.0 - a.0 - shift).abs() < 1e-9 && (b.1 - a.1).abs() < 1e-9, "{a:?} -> {b:?}");
    }
    assert_eq!(plain.data_csv(), moved.data_csv());
}

#[test]
fn writes_an_svg_with_the_labels_and_refuses_an_empty_chart() {
    let dir = tmp("svg");
    let path = dir.join("c.svg");
    sample().write(&path).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.contains("Test chart") && svg.contains("friction F<tspan") && svg.contains("data"));
    assert!(!svg.contains("F_f"), "no literal underscore: {svg}");
    // Legend swatch of the markers series is a marker: 2 data circles + 1 in the legend.
    // (the error bars draw open circles of their own; markers are filled)
    let filled = svg.split("<circle").skip(1).filter(|c| c.contains(r#"stroke="none""#)).count();
    assert_eq!(filled, 3, "{svg}");
    let empty = Chart { y_log: true, ..Chart::new("e", "x", "y") }.with(Series::line("neg", vec![(1.0, -1.0)]));
    assert!(matches!(empty.write_svg(&dir.join("e.svg")), Err(PlotError::Empty { .. })));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unknown_extensions_are_errors_and_png_is_png() {
    let dir = tmp("fmt");
    let err = sample().write(&dir.join("p.txt")).unwrap_err();
    assert!(err.to_string().contains("\"txt\"") && err.to_string().contains(".svg or .png"), "{err}");
    assert!(!dir.join("p.txt").exists());
    sample().write(&dir.join("p.png")).unwrap();
    let bytes = std::fs::read(dir.join("p.png")).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(sample().sized(Some((100, 100)), None).is_err());
    assert!(sample().sized(None, Some(100.0)).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_data_csv_holds_every_plotted_number_with_units_in_the_header() {
    let dir = tmp("csv");
    let path = dir.join("fig.svg");
    let csv_path = sample().write_with_data(&path).unwrap();
    assert_eq!(csv_path, dir.join("fig.csv"));
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "series,style,load_l_un,friction_f_f_un,load_l_un_err,friction_f_f_un_err,friction_f_f_un_upper,load_l_un_upper"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 10 + 2 + 1);
    assert_eq!(rows[3], "model,line,3,9,,,,");
    assert_eq!(rows[11], "data,markers,2,3.9,,0.4,,");
    assert_eq!(rows[12], "measured range,y-range,,2,,,5,");
    // the JSON holds the same numbers under the same keys
    let json = sample().data_json();
    let data = &json["series"][1];
    assert_eq!(data["name"], "data");
    assert_eq!(data["friction_f_f_un_err"], serde_json::json!([0.3, 0.4]));
    assert_eq!(json["series"][2]["friction_f_f_un_upper"], serde_json::json!([5.0]));
    assert!(json["series"][0].get("load_l_un_err").is_none());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn log_ticks_use_one_format() {
    let log = Scale::Log;
    assert_eq!(tick_label(-3.0, log, -4.0, 0.0), "10⁻³");
    assert_eq!(tick_label(2.0, log, -1.0, 3.0), "10²");
    // between decades only on short axes: as a·10ⁿ far from 1, else plain numbers
    assert_eq!(tick_label(-4.0 + 2f64.log10(), log, -5.0, -3.0), "2·10⁻⁴");
    assert_eq!(tick_label(-4.0 + 2f64.log10(), log, -8.0, -3.0), "");
    assert_eq!(tick_label(1.0 + 2f64.log10(), log, 1.0, 2.5), "20");
    assert_eq!(tick_label(2.0, log, 1.0, 2.5), "100");
    assert_eq!(tick_label(-2.0 + 5f64.log10(), log, -2.1, -0.5), "0.05");
    assert_eq!(tick_label(2.5, Scale::Linear, 0.0, 10.0), "2.5");
    assert_eq!(tick_label(-2.5, Scale::Linear, -5.0, 5.0), "−2.5");
    assert_eq!(tick_label(3.2e-6, Scale::Linear, 0.0, 1e-5), "3.2·10⁻⁶");
    // the chosen ticks of a log axis: decades, and 2, 5 between them on short axes
    let (bold, light) = ticks(log, -1.35, 0.2, 10.0);
    let labels: Vec<String> = bold.iter().map(|v| tick_label(*v, log, -1.35, 0.2)).collect();
    assert_eq!(labels, ["0.05", "0.1", "0.2", "0.5", "1"]);
    let labels: Vec<String> = bold.iter().map(|v| tick_label(*v - 5.0, log, -6.35, -4.8)).collect();
    assert_eq!(labels, ["5·10⁻⁷", "10⁻⁶", "2·10⁻⁶", "5·10⁻⁶", "10⁻⁵"]);
    assert!(light.len() > bold.len());
    let (bold, _) = ticks(log, -6.2, 0.3, 10.0);
    assert_eq!(bold, [-6.0, -5.0, -4.0, -3.0, -2.0, -1.0, 0.0]);
    // symmetric log: 0 and signed powers of ten, both sides visible
    let sym = Scale::SymLog(1e-5);
    let (lo, hi) = (sym.to_axis(-0.03), sym.to_axis(1.0));
    let (bold, _) = ticks(sym, lo, hi, 10.0);
    let labels: Vec<String> = bold.iter().map(|v| tick_label(*v, sym, lo, hi)).collect();
    assert_eq!(labels, ["−10⁻²", "−10⁻³", "−10⁻⁴", "0", "10⁻⁴", "10⁻³", "10⁻²", "10⁻¹", "10⁰"]);
    assert!((sym.to_data(sym.to_axis(-2e-5)) + 2e-5).abs() < 1e-18);
}

#[test]
fn column_keys_are_ascii_with_units() {
    assert_eq!(column_key("V_pull² (V²)"), "v_pull2_v2");
    assert_eq!(column_key("apparent friction coefficient μ_e,a"), "apparent_friction_coefficient_mu_e_a");
    assert_eq!(column_key("load L (µN)"), "load_l_un");
}
