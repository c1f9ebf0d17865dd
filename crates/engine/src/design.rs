//! Design studies (`study --vary`, a scenario's `design` section): one complete Monte Carlo study
//! per design point, ranked. The plan (the varied fields, the points, the ranking) and the
//! designs' studies; the loop over them is the study loop of [`crate::study`].

use std::path::Path;

use stiction_study::design::{self, DesignRow, RankBy, Vary};
use stiction_study::{Study, StudyConfig};

use crate::Error;

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
pub fn section(scenario: &Path, sets: &[String]) -> Result<Option<stiction_scenario::design::DesignSpec>, Error> {
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
    section: Option<&stiction_scenario::design::DesignSpec>,
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
