//! `stiction study SCENARIO --vary PATH=V1,V2,...`: a design study, one complete Monte Carlo study
//! per design point: the flags to the engine's plan (`stiction_engine::design`, which also runs
//! each design into its folder), the --out folder's rules and manifest, the design table and the
//! design charts.

use std::path::Path;

use stiction_engine::design::{
    DesignPlan, DesignReport, DesignRequest, DesignRow, DesignSpec, DesignsOutcome, RankBy, Vary, design_folder,
    design_name, is_design_name, plan, prepare_designs, run_designs, write_tables,
};
use stiction_engine::study::{LOG_NAME, Spread, StudyConfig, digits};
use stiction_plot::{Chart, Marker, Series};

use crate::cmd::study_common::{Args, Progress, StudyFolder};
use crate::output::{CliResult, ensure_dir, print_json};

/// The stem of a varied field's design chart.
fn chart_stem(v: &Vary) -> String {
    format!("design_{}", v.path.replace(['.', '/'], "_"))
}

/// What [`prepare_top`] found in a design study's --out: the names an earlier design study of
/// the folder listed, and the stale design folders (of an earlier study with more designs).
struct Top {
    listed: Vec<String>,
    stale: Vec<String>,
}

/// The `--out` rules of a design study's folder, checked before any work. The folder is written
/// in place (its designs' logs grow sample by sample), like a study's folder, and follows the same
/// rules: names that no earlier stiction run listed in its manifest.json (a user's designs.csv,
/// notes, a design-NNN folder no design study made) are refused unless --force (then left
/// alone); each design folder follows a study folder's rules (an existing log needs --resume to
/// finish it or --force to start again; --force removes the earlier run's files). The manifest is
/// rewritten at once to list this run's design folders beside the earlier ones, so an
/// interrupted run leaves nothing unaccounted for.
fn prepare_top(out: &Path, varies: &[Vary], n: usize, args: &Args) -> Result<Top, Box<dyn std::error::Error>> {
    ensure_dir(out)?;
    let own: Vec<String> = (0..n).map(design_name).collect();
    let own_refs: Vec<&str> = own.iter().map(String::as_str).collect();
    crate::output::check_foreign(out, &own_refs, args.force).map_err(|e| format!("--out: {e}"))?;
    let listed = crate::output::listed_files(out)?;
    let mut outputs = vec!["designs.csv".to_string(), "designs.json".into()];
    for v in varies {
        outputs.extend(["svg", "png", "csv"].map(|e| format!("{}.{e}", chart_stem(v))));
    }
    for f in &outputs {
        crate::output::check_output_flag("--out", &out.join(f))?;
    }
    for d in 0..n {
        let dir = design_folder(out, d);
        match std::fs::symlink_metadata(&dir) {
            Ok(m) if !m.is_dir() => {
                return Err(format!("--out: {} exists and is not a folder", dir.display()).into());
            }
            Ok(_) => {}
            Err(_) => continue,
        }
        crate::output::check_foreign(&dir, &[LOG_NAME], args.force)?;
        let log = dir.join(LOG_NAME);
        if !args.resume && std::fs::symlink_metadata(&log).is_ok() {
            if !args.force {
                return Err(format!(
                    "--out: {} exists: this folder holds a design study already; add --resume to finish it, or \
                     --force to start again",
                    log.display()
                )
                .into());
            }
            let mut old = crate::output::listed_files(&dir)?;
            old.extend([LOG_NAME.to_string(), crate::output::MANIFEST.to_string()]);
            for f in old {
                let p = dir.join(&f);
                if std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_file()) {
                    std::fs::remove_file(&p).map_err(|e| format!("cannot remove {}: {e}", p.display()))?;
                }
            }
        }
    }
    // Design folders beyond this study's count that an earlier design study of this folder
    // listed: stale, removed when this study has finished.
    let mut stale: Vec<String> = listed.iter().filter(|f| is_design_name(f) && !own.contains(f)).cloned().collect();
    stale.retain(|f| out.join(f).is_dir());
    stale.sort();
    let mut in_progress = listed.clone();
    in_progress.extend(own.iter().filter(|f| !listed.contains(f)).cloned());
    crate::output::write_manifest(out, "study --vary", &in_progress)?;
    Ok(Top { listed, stale })
}

/// The end of a design study with --out: removes the stale design folders and the files of the
/// earlier run that this one did not write again (only files and folders an earlier design study
/// listed; inside a stale design folder only the files its own manifest lists and its log), says
/// what it removed, and writes the manifest of this run's `files`.
fn finish_top(out: &Path, top: &Top, files: &[String], args: &Args) -> CliResult {
    let mut removed = Vec::new();
    let mut kept = Vec::new();
    for name in &top.stale {
        let dir = out.join(name);
        let mut ours = crate::output::listed_files(&dir)?;
        ours.extend([LOG_NAME.to_string(), crate::output::MANIFEST.to_string()]);
        for f in ours {
            let p = dir.join(&f);
            if std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_file()) {
                std::fs::remove_file(&p).map_err(|e| format!("cannot remove {}: {e}", p.display()))?;
            }
        }
        if std::fs::remove_dir(&dir).is_ok() { removed.push(name.clone()) } else { kept.push(name.clone()) }
    }
    for f in top.listed.iter().filter(|f| !files.contains(f) && !is_design_name(f)) {
        let p = out.join(f);
        if std::fs::symlink_metadata(&p).is_ok_and(|m| m.is_file()) {
            let _ = std::fs::remove_file(&p);
        }
    }
    let mut listed = files.to_vec();
    listed.extend(kept.iter().cloned());
    crate::output::write_manifest(out, "study --vary", &listed)?;
    if !args.quiet && !args.json && (!removed.is_empty() || !kept.is_empty()) {
        crate::errln!(
            "{}: removed {} stale design folder(s) of an earlier design study with more designs ({}){}",
            out.display(),
            removed.len(),
            removed.join(", "),
            if kept.is_empty() {
                String::new()
            } else {
                format!("; kept {} that hold other files (their study files removed)", kept.join(", "))
            }
        );
    }
    Ok(())
}

pub use stiction_engine::design::section;

/// Runs a design study: the study arguments with at least one --vary, or the scenario's `design`
/// section (`section`); flags override the section, and the program says so.
pub fn run(args: Args, config: StudyConfig, section: Option<DesignSpec>) -> CliResult {
    let say = |what: &str| {
        if !args.quiet && !args.json {
            crate::errln!("{what}");
        }
    };
    let req = DesignRequest {
        scenario: &args.scenario,
        sets: &args.sets,
        vary: &args.vary,
        design_points: args.design_points,
        rank_by: args.rank_by.map(RankBy::from),
        seed: args.seed,
    };
    let design_plan = plan(&req, section.as_ref(), &config, &say)?;
    let DesignPlan { varies, points, rank_by } = &design_plan;
    let rank_by = *rank_by;
    // The --out folder's rule, checked before any work (as every command's): files no stiction
    // run listed are refused unless --force.
    if let Some(out) = &args.out {
        let own: Vec<String> = (0..points.len()).map(design_name).collect();
        let own: Vec<&str> = own.iter().map(String::as_str).collect();
        crate::output::check_foreign(out, &own, args.force).map_err(|e| format!("--out: {e}"))?;
    }
    let pool = stiction_engine::design::thread_pool(args.threads, &crate::cmd::study_common::flag)?;
    // Every design is prepared (and so checked) before any runs: a value that makes one design
    // invalid stops the study at once, naming the design.
    let studies = prepare_designs(&args.scenario, &args.sets, varies, points, &config)?;
    // The folder's and the design folders' rules (and the manifest of the run in progress).
    let top = match &args.out {
        Some(out) => Some(prepare_top(out, varies, points.len(), &args)?),
        None => None,
    };
    let temporary = args.out.is_none();
    let root = match &args.out {
        Some(d) => d.clone(),
        None => std::env::temp_dir().join(format!("stiction-design-{}", std::process::id())),
    };
    if temporary {
        let _ = std::fs::remove_dir_all(&root);
    }
    ensure_dir(&root)?;
    let per = config.shard_len();
    let progress = Progress::new(per * points.len(), 0, args.quiet || args.json);
    crate::output::stop_cleanly();
    let hooks = StudyFolder { fig: &args.fig, manifest: true };
    let kept: Option<&dyn stiction_engine::study_folder::FolderHooks> = if temporary { None } else { Some(&hooks) };
    let ran = run_designs(
        &design_plan,
        &studies,
        &root,
        args.resume,
        kept,
        &pool,
        &|n| progress.update(n),
        &crate::output::INTERRUPT,
    );
    let result: Result<Vec<DesignRow>, Box<dyn std::error::Error>> = match ran {
        Ok(DesignsOutcome::Finished(rows)) => Ok(rows),
        Ok(DesignsOutcome::Interrupted { logged, dir }) => {
            Err(Box::new(crate::cmd::study_common::interrupted(logged, per * points.len(), &dir, temporary)))
        }
        Err(e) => Err(e),
    };
    progress.finish(if result.is_ok() { per * points.len() } else { 0 });
    if temporary {
        let _ = std::fs::remove_dir_all(&root);
    }
    let rows = result?;
    let ranking = rank_by.rank(&rows);
    if let (Some(out), Some(top)) = (&args.out, &top) {
        let report = DesignReport {
            scenario: args.scenario.display().to_string(),
            varied: varies,
            rank_by,
            ranking: ranking.clone(),
            designs: &rows,
        };
        let mut files = write_tables(out, &report)?;
        for (k, v) in varies.iter().enumerate() {
            let chart = args.fig.apply(design_chart(varies, &rows, k, rank_by))?;
            files.extend(crate::output::write_chart_files(out, &chart_stem(v), &chart)?);
        }
        files.extend((0..points.len()).map(design_name));
        finish_top(out, top, &files, &args)?;
    }
    if args.json {
        return print_json(&DesignReport {
            scenario: args.scenario.display().to_string(),
            varied: varies,
            rank_by,
            ranking,
            designs: &rows,
        });
    }
    report(&args, varies, &rows, &ranking, rank_by, &config);
    Ok(())
}

fn criterion_name(r: RankBy) -> &'static str {
    match r {
        RankBy::Narrowest => "width of the 5-95 % interval of mu_e,a",
        RankBy::LeastBias => "median bias of mu_e,a against each device's own s / p_mean",
        RankBy::MostUsable => "fraction of experiments with a usable eq. 10 line",
    }
}

/// The criterion's value and standard error of a row, as drawn (not negated).
fn criterion(r: &DesignRow, by: RankBy) -> Option<(f64, Option<f64>)> {
    match by {
        RankBy::Narrowest => r.mu_interval_width.map(|w| (w, r.mu_interval_width_se)),
        RankBy::LeastBias => r.mu_bias.map(|b| (b, r.mu_bias_se)),
        RankBy::MostUsable => Some((r.usable_fraction, Some(r.usable_fraction_se).filter(|s| *s > 0.0))),
    }
}

fn report(args: &Args, varies: &[Vary], rows: &[DesignRow], ranking: &[usize], by: RankBy, config: &StudyConfig) {
    crate::outln!(
        "Design study of {}: {} designs x {} samples{} (seed {}, the same draws in every design)",
        args.scenario.display(),
        rows.len(),
        config.samples,
        if config.shard_count > 1 {
            format!(", shard {}/{}", config.shard_index, config.shard_count)
        } else {
            String::new()
        },
        config.seed
    );
    crate::outln!("  ranked by the {} (best first; digits as the standard errors allow):", criterion_name(by));
    let mut head: Vec<String> = vec!["rank".into(), "design".into()];
    head.extend(varies.iter().map(|v| v.path.clone()));
    head.extend(
        [
            "usable",
            "mu_e,a median [95 % CI]",
            "5-95 % width",
            "mu_e,a lab 95 % CI",
            "F_a0 median (uN)",
            "F_a0 lab 95 % CI (uN)",
            "s/p_mean",
            "bias",
        ]
        .map(String::from),
    );
    let mut t = crate::output::TextTable::new(&head);
    let dash = || "-".to_string();
    for (rank, &d) in ranking.iter().enumerate() {
        let r = &rows[d];
        let mut cells = vec![(rank + 1).to_string(), d.to_string()];
        cells.extend(varies.iter().map(|v| r.values.get(&v.path).cloned().unwrap_or_default()));
        let f_se = Some(r.usable_fraction_se).filter(|s| *s > 0.0);
        cells.push(format!("{} of {} ({})", r.with_fit, r.samples, digits(r.usable_fraction, f_se)));
        let mu = r.mu_apparent.as_ref();
        let med_se = mu.and_then(|s| s.median_ci).map(|[a, b]| (b - a) / 3.92);
        cells.push(mu.map_or_else(dash, |s| match s.median_ci {
            Some([a, b]) => format!("{} [{}, {}]", digits(s.median, med_se), digits(a, med_se), digits(b, med_se)),
            None => digits(s.median, None),
        }));
        // Without an interval for p05 and p95 (too few samples) the width has no standard error:
        // two significant digits, marked as rough.
        cells.push(r.mu_interval_width.map_or_else(dash, |w| match r.mu_interval_width_se {
            Some(se) => digits(w, Some(se)),
            None => format!("~{}", digits(w, Some(10f64.powf(w.abs().log10().floor() - 1.0)))),
        }));
        // The median width of a lab interval, to the digit its order-statistic interval allows.
        let median = |s: Option<&Spread>, scale: f64| {
            s.map(|s| digits(s.median * scale, s.median_ci.map(|[a, b]| (b - a) / 3.92 * scale)))
        };
        let pair = |a: Option<String>, b: Option<String>| match (a, b) {
            (None, None) => dash(),
            (a, b) => format!("{} / {}", a.unwrap_or_else(dash), b.unwrap_or_else(dash)),
        };
        let li = &r.lab_intervals;
        cells.push(pair(
            median(li.mu_ci95_width.as_ref(), 1.0),
            median(li.mu_ci95_width_with_calibration.as_ref(), 1.0),
        ));
        cells.push(r.apparent_adhesion_force_n.as_ref().map_or_else(dash, |s| {
            let se = s.median_ci.map(|[a, b]| (b - a) / 3.92 * 1e6);
            digits(s.median * 1e6, se)
        }));
        cells.push(pair(
            median(li.fa0_ci95_width_n.as_ref(), 1e6),
            median(li.fa0_ci95_width_with_calibration_n.as_ref(), 1e6),
        ));
        cells.push(median(r.interface_mu.as_ref(), 1.0).unwrap_or_else(dash));
        cells.push(r.mu_bias.map_or_else(dash, |b| digits(b, r.mu_bias_se)));
        t.row(cells);
    }
    t.print("    ");
    let without: Vec<String> = rows
        .iter()
        .filter(|r| !r.reasons.is_empty())
        .map(|r| {
            let why: Vec<String> = r.reasons.iter().map(|(k, n)| format!("{n} {k}")).collect();
            format!("design {}: {}", r.design, why.join(", "))
        })
        .collect();
    if !without.is_empty() {
        crate::outln!("  experiments without a usable line, by reason (see each design's samples.csv):");
        for w in without {
            crate::outln!("    {w}");
        }
    }
    crate::outln!(
        "  lab 95 % CI: median width of the interval each experiment's own eq. 10 fit gives, from the regression \
         alone / with the calibration uncertainty ({} draws); s/p_mean and bias: median over the experiments of \
         each device's own interface coefficient and of mu_e,a minus it",
        rows.first().map_or(0, |r| r.lab_intervals.calibration_draws)
    );
}

/// The criterion against varied parameter `k`, one series per combination of the other varied
/// values, with 95 % error bars (1.96 standard errors). Numeric values (with units, as `--set`
/// takes them) go on a numeric axis in SI; others at positions 1, 2, ... with their text as ticks.
fn design_chart(varies: &[Vary], rows: &[DesignRow], k: usize, by: RankBy) -> Chart {
    let v = &varies[k];
    let numeric: Option<Vec<f64>> =
        v.values.iter().map(|x| stiction_units::parse_any(x.trim()).ok().map(|q| q.0)).collect();
    let x_of = |val: &str| -> f64 {
        let pos = v.values.iter().position(|x| x == val).unwrap_or(0);
        match &numeric {
            Some(n) => n[pos],
            None => pos as f64 + 1.0,
        }
    };
    let others: Vec<&Vary> = varies.iter().enumerate().filter(|(j, _)| *j != k).map(|(_, w)| w).collect();
    let mut groups: Vec<(String, Vec<&DesignRow>)> = Vec::new();
    for r in rows {
        let label = others
            .iter()
            .map(|w| format!("{} = {}", w.path, r.values.get(&w.path).map_or("", String::as_str)))
            .collect::<Vec<_>>()
            .join(", ");
        match groups.iter_mut().find(|g| g.0 == label) {
            Some(g) => g.1.push(r),
            None => groups.push((label, vec![r])),
        }
    }
    let (y_label, y_key) = match by {
        RankBy::Narrowest => ("width of the 5-95 % interval of μ_e,a", "mu_interval_width"),
        RankBy::LeastBias => ("median μ_e,a − s / p_mean (bias)", "mu_bias"),
        RankBy::MostUsable => ("fraction of experiments with a usable line", "usable_fraction"),
    };
    let unit = match &numeric {
        Some(_) => stiction_units::parse_any(v.values[0].trim()).map(|q| unit_name(q.1)).unwrap_or_default(),
        None => String::new(),
    };
    let short = match by {
        RankBy::Narrowest => "5-95 % width of μ_e,a",
        RankBy::LeastBias => "bias of μ_e,a against s / p_mean",
        RankBy::MostUsable => "usable experiments",
    };
    let mut chart = Chart::new(
        format!("Design study: {short} ({} designs)", rows.len()),
        if unit.is_empty() { v.path.clone() } else { format!("{} ({unit})", v.path) },
        y_label,
    )
    .keys(stiction_units::key_with_unit(&v.path.replace('.', "_"), &unit), y_key);
    // One marker shape per series, and the series drawn side by side, 1.5 % of the plot's width
    // apart (a dodge: the CSV keeps the true x), so that designs of nearly the same value (e.g.
    // two clamp ranges that start below the contact voltage) do not hide under each other.
    const SHAPES: [Marker; 5] =
        [Marker::Diamond, Marker::Circle, Marker::Square, Marker::Triangle, Marker::TriangleDown];
    let n_groups = groups.len();
    for (g, (label, members)) in groups.into_iter().enumerate() {
        let dodge = 0.015 * (g as f64 - (n_groups as f64 - 1.0) / 2.0);
        let (mut pts, mut err) = (Vec::new(), Vec::new());
        for r in members {
            if let Some((y, se)) = criterion(r, by) {
                pts.push((x_of(&r.values[&v.path]), y));
                err.push(1.96 * se.unwrap_or(0.0));
            }
        }
        let name = if label.is_empty() { "designs (95 % intervals)".to_string() } else { label };
        let series = Series::markers(name, pts).with_y_err(err);
        // (A single series keeps the default marker, centred.)
        let series = if n_groups > 1 { series.with_marker(SHAPES[g % SHAPES.len()]).with_dodge(dodge) } else { series };
        chart.series.push(series);
    }
    // Widths and fractions from 0, with headroom above the points for the legend.
    if by != RankBy::LeastBias {
        let top = chart
            .series
            .iter()
            .flat_map(|s| s.points.iter().zip(s.y_err.iter().flatten()).map(|(p, e)| p.1 + e))
            .fold(0.0f64, f64::max);
        if top > 0.0 {
            chart.y_range = Some((0.0, 1.5 * top));
        }
    }
    if numeric.is_none() {
        chart.x_ticks = Some(v.values.iter().enumerate().map(|(i, x)| (i as f64 + 1.0, x.clone())).collect());
        chart.x_range = Some((0.5, v.values.len() as f64 + 0.5));
    }
    chart.legend = stiction_plot::LegendPosition::UpperRight;
    chart
}

/// The SI unit name of a parsed quantity's dimension ("" for a pure number).
fn unit_name(dim: stiction_units::DimensionVector) -> String {
    use stiction_units::Dimension as D;
    [D::Length, D::Force, D::Pressure, D::Stiffness, D::Voltage, D::ForcePerVoltageSquared, D::Area]
        .iter()
        .find(|d| d.vector() == dim)
        .map_or(String::new(), |d| d.si_unit().to_string())
}
