//! `stiction plot`: the paper's figures recomputed, and the actuator hysteresis.

use std::path::{Path, PathBuf};

use stiction_engine::plot::{Fig2Curves, fig2_curves, fig3_curve};
use stiction_engine::scenario::Scenario;
use stiction_plot::{Chart, LegendPosition, Series};

use crate::figargs::FigureArgs;
use crate::format::sig3;
use crate::output::{CliResult, chart_format};

/// Which figure.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Figure {
    /// Fig. 2: fraction of summits in contact N* at L* = 0 against the adhesion parameter theta
    /// (with --scenario: the scenario's theta marked, the axis extended to it).
    Fig2,
    /// Fig. 3: normalized real area A* against normalized load L* for theta = 10, 15, 30, inf, on a
    /// symmetric-log load axis that shows the adhesive branches and pull-off (with --scenario: the
    /// scenario's theta added).
    Fig3,
    /// Fig. 7: friction against load in the discrete model (eq. 12); default the paper's N = 3,
    /// R = 0.5 um, s = 1.4 GPa, DMT (Table 1); with --scenario (and --set) the scenario's material,
    /// summit radius, contact law and number of contacts, and its reference values.
    Fig7,
    /// Hysteresis of a scenario's actuator array: travel against voltage, loading and unloading.
    Actuator,
    /// The friction meter of a scenario (--scenario) over relative humidities (--rh): mu_e,a, F_a0
    /// and the capillary share of the adhesive load against RH, the dry point (RH = 0) first, with
    /// the scenario's measured reference at the humidity of its experiment; --out is a folder.
    Humidity,
}

impl Figure {
    fn name(self) -> &'static str {
        match self {
            Figure::Fig2 => "fig2",
            Figure::Fig3 => "fig3",
            Figure::Fig7 => "fig7",
            Figure::Actuator => "actuator",
            Figure::Humidity => "humidity",
        }
    }
}

/// Recompute a figure and write it as SVG (or PNG when the file name ends in .png), with its data
/// as CSV beside it.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The figure.
    #[arg(value_enum)]
    pub figure: Figure,
    /// Output file (.svg or .png); the data go beside it as .csv. For `humidity`: an output folder
    /// (results.json, humidity.csv, humidity-mu, humidity-fa0 and humidity-share as .svg, .png and
    /// .csv, manifest.json); optional there.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Scenario file: its parameters for fig2, fig3, fig7, actuator and humidity (required for
    /// actuator and humidity).
    #[arg(long)]
    pub scenario: Option<PathBuf>,
    /// Actuator array name in the scenario (for `actuator`; default: the only one, or `clamp`).
    #[arg(long)]
    pub array: Option<String>,
    /// Override a scenario field (repeatable; needs --scenario), as in `stiction run`.
    #[arg(long = "set", value_name = "PATH=VALUE", requires = "scenario")]
    pub sets: Vec<String>,
    /// Relative humidities for `humidity`: a list (0.1,0.35 or "35 %") or FROM:TO:STEPS, each in
    /// [0, 1), increasing; the dry point 0 is put first when missing (default 0:0.9:10).
    #[arg(long, value_name = "LIST|FROM:TO:STEPS", allow_hyphen_values = true)]
    pub rh: Option<String>,
    /// For `humidity`: print one JSON object on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
    /// For `humidity`: write into an --out folder that holds files not from an earlier stiction run.
    #[arg(long)]
    pub force: bool,
    /// Figure size and font.
    #[command(flatten)]
    pub fig: FigureArgs,
}

/// Writes a chart to `path` as SVG, or PNG by extension, with the plotted numbers as CSV beside it
/// (so it can be re-plotted in another tool); both files atomically. Errors name the path.
pub fn write_chart(chart: &Chart, path: &Path) -> CliResult {
    chart_format(path)?;
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        crate::output::ensure_dir(dir)?;
    }
    chart.write_with_data(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    crate::output::record_layout(path, || chart.layout())
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    if matches!(args.figure, Figure::Humidity) {
        return humidity(&args);
    }
    for (given, flag) in [(args.rh.is_some(), "--rh"), (args.json, "--json"), (args.force, "--force")] {
        if given {
            return Err(
                format!("{flag} is used only by `plot humidity`; `plot {}` has none", args.figure.name()).into()
            );
        }
    }
    let out =
        args.out.as_ref().ok_or_else(|| format!("`plot {}` needs --out FILE.svg or FILE.png", args.figure.name()))?;
    chart_format(out).map_err(|e| format!("--out {e}"))?;
    if args.array.is_some() && !matches!(args.figure, Figure::Actuator) {
        return Err(format!(
            "--array is used only by `plot actuator`; `plot {}` has no actuator array",
            args.figure.name()
        )
        .into());
    }
    let scenario = match &args.scenario {
        Some(path) => Some((Scenario::load(path, &args.sets)?, path.parent().map(PathBuf::from).unwrap_or_default())),
        None => None,
    };
    let scenario_ref = scenario.as_ref().map(|(s, b)| (s, b.as_path()));
    let chart = match args.figure {
        Figure::Fig2 => fig2(scenario_ref)?,
        Figure::Fig3 => fig3(scenario_ref)?,
        Figure::Fig7 => match scenario_ref {
            Some((s, base)) => {
                crate::cmd::discrete::fig7_chart(&crate::cmd::discrete::Fig7Setup::of_scenario(s, base)?)?
            }
            None => crate::cmd::discrete::fig7_chart(&crate::cmd::discrete::Fig7Setup::paper())?,
        },
        Figure::Actuator => {
            let path = args.scenario.as_ref().ok_or("`plot actuator` needs --scenario FILE.json")?;
            crate::cmd::actuator::hysteresis_chart(path, args.array.as_deref(), &args.sets)?
        }
        Figure::Humidity => return humidity(&args),
    };
    write_chart(&args.fig.apply(chart)?, out)?;
    crate::errln!("wrote {} and {}", out.display(), stiction_plot::data_path(out).display());
    Ok(())
}

/// `plot humidity`: the sweep of [`stiction_engine::humidity::sweep`], printed as a table or JSON and
/// written with its figures to the --out folder.
fn humidity(args: &Args) -> CliResult {
    use crate::cmd::humidity as h;
    use crate::output::{OutputSet, TextTable, print_json};
    if args.array.is_some() {
        return Err("--array is used only by `plot actuator`; `plot humidity` has no actuator array".into());
    }
    let rhs = stiction_engine::humidity::rh_grid(args.rh.as_deref())?;
    let path = args.scenario.as_ref().ok_or("`plot humidity` needs --scenario FILE.json")?;
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "plot humidity", args.force)?),
        None => None,
    };
    let bar = indicatif::ProgressBar::new(rhs.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} humidities {pos}/{len} [{bar:30}] {elapsed_precise}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let source = stiction_engine::ScenarioSource::file(path, &args.sets)?;
    let sweep = stiction_engine::humidity::sweep(&source, &rhs, &mut |done, _| bar.set_position(done as u64))?;
    bar.finish_and_clear();
    if let Some(mut set) = outputs {
        let charts: Vec<(&str, Chart)> = h::charts(&sweep)
            .into_iter()
            .map(|(n, c)| Ok((n, args.fig.apply(c)?)))
            .collect::<Result<_, Box<dyn std::error::Error>>>()?;
        let mut json = serde_json::to_value(&sweep)?;
        if let Some(obj) = json.as_object_mut() {
            let figures: serde_json::Map<String, serde_json::Value> =
                charts.iter().map(|(n, c)| (n.to_string(), c.data_json())).collect();
            obj.insert("figures".into(), serde_json::Value::Object(figures));
        }
        set.add_bytes("results.json", crate::output::json_text(&json)?.as_bytes())?;
        set.add_bytes("humidity.csv", &h::table_csv(&sweep)?)?;
        for (stem, chart) in &charts {
            set.add_figure(stem, chart)?;
        }
        set.commit()?;
    }
    if args.json {
        return print_json(&sweep);
    }
    crate::outln!("stiction plot humidity --scenario {}", sweep.scenario);
    crate::outln!(
        "  contact model: {}, {:.2} C, water contact angle {:.0} deg / {:.0} deg (sidewall / shoe)",
        sweep.contact_model,
        sweep.temperature_k - 273.15,
        sweep.contact_angle_rad.to_degrees(),
        sweep.counter_face_contact_angle_rad.to_degrees()
    );
    let mut t = TextTable::new(&["RH (%)", "mu_e,a", "F_a0 (uN)", "capillary share (%)", "h_m (nm)", "note"]);
    let opt = |x: Option<f64>, scale: f64, prec: usize| x.map_or("-".to_string(), |v| format!("{:.prec$}", v * scale));
    for p in &sweep.points {
        t.row(vec![
            format!("{:.1}", p.relative_humidity * 100.0),
            opt(p.mu_apparent, 1.0, 3),
            opt(p.apparent_adhesion_force_n, 1e6, 3),
            opt(p.capillary_share, 100.0, 1),
            opt(p.meniscus_height_m, 1e9, 3),
            p.reason.clone().unwrap_or_default(),
        ]);
    }
    t.print("  ");
    for w in &sweep.warnings {
        crate::outln!("  warning [{}]: {}", w.code, w.message);
    }
    if let Some(r) = &sweep.reference {
        let at = match r.relative_humidity {
            Some(rh) => format!(" at RH = {:.1} %", rh * 100.0),
            None => ", humidity not stated".into(),
        };
        crate::outln!(
            "  reference, measured ({}){at}: mu_e,a = {}, F_a0 = {} uN",
            r.source,
            r.mu_apparent.map_or("-".into(), |m| format!("{m}")),
            r.apparent_adhesion_force_n.map_or("-".into(), |f| format!("{}", (f * 1e12).round() / 1e6))
        );
    }
    if let Some(dir) = &args.out {
        crate::outln!(
            "\nwrote {}/results.json, humidity.csv, humidity-mu, humidity-fa0 and humidity-share (.svg, .png, .csv), \
             manifest.json",
            dir.display()
        );
    }
    Ok(())
}

use stiction_engine::plot::scenario_theta;

/// Fig. 2: N*(L* = 0) against theta, from 0.5 to 40 (the paper: 1 to 30), on log axes; with a
/// scenario, its theta marked and the axis extended to it.
pub fn fig2(scenario: Option<(&Scenario, &Path)>) -> Result<Chart, Box<dyn std::error::Error>> {
    let theta = match scenario {
        Some((s, base)) => Some(
            scenario_theta(s, base)?
                .ok_or("the scenario has no adhesion (work_of_adhesion = 0): theta is infinite, N* = 0")?,
        ),
        None => None,
    };
    // N* of the scenario, as log10 (it underflows f64 for theta above about 10^3).
    let Fig2Curves { curve: pts, scenario: state, drawable } = fig2_curves(theta)?;
    let mut chart = Chart::new(
        "Fig. 2: summits in contact at zero load (GW + DMT, eq. 5a, 8)",
        "adhesion parameter θ (eq. 9)",
        "fraction of summits in contact N* at L* = 0",
    )
    .keys("theta", "n_star")
    .with(Series::line("N* = F₀(h) at L* = 0", pts));
    if let Some((t, st)) = state {
        let n_text = if st.n_star > 0.0 && st.log10_n_star > -300.0 {
            sig3(st.n_star)
        } else {
            format!("10{}", stiction_plot::superscript(st.log10_n_star.round() as i64))
        };
        if drawable {
            chart
                .series
                .push(Series::markers(format!("this scenario: θ = {}, N* = {n_text}", sig3(t)), vec![(t, st.n_star)]));
            chart.note = Some("θ of the scenario from its σ, R, D and Δγ (eq. 9)".into());
        } else {
            chart.note = Some(format!(
                "this scenario: θ = {} (eq. 9, from its σ, R, D and Δγ), N* = {n_text}: far beyond this axis",
                sig3(t)
            ));
        }
    }
    chart.x_log = true;
    chart.y_log = true;
    chart.legend = LegendPosition::LowerLeft;
    Ok(chart)
}

/// Fig. 3: A* against L* for theta = 10, 15, 30 and infinity (and a scenario's theta), on a
/// symmetric-log load axis: the pull-off loads (L* = -0.024 for theta = 10 down to about -2e-5
/// for theta = 30) and the adhesive branches are visible beside the loaded range up to L* = 1.
pub fn fig3(scenario: Option<(&Scenario, &Path)>) -> Result<Chart, Box<dyn std::error::Error>> {
    let mut chart = Chart::new(
        "Fig. 3: real area against load (GW + DMT, eq. 5b, 8)",
        "normalized load L* (eq. 8), axis sign(L*)·log₁₀(1 + |L*|/10⁻⁶)",
        "normalized real area A* (eq. 5b)",
    )
    .keys("l_star", "a_star")
    .with_note("each curve starts at its pull-off load (dot): the adhesive branch reaches L* < 0");
    let mut pull_offs = Vec::new();
    let mut hidden: Vec<String> = Vec::new();
    let mut thetas: Vec<(String, Option<f64>)> = vec![
        ("(1) θ = 10".into(), Some(10.0)),
        ("(2) θ = 15".into(), Some(15.0)),
        ("(3) θ = 30".into(), Some(30.0)),
        ("(4) θ = ∞ (GW, no adhesion)".into(), None),
    ];
    if let Some((s, base)) = scenario {
        let t = scenario_theta(s, base)?;
        thetas.push((format!("this scenario: θ = {}", t.map_or("∞".to_string(), sig3)), t));
    }
    for (label, theta) in thetas {
        // Loads spaced evenly in the symmetric-log coordinate, so both branches get points.
        let curve = fig3_curve(theta)?;
        let pts = curve.points;
        if let (Some(t), Some(po)) = (theta, curve.pull_off) {
            if po.a_star >= A_STAR_FLOOR {
                pull_offs.push((po.l_star, po.a_star));
            } else {
                hidden.push(format!(
                    "θ = {}: pull-off at L* = −10{}, A* = 10{} (below these axes)",
                    sig3(t),
                    stiction_plot::superscript(po.log10_abs_l_star.round() as i64),
                    stiction_plot::superscript(po.a_star.log10().round() as i64)
                ));
            }
        }
        chart.series.push(Series::line(label, pts));
    }
    chart.series.push(Series::markers("pull-off (L* = −P_c*)", pull_offs).with_color(5));
    if !hidden.is_empty() {
        chart.note = Some(format!("{}\n{}", chart.note.take().unwrap_or_default(), hidden.join("; ")));
    }
    chart.x_symlog = Some(1e-6);
    chart.y_log = true;
    // From the GW curve's A* at L* = 1e-6 (about 5e-6) up: a large theta's branch near its
    // pull-off (A* down to 1e-20) would squash the paper's curves.
    let top = chart.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).fold(0.0, f64::max);
    chart.y_range = Some((A_STAR_FLOOR, top * 1.5));
    chart.legend = LegendPosition::LowerRight;
    Ok(chart)
}

/// Lowest A* drawn in Fig. 3.
const A_STAR_FLOOR: f64 = 1e-6;
