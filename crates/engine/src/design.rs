//! Design studies (`study --vary`, a scenario's `design` section): one complete Monte Carlo study
//! per design point, ranked. The plan (the varied fields, the points, the ranking) and the
//! designs' studies, and the loop that runs each design's study into its own folder
//! (`design-NNN`, a study folder: [`crate::study_folder`]).

use std::path::{Path, PathBuf};

use stiction_study::design;
use stiction_study::{Study, StudyConfig};

use crate::Error;
use crate::check::Names;
use crate::study_folder::{Folder, FolderHooks, Outcome, ensure_dir, run_study};

// A design study's types that a front end names or prints.
pub use stiction_scenario::design::DesignSpec;
pub use stiction_study::design::{DesignRow, RankBy, Vary, designs_csv};

/// What `study --vary ... --json` prints.
#[derive(serde::Serialize)]
pub struct DesignReport<'a> {
    /// The scenario file.
    pub scenario: String,
    /// The varied fields.
    pub varied: &'a [Vary],
    /// The ranking criterion.
    pub rank_by: RankBy,
    /// Design numbers, best first.
    pub ranking: Vec<usize>,
    /// One row per design.
    pub designs: &'a [DesignRow],
}

/// A design study's request.
pub struct DesignRequest<'a> {
    /// The scenario file.
    pub scenario: &'a Path,
    /// Its overrides.
    pub sets: &'a [String],
    /// The varied fields, "PATH=V1,V2,..." or "PATH=LO..HI" (override the scenario's section).
    pub vary: &'a [String],
    /// With ranges: the number of space-filling design points.
    pub design_points: Option<usize>,
    /// How the designs are ranked (default: the section's criterion, else narrowest).
    pub rank_by: Option<RankBy>,
    /// The study's seed (also of the Latin hypercube).
    pub seed: u64,
}

/// The varied fields, the design points (one value per varied field each) and the ranking.
pub struct DesignPlan {
    /// The varied fields.
    pub varies: Vec<Vary>,
    /// The design points.
    pub points: Vec<Vec<String>>,
    /// The ranking criterion.
    pub rank_by: RankBy,
}

/// The scenario's `design` section (with the `--set`s applied), checked field by field; None
/// when it has none.
pub fn section(scenario: &Path, sets: &[String]) -> Result<Option<DesignSpec>, Error> {
    let value = stiction_scenario::Scenario::load_json(scenario, sets)?;
    if value.get("design").is_none_or(serde_json::Value::is_null) {
        return Ok(None);
    }
    let parsed = stiction_scenario::Scenario::from_value_with_sets(value, scenario, sets)?;
    Ok(parsed.design)
}

/// The plan of a design study: the request's fields override the scenario's `design` section
/// (`say` tells the user so); two designs that would run the same study are refused before
/// anything runs.
pub fn plan(
    req: &DesignRequest,
    section: Option<&DesignSpec>,
    config: &StudyConfig,
    say: &dyn Fn(&str),
) -> Result<DesignPlan, Error> {
    let (mut varies, design_points) = match section {
        Some(sec) if req.vary.is_empty() => {
            let varies: Vec<Vary> = sec
                .varied()
                .map_err(|m| format!("{}: {m}", req.scenario.display()))?
                .into_iter()
                .map(|(path, values, range)| Vary::from_section(&path, values, range.as_deref()))
                .collect::<Result<_, _>>()
                .map_err(|e| format!("{}: {e}", req.scenario.display()))?;
            if req.design_points.is_some() && sec.points.is_some() {
                say("--design-points overrides the scenario's `design.points`");
            }
            (varies, req.design_points.or(sec.points))
        }
        _ => {
            if section.is_some_and(|s| !s.vary.is_empty() || !s.ranges.is_empty()) {
                say(
                    "--vary overrides the scenario's design (`design.vary`, `design.ranges` and `design.points` are not used)",
                );
            }
            (req.vary.iter().map(|v| Vary::parse(v)).collect::<Result<_, _>>()?, req.design_points)
        }
    };
    let criterion = section.and_then(|s| s.criterion);
    if req.rank_by.is_some() && criterion.is_some() {
        say("--rank-by overrides the scenario's `design.criterion`");
    }
    let rank_by: RankBy = match (req.rank_by, criterion) {
        (Some(r), _) => r,
        (None, Some(c)) => match c {
            stiction_scenario::design::DesignCriterion::Narrowest => RankBy::Narrowest,
            stiction_scenario::design::DesignCriterion::LeastBias => RankBy::LeastBias,
            stiction_scenario::design::DesignCriterion::MostUsable => RankBy::MostUsable,
        },
        (None, None) => RankBy::Narrowest,
    };
    let points = design::grid(&mut varies, req.sets, design_points, req.seed, config.vary_surface)?;
    // Two designs that would run the same study (equal once units are read and ignored fields
    // dropped) are refused before anything runs.
    let base = stiction_scenario::Scenario::load_json(req.scenario, req.sets)?;
    design::check_distinct(&base, &varies, &points, config.vary_surface)?;
    drop(base);
    Ok(DesignPlan { varies, points, rank_by })
}

/// Every design's study, prepared (and so checked) before any runs: a value that makes one design
/// invalid stops the study at once, naming the design.
pub fn prepare_designs(
    scenario: &Path,
    sets: &[String],
    varies: &[Vary],
    points: &[Vec<String>],
    config: &StudyConfig,
) -> Result<Vec<Study>, Error> {
    let name = |p: &[String]| design::label(varies, p);
    let mut studies = Vec::with_capacity(points.len());
    for (d, p) in points.iter().enumerate() {
        let sets = design::sets_for(sets, varies, p);
        let study = crate::study::prepare_study(scenario, &sets, config)
            .map_err(|e| format!("design {d} ({}): {e}", name(p)))?;
        studies.push(study);
    }
    Ok(studies)
}

/// The folder of design `d` inside a design study's folder `root`.
pub fn design_folder(root: &Path, d: usize) -> PathBuf {
    root.join(design_name(d))
}

/// The name of design `d`'s folder: `design-NNN`.
pub fn design_name(d: usize) -> String {
    format!("design-{d:03}")
}

/// Whether a name is a design folder's (`design-` and at least three digits).
pub fn is_design_name(n: &str) -> bool {
    n.strip_prefix("design-").is_some_and(|d| d.len() >= 3 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// Whether `dir` is a design study's folder: it holds designs.json or a `design-NNN` folder.
pub fn is_design_study(dir: &Path) -> bool {
    dir.join("designs.json").is_file()
        || std::fs::read_dir(dir).is_ok_and(|mut e| {
            e.any(|e| e.is_ok_and(|e| e.path().is_dir() && is_design_name(&e.file_name().to_string_lossy())))
        })
}

/// The worker pool of a design study's `threads` (default: all cores), 1 to
/// [`stiction_study::MAX_THREADS`]; `names` names the field in a refusal (without the core count
/// a study's refusal gives).
pub fn thread_pool(threads: Option<usize>, names: &Names) -> Result<rayon::ThreadPool, Error> {
    if let Some(t) = threads
        && (t == 0 || t > stiction_study::MAX_THREADS)
    {
        return Err(format!("{} {t}: expected 1 to {}", names("threads"), stiction_study::MAX_THREADS).into());
    }
    crate::study::thread_pool(threads, names)
}

/// How [`run_designs`] ended.
pub enum DesignsOutcome {
    /// Every design's study is complete: one row per design, in design order.
    Finished(Vec<DesignRow>),
    /// Stopped by `interrupt` in the design whose folder is `dir`.
    Interrupted {
        /// Samples in the logs of all designs so far (the designs before `dir`'s complete).
        logged: usize,
        /// The folder of the design that was running.
        dir: PathBuf,
    },
}

/// Runs each design's study, in design order, into its folder `root/design-NNN` (created; a kept
/// study folder with `kept`'s hooks, or without hooks a log that is only summarised, the caller
/// removing `root`), with `resume` finishing logs an earlier run left. `progress(n)`: samples in
/// the logs of all designs so far (design `d` counts from `d` times the shard's length). An
/// `interrupt` stops it with what the logs hold.
#[allow(clippy::too_many_arguments)]
pub fn run_designs(
    plan: &DesignPlan,
    studies: &[Study],
    root: &Path,
    resume: bool,
    kept: Option<&dyn FolderHooks>,
    pool: &rayon::ThreadPool,
    progress: &(dyn Fn(usize) + Sync),
    interrupt: &std::sync::atomic::AtomicBool,
) -> Result<DesignsOutcome, Error> {
    let mut rows = Vec::with_capacity(plan.points.len());
    for (d, (p, study)) in plan.points.iter().zip(studies).enumerate() {
        let dir = design_folder(root, d);
        ensure_dir(&dir)?;
        let offset = d * study.config.shard_len();
        let folder = match kept {
            Some(hooks) => Folder::Kept(hooks),
            None => Folder::Temporary(None),
        };
        let opened = |done: usize, _: &Path| progress(offset + done);
        let ran = run_study(study, &dir, resume, folder, pool, &opened, &|n| progress(offset + n), interrupt)?;
        let summary = match ran {
            Outcome::Finished { summary, .. } => *summary,
            Outcome::Interrupted { logged } => return Ok(DesignsOutcome::Interrupted { logged: offset + logged, dir }),
        };
        rows.push(DesignRow::new(d, &plan.varies, p, &summary));
    }
    Ok(DesignsOutcome::Finished(rows))
}

/// Writes a design study's tables into its folder `out`: designs.csv (one line per design) and
/// designs.json (the report, what `study --vary ... --json` prints). Returns their names.
pub fn write_tables(out: &Path, report: &DesignReport) -> Result<Vec<String>, Error> {
    let write = |name: &str, bytes: &[u8]| stiction_units::io::write_atomic(&out.join(name), bytes);
    write("designs.csv", &designs_csv(report.varied, report.designs)?)?;
    write("designs.json", (serde_json::to_string_pretty(report)? + "\n").as_bytes())?;
    Ok(vec!["designs.csv".to_string(), "designs.json".to_string()])
}
