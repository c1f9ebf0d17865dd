//! Renders charts like the program's at the journal preset and at 400 x 280 px, for looking at.
use stiction_plot::{Chart, ImageMap, Series};

fn chart() -> Chart {
    let model = |a: f64| {
        (0..60)
            .map(|i| {
                let x = i as f64 * 0.5;
                (x, a * x + 2.0 + 0.3 * (x * 0.4).sin())
            })
            .collect::<Vec<_>>()
    };
    let mut c = Chart::new(
        "Static friction F_f against load L: virtual meter, eq. 10 fit and the paper's measurement (Tas et al. 2000)",
        "load L (µN)",
        "static friction F_f (µN)",
    )
    .with(Series::line("explicit solver, one loading path from pull-off", model(0.7)))
    .with(Series::dashed("eq. 10: μ_e,a = 0.70 (slope at 3 µN), F_a0 = 2.00 µN", model(0.65)))
    .with(Series::line("gw-dmt", model(0.6)))
    .with(Series::markers("measured (mean, error bar: SD of repeats)", vec![(2.0, 3.5), (10.0, 9.4), (20.0, 16.0), (29.0, 22.0)]).with_y_err(vec![0.5, 0.8, 1.0, 1.1]))
    .with(Series::y_range("measured μ_e,a = 0.7 ± 0.3", 1.0, 3.0))
    .with_note("measured ±: uncertainty stated by the paper, from the uncertainty of the conversion factors a_clamp and a_pull; virtual meter: shoe clamped anew at each load");
    c.legend = stiction_plot::LegendPosition::UpperLeft;
    c
}

fn main() {
    let out = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or("/tmp/fp".into()));
    let c = chart();
    c.clone().physical((85.0, 60.0), None).unwrap().write(&out.join("journal.png")).unwrap();
    c.clone().physical((85.0, 60.0), None).unwrap().write(&out.join("journal.svg")).unwrap();
    c.clone().sized(Some((400, 280)), None).unwrap().write(&out.join("small.png")).unwrap();
    c.write(&out.join("default.png")).unwrap();
    for (name, l) in [
        ("journal", chart().physical((85.0, 60.0), None).unwrap().layout().unwrap()),
        ("small", chart().sized(Some((400, 280)), None).unwrap().layout().unwrap()),
    ] {
        println!("{name}: {:?}", l.problems());
    }
    let n = 64;
    let values: Vec<f64> = (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64, (i / n) as f64);
            1e9 * (1.0 + (x * 0.2).sin() * (y * 0.15).cos()) * 14.0
        })
        .collect();
    let m = ImageMap {
        title: "Pressure at the last state, load 3 µN".into(),
        x_label: "x (µm)".into(),
        y_label: "y (µm)".into(),
        value_label: "pressure".into(),
        value_unit: Some("Pa".into()),
        nx: n,
        ny: n,
        values,
        x_max: 6.4,
        y_max: 6.4,
        markers: vec![(1.0, 2.0), (3.0, 3.5)],
        ..Default::default()
    };
    m.write(&out.join("map.png")).unwrap();
    m.write(&out.join("map.svg")).unwrap();
    let mut j = m.clone();
    j.size_mm = Some((85.0, 70.0));
    j.write(&out.join("map_journal.png")).unwrap();
    println!("map: {:?}", j.layout().unwrap().problems());
}
