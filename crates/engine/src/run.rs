//! `run`: the friction-meter experiment of a scenario (the paper's section 5, Fig. 5).

use std::path::Path;

use serde::Serialize;
use stiction_meter::measured::read_measured_voltages;
use stiction_scenario::Scenario;

// The meter's types that a front end names or prints: the meter that ran, its result, the
// humidity of a humid run, an eq. 10 line, the measured voltages beside the model.
pub use stiction_meter::fit::LineFit;
pub use stiction_meter::measured::Comparison;
pub use stiction_meter::{Humidity, Meter, MeterResult};

use crate::Error;
use crate::scenario_source::ScenarioSource;

/// What `run --json` prints: the scenario's name and description, the meter's result (its
/// fields at the top level) and the measured voltages beside the model.
#[derive(Serialize)]
pub struct RunOutput<'a> {
    /// The scenario's name (its path, or "<scenario>").
    pub scenario: String,
    /// The scenario's description.
    pub description: &'a str,
    /// The points and the eq. 10 fit.
    #[serde(flatten)]
    pub result: &'a MeterResult,
    /// The scenario's measured voltages beside the model, when it has a `measured` section.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured: Option<Comparison>,
}

/// A finished friction-meter experiment: the meter (for the figures' curves), its result with the
/// scenario's notes before the fit's warnings, and the measured voltages beside the model.
pub struct Experiment {
    /// The meter that ran (its contact model draws the figures' curves).
    pub meter: Meter,
    /// The points and the eq. 10 fit.
    pub result: MeterResult,
    /// The scenario's measured voltages beside the model, when it has a `measured` section.
    pub measured: Option<Comparison>,
}

/// Runs the friction meter of `scenario` (named `name` in errors; relative paths from `base`):
/// clamp at each clamp voltage, ramp the pull voltage until slip, fit eq. 10. `progress(done,
/// total)` after each clamp voltage.
pub fn experiment(
    scenario: &Scenario,
    name: &str,
    base: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Experiment, Error> {
    // One source of truth: a given spring force that contradicts the clamp spring is refused.
    if let Some(conflict) = scenario.spring_force_conflict() {
        return Err(format!("{name}: {conflict}").into());
    }
    let mut meter = Meter::from_scenario(scenario, base).map_err(|e| format!("{name}: {e}"))?;
    let mut result = meter.run(progress)?;
    // What the scenario's loading and calibrations say comes first, then the fit's own warnings.
    let mut warnings = scenario.notes.clone();
    for (name, spec) in &scenario.actuators {
        if let Some(r) = spec.calibration_rederived() {
            warnings.push(stiction_scenario::Warning::new("calibration_rederived", format!("actuators.{name}: {r}")));
        }
    }
    // A statistical model on a height-map sidewall takes its summit statistics from the whole map
    // (the numbers `stiction topography` prints): say so, with the numbers.
    let model = scenario.contact_or_default().model;
    if matches!(model, stiction_scenario::ContactModel::Gw | stiction_scenario::ContactModel::Discrete)
        && let Ok(surface) = scenario.require_surface()
        && surface.source == stiction_surface::SurfaceSource::HeightMap
    {
        let st = stiction_surface::map_summit_statistics(surface, base).map_err(|e| format!("{name}: {e}"))?;
        warnings.push(stiction_scenario::Warning::new(
            "statistics_from_map",
            format!(
                "the {model} model uses {}: {} summits, eta = {:.3} 1/um^2, sigma_s = {:.3} nm, R = {:.3} um; \
                 not the patch under the shoe",
                st.source,
                st.summit_count,
                st.summit_density_per_m2 * 1e-12,
                st.summit_sd_m * 1e9,
                st.summit_radius_m * 1e6,
            ),
        ));
    }
    warnings.append(&mut result.warnings);
    result.warnings = warnings;
    let measured = match &scenario.measured {
        Some(m) => {
            let data = read_measured_voltages(&base.join(&m.voltages_csv))?;
            Some(meter.compare(&data, result.reduction)?)
        }
        None => None,
    };
    Ok(Experiment { meter, result, measured })
}

/// The JSON object `stiction run SCENARIO --json` prints for `scenario` named `name` (its
/// `scenario` field) with relative paths from `base`.
pub fn run_json(
    scenario: &Scenario,
    name: &str,
    base: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<serde_json::Value, Error> {
    let e = experiment(scenario, name, base, progress)?;
    let output = RunOutput {
        scenario: name.to_string(),
        description: &scenario.description,
        result: &e.result,
        measured: e.measured,
    };
    Ok(crate::json::finite_value(&output)?)
}

/// The request of `run`: a scenario (a file or a tree built in memory, with its overrides).
pub struct RunRequest {
    /// The scenario.
    pub scenario: ScenarioSource,
}

/// [`run_json`] of a request: the scenario parsed with its overrides, named by its source.
pub fn run(req: &RunRequest, progress: &mut dyn FnMut(usize, usize)) -> Result<serde_json::Value, Error> {
    let parsed = req.scenario.parse(&[])?;
    run_json(&parsed, &req.scenario.name(), &req.scenario.base, progress)
}

/// The discrete model's friction curve with N = 3 contacts (eq. 12, DMT), the paper's own
/// analysis, for the scenario's material and model summit radius (relative paths from `base`),
/// from its pull-off up to `max_load_n`: (load in uN, friction in uN). Figures 5 and 7 of `run`.
pub fn discrete_curve_n3(scenario: &Scenario, base: &Path, max_load_n: f64) -> Result<Vec<(f64, f64)>, Error> {
    let material = scenario.require_material()?;
    let radius_m = stiction_meter::model_summit_radius_m(scenario.require_surface()?, base)?;
    crate::discrete::friction_curve_n3(material, radius_m, max_load_n)
}

/// The explicit solver's own curve of a meter that ran: one shoe loaded up from its pull-off to
/// `max_load_n` in 120 steps, (load in uN, friction capacity s A_r in uN). None for the other
/// contact models, or where the path cannot be followed. (A shoe loaded this way may rest on
/// another set of summits than the meter's points, clamped anew at each load: static friction
/// depends on the load path.) Fig. 7 of `run`.
pub fn loading_curve_un(meter: &mut Meter, max_load_n: f64) -> Option<Vec<(f64, f64)>> {
    let stiction_meter::ContactModel::Explicit(solver) = meter.contact_model() else { return None };
    solver.reset();
    let sweep = solver.loading_curve(max_load_n, 120).ok()?;
    Some(sweep.points.iter().map(|e| (e.load_n * 1e6, e.friction_capacity_n * 1e6)).collect())
}
