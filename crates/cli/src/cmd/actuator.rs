//! `stiction actuator`: one gap-closing actuator array of a scenario.

use std::path::{Path, PathBuf};

use stiction_engine::actuator::{
    ActuatorRequest, ActuatorRun, ArraySpec, GapClosingActuator, Sweep, SweepPoint, TransientComparison,
    TransientEvent, TransientReport, ValidationPoint, ValidationReport, actuator, model_curves, validation_curves,
};
use stiction_plot::{Chart, Series};
use stiction_units::{Constraint, Dimension};

use crate::figargs::FigureArgs;
use crate::output::{CliResult, OutputSet, TextTable, print_json, print_table, q, quantity};

/// Pull-in, release, conversion factor and stiffness of an actuator array; sweeps; validation against measurements.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file.
    pub scenario: PathBuf,
    /// Which array of the scenario's `actuators` (default: the only one; `clamp` and `pull` in the meter).
    #[arg(long)]
    pub array: Option<String>,
    /// Also sweep the voltage up and back down: travel x(V) and force F(V) on loading and unloading.
    #[arg(long)]
    pub sweep: bool,
    /// Highest sweep voltage (default 1.3 x the pull-in voltage).
    #[arg(long, value_parser = quantity(Dimension::Voltage, Constraint::Positive))]
    pub sweep_max: Option<f64>,
    /// Number of voltage steps of each sweep direction (2 to 1 000 000).
    #[arg(long, default_value_t = 200, value_parser = clap::value_parser!(u32).range(2..=1_000_000))]
    pub sweep_steps: u32,
    /// Compare predicted pull-in and release with a measured CSV
    /// (finger_length_drawn_um, pull_in_v_1.., release_v), one prediction per finger length.
    #[arg(long, value_name = "MEASURED.csv", conflicts_with = "transients", group = "measured")]
    pub validate: Option<PathBuf>,
    /// Simulate every measured pull-in and release time of a CSV (finger_length_um, event, voltage_v,
    /// time_us, optional repeat and external_force_n) and compare: pull-in is a voltage step from rest
    /// until the stop, release is from the stop with the voltage switched off until the open position.
    #[arg(long, value_name = "MEASURED.csv", group = "measured")]
    pub transients: Option<PathBuf>,
    /// With --validate or --transients: also report the error with each physics switch toggled.
    #[arg(long, requires = "measured")]
    pub switches: bool,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Write results.json and plots (SVG and PNG) to this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write into an --out folder that holds files not from an earlier stiction run.
    #[arg(long)]
    pub force: bool,
    /// Override a scenario field (repeatable): --set actuators.gca.undercut="0.3 um".
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Figure size and font (with --out).
    #[command(flatten)]
    pub fig: FigureArgs,
}

impl Args {
    /// The engine's request of these flags (the sweep also for the --out figures).
    pub fn request(&self) -> ActuatorRequest {
        ActuatorRequest {
            array: self.array.clone(),
            sweep: self.sweep || self.out.is_some(),
            sweep_max_v: self.sweep_max,
            sweep_steps: self.sweep_steps as usize,
            validate: self.validate.clone(),
            transients: self.transients.clone(),
            switches: self.switches,
        }
    }
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    // Check the output folder before the work, so a refusal (a symbolic link, foreign files) comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "actuator", args.force)?),
        None => None,
    };
    let ActuatorRun { name, spec, model, summary } = actuator(&args.scenario, &args.sets, &args.request())?;
    let pull_in_limited_by_stop = summary.pull_in_limited_by_stop;
    if let (Some(mut set), Some(dir)) = (outputs, &args.out) {
        set.add_bytes("results.json", crate::output::json_text(&summary)?.as_bytes())?;
        if let Some(sweep) = &summary.sweep {
            set.add_figure("hysteresis", &args.fig.apply(sweep_chart(&name, sweep, &model))?)?;
        }
        if let Some(report) = &summary.validation {
            set.add_figure("validation", &args.fig.apply(validation_chart(&spec, report)?)?)?;
        }
        if let Some(report) = &summary.transients {
            write_transients(&mut set, report, &model_curves(&spec, report)?, &args.fig)?;
        }
        set.commit()?;
        crate::errln!("wrote {}", dir.display());
    }
    if args.json {
        return print_json(&summary);
    }
    print_table(
        &format!("Gap-closing actuator array `{name}`"),
        &[
            ("pull-in voltage", q(summary.pull_in_voltage_v, Dimension::Voltage)),
            (
                "pull-in travel",
                format!(
                    "{}{}",
                    q(summary.pull_in_travel_m, Dimension::Length),
                    if pull_in_limited_by_stop { " (stop reached first)" } else { "" }
                ),
            ),
            ("release voltage", summary.release_voltage_v.map_or("- (no stop)".into(), |v| q(v, Dimension::Voltage))),
            (
                "conversion factor a = F/V^2",
                format!(
                    "{:.4e} N/V^2 at travel {}",
                    summary.conversion_factor_n_per_v2,
                    q(spec.operating_travel, Dimension::Length)
                ),
            ),
            ("spring stiffness", format!("{:.4} N/m", summary.spring_stiffness_n_per_m)),
            ("front gap (as built)", q(summary.front_gap_m, Dimension::Length)),
        ],
    );
    if let Some(sweep) = &summary.sweep {
        print_sweep(sweep);
    }
    if let Some(r) = &summary.validation {
        crate::outln!(
            "\nValidation against {} ({} finger lengths)",
            args.validate.as_ref().map_or(String::new(), |p| p.display().to_string()),
            r.points.len()
        );
        let mut t = TextTable::new(&[
            "L_f (um)",
            "pull-in measured (V)",
            "pull-in model (V)",
            "error",
            "release measured (V)",
            "release model (V)",
            "error",
        ]);
        for p in &r.points {
            t.row(vec![
                format!("{:.2}", p.finger_length_m * 1e6),
                format!("{:.2}", p.pull_in_v_measured),
                format!("{:.2}", p.pull_in_v_model),
                format!("{:+.1} %", 100.0 * p.pull_in_rel_error),
                format!("{:.2}", p.release_v_measured),
                format!("{:.2}", p.release_v_model),
                format!("{:+.1} %", 100.0 * p.release_rel_error),
            ]);
        }
        t.print("  ");
        crate::outln!(
            "  mean |relative error|: pull-in {:.1} %, release {:.1} %",
            100.0 * r.pull_in_mean_abs_rel_error,
            100.0 * r.release_mean_abs_rel_error
        );
    }
    if let Some(r) = &summary.transients {
        print_transients(args.transients.as_deref(), r);
    }
    if let Some(sw) = &summary.transient_switches {
        crate::outln!("\nTransient model ingredients, one changed at a time (relative errors of the times)");
        let pct = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{:.1} %", 100.0 * x));
        let signed = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{:+.1} %", 100.0 * x));
        let mut t = TextTable::new(&[
            "switch",
            "pull-in mean |err|",
            "release mean |err|",
            "pull-in mean err",
            "release mean err",
            "not predicted",
        ]);
        for s in sw {
            t.row(vec![
                s.switch.clone(),
                pct(s.pull_in_time_mean_abs_rel_error),
                pct(s.release_time_mean_abs_rel_error),
                signed(s.pull_in_time_mean_rel_error),
                signed(s.release_time_mean_rel_error),
                s.unpredicted.to_string(),
            ]);
        }
        t.print("  ");
    }
    if let Some(sw) = &summary.switches {
        crate::outln!("\nPhysics switches, one changed at a time (relative errors of the voltages)");
        let mut t = TextTable::new(&[
            "switch",
            "pull-in mean |err|",
            "release mean |err|",
            "pull-in mean err",
            "release mean err",
        ]);
        for s in sw {
            t.row(vec![
                s.switch.clone(),
                format!("{:.1} %", 100.0 * s.pull_in_mean_abs_rel_error),
                format!("{:.1} %", 100.0 * s.release_mean_abs_rel_error),
                format!("{:+.1} %", 100.0 * s.pull_in_mean_rel_error),
                format!("{:+.1} %", 100.0 * s.release_mean_rel_error),
            ]);
        }
        t.print("  ");
    }
    Ok(())
}

/// Travel against voltage on loading and unloading, with the pull-in (and release) points; the
/// y axis fitted to the drawn travel. Without a stop the array collapses at pull-in and stays
/// collapsed on unloading (no finite travel to draw): the note says so instead of listing an
/// empty curve.
fn sweep_chart(name: &str, sweep: &Sweep, model: &GapClosingActuator) -> Chart {
    let finite = |v: &[SweepPoint]| -> Vec<(f64, f64)> {
        v.iter().filter(|p| p.travel_m.is_finite()).map(|p| (p.voltage_v, p.travel_m * 1e6)).collect()
    };
    let (mut up, down) = (finite(&sweep.loading), finite(&sweep.unloading));
    // The sweep's voltage steps end below pull-in, where x(V) turns vertical; the stable branch is
    // closed up to the pull-in point from the equilibrium voltage V(x) at 24 travels between the
    // last stable step and x_pi (exact points of the same curve, not an interpolation). With a stop,
    // the curve then jumps at V_pi from x_pi to the stop, so the pull-in marker lies where the drawn
    // curve jumps.
    if let Ok(pi) = model.pull_in()
        && !pi.limited_by_stop
    {
        let x_pi_um = pi.travel_m * 1e6;
        // The stable branch: the sweep's points below the pull-in travel and voltage.
        let split = up.iter().position(|&(v, x)| x > x_pi_um || v > pi.voltage_v).unwrap_or(up.len());
        let rest = up.split_off(split);
        if let Some(&(v_last, x_last_um)) = up.last()
            && x_pi_um > x_last_um
        {
            let x_last = x_last_um * 1e-6;
            for k in 1..=24 {
                let x = x_last + (pi.travel_m - x_last) * f64::from(k) / 24.0;
                let v = if k == 24 { pi.voltage_v } else { model.equilibrium_voltage_v(x) };
                if v.is_finite() && v >= v_last && v <= pi.voltage_v {
                    up.push((v, x * 1e6));
                }
            }
        }
        if let (Some(stop), Some(_)) = (model.stop_travel_m, rest.first()) {
            // The jump to the stop at V_pi, then the sweep's points on the stop.
            up.push((pi.voltage_v, stop * 1e6));
            up.extend(rest.into_iter().filter(|p| p.0 > pi.voltage_v));
        }
    }
    // Without a stop the unloading branch is collapsed down to 0 V: at most its last point is finite.
    let both = down.len() >= 2;
    let mut chart = Chart::new(
        format!("Actuator {name}: travel against voltage, {}", if both { "loading and unloading" } else { "loading" }),
        "voltage V (V)",
        "travel x (µm)",
    )
    .keys("voltage_v", "travel_um")
    .with(Series::line("loading (increasing V)", up.clone()));
    if both {
        chart.series.push(Series::dashed("unloading (decreasing V)", down.clone()));
    }
    let mut marks = Vec::new();
    if let Ok(pi) = model.pull_in() {
        marks.push(Series::markers(
            format!("pull-in: {:.2} V at x = {:.3} µm", pi.voltage_v, pi.travel_m * 1e6),
            vec![(pi.voltage_v, pi.travel_m * 1e6)],
        ));
        let vmax = sweep.loading.last().map_or(0.0, |p| p.voltage_v);
        chart.note = Some(match (model.stop_travel_m, model.release_voltage_v()) {
            (Some(stop), Ok(release)) if !pi.limited_by_stop => {
                marks.push(Series::markers(format!("release: {release:.2} V"), vec![(release, stop * 1e6)]));
                format!(
                    "stop at x = {:.3} µm: after pull-in the array rests on it until the voltage falls to the release voltage",
                    stop * 1e6
                )
            }
            (Some(stop), _) => format!("the stop at x = {:.3} µm is reached before pull-in", stop * 1e6),
            (None, _) => format!(
                "no stop in the scenario: at pull-in ({:.2} V) the gap closes (collapse, not drawn);\non unloading from \
                 {vmax:.1} V the array stays collapsed down to 0 V, so there is no unloading curve",
                pi.voltage_v
            ),
        });
    }
    let top = up.iter().chain(&down).chain(marks.iter().flat_map(|m| &m.points)).map(|p| p.1).fold(0.0, f64::max);
    for (k, m) in marks.into_iter().enumerate() {
        chart.series.push(m.with_color(2 + k));
    }
    chart.y_range = Some((0.0, top * 1.08));
    chart
}

/// Measured pull-in and release (mean, with the spread of repeats) against finger length, with the
/// model curves evaluated at 24 finger lengths spread evenly over the measured range (the same model
/// as the report's points, not straight segments between the measured lengths).
pub fn validation_chart(spec: &ArraySpec, r: &ValidationReport) -> Result<Chart, Box<dyn std::error::Error>> {
    let um = |p: &ValidationPoint| p.finger_length_m * 1e6;
    let model = validation_curves(spec, r)?;
    let curve =
        |f: fn(&ValidationPoint) -> f64| -> Vec<(f64, f64)> { model.points.iter().map(|p| (um(p), f(p))).collect() };
    let n_rep = r.points.len();
    let mut chart = Chart::new(
        format!(
            "GCA pull-in and release: model vs measured (mean |err| {:.1} % / {:.1} %)",
            100.0 * r.pull_in_mean_abs_rel_error,
            100.0 * r.release_mean_abs_rel_error
        ),
        "drawn finger length (µm)",
        "voltage (V)",
    )
    .keys("finger_length_um", "voltage_v")
    .with(Series::line("pull-in, model", curve(|p| p.pull_in_v_model)).with_color(0))
    .with(Series::dashed("release, model", curve(|p| p.release_v_model)).with_color(1))
    .with(
        Series::markers(
            format!("pull-in, measured (mean, SD of repeats; {n_rep} lengths)"),
            r.points.iter().map(|p| (um(p), p.pull_in_v_measured)).collect(),
        )
        .with_y_err(r.points.iter().map(|p| p.pull_in_v_spread).collect())
        .with_color(0),
    )
    .with(
        Series::markers(
            "release, measured (mean, SD of repeats)",
            r.points.iter().map(|p| (um(p), p.release_v_measured)).collect(),
        )
        .with_y_err(r.points.iter().map(|p| p.release_v_spread).collect())
        .with_color(1),
    );
    chart.legend = stiction_plot::LegendPosition::UpperRight;
    Ok(chart)
}

/// The hysteresis chart of `stiction plot actuator`.
pub fn hysteresis_chart(
    path: &Path,
    array: Option<&str>,
    sets: &[String],
) -> Result<Chart, Box<dyn std::error::Error>> {
    let (name, model, sweep) = stiction_engine::actuator::hysteresis(path, array, sets)?;
    Ok(sweep_chart(&name, &sweep, &model))
}

fn print_transients(path: Option<&Path>, r: &TransientReport) {
    crate::outln!(
        "\nPull-in and release times against {} ({} points)",
        path.map_or(String::new(), |p| p.display().to_string()),
        r.points.len()
    );
    let mut t =
        TextTable::new(&["L_f (um)", "event", "V (V)", "measured (us)", "SD (us)", "model (us)", "error", "note"]);
    for p in &r.points {
        t.row(vec![
            format!("{:.2}", p.finger_length_m * 1e6),
            p.event.to_string(),
            format!("{:.1}", p.voltage_v),
            format!("{:.2}", p.measured_mean_s * 1e6),
            format!("{:.2}", p.measured_sd_s * 1e6),
            p.predicted_s.map_or("-".to_string(), |t| format!("{:.2}", t * 1e6)),
            p.rel_error.map_or("-".to_string(), |e| format!("{:+.1} %", 100.0 * e)),
            p.no_prediction.clone().unwrap_or_default(),
        ]);
    }
    t.print("  ");
    crate::outln!();
    let mut t = TextTable::new(&["event", "L_f (um)", "mean |err|", "mean err", "RMSE (us)", "not predicted"]);
    for e in &r.errors {
        t.row(vec![
            e.event.to_string(),
            e.finger_length_m.map_or("all".to_string(), |l| format!("{:.2}", l * 1e6)),
            e.mean_abs_rel_error.map_or("n/a (no point predicted)".into(), |v| format!("{:.1} %", 100.0 * v)),
            e.mean_rel_error.map_or("n/a".into(), |v| format!("{:+.1} %", 100.0 * v)),
            e.rmse_s.map_or("n/a".into(), |v| format!("{:.2}", v * 1e6)),
            e.unpredicted.to_string(),
        ]);
    }
    t.print("  ");
}

/// Most rows of each sweep direction in the text output (`--json` and `--out` have every step).
const SWEEP_TEXT_ROWS: usize = 25;

/// The voltage sweep as text: where the array pulls in and releases, and a table of travel and
/// forces, thinned to at most [`SWEEP_TEXT_ROWS`] rows per direction (always with the rows on both
/// sides of a jump).
fn print_sweep(sweep: &Sweep) {
    for (title, pts) in [("loading (increasing V)", &sweep.loading), ("unloading (decreasing V)", &sweep.unloading)] {
        let n = pts.len();
        if n == 0 {
            continue;
        }
        let jump = pts.windows(2).position(|w| w[0].at_stop != w[1].at_stop);
        let every = n.div_ceil(SWEEP_TEXT_ROWS).max(1);
        crate::outln!(
            "\nVoltage sweep, {title}: {n} steps from {:.3} V to {:.3} V{}",
            pts[0].voltage_v,
            pts[n - 1].voltage_v,
            if every > 1 {
                format!(", one row in {every} shown (every step in --json and --out)")
            } else {
                String::new()
            }
        );
        if let Some(k) = jump {
            let what = if pts[k + 1].at_stop { "pulls in to the stop" } else { "releases from the stop" };
            crate::outln!("  the array {what} between {:.3} V and {:.3} V", pts[k].voltage_v, pts[k + 1].voltage_v);
        }
        let mut t = TextTable::new(&[
            "V (V)",
            "travel x (um)",
            "electrostatic F (uN)",
            "spring F (uN)",
            "stop F (uN)",
            "at stop",
        ]);
        for (i, p) in pts.iter().enumerate() {
            let near_jump = jump.is_some_and(|k| i == k || i == k + 1);
            if i % every != 0 && i != n - 1 && !near_jump {
                continue;
            }
            t.row(vec![
                format!("{:.3}", p.voltage_v),
                format!("{:.4}", p.travel_m * 1e6),
                format!("{:.4}", p.electrostatic_force_n * 1e6),
                format!("{:.4}", p.spring_force_n * 1e6),
                format!("{:.4}", p.stop_force_n * 1e6),
                if p.at_stop { "yes".into() } else { "no".into() },
            ]);
        }
        t.print("  ");
    }
}

/// `transients.csv` (every point) and one figure per finger length (`transients_L<um>.svg/.png`):
/// measured mean with the SD of the repeats as error bars, and the model, time against voltage.
fn write_transients(set: &mut OutputSet, r: &TransientReport, curves: &TransientReport, fig: &FigureArgs) -> CliResult {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "finger_length_um",
        "event",
        "voltage_v",
        "external_force_n",
        "repeats",
        "measured_mean_us",
        "measured_sd_us",
        "predicted_us",
        "rel_error",
    ])?;
    for p in &r.points {
        w.write_record([
            // um, rounded to 1e-9 um so that 15.3e-6 m prints as 15.3, not 15.299999999999999.
            format!("{}", (p.finger_length_m * 1e15).round() / 1e9),
            p.event.name().to_string(),
            format!("{}", p.voltage_v),
            format!("{}", p.external_force_n),
            format!("{}", p.repeats),
            format!("{}", (p.measured_mean_s * 1e15).round() / 1e9),
            format!("{}", (p.measured_sd_s * 1e15).round() / 1e9),
            p.predicted_s.map_or(String::new(), |t| format!("{}", t * 1e6)),
            p.rel_error.map_or(String::new(), |e| format!("{e}")),
        ])?;
    }
    set.add_bytes("transients.csv", &w.into_inner()?)?;
    let mut lengths: Vec<f64> = r.points.iter().map(|p| p.finger_length_m).collect();
    lengths.sort_by(f64::total_cmp);
    lengths.dedup();
    for l in lengths {
        set.add_figure(&format!("transients_L{:.2}um", l * 1e6), &fig.apply(transient_chart(r, curves, l))?)?;
    }
    Ok(())
}

/// Time against voltage at one finger length: measured (mean, SD of repeats) and model.
fn transient_chart(r: &TransientReport, curves: &TransientReport, length_m: f64) -> Chart {
    let err = |event: TransientEvent| {
        r.errors
            .iter()
            .find(|e| e.event == event && e.finger_length_m == Some(length_m))
            .and_then(|e| e.mean_abs_rel_error)
            .map_or("n/a".to_string(), |e| format!("{:.1} %", 100.0 * e))
    };
    let mut chart = Chart::new(
        format!(
            "GCA, {:.2} µm fingers: pull-in and release times (mean |err| {} / {})",
            length_m * 1e6,
            err(TransientEvent::PullIn),
            err(TransientEvent::Release)
        ),
        "voltage (V): pull-in step / release hold",
        "time (µs)",
    )
    .keys("voltage_v", "time_us");
    for (event, label) in [(TransientEvent::PullIn, "pull-in"), (TransientEvent::Release, "release")] {
        let pts: Vec<&TransientComparison> =
            r.points.iter().filter(|p| p.event == event && p.finger_length_m == length_m).collect();
        if pts.is_empty() {
            continue;
        }
        chart = chart
            .with(
                Series::markers(
                    format!("{label}, measured (mean, SD of repeats)"),
                    pts.iter().map(|p| (p.voltage_v, p.measured_mean_s * 1e6)).collect(),
                )
                .with_y_err(pts.iter().map(|p| p.measured_sd_s * 1e6).collect())
                .with_color(if event == TransientEvent::PullIn { 0 } else { 1 }),
            )
            .with({
                // The model curve where there is one, else the model at the measured voltages.
                let on_curve: Vec<&TransientComparison> =
                    curves.points.iter().filter(|p| p.event == event && p.finger_length_m == length_m).collect();
                let src = if on_curve.is_empty() { &pts } else { &on_curve };
                let line: Vec<(f64, f64)> =
                    src.iter().filter_map(|p| p.predicted_s.map(|t| (p.voltage_v, t * 1e6))).collect();
                match event {
                    TransientEvent::PullIn => Series::line(format!("{label}, model"), line).with_color(0),
                    TransientEvent::Release => Series::dashed(format!("{label}, model"), line).with_color(1),
                }
            });
    }
    let top = r
        .points
        .iter()
        .filter(|p| p.finger_length_m == length_m)
        .map(|p| (p.measured_mean_s + p.measured_sd_s).max(p.predicted_s.unwrap_or(0.0)) * 1e6)
        .fold(0.0, f64::max);
    // Headroom for the legend box (top left).
    chart.y_range = Some((0.0, 1.4 * top));
    chart
}
