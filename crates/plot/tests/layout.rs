//! Engine-level layout test: charts shaped like the program's (many series, long titles, long
//! legend names, notes, named ticks, log axes, data in every corner), drawn at the single-column
//! journal preset (85 mm x 60 mm, 8 pt) and at 400 x 280 px, checked from the element boxes the
//! chart reports: every text inside the canvas, tick labels of an axis not touching, no text over
//! the plot area or over other text, and the legend over no drawn data point.

use stiction_plot::{Chart, Layout, LegendPosition, Rect, Series};

fn fig7_like() -> Chart {
    let curve = |a: f64, b: f64| (0..80).map(|i| (i as f64 * 0.4, a * i as f64 * 0.4 + b)).collect::<Vec<_>>();
    let mut c = Chart::new(
        "Static friction against load: explicit solver, discrete model and eq. 10 fit, with the paper's measurement",
        "load L (µN)",
        "static friction F_f (µN)",
    )
    .with(Series::y_range("measured F_a0 = 2 ± 1.3 µN (Tas et al., MEMS 2000, section 5)", 0.7, 3.3))
    .with(Series::line("explicit solver, one loading path from pull-off", curve(0.74, 2.6)))
    .with(Series::dashed("discrete model N = 3 (eq. 12)", curve(0.7, 2.2)))
    .with(Series::dashed("eq. 10: μ_e,a = 0.74 (slope at 3 µN), F_a0 = 2.60 µN", curve(0.74, 2.5)))
    .with(
        Series::markers("measured (mean, error bar: SD of repeats)", vec![(3.0, 4.6), (12.0, 11.5), (25.0, 21.0)])
            .with_y_err(vec![0.6, 0.9, 1.4]),
    )
    .with_note("measured ±: uncertainty stated by the paper, from the uncertainty of the conversion factors a_clamp and a_pull");
    c.legend = LegendPosition::LowerRight;
    c
}

fn sensitivity_like() -> Chart {
    let names = ["a_clamp", "a_pull", "F_spring", "summit radius R", "sidewall + interactions", "surface.sigma"];
    let series = |name: &str, off: f64, k: f64| {
        let pts: Vec<(f64, f64)> =
            (0..names.len()).map(|i| (i as f64 + 1.0 + off, k * (0.1 + 0.12 * i as f64))).collect();
        Series::markers(name, pts).with_y_err(vec![0.05; names.len()])
    };
    let mut c = Chart::new(
        "Share of the variance by input (160 samples with a fit)",
        "input",
        "Sobol index (95 % bootstrap intervals)",
    )
    .with(series("μ_e,a, first order", -0.15, 1.0))
    .with(series("μ_e,a, total order", -0.05, 1.2))
    .with(series("F_a0, first order", 0.05, 0.8))
    .with(series("F_a0, total order", 0.15, 0.9));
    c.x_ticks = Some(names.iter().enumerate().map(|(i, n)| (i as f64 + 1.0, n.to_string())).collect());
    c.x_range = Some((0.5, names.len() as f64 + 0.5));
    c.legend = LegendPosition::UpperRight;
    c
}

fn psd_like() -> Chart {
    let pts: Vec<(f64, f64)> = (0..200)
        .map(|i| {
            let q = 10f64.powf(-2.0 + i as f64 * 0.02);
            (q, 1e-3 * q.powf(-3.0))
        })
        .collect();
    let fit: Vec<(f64, f64)> = pts.iter().map(|&(q, _)| (q, 1.2e-3 * q.powf(-3.0))).collect();
    Chart {
        x_log: true,
        y_log: true,
        ..Chart::new("Power spectral density of the measured height map", "wavenumber q (1/µm)", "PSD C(q) (nm² µm²)")
    }
    .with(Series::markers("measured", pts))
    .with(Series::dashed("self-affine fit, H = 0.9", fit))
}

fn residuals_like() -> Chart {
    // Points in every corner: no corner is free, the legend must go below the axes.
    let mut pts = Vec::new();
    for i in 0..40 {
        let x = i as f64;
        pts.push((x, if i % 2 == 0 { 380.0 - 0.5 * x } else { -350.0 + 0.5 * x }));
    }
    Chart::new("Residuals of V_pull² by model", "V_clamp² (V²)", "residual of V_pull² (V²)")
        .with(Series::markers("gw-dmt", pts.clone()))
        .with(Series::markers("explicit", pts.iter().map(|p| (p.0 + 0.3, p.1 * 0.8)).collect()))
        .with(Series::dashed("zero", vec![(0.0, 0.0), (40.0, 0.0)]))
}

fn journal(c: Chart) -> Chart {
    c.physical((85.0, 60.0), None).unwrap().sized(None, Some(8.0 * 4.0 / 3.0)).unwrap()
}

fn small(c: Chart) -> Chart {
    c.sized(Some((400, 280)), None).unwrap()
}

fn inside(canvas: &Rect, r: &Rect) -> bool {
    r.x0 >= canvas.x0 - 0.5 && r.y0 >= canvas.y0 - 0.5 && r.x1 <= canvas.x1 + 0.5 && r.y1 <= canvas.y1 + 0.5
}

/// The checks, written out here rather than through `Layout::problems`, so the test does not
/// trust the code it tests.
fn check(name: &str, l: &Layout) {
    check_sized(name, l, false)
}

/// As [`check`]; `fixed_aspect`: the plot keeps its data's aspect ratio (a map), so it need only
/// fill half the canvas one way.
fn check_sized(name: &str, l: &Layout, fixed_aspect: bool) {
    let canvas = Rect { x0: 0.0, y0: 0.0, x1: l.width, y1: l.height };
    for t in l.texts() {
        assert!(
            inside(&canvas, &t.rect),
            "{name}: {:?} at {:?} leaves the {} x {} canvas",
            t.text,
            t.rect,
            l.width,
            l.height
        );
    }
    for (axis, ticks) in [("x", &l.x_ticks), ("y", &l.y_ticks)] {
        assert!(ticks.len() >= 2, "{name}: fewer than two {axis} tick labels: {ticks:?}");
        for (i, a) in ticks.iter().enumerate() {
            for b in &ticks[i + 1..] {
                assert!(!a.rect.overlaps(&b.rect), "{name}: {axis} tick labels {:?} and {:?} overlap", a.text, b.text);
            }
        }
    }
    let legend = l.legend.expect("every test chart has a legend");
    for p in &l.points {
        assert!(
            !(p.0 >= legend.x0 && p.0 <= legend.x1 && p.1 >= legend.y0 && p.1 <= legend.y1),
            "{name}: legend {legend:?} covers the data point {p:?}"
        );
    }
    if !l.legend_inside {
        assert!(!legend.overlaps(&l.plot), "{name}: a legend below the axes overlaps them");
    }
    let outer: Vec<_> = l
        .title
        .iter()
        .chain(&l.caption)
        .chain(&l.x_label)
        .chain(&l.y_label)
        .chain(&l.x_ticks)
        .chain(&l.y_ticks)
        .collect();
    for (i, a) in outer.iter().enumerate() {
        assert!(!a.rect.overlaps(&l.plot), "{name}: {:?} lies over the plot area {:?}", a.text, l.plot);
        for b in &outer[i + 1..] {
            assert!(!a.rect.overlaps(&b.rect), "{name}: {:?} and {:?} overlap", a.text, b.text);
        }
        if !l.legend_inside {
            assert!(!a.rect.overlaps(&legend), "{name}: {:?} lies under the legend", a.text);
        }
    }
    // A plot big enough to read: at least a third of the canvas each way (a map: half one way).
    let big = if fixed_aspect {
        l.plot.width() >= l.width / 2.0 || l.plot.height() >= l.height / 2.0
    } else {
        l.plot.width() >= l.width / 3.0 && l.plot.height() >= l.height / 3.0
    };
    assert!(big, "{name}: plot {:?} too small", l.plot);
}

#[test]
fn charts_like_the_programs_fit_a_journal_column_and_a_small_preview() {
    for (name, c) in [
        ("fig7", fig7_like()),
        ("sensitivity", sensitivity_like()),
        ("psd", psd_like()),
        ("residuals", residuals_like()),
    ] {
        let j = journal(c.clone()).layout().unwrap();
        // 85 mm at 96 px per inch.
        assert!((j.width - 85.0 / 25.4 * 96.0).abs() < 1e-9);
        check(&format!("{name} at 85 mm x 60 mm, 8 pt"), &j);
        check(&format!("{name} at 400 x 280 px"), &small(c).layout().unwrap());
    }
}

/// Charts of ordinary size keep the font asked for (the layout shrinks text only when it must).
#[test]
fn ordinary_charts_keep_the_font_size_asked_for() {
    let l = journal(psd_like()).layout().unwrap();
    assert_eq!(l.font_px, 8.0 * 4.0 / 3.0);
    // the legend found a free corner: data run along the diagonal, the upper right is free
    assert!(l.legend_inside, "{:?}", l.legend);
    let l = residuals_like().layout().unwrap();
    assert!(!l.legend_inside, "no corner is free of data: the legend goes below the axes");
}

/// A wide height map with summits and a pressure map in Pa, at both sizes: the same checks
/// (the colour bar is the legend, its labels among the y tick labels).
#[test]
fn maps_fit_a_journal_column_and_a_small_preview() {
    use stiction_plot::ImageMap;
    let (nx, ny) = (256, 80);
    let values: Vec<f64> =
        (0..nx * ny).map(|i| 2.8e10 * (((i % nx) as f64 * 0.1).sin() * ((i / nx) as f64 * 0.2).cos()).abs()).collect();
    let map = ImageMap {
        title: "Pressure at the last state of the sweep, load 2 GPa nominal (BEM, 256 x 80 cells)".into(),
        x_label: "x (µm)".into(),
        y_label: "y (µm)".into(),
        value_label: "pressure".into(),
        value_unit: Some("Pa".into()),
        nx,
        ny,
        values,
        x_max: 25.6,
        y_max: 8.0,
        markers: vec![(3.0, 4.0), (20.0, 1.0)],
        ..ImageMap::default()
    };
    assert_eq!(map.display_scale().1, "pressure (GPa)");
    let journal = ImageMap { size_mm: Some((85.0, 60.0)), font_px: Some(8.0 * 4.0 / 3.0), ..map.clone() };
    let small = ImageMap { size_px: Some((400, 280)), ..map };
    for (name, m) in [("map at 85 mm", journal), ("map at 400 x 280", small)] {
        let l = m.layout().unwrap();
        check_sized(name, &l, true);
        // square cells: the image keeps the map's aspect ratio
        assert!((l.plot.width() / l.plot.height() - 25.6 / 8.0).abs() < 1e-6, "{name}: {:?}", l.plot);
    }
}

/// The legibility floor: a chart far too crowded for a journal column (24 series with long
/// names, a three-line title and a long caption: no placement fits at any size) is drawn at 0.85 of the 8 pt asked for at the
/// least (6.8 pt, FONT_FLOOR), never smaller; a layout whose font fell under the floor is
/// reported by `Layout::problems`. Without a font size, a 400 x 280 px canvas gets 8 pt (10.67
/// px) and an 800 x 560 one 15 px.
#[test]
fn crowded_charts_never_fall_below_the_font_floor() {
    let mut c = Chart::new(
        "A title long enough to wrap onto three lines at a journal column's width, so that the title alone takes a good part of the height of the figure",
        "a long x axis label with its unit (µN)",
        "a long y axis label with its unit (µN)",
    )
    .with_note("A caption of two or three lines at this width, which the layout must keep below the figure whatever else it has to do to fit the rest.");
    for k in 0..24 {
        let pts: Vec<(f64, f64)> = (0..50).map(|i| (i as f64, (i as f64 * 0.2 + k as f64).sin() + k as f64)).collect();
        c = c.with(Series::line(format!("series number {k} with a long legend name"), pts));
    }
    let asked = 8.0 * 4.0 / 3.0;
    let l = journal(c).layout().unwrap();
    assert!(l.font_px >= stiction_plot::FONT_FLOOR * asked - 1e-9, "font {} px under the floor", l.font_px);
    assert_eq!(stiction_plot::FONT_FLOOR, 0.85);
    assert_eq!(l.requested_font_px, asked);
    let mut under = l.clone();
    under.font_px = 0.8 * asked;
    assert!(under.problems().iter().any(|p| p.contains("fell back")), "{:?}", under.problems());
    assert_eq!(small(psd_like()).font_size_px(), asked);
    assert_eq!(psd_like().sized(Some((800, 560)), None).unwrap().font_size_px(), 15.0);
}
