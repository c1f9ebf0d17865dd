//! What `stiction study` and design studies (cmd::design) share: the command's arguments, the
//! progress line, the summary's text report and the study folder's figures and manifest (the
//! command line's part of a study folder; the loop and the folder's data files are the engine's,
//! `stiction_engine::study_folder`).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use stiction_engine::design::RankBy;
use stiction_engine::scenario::ReferenceSpec;
use stiction_engine::study::{FigureData, InputShare, LOG_NAME, REASONS, Spread, StudySummary, digits, usable_se};
use stiction_engine::study_folder::FolderHooks;
use stiction_plot::{Chart, Series};

use crate::figargs::{FigureArgs, reference};
use crate::output::{CliResult, print_json};

/// Run the friction meter on many realisations of a scenario: every parameter written with an
/// uncertainty is drawn anew, and each sample gets its own rough surface. Reports the spread of
/// mu_e,a and F_a0 (eq. 10) and which input explains how much of it. Same seed, same bytes,
/// whatever --threads or --shard.
///
/// Each finished sample is appended to OUT/samples.log at once; a killed study is finished with
/// --resume (same bytes as an uninterrupted run); shards are combined with `stiction merge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file.
    pub scenario: PathBuf,
    /// Number of samples of the whole study (at most 1e7; STICTION_MAX_SAMPLES raises it).
    #[arg(long, default_value_t = 100)]
    pub samples: usize,
    /// Base seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Keep the scenario's surface for every sample (vary only the uncertain parameters).
    #[arg(long)]
    pub fixed_surface: bool,
    /// Run only shard K of M (samples with index % M == K), as "K/M"; combine the shards' folders
    /// with `stiction merge DIR... --out DIR`.
    #[arg(long, value_name = "K/M")]
    pub shard: Option<String>,
    /// How the virtual lab converts voltages to forces: with the file's nominal factors (as the
    /// paper did), or with each device's arrays calibrated from their own pull-in voltages.
    #[arg(long, value_enum, default_value = "nominal")]
    pub calibration: CalibrationArg,
    /// How the pull shuttle is followed after each slip (with `meter.slip_dynamics`): the light
    /// path (energy criterion + RK4, validated against rapier) or the full rapier rigid body.
    #[arg(long, value_enum, default_value = "light")]
    pub slip_path: SlipPathArg,
    /// Worker threads (default: all cores; at most 1024).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write samples.log, study.json, samples.csv, sensitivity.csv and plots (SVG, PNG) to this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Finish the study whose log is in --out (after a kill): the result is the same bytes as an
    /// uninterrupted run.
    #[arg(long, requires = "out")]
    pub resume: bool,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are left
    /// alone), or start a new study over a finished one there (its files are replaced).
    #[arg(long)]
    pub force: bool,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
    /// Print one JSON object (study.json) instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Override a scenario field (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// A design study: run the whole study once per value of this field (values as --set takes
    /// them), over the grid of every --vary; same seeds in every design. Writes OUT/design-NNN
    /// (each a study folder), designs.csv, designs.json and a design chart per varied field.
    /// Overrides the scenario's `design` section (which offers the same).
    #[arg(long = "vary", value_name = "PATH=V1,V2,...")]
    pub vary: Vec<String>,
    /// With a range --vary "PATH=LO..HI": the number of design points of the space-filling (Latin
    /// hypercube, seeded by --seed) design over all ranges.
    #[arg(long, value_name = "N")]
    pub design_points: Option<usize>,
    /// How a design study ranks its designs (default: the scenario's `design.criterion`, else
    /// narrowest).
    #[arg(long, value_enum)]
    pub rank_by: Option<RankByArg>,
    /// Figure size and font.
    #[command(flatten)]
    pub fig: FigureArgs,
}

/// The --calibration choices.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum CalibrationArg {
    /// The nominal conversion factors and spring force of the scenario.
    Nominal,
    /// Conversion factors from each device's measured pull-in voltages.
    PullIn,
}

/// The --slip-path choices.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum SlipPathArg {
    /// Energy criterion for the runaway plus an RK4 integrator for the time to the stop.
    Light,
    /// The rapier rigid-body trajectory (about 100 times slower).
    RigidBody,
}

pub(crate) use stiction_engine::study::{parse_shard, prepare_study};

/// The command line's name of a study request's field (`threads` -> `--threads`).
pub(crate) fn flag(field: &str) -> String {
    format!("--{}", field.replace('_', "-"))
}

/// Progress: a bar on a terminal, a plain line every 5 s elsewhere, nothing with --quiet.
pub(crate) struct Progress {
    bar: Option<ProgressBar>,
    plain: Option<Mutex<(Instant, Instant)>>,
    total: usize,
    start_done: std::sync::atomic::AtomicUsize,
}

impl Progress {
    pub(crate) fn new(total: usize, start_done: usize, quiet: bool) -> Progress {
        let terminal = std::io::stderr().is_terminal();
        let bar = (!quiet && terminal).then(|| {
            let b = ProgressBar::new(total as u64);
            b.set_style(
                ProgressStyle::with_template("{spinner} samples {pos}/{len} [{bar:30}] {per_sec} eta {eta}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            b.set_position(start_done as u64);
            b.reset_eta();
            b
        });
        let now = Instant::now();
        let plain = (!quiet && !terminal).then(|| Mutex::new((now, now)));
        Progress { bar, plain, total, start_done: start_done.into() }
    }

    pub(crate) fn line(&self, done: usize, elapsed: Duration) -> String {
        let secs = elapsed.as_secs_f64().max(1e-9);
        let start = self.start_done.load(std::sync::atomic::Ordering::Relaxed);
        let rate = (done - start.min(done)) as f64 / secs;
        let left =
            if rate > 0.0 { format!("{:.0} s", (self.total - done.min(self.total)) as f64 / rate) } else { "?".into() };
        format!(
            "study: {done}/{} samples ({:.0} %), {rate:.0} samples/s, about {left} left",
            self.total,
            100.0 * done as f64 / self.total.max(1) as f64
        )
    }

    /// Counts the rate from `done` samples on (those found in a resumed log).
    pub(crate) fn restart_at(&self, done: usize) {
        self.start_done.store(done, std::sync::atomic::Ordering::Relaxed);
        if let Some(b) = &self.bar {
            b.set_position(done as u64);
            b.reset_eta();
        }
        if let Some(p) = &self.plain {
            let now = Instant::now();
            *p.lock().unwrap_or_else(|e| e.into_inner()) = (now, now);
        }
    }

    pub(crate) fn update(&self, done: usize) {
        if let Some(b) = &self.bar {
            b.set_position(done as u64);
        }
        if let Some(p) = &self.plain {
            let mut g = p.lock().unwrap_or_else(|e| e.into_inner());
            let now = Instant::now();
            if now.duration_since(g.1) >= Duration::from_secs(5) {
                g.1 = now;
                crate::errln!("{}", self.line(done, now.duration_since(g.0)));
            }
        }
    }

    pub(crate) fn finish(&self, done: usize) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
        if let Some(p) = &self.plain {
            let g = p.lock().unwrap_or_else(|e| e.into_inner());
            crate::errln!("{}", self.line(done, g.0.elapsed()));
        }
    }
}

/// What an interrupted study kept and how to finish it (the command line again, with --resume).
pub(crate) fn interrupted(logged: usize, total: usize, dir: &Path, temporary: bool) -> crate::output::Interrupted {
    if temporary {
        return crate::output::Interrupted(format!(
            "interrupted after {logged} of {total} samples; without --out nothing is kept (give --out DIR to be able \
             to resume)"
        ));
    }
    let quote = |a: String| {
        if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./=:,+@%".contains(c)) {
            a
        } else {
            format!("'{}'", a.replace('\'', "'\\''"))
        }
    };
    let mut words: Vec<String> = std::env::args().map(quote).collect();
    if let Some(first) = words.first_mut() {
        *first = "stiction".into();
    }
    if !words.iter().any(|w| w == "--resume") {
        words.push("--resume".into());
    }
    words.retain(|w| w != "--force");
    crate::output::Interrupted(format!(
        "interrupted: {logged} of {total} samples are in {}; finish the study with:\n  {}",
        dir.join(LOG_NAME).display(),
        words.join(" ")
    ))
}

/// The command line's part of a study folder the engine writes: its figures (drawn here) and,
/// for a folder written in place (`manifest`), its manifest.json: removed while the study runs
/// (the folder is not complete), written with the folder's files at the end.
pub(crate) struct StudyFolder<'a> {
    /// Figure size and font.
    pub fig: &'a FigureArgs,
    /// Whether the folder's manifest is this command's to keep (a staged `merge` folder's is
    /// the output set's).
    pub manifest: bool,
}

impl FolderHooks for StudyFolder<'_> {
    fn opened(&self, dir: &Path) -> CliResult {
        let manifest = dir.join(crate::output::MANIFEST);
        if self.manifest && manifest.exists() {
            std::fs::remove_file(&manifest).map_err(|e| format!("cannot remove {}: {e}", manifest.display()))?;
        }
        Ok(())
    }

    fn figures(
        &self,
        dir: &Path,
        summary: &StudySummary,
        fig: &FigureData,
    ) -> Result<Vec<String>, Box<dyn std::error::Error>> {
        write_figures(summary, fig, dir, self.fig)
    }

    fn finished(&self, dir: &Path, files: &[String]) -> CliResult {
        if self.manifest {
            crate::output::write_manifest(dir, "study", files)?;
        }
        Ok(())
    }
}

/// Prints the summary (or JSON).
pub(crate) fn report(summary: &StudySummary, json: bool, scenario: &Path) -> CliResult {
    if json {
        return print_json(summary);
    }
    let c = &summary.config;
    crate::outln!(
        "Monte Carlo study of {} ({} samples{}, seed {})",
        scenario.display(),
        summary.samples_done,
        if c.shard != "0/1" { format!(", shard {}", c.shard) } else { String::new() },
        c.seed
    );
    // Only the digits the sample size supports: the mean to its standard error's leading digit,
    // the percentiles to that of their order-statistic intervals (half-width / 1.96).
    let show = |name: &str, s: &Option<Spread>, scale: f64, unit: &str| match s {
        Some(s) => {
            let q_se = |ci: Option<[f64; 2]>| ci.map(|[a, b]| (b - a) * scale / 3.92);
            let q = |v: f64, ci: Option<[f64; 2]>| digits(v * scale, q_se(ci));
            // A standard error at rounding level is no spread: "+/- 0", the mean to 3 digits.
            let se = usable_se(s.mean * scale, Some(s.mean_se * scale));
            crate::outln!(
                "  {name:<28} mean {} +/- {}{unit} (Monte Carlo s.e.) sd {}{unit}  median {}{unit}  5-95 %: {}..{}{unit}  (n = {})",
                digits(s.mean * scale, se),
                se.map_or("0".into(), |e| digits(e, Some(e))),
                digits(s.sd * scale, se),
                q(s.median, s.median_ci),
                q(s.p05, s.p05_ci),
                q(s.p95, s.p95_ci),
                s.count
            )
        }
        None => crate::outln!("  {name:<28} no sample gave a value"),
    };
    show("mu_e,a", &summary.mu_apparent, 1.0, "");
    show("F_a0", &summary.apparent_adhesion_force_n, 1e6, " uN");
    {
        // A median to the digit its order-statistic interval allows.
        let median = |x: &Option<Spread>, scale: f64| {
            x.as_ref()
                .map_or("-".to_string(), |s| digits(s.median * scale, s.median_ci.map(|[a, b]| (b - a) / 3.92 * scale)))
        };
        let li = &summary.lab_intervals;
        if li.mu_ci95_width.is_some() {
            crate::outln!(
                "  {:<28} mu_e,a {} (regression) / {} (with calibration, {} draws); F_a0 {} / {} uN",
                "lab 95 % CI, median width",
                median(&li.mu_ci95_width, 1.0),
                median(&li.mu_ci95_width_with_calibration, 1.0),
                li.calibration_draws,
                median(&li.fa0_ci95_width_n, 1e6),
                median(&li.fa0_ci95_width_with_calibration_n, 1e6)
            );
        }
        if let Some(b) = &summary.mu_bias {
            crate::outln!(
                "  {:<28} each device's own s / p_mean: median {}; bias of mu_e,a against it: median {}, mean {}",
                "interface coefficient",
                median(&summary.interface_mu, 1.0),
                median(&summary.mu_bias, 1.0),
                digits(b.mean, Some(b.mean_se).filter(|e| *e > 0.0))
            );
        }
    }
    if let Some(r) = &summary.reference {
        crate::outln!("  {}", reference::text(r));
    }
    if !summary.reasons.is_empty() {
        crate::outln!(
            "  samples without a fit ({} ran without one, {} failed), by reason:",
            summary.without_fit,
            summary.failed
        );
        for (code, n) in &summary.reasons {
            let what = REASONS.iter().find(|r| r.0 == code).map_or("", |r| r.1);
            crate::outln!("    {n:>8}  {code}: {what}");
        }
    }
    let s = &summary.sensitivity;
    if s.samples >= 20 {
        crate::outln!(
            "  share of the variance (Sobol indices, first order S and total order ST, with 95 % bootstrap intervals; \
             Spearman rho), {} samples with a fit:",
            s.samples
        );
        // An index with its interval, to the digit the interval's half-width supports.
        let f = |x: Option<f64>, ci: Option<[f64; 2]>| match (x, ci) {
            (Some(v), Some([a, b])) => {
                let se = Some((b - a) / 3.92).filter(|e| *e > 0.0).map(|e| e.max(0.005));
                let d = digits;
                format!("{} [{}, {}]", d(v, se), d(a, se), d(b, se))
            }
            (Some(v), None) => format!("{v:.2}"),
            _ => "-".to_string(),
        };
        let rho = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:+.2}"));
        let mut t = crate::output::TextTable::new(&[
            "input",
            "mu_e,a: S",
            "mu_e,a: ST",
            "mu_e,a: rho",
            "F_a0: S",
            "F_a0: ST",
            "F_a0: rho",
        ]);
        for r in &s.inputs {
            t.row(vec![
                r.input.clone(),
                f(r.mu_first_order, r.mu_first_order_ci),
                f(r.mu_total_order, r.mu_total_order_ci),
                rho(r.mu_spearman),
                f(r.fa0_first_order, r.fa0_first_order_ci),
                f(r.fa0_total_order, r.fa0_total_order_ci),
                rho(r.fa0_spearman),
            ]);
        }
        t.print("    ");
    }
    Ok(())
}

fn write_figures(
    summary: &StudySummary,
    fig: &FigureData,
    dir: &Path,
    figargs: &FigureArgs,
) -> Result<Vec<String>, Box<dyn std::error::Error>> {
    let mut written = Vec::new();
    // A figure without data is left out (a shard or a tiny study may have no fit or too few
    // samples for the sensitivity table, which needs 20 with a fit). Each figure has its data as
    // CSV beside it (same stem, the plot crate's columns with units).
    let has_sens = summary.sensitivity.inputs.iter().any(|r| r.mu_first_order.is_some());
    let r = summary.reference.as_ref();
    let charts = [
        ("mu_cdf", !fig.mu_sorted.is_empty(), cdf_chart(fig, r)),
        ("mu_vs_fa0", !fig.scatter.is_empty(), scatter_chart(fig, r)),
        // Not "sensitivity": its data CSV would overwrite the sensitivity table (sensitivity.csv).
        ("sensitivity_indices", has_sens, sensitivity_chart(summary)),
    ];
    for (name, _, chart) in charts.into_iter().filter(|c| c.1) {
        let chart = figargs.apply(chart)?;
        written.extend(crate::output::write_chart_files(dir, name, &chart)?);
    }
    Ok(written)
}

/// The empirical CDF F(x_(i)) = i/n (i = 1..n) of the sorted values, as the corners of its
/// staircase: (x_(1), 0), then (x_(i), i/n). Above 2000 values, every k-th value (and the last),
/// so each drawn step may hold k values.
fn cdf_points(fig: &FigureData) -> Vec<(f64, f64)> {
    let n = fig.mu_sorted.len();
    if n == 0 {
        return Vec::new();
    }
    let step = n.div_ceil(2000).max(1);
    let mut pts = vec![(fig.mu_sorted[0], 0.0)];
    pts.extend((step - 1..n).step_by(step).map(|i| (fig.mu_sorted[i], (i + 1) as f64 / n as f64)));
    if !n.is_multiple_of(step) {
        pts.push((fig.mu_sorted[n - 1], 1.0));
    }
    pts
}

fn cdf_chart(fig: &FigureData, r: Option<&ReferenceSpec>) -> Chart {
    let mut chart = Chart::new(
        format!("Spread of the apparent friction coefficient over {} virtual meters", fig.mu_sorted.len()),
        "apparent friction coefficient μ_e,a (eq. 10)",
        "cumulative fraction of samples",
    )
    .keys("mu_apparent", "cumulative_fraction")
    .with(Series::step(format!("virtual meters, empirical CDF i/n (n = {})", fig.mu_sorted.len()), cdf_points(fig)));
    if let Some(r) = r
        && let (Some((a, b)), Some(label)) = (reference::mu_range(r), reference::mu_label(r))
    {
        chart.series.push(Series::x_range(label, a, b).with_color(1));
        chart.note = reference::meaning_note(r);
    }
    chart.legend = stiction_plot::LegendPosition::LowerRight;
    chart.y_range = Some((0.0, 1.0));
    chart
}

fn scatter_chart(fig: &FigureData, r: Option<&ReferenceSpec>) -> Chart {
    let pts: Vec<(f64, f64)> = fig.scatter.iter().map(|&(f, m)| (f * 1e6, m)).collect();
    let mut chart = Chart::new(
        format!("μ_e,a against F_a0 over {} virtual meters", pts.len()),
        "apparent zero-load adhesion force F_a0 (µN)",
        "apparent friction coefficient μ_e,a",
    )
    .keys("fa0_un", "mu_apparent")
    .with(Series::markers("virtual meters", pts));
    if let Some(r) = r {
        match (r.mu_apparent, r.apparent_adhesion_force) {
            (Some(m), Some(f)) => {
                let pm = |v: f64, u: Option<f64>| match u {
                    Some(u) => format!("{} ± {}", reference::num(v), reference::num(u)),
                    None => reference::num(v),
                };
                let label = format!(
                    "measured μ_e,a = {}, F_a0 = {} µN",
                    pm(m, r.mu_apparent_uncertainty),
                    pm(f * 1e6, r.apparent_adhesion_force_uncertainty.map(|u| u * 1e6))
                );
                chart.series.push(
                    Series::markers(format!("{label} ({})", r.source), vec![(f * 1e6, m)])
                        .with_y_err(vec![r.mu_apparent_uncertainty.unwrap_or(0.0)])
                        .with_x_err(vec![r.apparent_adhesion_force_uncertainty.unwrap_or(0.0) * 1e6])
                        .with_color(1),
                );
            }
            (Some(_), None) => {
                if let (Some((a, b)), Some(label)) = (reference::mu_range(r), reference::mu_label(r)) {
                    chart.series.push(Series::y_range(label, a, b).with_color(1));
                }
            }
            (None, Some(_)) => {
                if let (Some((a, b)), Some(label)) = (reference::adhesion_range_un(r), reference::adhesion_label(r)) {
                    chart.series.push(Series::x_range(label, a, b).with_color(1));
                }
            }
            (None, None) => {}
        }
        chart.note = reference::meaning_note(r);
    }
    chart.legend = stiction_plot::LegendPosition::UpperRight;
    chart
}

/// First- and total-order Sobol indices with their 95 % bootstrap intervals at x = input number
/// (1, 2, ...), mu_e,a and F_a0 side by side.
fn sensitivity_chart(summary: &StudySummary) -> Chart {
    let rows = &summary.sensitivity.inputs;
    // Short names that fit under a tick: the paper's symbols for the inputs it names
    // (a_clamp, a_pull, F_spring, R), else the last two parts of the JSON path.
    let short = |s: &str| -> String {
        if s.contains(' ') {
            return "sidewall + interactions".into();
        }
        let parts: Vec<&str> = s.split('.').collect();
        match parts.as_slice() {
            ["actuators", name, "conversion_factor"] => format!("a_{name}"),
            ["meter", "spring_force"] => "F_spring".into(),
            ["surface", "summit_radius"] => "summit radius R".into(),
            _ => parts[parts.len().saturating_sub(2)..].join("."),
        }
    };
    let names: Vec<String> = rows.iter().map(|r| short(&r.input)).collect();
    type Pick = dyn Fn(&InputShare) -> (Option<f64>, Option<[f64; 2]>);
    // One series of markers per index (at the input's number, offset), drawn over its 95 % bootstrap
    // intervals: a vertical segment from the interval's low to its high end (the intervals are
    // not symmetric about the estimate), named like its index's markers (the legend lists each
    // name once); every point labelled with the input's path (the data CSV's `label` column).
    let mut chart = Chart::new(
        format!("Share of the variance by input ({} samples with a fit)", summary.sensitivity.samples),
        "input",
        "Sobol index (bars: 95 % bootstrap intervals)",
    )
    .keys("input_number", "sobol_index");
    let picks: [(&str, f64, &Pick); 4] = [
        ("μ_e,a, first order", -0.15, &|r| (r.mu_first_order, r.mu_first_order_ci)),
        ("μ_e,a, total order", -0.05, &|r| (r.mu_total_order, r.mu_total_order_ci)),
        ("F_a0, first order", 0.05, &|r| (r.fa0_first_order, r.fa0_first_order_ci)),
        ("F_a0, total order", 0.15, &|r| (r.fa0_total_order, r.fa0_total_order_ci)),
    ];
    let mut segments = Vec::new();
    for (k, (name, off, f)) in picks.iter().enumerate() {
        let (mut pts, mut inputs) = (Vec::new(), Vec::new());
        for (i, r) in rows.iter().enumerate() {
            if let (Some(v), ci) = f(r) {
                let x = i as f64 + 1.0 + off;
                pts.push((x, v));
                inputs.push(r.input.clone());
                if let Some([lo, hi]) = ci {
                    segments.push(
                        Series::line(*name, vec![(x, lo), (x, hi)]).with_color(k).with_labels(vec![r.input.clone(); 2]),
                    );
                }
            }
        }
        chart.series.push(Series::markers(*name, pts).with_color(k).with_labels(inputs));
    }
    chart.series.extend(segments);
    chart.x_ticks = Some(names.iter().enumerate().map(|(i, n)| (i as f64 + 1.0, n.clone())).collect());
    chart.x_range = Some((0.5, rows.len() as f64 + 0.5));
    chart.legend = stiction_plot::LegendPosition::UpperRight;
    chart
}

/// The --rank-by choices.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default)]
pub enum RankByArg {
    /// Narrowest 5-95 % interval of mu_e,a first.
    #[default]
    Narrowest,
    /// Smallest |median mu_e,a - the interface's own coefficient s / p_mean| first.
    LeastBias,
    /// Largest fraction of experiments with a usable eq. 10 line first.
    MostUsable,
}

impl From<RankByArg> for RankBy {
    fn from(r: RankByArg) -> RankBy {
        match r {
            RankByArg::Narrowest => RankBy::Narrowest,
            RankByArg::LeastBias => RankBy::LeastBias,
            RankByArg::MostUsable => RankBy::MostUsable,
        }
    }
}
