//! `stiction plot`: the paper's figures recomputed, and the actuator hysteresis.

use std::path::{Path, PathBuf};

use stiction_contact::gw;
use stiction_plot::{Chart, Series};

use crate::output::CliResult;

/// Which figure.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Figure {
    /// Fig. 2: fraction of summits in contact N* at L* = 0 against the adhesion parameter theta.
    Fig2,
    /// Fig. 3: normalized real area A* against normalized load L* for theta = 10, 15, 30, inf.
    Fig3,
    /// Fig. 7: friction against load in the discrete model, N = 3, R = 0.5 um, s = 1.4 GPa (Table 1).
    Fig7,
    /// Hysteresis of a scenario's actuator array: travel against voltage, loading and unloading.
    Actuator,
}

/// Recompute a figure and write it as SVG (or PNG when the file name ends in .png).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The figure.
    #[arg(value_enum)]
    pub figure: Figure,
    /// Output file (.svg or .png).
    #[arg(long)]
    pub out: PathBuf,
    /// Scenario file (for `actuator`).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Actuator array name in the scenario (for `actuator`; default: the only one, or `clamp`).
    #[arg(long)]
    pub array: Option<String>,
    /// Override a scenario field (repeatable), as in `stiction run`.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
}

/// The image format of an output path: "svg" or "png" by its extension; any other is an error.
pub fn chart_format(path: &Path) -> Result<&'static str, String> {
    match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).as_deref() {
        Some("svg") => Ok("svg"),
        Some("png") => Ok("png"),
        other => Err(format!(
            "{}: unknown image extension {}; expected .svg or .png",
            path.display(),
            other.map_or("(none)".to_string(), |e| format!(".{e}"))
        )),
    }
}

/// Renders a chart to `path` (SVG or PNG by extension; any other is an error naming it). The plot
/// crate writes it atomically and never through a symbolic link.
pub fn render_chart(chart: &Chart, path: &Path) -> CliResult {
    chart_format(path)?;
    chart.write(path)?;
    Ok(())
}

/// Writes a chart to `path` as SVG, or PNG by extension, with the plotted numbers as CSV beside it
/// (so it can be re-plotted in another tool); both files atomically. Errors name the path.
pub fn write_chart(chart: &Chart, path: &Path) -> CliResult {
    chart_format(path)?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        crate::output::ensure_dir(dir)?;
    }
    chart.write_with_data(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    Ok(())
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    chart_format(&args.out).map_err(|e| format!("--out {e}"))?;
    if !matches!(args.figure, Figure::Actuator) {
        for (flag, given) in [
            ("--scenario", args.scenario.is_some()),
            ("--array", args.array.is_some()),
            ("--set", !args.sets.is_empty()),
        ] {
            if given {
                return Err(format!(
                    "{flag} is used only by `plot actuator`; `plot {}` draws the paper's figure from its own numbers",
                    format!("{:?}", args.figure).to_lowercase()
                )
                .into());
            }
        }
    }
    let chart = match args.figure {
        Figure::Fig2 => fig2()?,
        Figure::Fig3 => fig3()?,
        Figure::Fig7 => crate::cmd::discrete::fig7_chart()?,
        Figure::Actuator => {
            let path = args.scenario.as_ref().ok_or("`plot actuator` needs --scenario FILE.json")?;
            crate::cmd::actuator::hysteresis_chart(path, args.array.as_deref(), &args.sets)?
        }
    };
    write_chart(&chart, &args.out)?;
    crate::errln!("wrote {}", args.out.display());
    Ok(())
}

/// Fig. 2: N*(L* = 0) against theta, from 1 to 40.
pub fn fig2() -> Result<Chart, Box<dyn std::error::Error>> {
    let pts = gw::fig2_series(0.5, 40.0, 80)?;
    let mut chart = Chart::new(
        "Fig. 2: summits in contact at zero load (GW + DMT, eq. 5a, 8)",
        "adhesion parameter theta (eq. 9)",
        "fraction of summits in contact N* at L* = 0",
    )
    .with(Series::line("N* = F_0(h), L* = 0", pts));
    chart.y_log = true;
    Ok(chart)
}

/// Fig. 3: A* against L* for theta = 10, 15, 30 and infinity.
pub fn fig3() -> Result<Chart, Box<dyn std::error::Error>> {
    let mut chart = Chart::new(
        "Fig. 3: real area against load (GW + DMT, eq. 5b, 8)",
        "normalized load L* (eq. 8)",
        "normalized real area A* (eq. 5b)",
    );
    for (label, theta) in
        [("(1) theta = 10", Some(10.0)), ("(2) theta = 15", Some(15.0)), ("(3) theta = 30", Some(30.0))]
    {
        chart.series.push(Series::line(label, gw::fig3_series(theta, -1.0, 1.0, 200)?));
    }
    chart.series.push(Series::line("(4) theta = inf (GW)", gw::fig3_series(None, 1e-4, 1.0, 200)?));
    Ok(chart)
}
