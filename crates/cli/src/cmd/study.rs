//! `stiction study`: Monte Carlo over a scenario's uncertain parameters and surface realisations.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use indicatif::{ProgressBar, ProgressStyle};
use stiction_plot::{Chart, Series};
use stiction_study::{Calibration, StudyConfig, StudyResult, run_study};

use crate::output::{CliResult, OutputSet, print_json};

/// Run the friction meter on many realisations of a scenario: every parameter written with an
/// uncertainty is drawn anew, and each sample gets its own rough surface. Reports the spread of
/// mu_e,a and F_a0 (eq. 10). Same seed, same bytes, whatever --threads or --shard.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file.
    pub scenario: PathBuf,
    /// Number of samples of the whole study.
    #[arg(long, default_value_t = 100)]
    pub samples: usize,
    /// Base seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Keep the scenario's surface for every sample (vary only the uncertain parameters).
    #[arg(long)]
    pub fixed_surface: bool,
    /// Run only shard K of M (samples with index % M == K), as "K/M"; merge the outputs afterwards.
    #[arg(long, value_name = "K/M")]
    pub shard: Option<String>,
    /// How the virtual lab converts voltages to forces: with the file's nominal factors (as the
    /// paper did), or with each device's arrays calibrated from their own pull-in voltages.
    #[arg(long, value_enum, default_value = "nominal")]
    pub calibration: CalibrationArg,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Write study.json, samples.csv and plots (SVG, PNG) to this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Write into an --out folder that holds files not from an earlier stiction run.
    #[arg(long)]
    pub force: bool,
    /// Override a scenario field (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
}

/// The --calibration choices.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum CalibrationArg {
    /// The nominal conversion factors and spring force of the scenario.
    Nominal,
    /// Conversion factors from each device's measured pull-in voltages.
    PullIn,
}

fn parse_shard(s: &str) -> Result<(usize, usize), String> {
    let (k, m) = s.split_once('/').ok_or_else(|| format!("--shard {s:?}: expected K/M, like 0/4"))?;
    let k: usize = k.trim().parse().map_err(|_| format!("--shard {s:?}: K is not a whole number"))?;
    let m: usize = m.trim().parse().map_err(|_| format!("--shard {s:?}: M is not a whole number"))?;
    if m == 0 || k >= m {
        return Err(format!("--shard {s:?}: expected 0 <= K < M"));
    }
    Ok((k, m))
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let (shard_index, shard_count) = match &args.shard {
        Some(s) => parse_shard(s)?,
        None => (0, 1),
    };
    let calibration = match args.calibration {
        CalibrationArg::Nominal => Calibration::Nominal,
        CalibrationArg::PullIn => Calibration::PullIn,
    };
    let config = StudyConfig {
        calibration,
        samples: args.samples,
        seed: args.seed,
        vary_surface: !args.fixed_surface,
        shard_index,
        shard_count,
    };
    let total = (0..args.samples).filter(|i| i % shard_count == shard_index).count();
    let bar = ProgressBar::new(total as u64);
    bar.set_style(
        ProgressStyle::with_template("{spinner} samples {pos}/{len} [{bar:30}] {elapsed_precise} eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let done = AtomicUsize::new(0);
    let progress = || {
        let n = done.fetch_add(1, Ordering::Relaxed) + 1;
        bar.set_position(n as u64);
    };
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = args.threads {
        if t == 0 {
            return Err("--threads must be at least 1".into());
        }
        pool = pool.num_threads(t);
    }
    let pool = pool.build()?;
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "study", args.force)?),
        None => None,
    };
    let result = pool.install(|| run_study(&args.scenario, &args.sets, &config, &progress))?;
    bar.finish_and_clear();
    if let Some(mut set) = outputs {
        set.add_bytes("study.json", (serde_json::to_string_pretty(&result)? + "\n").as_bytes())?;
        let mut w = csv::Writer::from_writer(Vec::new());
        let params: Vec<String> = result
            .samples
            .iter()
            .find(|s| s.error.is_none())
            .map(|s| s.draws.iter().map(|d| d.path.clone()).collect())
            .unwrap_or_default();
        let mut header =
            vec!["index".to_string(), "mu_apparent".into(), "apparent_adhesion_force_n".into(), "mean_contacts".into()];
        header.extend(params.iter().cloned());
        header.push("error".into());
        w.write_record(&header)?;
        for s in &result.samples {
            let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
            let mut row =
                vec![s.index.to_string(), opt(s.mu_apparent), opt(s.apparent_adhesion_force_n), opt(s.mean_contacts)];
            for p in &params {
                row.push(s.draws.iter().find(|d| &d.path == p).map_or(String::new(), |d| format!("{:e}", d.value)));
            }
            row.push(s.error.clone().unwrap_or_default());
            w.write_record(&row)?;
        }
        let csv_bytes = w.into_inner().map_err(|e| format!("samples.csv: {e}"))?;
        set.add_bytes("samples.csv", &csv_bytes)?;
        for (name, chart) in [("mu_cdf", cdf_chart(&result)), ("mu_vs_fa0", scatter_chart(&result))] {
            set.add_chart(&format!("{name}.svg"), &chart)?;
            set.add_chart(&format!("{name}.png"), &chart)?;
        }
        set.commit()?;
    }
    if args.json {
        return print_json(&result);
    }
    crate::outln!(
        "Monte Carlo study of {} ({} samples{}, seed {})",
        args.scenario.display(),
        result.samples.len(),
        if shard_count > 1 { format!(", shard {shard_index}/{shard_count}") } else { String::new() },
        args.seed
    );
    let show = |name: &str, s: &Option<stiction_study::Spread>, scale: f64, unit: &str| match s {
        Some(s) => crate::outln!(
            "  {name:<28} mean {:.3}{unit} sd {:.3}{unit}  5-95 %: {:.3}..{:.3}{unit}  (n = {})",
            s.mean * scale,
            s.sd * scale,
            s.p05 * scale,
            s.p95 * scale,
            s.count
        ),
        None => crate::outln!("  {name:<28} no sample gave a value"),
    };
    show("mu_e,a (paper 0.7 +/- 0.3)", &result.mu_apparent, 1.0, "");
    show("F_a0 (paper 2.0 +/- 1.3 uN)", &result.apparent_adhesion_force_n, 1e6, " uN");
    if result.without_fit > 0 {
        crate::outln!(
            "  {} samples had fewer than two slip points with L > 0 (their clamp voltages hardly reached contact): no fit",
            result.without_fit
        );
    }
    if result.failed > 0 {
        crate::outln!("  {} samples failed; their errors are in the JSON output and samples.csv", result.failed);
        for s in result.samples.iter().filter(|s| s.error.is_some()).take(3) {
            crate::outln!("    sample {}: {}", s.index, s.error.as_deref().unwrap_or(""));
        }
    }
    Ok(())
}

fn cdf_chart(r: &StudyResult) -> Chart {
    let mut mus: Vec<f64> = r.samples.iter().filter_map(|s| s.mu_apparent).collect();
    mus.sort_by(f64::total_cmp);
    let n = mus.len().max(1) as f64;
    let pts: Vec<(f64, f64)> = mus.iter().enumerate().map(|(i, &m)| (m, (i as f64 + 0.5) / n)).collect();
    Chart::new(
        format!("Spread of the apparent friction coefficient ({} samples)", mus.len()),
        "apparent friction coefficient mu_e,a (eq. 10)",
        "cumulative fraction of samples",
    )
    .with(Series::line("virtual meters", pts))
    .with(Series::markers("paper: 0.7 +/- 0.3", vec![(0.7, 0.5)]).with_y_err(vec![0.0]))
    .with(Series::dashed("", vec![(0.4, 0.5), (1.0, 0.5)]))
}

fn scatter_chart(r: &StudyResult) -> Chart {
    let pts: Vec<(f64, f64)> =
        r.samples.iter().filter_map(|s| Some((s.apparent_adhesion_force_n? * 1e6, s.mu_apparent?))).collect();
    Chart::new(
        "mu_e,a against F_a0 over the samples",
        "apparent zero-load adhesion force F_a0 (uN)",
        "apparent friction coefficient mu_e,a",
    )
    .with(Series::markers("virtual meters", pts))
    .with(Series::markers("paper (measured)", vec![(2.0, 0.7)]).with_y_err(vec![0.3]))
}
