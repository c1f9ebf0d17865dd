//! `contact`: the explicit asperity-by-asperity solver (or the boundary-element model) on a
//! scenario's surface, at a load or over a sweep of loads.

use serde::{Deserialize, Serialize};
use stiction_contact::explicit::{ExplicitSolver, Sweep};
use stiction_contact::single::Branch;
use stiction_meter::{ContactModel, build_contact_model};
use stiction_scenario::{ContactModel as ModelKind, ContactSpec, MaterialSpec};
use stiction_units::Dimension;

use crate::Error;
use crate::check::Names;
use crate::scenario_source::ScenarioSource;

// The explicit solver's types that a front end names or prints: how much of a state to report,
// an equilibrium, an event of a load sweep.
pub use stiction_contact::explicit::{Detail, Equilibrium, SweepEvent};

/// Shoe degrees of freedom.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// Approach and two tilts free.
    Tilt,
    /// Approach only (the GW situation).
    Flat,
    /// Only the `contacts` highest summits carry the shoe (eq. 12).
    Fixed,
}

/// Which solver runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Model {
    /// The explicit asperity-by-asperity solver (summits, tilting rigid shoe).
    #[default]
    Explicit,
    /// The FFT boundary-element solver on the height-map patch under the shoe (needs
    /// `surface.source` = "height_map"; settings from `contact.bem`).
    Bem,
}

/// Equilibrium of a rigid shoe on the scenario's rough surface under a normal load, or over a
/// sweep of loads (each from the previous equilibrium).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactRequest {
    /// The solver.
    #[serde(default)]
    pub model: Model,
    /// One normal load, N, compressive positive (negative = adhesive pull, down to pull-off).
    #[serde(default)]
    pub load_n: Option<f64>,
    /// A sweep of loads, N, in order (instead of `load_n`).
    #[serde(default)]
    pub loads_n: Option<Vec<f64>>,
    /// Shoe degrees of freedom (default: the scenario's, else tilt).
    #[serde(default)]
    pub mode: Option<Mode>,
    /// Number of contacts for mode fixed.
    #[serde(default)]
    pub contacts: Option<usize>,
    /// Also list every summit in contact (interference, load, contact radius, peak pressure).
    #[serde(default)]
    pub summits: bool,
}

impl ContactRequest {
    /// Checks the load against the domain of `load` (a sweep's loads are checked as the solver
    /// meets them), naming the field as `names` calls it; the warnings of a load outside its usual
    /// range come back.
    pub fn validate(&self, names: &Names) -> Result<Vec<stiction_scenario::Warning>, Error> {
        let mut warnings = Vec::new();
        if let Some(l) = self.load_n {
            crate::check::domain(&mut warnings, names, "load_n", "load", l)?;
        }
        Ok(warnings)
    }
}

/// Default of `--max-sweep-steps`: a million equilibria take minutes and their rows about 100 MB.
pub const DEFAULT_MAX_SWEEP_STEPS: usize = 1_000_000;

/// The explicit solver of the scenario `source` with the request's mode and contacts applied: the
/// solver, the scenario's contact settings and its material.
pub fn explicit_solver(
    req: &ContactRequest,
    source: &ScenarioSource,
) -> Result<(Box<ExplicitSolver>, ContactSpec, MaterialSpec), Error> {
    let mut sets = Vec::new();
    sets.push("contact.model=\"explicit\"".into());
    match req.mode {
        Some(Mode::Tilt) => sets.push("contact.mode=\"tilt\"".into()),
        Some(Mode::Flat) => sets.push("contact.mode=\"flat\"".into()),
        Some(Mode::Fixed) => sets.push("contact.mode=\"fixed\"".into()),
        None => {}
    }
    if let Some(n) = req.contacts {
        sets.push(format!("contact.contacts={n}"));
    }
    let scenario = source.parse(&sets)?;
    let name = source.name();
    let material = scenario.require_material().map_err(|e| format!("{name}: {e}"))?.clone();
    let c = scenario.contact_or_default();
    debug_assert_eq!(c.model, ModelKind::Explicit);
    let model = build_contact_model(&scenario, &material, &source.base).map_err(|e| format!("{name}: {e}"))?;
    let ContactModel::Explicit(solver) = model else {
        return Err("the explicit solver could not be built".into());
    };
    Ok((solver, c, material))
}

/// What `contact --json` prints: one equilibrium, a sweep {"points", "events"}, or the
/// boundary-element model's run.
#[derive(Serialize)]
#[serde(untagged)]
pub enum ContactOutput {
    /// The equilibrium at one load.
    Point(Box<Equilibrium>),
    /// A sweep of loads.
    Sweep(Sweep),
    /// The boundary-element model at each load.
    Bem(BemRun),
}

/// A finished `contact`: its output and, for the explicit solver, what a text table says of it.
pub struct ContactRun {
    /// The result.
    pub output: ContactOutput,
    /// The explicit solver's summit count, contact settings and material (None for the BEM).
    pub explicit: Option<(usize, ContactSpec, MaterialSpec)>,
}

/// Runs the request on the scenario `source`; `detail` says how much per-contact detail the
/// solver keeps (the front end's table or JSON needs). `names` names the request's fields in a
/// refusal.
pub fn contact(
    req: &ContactRequest,
    source: &ScenarioSource,
    detail: Detail,
    names: &Names,
) -> Result<ContactRun, Error> {
    if req.model == Model::Bem {
        return Ok(ContactRun { output: ContactOutput::Bem(bem_run(req, source, names)?), explicit: None });
    }
    let (mut solver, c, material) = explicit_solver(req, source)?;
    solver.set_detail(detail);
    let output = if let Some(loads) = &req.loads_n {
        let increasing = loads.last() >= loads.first();
        ContactOutput::Sweep(solver.sweep(loads, if increasing { Branch::Loading } else { Branch::Unloading })?)
    } else {
        let load = req.load_n.ok_or_else(|| format!("give {} or {}", names("load_n"), names("loads_n")))?;
        ContactOutput::Point(Box::new(solver.solve(load)?))
    };
    Ok(ContactRun { output, explicit: Some((solver.len(), c, material)) })
}

/// The result as a JSON value (what `contact --json` prints), every number checked finite:
/// full per-summit detail with `summits`, else the contact indices.
pub fn contact_json(req: &ContactRequest, source: &ScenarioSource, names: &Names) -> Result<serde_json::Value, Error> {
    let detail = if req.summits { Detail::Full } else { Detail::Indices };
    Ok(crate::json::finite_value(&contact(req, source, detail, names)?.output)?)
}

/// One load of the boundary-element model: its state, or why the model found none.
#[allow(missing_docs)]
#[derive(serde::Serialize)]
pub struct BemPoint {
    pub load_n: f64,
    /// The contact state (absent when the model found no state at this load).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub state: Option<BemState>,
    /// Why the model found no state at this load (e.g. a tilting shoe that does not balance);
    /// the sweep goes on from the last state it found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// The contact state of one load of the boundary-element model.
#[allow(missing_docs)]
#[derive(serde::Serialize)]
pub struct BemState {
    pub real_area_m2: f64,
    pub contact_fraction: f64,
    pub patches: usize,
    pub mean_gap_m: f64,
    /// The Dugdale tension over the cohesive zone, N (the contact pressure carries L plus it).
    pub adhesive_load_n: f64,
    pub cohesive_fraction: f64,
    /// s A_r with the material's shear strength, N.
    pub friction_capacity_n: f64,
    pub max_pressure_pa: f64,
    /// The shoe's tilts (dw/dx, dw/dy), rad: written when the shoe tilts (`contact.bem.tilt`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tilt_x_rad: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tilt_y_rad: Option<f64>,
    /// With the hardness cap (`contact.bem.plastic`): the part of the real area at the hardness,
    /// m^2 (within [0, real_area_m2]); absent for an elastic model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_area_m2: Option<f64>,
    pub iterations: usize,
}

/// The boundary-element model at each load.
#[allow(missing_docs)]
#[derive(serde::Serialize)]
pub struct BemRun {
    pub model: &'static str,
    pub grid: stiction_bem::Grid,
    /// The shoe face: a finite patch on the wall ("non_periodic") or one periodic cell.
    pub boundary: stiction_bem::Boundary,
    /// Whether the shoe tilts until the moments balance (`contact.bem.tilt`).
    pub tilt: bool,
    /// The hardness the contact pressure is capped at (`contact.bem.plastic`), Pa; absent: elastic.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hardness_pa: Option<f64>,
    /// Block factors (x, y) from the map's pixels to the grid.
    pub coarsening: (usize, usize),
    pub e_star_pa: f64,
    pub dugdale: Option<stiction_bem::Dugdale>,
    /// Why `dugdale` is null: no adhesion (law "hertz" or no work of adhesion).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dugdale_note: Option<&'static str>,
    pub shear_strength_pa: f64,
    pub points: Vec<BemPoint>,
}

/// The boundary-element model of the scenario `source` at each load of the request (N,
/// compressive, in order; the loading branch).
pub fn bem_run(req: &ContactRequest, source: &ScenarioSource, names: &Names) -> Result<BemRun, Error> {
    if req.mode.is_some() || req.contacts.is_some() || req.summits {
        return Err(format!(
            "{}, {} and {} belong to the explicit solver; {} bem has a flat shoe and reports contact patches",
            names("mode"),
            names("contacts"),
            names("summits"),
            names("model")
        )
        .into());
    }
    let scenario = source.parse(&["contact.model=\"bem\"".into()])?;
    let name = source.name();
    let material = scenario.require_material().map_err(|e| format!("{name}: {e}"))?.clone();
    let mut bem = stiction_meter::build_bem(&scenario, &material, &source.base).map_err(|e| format!("{name}: {e}"))?;
    let loads = match (&req.loads_n, req.load_n) {
        (Some(l), _) => l.clone(),
        (None, Some(l)) => vec![l],
        (None, None) => return Err(format!("give {} or {}", names("load_n"), names("loads_n")).into()),
    };
    if let Some(l) = loads.iter().find(|l| l.is_nan() || **l <= 0.0) {
        return Err(format!(
            "load {}: {} bem follows the loading branch and needs compressive loads > 0",
            stiction_units::format_quantity(*l, Dimension::Force),
            names("model")
        )
        .into());
    }
    let grid = bem.grid();
    let mut points = Vec::with_capacity(loads.len());
    let shoe = bem.shoe();
    for &load in &loads {
        let pose = match bem.solve_full(load) {
            Ok(pose) => pose,
            // A load without a state is null with its reason, as in the meter; the sweep goes on.
            Err(stiction_meter::MeterError::Contact(why)) => {
                points.push(BemPoint { load_n: load, state: None, error: Some(why) });
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        let state = bem.state_of(load, &pose);
        // Patches are at most the grid's points.
        let at = format!("a load of {}", stiction_units::format_quantity(load, Dimension::Force));
        stiction_meter::invariants::check_state_at(&state, grid.area_m2(), grid.len() as f64, &at)?;
        let s = &pose.0;
        points.push(BemPoint {
            load_n: s.load_n(&grid),
            state: Some(BemState {
                real_area_m2: s.contact_area_m2,
                contact_fraction: s.contact_fraction,
                patches: s.patches,
                mean_gap_m: s.mean_gap_m,
                adhesive_load_n: state.adhesive_load_n,
                cohesive_fraction: s.cohesive_fraction,
                friction_capacity_n: s.friction_n(material.shear_strength),
                max_pressure_pa: state.max_pressure_pa,
                tilt_x_rad: shoe.tilting.then_some(state.tilt_x_rad),
                tilt_y_rad: shoe.tilting.then_some(state.tilt_y_rad),
                plastic_area_m2: state.plastic_area_m2,
                iterations: s.iterations,
            }),
            error: None,
        });
    }
    Ok(BemRun {
        model: "bem",
        grid,
        boundary: shoe.boundary,
        tilt: shoe.tilting,
        hardness_pa: shoe.hardness_pa,
        coarsening: bem.coarsening,
        e_star_pa: 0.75 / material.compliance_per_pa(),
        dugdale: bem.law(),
        dugdale_note: bem.law().is_none().then_some("no adhesion: law \"hertz\" or no work of adhesion"),
        shear_strength_pa: material.shear_strength,
        points,
    })
}
