//! Draws every series style on a log-log and a linear chart, to look at the swatches and ticks:
//! `cargo run --release -p stiction-plot --example styles -- OUT_DIR`.

use std::path::PathBuf;

use stiction_plot::{Chart, LegendPosition, Series};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "target/plot-styles".into()));
    std::fs::create_dir_all(&dir)?;
    let xs: Vec<f64> = (0..60).map(|i| 10f64.powf(-3.0 + i as f64 * 0.1)).collect();
    let log = Chart {
        x_log: true,
        y_log: true,
        legend: LegendPosition::LowerRight,
        ..Chart::new("Every series style on log axes", "load L* (normalised)", "real contact area A* (normalised)")
    }
    .with_note("a note under the title says what the reader must know")
    .with(Series::band("model band", xs.iter().map(|&x| (x, 0.5 * x, 2.0 * x)).collect()).with_color(0))
    .with(Series::line("line", xs.iter().map(|&x| (x, x)).collect()).with_color(0))
    .with(Series::dashed("dashed", xs.iter().map(|&x| (x, x.powf(0.8))).collect()))
    .with(Series::markers("markers with error bars", vec![(1e-2, 2e-2), (1e-1, 1.5e-1)]).with_y_err(vec![5e-3, 5e-2]))
    .with(Series::x_range("reference range of x", 0.3, 1.0));
    log.write_with_data(&dir.join("log.png"))?;
    let lin = Chart::new(
        "Step CDF and a point with two error bars",
        "apparent friction coefficient μₑ,ₐ",
        "cumulative fraction",
    )
    .with(Series::step("virtual meters", (0..20).map(|i| (0.5 + 0.02 * i as f64, (i as f64 + 0.5) / 20.0)).collect()))
    .with(Series::markers("paper: 0.7 ± 0.3", vec![(0.7, 0.5)]).with_x_err(vec![0.3]).with_y_err(vec![0.1]))
    .with(Series::y_range("y range", 0.2, 0.3));
    lin.write_with_data(&dir.join("lin.png"))?;
    Ok(())
}
