//! The two figures of docs/published.md from data/published-friction/atlas.csv (written by
//! scripts/published-atlas.py, which runs this example): predicted against measured friction
//! coefficients, and the lab's coefficient against the load per apparent area with the adhesion.
//!
//! `cargo run --release -p stiction-plot --example published_atlas -- <atlas.csv> <out dir>`
use std::collections::HashMap;

use stiction_plot::{Chart, LegendPosition, Series};

/// The names in the order of their x values ("a 0.27, b 0.45").
fn order(x: &[f64], names: &[String]) -> String {
    let mut v: Vec<(f64, &String)> = x.iter().copied().zip(names).collect();
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    v.iter()
        .map(|(x, n)| if *x >= 100.0 { format!("{n} ({x:.0})") } else { format!("{n} ({x:.3})") })
        .collect::<Vec<_>>()
        .join(", ")
}

fn main() {
    let mut args = std::env::args().skip(1);
    let csv_path = args.next().unwrap_or_else(|| "data/published-friction/atlas.csv".into());
    let out = std::path::PathBuf::from(args.next().unwrap_or_else(|| "docs/figures".into()));
    let mut reader = csv::Reader::from_path(&csv_path).expect("the atlas CSV");
    let header: Vec<String> = reader.headers().expect("a header").iter().map(str::to_string).collect();
    let rows: Vec<HashMap<String, String>> = reader
        .records()
        .map(|r| header.iter().cloned().zip(r.expect("a row").iter().map(str::to_string)).collect())
        .collect();
    let num = |r: &HashMap<String, String>, k: &str| r[k].parse::<f64>().ok();
    let mu: Vec<&HashMap<String, String>> = rows.iter().filter(|r| r["quantity"] == "mu").collect();
    let names: Vec<String> = mu.iter().map(|r| r["experiment"].clone()).collect();

    // Figure 1: predicted against measured.
    let measured: Vec<f64> = mu.iter().map(|r| num(r, "measured").unwrap()).collect();
    let x_err: Vec<f64> = mu.iter().map(|r| num(r, "measured_uncertainty").unwrap_or(0.0)).collect();
    let lo: Vec<f64> = mu.iter().map(|r| num(r, "predicted_p05").unwrap()).collect();
    let hi: Vec<f64> = mu.iter().map(|r| num(r, "predicted_p95").unwrap()).collect();
    let med: Vec<f64> = mu.iter().map(|r| num(r, "predicted_median").unwrap()).collect();
    let mid: Vec<(f64, f64)> =
        measured.iter().zip(lo.iter().zip(&hi)).map(|(&m, (&l, &h))| (m, 0.5 * (l + h))).collect();
    let half: Vec<f64> = lo.iter().zip(&hi).map(|(l, h)| 0.5 * (h - l)).collect();
    let diag = vec![(0.1, 0.1), (10.0, 10.0)];
    let mut c = Chart::new(
        "Published MEMS static friction: predicted (stiction study over the unknowns) against measured",
        "measured friction coefficient (as published)",
        "predicted μ_e,a",
    )
    .with(Series::dashed("predicted = measured", diag))
    .with(
        Series::markers("predicted 5-95 % (vertical bar, square at its middle); measured ± stated uncertainty", mid)
            .with_y_err(half)
            .with_x_err(x_err)
            .with_marker(stiction_plot::Marker::Square),
    )
    .with(Series::markers("predicted median", measured.iter().copied().zip(med.iter().copied()).collect()).with_labels(names.clone()))
    .with_note(format!(
        "left to right: {}; 64 samples, seed 1 (scripts/published-atlas.py); the pentanol row (a force) is in the table only",
        order(&measured, &names)
    ));
    c.x_log = true;
    c.y_log = true;
    c.x_range = Some((0.1, 10.0));
    c.y_range = Some((0.05, 10.0));
    c.legend = LegendPosition::UpperLeft;
    c.write(&out.join("published-predicted-vs-measured.png")).expect("write");
    c.write_with_data(&out.join("published-predicted-vs-measured.svg")).expect("write");

    // Figure 2: the lab's coefficient against the load per apparent area, with the adhesion.
    let load: Vec<f64> = mu.iter().map(|r| num(r, "load_per_area_pa").unwrap()).collect();
    let lab: Vec<f64> = mu.iter().map(|r| num(r, "lab_number_nominal").unwrap()).collect();
    let names2: Vec<String> = mu.iter().map(|r| r["experiment"].clone()).collect();
    let mut sorted: Vec<(f64, String)> = mu
        .iter()
        .map(|r| (num(r, "load_per_area_pa").unwrap(), format!("{} {}", r["experiment"], r["adhesion_ratio"])))
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let ratios: Vec<String> = sorted.into_iter().map(|(_, s)| s).collect();
    let labels: Vec<String> = mu
        .iter()
        .map(|r| format!("{} (F_a0/L = {}, {})", r["experiment"], r["adhesion_ratio"], r["lab_reduction"]))
        .collect();
    let mut c = Chart::new(
        "The lab's friction coefficient against the load per apparent area: measured and the virtual lab's",
        "mean applied load per apparent area L/A_a (Pa)",
        "friction coefficient",
    )
    .with(
        Series::markers("measured (as published)", load.iter().copied().zip(measured.iter().copied()).collect())
            .with_y_err(mu.iter().map(|r| num(r, "measured_uncertainty").unwrap_or(0.0)).collect())
            .with_labels(names),
    )
    .with(
        Series::markers(
            "virtual lab's number, nominal inputs (its own reduction)",
            load.iter().copied().zip(lab).collect(),
        )
        .with_labels(labels)
        .with_marker(stiction_plot::Marker::Triangle),
    )
    .with_note(format!(
        "left to right: {}; F_a0/L at the nominal inputs: {}",
        order(&load, &names2),
        ratios.join(", ")
    ));
    c.x_log = true;
    c.y_log = true;
    c.y_range = Some((0.05, 10.0));
    c.legend = LegendPosition::UpperRight;
    c.write(&out.join("published-spread.png")).expect("write");
    c.write_with_data(&out.join("published-spread.svg")).expect("write");
}
