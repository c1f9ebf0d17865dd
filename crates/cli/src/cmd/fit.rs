//! `stiction fit`: measured friction-meter voltages against physics (eq. 10 with regression and
//! calibration uncertainty; maximum-likelihood shear strength per contact model; ranked models).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use stiction_engine::fit::{self, Dataset, Estimate, FitData, FitReport, FitRequest};
use stiction_engine::scenario::Scenario;
use stiction_plot::{Chart, Series};
use stiction_units::io::write_atomic;
use stiction_units::{Constraint, Dimension};

use crate::figargs::FigureArgs;
use crate::output::{CliResult, OutputSet, print_json, quantity};

/// Fit measured (V_clamp, V_pull) data: eq. 10 with regression and calibration intervals, and the
/// shear strength s of each contact model by maximum likelihood, ranked by AIC.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The measured voltages: CSV with columns v_clamp_v, v_pull_v [, v_pull_sd_v, device]
    /// (default: the scenario's `measured.voltages_csv`).
    pub data: Option<PathBuf>,
    /// The scenario of the device (actuators, spring, surface, material, contact law).
    #[arg(long)]
    pub scenario: PathBuf,
    /// Models to fit, comma-separated: discrete-nN, gw-dmt, explicit, explicit-ensemble.
    #[arg(long, default_value = "discrete-n1,discrete-n2,discrete-n3,gw-dmt,explicit,explicit-ensemble")]
    pub models: String,
    /// Free parameters: s, optionally R and F_spring (s,R,F_spring).
    #[arg(long, default_value = "s")]
    pub free: String,
    /// Surface realisations of the explicit ensemble (its band).
    #[arg(long, default_value_t = 100)]
    pub surfaces: usize,
    /// Calibration Monte Carlo draws.
    #[arg(long, default_value_t = 4000)]
    pub draws: usize,
    /// Seed of the calibration Monte Carlo (and of --synthesize).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Write report.json, the figures (SVG, PNG) and their data (CSV) to this folder, with a
    /// manifest.json; the folder is replaced as a whole.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are
    /// left alone; the earlier run's files are replaced or removed).
    #[arg(long)]
    pub force: bool,
    /// Override a scenario field (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Print one JSON object on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Instead of fitting: run the scenario's virtual meter at its clamp voltages and write a
    /// labelled synthetic data file here (with --noise and --repeats).
    #[arg(long, value_name = "FILE.csv")]
    pub synthesize: Option<PathBuf>,
    /// Gaussian noise SD on the synthetic pull voltage ("0.3 V").
    #[arg(long, default_value = "0.3 V", value_parser = quantity(Dimension::Voltage, Constraint::NonNegative))]
    pub noise: f64,
    /// Repeats per clamp voltage in the synthetic file.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Figure size and font (with --out).
    #[command(flatten)]
    pub fig: FigureArgs,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let scenario = Scenario::load(&args.scenario, &args.sets)?;
    let json = Scenario::load_json(&args.scenario, &args.sets)?;
    if scenario.structure.is_some() && args.synthesize.is_none() {
        return run_structure(&args, &scenario, &json);
    }
    fit::check_spring(&scenario, &args.scenario.display().to_string())?;
    let base = args.scenario.parent().map(PathBuf::from).unwrap_or_default();
    if let Some(out) = &args.synthesize {
        // DATA is not read when synthesizing, but it is this command's input all the same.
        if let Some(d) = &args.data {
            stiction_units::io::declare_input(d);
        }
        crate::output::check_output_flag("--synthesize", out)?;
        return synthesize(&args, &scenario, &base, out);
    }
    let req = args.request()?;
    let data = fit::read_data(&req.data, &scenario, &base)?;
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "fit", args.force)?),
        None => None,
    };
    let report = fit::analyse(&req, &data, &scenario, &json, &base)?;
    if let Some(mut set) = outputs {
        set.add_bytes("report.json", crate::output::json_text(&report)?.as_bytes())?;
        write_figures(&mut set, &data, &report, &args.fig)?;
        set.commit()?;
    }
    if args.json {
        return print_json(&report);
    }
    print_summary(&report);
    if let Some(dir) = &args.out {
        crate::outln!(
            "\nwrote {}/report.json, fit-vpull2, fit-friction-load, fit-residuals (.svg, .png, .csv), manifest.json",
            dir.display()
        );
    }
    Ok(())
}

/// `fit` of a structure's measured thresholds: eq. 10 on the forces its parts imply.
fn run_structure(args: &Args, scenario: &Scenario, json: &serde_json::Value) -> CliResult {
    let req = args.request()?;
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "fit", args.force)?),
        None => None,
    };
    let report = fit::structure_fit(&req, scenario, json, &|n| format!("--{n}"))?;
    if let Some(mut set) = outputs {
        set.add_bytes("report.json", crate::output::json_text(&report)?.as_bytes())?;
        set.add_figure("fit-friction-load", &args.fig.apply(structure_fit_chart(&report))?)?;
        set.commit()?;
    }
    if args.json {
        return print_json(&report);
    }
    let r = &report;
    crate::outln!(
        "data: {} ({} rows used, {} rejected; columns {} and {})",
        r.data,
        r.rows_used,
        r.rows_rejected.len(),
        r.normal_column,
        r.tangential_column
    );
    for rej in r.rows_rejected.iter().take(10) {
        crate::outln!("  rejected line {}: {}", rej.line, rej.reason);
    }
    crate::outln!(
        "\neq. 10 on the forces the structure's parts imply ({} + {}):",
        r.structure.normal,
        r.structure.tangential
    );
    let (mu, fa) = (&r.mu_apparent, &r.apparent_adhesion_force_n);
    print_eq10_estimates(mu, fa);
    if let Some(note) = &r.calibration.note {
        crate::outln!("  calibration: {note}");
    }
    let lab = &r.lab_coefficient;
    match lab.coefficient {
        Some(c) => crate::outln!("  the lab's reduction ({}): {c:.3} over {} points", lab.kind, lab.points),
        None => crate::outln!(
            "  the lab's reduction ({}): n/a: {}",
            lab.kind,
            lab.coefficient_reason.as_deref().unwrap_or("")
        ),
    }
    if let Some(note) = &r.resolution_note {
        crate::outln!("  {note}");
    }
    if let Some(dir) = &args.out {
        crate::outln!("\nwrote {}/report.json, fit-friction-load (.svg, .png, .csv), manifest.json", dir.display());
    }
    Ok(())
}

/// What the structure's normal part applies, for axis labels.
fn normal_axis(normal: &str) -> &'static str {
    match normal {
        "plate_electrode" => "normal load L from the plate voltage, a_n V_n² − F_0 (µN)",
        _ => "normal load L from the normal comb voltage, a_n V_n² − F_0 (µN)",
    }
}

/// What the structure's tangential part applies, for axis labels.
fn tangential_axis(tangential: &str) -> &'static str {
    match tangential {
        "released_spring" => "friction F_f = k x, released displacement that sticks (µN)",
        _ => "friction F_f = a_t V_t², tangential comb voltage at slip (µN)",
    }
}

/// A structure fit's figure: the measured points' friction against load through the parts, and
/// the eq. 10 line when it is determined.
fn structure_fit_chart(r: &fit::StructureFitReport) -> Chart {
    let file = Path::new(&r.data).file_name().map_or_else(|| r.data.clone(), |n| n.to_string_lossy().into_owned());
    let normal = if r.normal_column == "normal_load_n" {
        "normal load L as measured (µN)"
    } else {
        normal_axis(r.structure.normal)
    };
    let tangential = if r.tangential_column == "tangential_load_n" {
        "friction F_f, tangential load at slip as measured (µN)"
    } else {
        tangential_axis(r.structure.tangential)
    };
    let pts: Vec<(f64, f64)> = r.points.iter().map(|p| (p.load_n * 1e6, p.friction_n * 1e6)).collect();
    let (l0, l1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let mut chart = Chart::new(
        format!(
            "Friction against load: {file}; normal: {}, tangential: {} ({} protocol)",
            r.structure.normal.replace('_', " "),
            r.structure.tangential.replace('_', " "),
            r.structure.protocol.replace('_', " ")
        ),
        normal,
        tangential,
    )
    .keys("load_un", "friction_un");
    if let (Some(mu), Some(fa0)) = (r.mu_apparent.value, r.apparent_adhesion_force_n.value) {
        let fa0 = fa0 * 1e6;
        let start = -fa0.max(-l0.min(0.0));
        chart = chart.with(
            Series::dashed(
                format!("eq. 10 fit: μ_e,a = {mu:.3}, F_a0 = {fa0:.2} µN"),
                vec![(start, mu * (fa0 + start)), (l1, mu * (fa0 + l1))],
            )
            .with_color(0),
        );
    }
    chart = chart.with(Series::markers("measured threshold", pts).with_color(0));
    chart.legend = stiction_plot::LegendPosition::LowerRight;
    chart
}

/// The measured-voltage file: DATA, else the scenario's `measured.voltages_csv`.
impl Args {
    /// The engine's request of these flags.
    pub fn request(&self) -> Result<FitRequest, String> {
        Ok(FitRequest {
            data: self.data.clone().map_or(FitData::Scenario, FitData::File),
            models: fit::parse_models(&self.models, "--models")?,
            free: fit::parse_free(&self.free, "--free")?,
            surfaces: self.surfaces,
            draws: self.draws,
            seed: self.seed,
        })
    }
}

fn synthesize(args: &Args, scenario: &Scenario, base: &Path, out: &Path) -> CliResult {
    let command = format!(
        "stiction fit --scenario {} --synthesize {} --noise \"{} V\" --repeats {} --seed {}",
        args.scenario.display(),
        out.display(),
        args.noise,
        args.repeats,
        args.seed
    );
    let (text, rows) = fit::synthesize(
        scenario,
        &args.scenario.display().to_string(),
        base,
        args.noise,
        args.repeats,
        args.seed,
        &command,
    )?;
    write_atomic(out, text.as_bytes())?;
    crate::outln!("wrote {} ({rows} rows, synthetic)", out.display());
    Ok(())
}

/// The two lines of eq. 10's estimates (mu_e,a, and F_a0 in uN) with their regression and
/// calibrated 95 % intervals, or the reason each is not determined.
fn print_eq10_estimates(mu: &Estimate, fa: &Estimate) {
    match mu.value {
        Some(v) => crate::outln!(
            "  mu_e,a = {v:.3} +/- {} (regression), 95 %: {} regression, {} with calibration",
            num(mu.stderr, 1.0),
            ci(mu.ci95, 1.0),
            ci(mu.ci95_with_calibration, 1.0)
        ),
        None => crate::outln!("  mu_e,a = n/a: {}", mu.value_note.as_deref().unwrap_or("not determined")),
    }
    match fa.value {
        Some(v) => crate::outln!(
            "  F_a0   = {:.3} uN +/- {} (regression), 95 %: {} uN regression (Fieller), {} uN with calibration",
            v * 1e6,
            num(fa.stderr, 1e6),
            ci(fa.ci95, 1e6),
            ci(fa.ci95_with_calibration, 1e6)
        ),
        None => crate::outln!("  F_a0   = n/a: {}", fa.value_note.as_deref().unwrap_or("not determined")),
    }
}

fn num(v: Option<f64>, scale: f64) -> String {
    v.map_or("n/a".into(), |x| format!("{:.3}", x * scale))
}

fn ci(c: Option<[f64; 2]>, scale: f64) -> String {
    c.map_or("n/a".into(), |[a, b]| format!("[{:.3}, {:.3}]", a * scale, b * scale))
}

fn print_summary(r: &FitReport) {
    crate::outln!("data: {} ({} rows used, {} rejected)", r.data, r.rows_used, r.rows_rejected.len());
    for rej in r.rows_rejected.iter().take(10) {
        crate::outln!("  rejected line {}: {}", rej.line, rej.reason);
    }
    if r.rows_rejected.len() > 10 {
        crate::outln!("  ... {} more (see --json)", r.rows_rejected.len() - 10);
    }
    let (mu, fa) = (&r.mu_apparent, &r.apparent_adhesion_force_n);
    crate::outln!("\neq. 10 (nominal a_clamp, a_pull, F_spring; {}):", "weighted by the noise of V_pull^2");
    print_eq10_estimates(mu, fa);
    let shares = |m: &BTreeMap<String, f64>| {
        if m.is_empty() {
            return "n/a".to_string();
        }
        m.iter().map(|(k, v)| format!("{k} {:.1} %", 100.0 * v)).collect::<Vec<_>>().join(", ")
    };
    crate::outln!("  variance shares of mu_e,a: {}", shares(&r.variance_shares.mu_apparent));
    crate::outln!("  variance shares of F_a0:   {}", shares(&r.variance_shares.apparent_adhesion_force_n));
    if let Some(note) = &r.eq10.calibration.note {
        crate::outln!("  calibration: {note}");
    }
    for d in &r.devices {
        match &d.eq10 {
            Some(f) => crate::outln!(
                "  device {:>8}: mu_e,a {} {}, F_a0 {} uN ({} rows; regression interval only)",
                d.device,
                num(f.mu_apparent.value, 1.0),
                ci(f.mu_apparent.ci95, 1.0),
                num(f.apparent_adhesion_force_n.value, 1e6),
                d.rows_used
            ),
            None => crate::outln!("  device {:>8}: {}", d.device, d.note.clone().unwrap_or_default()),
        }
    }
    for note in &r.surface_notes {
        crate::outln!("\nsurface: {note}");
    }
    crate::outln!("\n{}", r.noise_note);
    crate::outln!();
    let mut t = crate::output::TextTable::new(&[
        "model",
        "s (GPa)",
        "95 % noise only (GPa)",
        "95 % with calibration (GPa)",
        "chi2",
        "dof",
        "AIC",
        "dAIC",
    ]);
    for m in &r.models {
        t.row(vec![
            m.name.clone(),
            format!("{:.4}", m.shear_strength_pa.value / 1e9),
            ci(m.shear_strength_pa.ci95, 1e-9),
            ci(m.shear_strength_pa.ci95_with_calibration, 1e-9),
            format!("{:.2}", m.chi2),
            m.dof.to_string(),
            format!("{:.2}", m.aic),
            m.delta_aic.map_or("n/a".into(), |d| format!("{d:.2}")),
        ]);
    }
    if !r.models.is_empty() {
        t.print("  ");
    }
    for m in &r.models {
        let name = &m.name;
        if let Some(note) = &m.shear_strength_pa.note {
            crate::outln!("  {name}: s: {note}");
        }
        let sh = &m.shear_strength_pa.variance_shares;
        if sh.is_empty() {
            crate::outln!("  {name}: s with calibration: {}", m.shear_strength_pa.ci95_with_calibration_note);
        } else {
            crate::outln!("  {name}: variance shares of s: {}", shares(sh));
        }
        if let Some(rough) = &m.roughness {
            crate::outln!(
                "  {name}: roughness: s over {} surfaces, 95 % {} GPa",
                rough.surfaces,
                ci(rough.shear_strength_ci95_pa, 1e-9)
            );
        }
        if let Some(rr) = &m.summit_radius_m {
            crate::outln!("  {name}: R = {:.3} um, 95 % {} um", rr.value * 1e6, ci(rr.ci95, 1e6));
        }
        if let Some(f) = &m.spring_force_n {
            crate::outln!("  {name}: F_spring = {:.3} uN, 95 % {} uN", f.value * 1e6, ci(f.ci95, 1e6));
        }
    }
    for f in &r.models_failed {
        crate::outln!("  {}: failed: {}", f.name, f.reason);
    }
    crate::outln!();
    for s in &r.model_selection {
        crate::outln!("{s}");
    }
}

/// Repeats of one (device, clamp voltage): pull voltage and its SD.
type Groups = BTreeMap<(String, u64), Vec<(f64, Option<f64>)>>;

/// Writes the three figures through [`OutputSet::add_chart`] (SVG, PNG and the data CSV of each).
fn write_figures(set: &mut OutputSet, data: &Dataset, r: &FitReport, fig: &FigureArgs) -> CliResult {
    for (stem, chart) in fit_charts(data, r) {
        set.add_figure(stem, &fig.apply(chart)?)?;
    }
    Ok(())
}

/// The fit's figures: V_pull² against V_clamp² (`fit-vpull2`), friction against load
/// (`fit-friction-load`) and the residuals (`fit-residuals`). Each model has its colour
/// ([`crate::charts::model_color`]) in all three; the models are drawn from the worst to the
/// best (AIC), and the measured points last, on top.
fn fit_charts(data: &Dataset, r: &FitReport) -> Vec<(&'static str, Chart)> {
    use crate::charts::model_color;
    let red = r.reduction;
    let file = Path::new(&r.data).file_name().map_or_else(|| r.data.clone(), |n| n.to_string_lossy().into_owned());
    // Data grouped by (device, V_clamp): mean V_pull^2 and its error bar (SD of the repeats, or
    // 2 V sd from the column).
    let mut groups: Groups = BTreeMap::new();
    let rejected: std::collections::BTreeSet<u64> = r.rows_rejected.iter().map(|x| x.line).collect();
    for row in data.rows.iter().filter(|row| !rejected.contains(&row.line)) {
        groups.entry((row.device.clone(), row.v_clamp_v.to_bits())).or_default().push((row.v_pull_v, row.v_pull_sd_v));
    }
    let mut pts = Vec::new();
    let mut errs = Vec::new();
    for ((_, bits), g) in &groups {
        let x = f64::from_bits(*bits).powi(2);
        let ys: Vec<f64> = g.iter().map(|(v, _)| v * v).collect();
        let n = ys.len() as f64;
        let m = ys.iter().sum::<f64>() / n;
        let err = if ys.len() > 1 {
            (ys.iter().map(|y| (y - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
        } else {
            g[0].1.map_or(0.0, |sd| 2.0 * g[0].0 * sd)
        };
        pts.push((x, m));
        errs.push(err);
    }
    let mut fig5 = Chart::new(
        format!("Pull voltage at slip: measured ({file}) and each model's fit of s"),
        "clamp voltage squared V_clamp² (V²)",
        "pull voltage squared at slip V_pull² (V²)",
    )
    .keys("v_clamp_squared_v2", "v_pull_squared_v2");
    let best = r.models.first().map(|m| m.name.clone());
    // Bands first (under every line), then the models from the worst to the best.
    for m in r.models.iter().rev() {
        let what = match &m.roughness {
            Some(rough) => format!("roughness band 95 %, {} surfaces", rough.surfaces - rough.surfaces_failed),
            None if Some(&m.name) == best.as_ref() && r.models.iter().all(|o| o.roughness.is_none()) => {
                "95 % band of s".to_string()
            }
            None => continue,
        };
        let band: Vec<(f64, f64, f64)> =
            m.curve.iter().filter_map(|c| c.band_v2.map(|b| (c.v_clamp_sq_v2, b[0], b[1]))).collect();
        if !band.is_empty() {
            fig5 = fig5.with(Series::band(format!("{} {what}", m.name), band).with_color(model_color(&m.name)));
        }
    }
    for m in r.models.iter().rev() {
        let line: Vec<(f64, f64)> =
            m.curve.iter().filter_map(|c| c.v_pull_sq_v2.map(|y| (c.v_clamp_sq_v2, y))).collect();
        let s_gpa = m.shear_strength_pa.value / 1e9;
        fig5 =
            fig5.with(Series::line(format!("{} (s = {s_gpa:.3} GPa)", m.name), line).with_color(model_color(&m.name)));
    }
    fig5 = fig5.with(
        Series::markers("measured (mean, error bar: SD of repeats)", pts.clone())
            .with_y_err(errs.clone())
            .with_color(0),
    );

    // F_f against L (uN), the paper's Fig. 7 view.
    let to_l = |x: f64| (red.a_clamp_n_per_v2 * x - red.spring_force_n) * 1e6;
    let to_f = |y: f64| red.a_pull_n_per_v2 * y * 1e6;
    let fl: Vec<(f64, f64)> = pts.iter().map(|p| (to_l(p.0), to_f(p.1))).collect();
    let fe: Vec<f64> = errs.iter().map(|e| red.a_pull_n_per_v2 * e * 1e6).collect();
    let (l0, l1) = fl.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let mut fig7 = Chart::new(
        format!("Friction against load: measured ({file}), nominal a_clamp, a_pull, F_spring"),
        "clamp load L (µN)",
        "friction force F_f (µN)",
    )
    .keys("load_un", "friction_un");
    for m in r.models.iter().rev() {
        let line: Vec<(f64, f64)> =
            m.curve.iter().filter_map(|c| c.v_pull_sq_v2.map(|y| (c.load_n * 1e6, to_f(y)))).collect();
        fig7 = fig7.with(Series::line(m.name.clone(), line).with_color(model_color(&m.name)));
    }
    // The eq. 10 line only when both of its numbers exist (a null has its reason in report.json).
    if let (Some(mu), Some(fa0)) = (r.mu_apparent.value, r.apparent_adhesion_force_n.value) {
        let fa0 = fa0 * 1e6;
        // From L = -F_a0 (F_f = 0), so the figure shows F_a0 where the line meets the axis.
        let eq10_line = vec![(-fa0.max(-l0.min(0.0)), mu * (fa0 - fa0.max(-l0.min(0.0)))), (l1, mu * (fa0 + l1))];
        fig7 = fig7.with(
            Series::dashed(
                format!("eq. 10 fit of the measured points: μ_e,a = {mu:.3}, F_a0 = {fa0:.2} µN"),
                eq10_line,
            )
            .with_color(0),
        );
    }
    fig7 = fig7.with(Series::markers("measured (mean, error bar: SD of repeats)", fl).with_y_err(fe).with_color(0));
    fig7.legend = stiction_plot::LegendPosition::LowerRight;

    // Residuals: one series per model.
    let mut res_chart = Chart::new(
        format!("Residuals of each model's best fit to {file}"),
        "clamp voltage squared V_clamp² (V²)",
        "V_pull² measured − model (V²)",
    )
    .keys("v_clamp_squared_v2", "residual_v_pull_squared_v2");
    let (x0, x1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    res_chart = res_chart.with(Series::dashed("zero", vec![(x0, 0.0), (x1, 0.0)]).with_color(7));
    for m in r.models.iter().rev().filter(|m| m.comparable) {
        let p: Vec<(f64, f64)> = m.residuals.iter().map(|(_, x, res)| (*x, *res)).collect();
        res_chart = res_chart.with(Series::markers(m.name.clone(), p).with_color(model_color(&m.name)));
    }
    vec![("fit-vpull2", fig5), ("fit-friction-load", fig7), ("fit-residuals", res_chart)]
}
