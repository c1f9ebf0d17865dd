//! `actuator`: one gap-closing actuator array of a scenario: pull-in, release, conversion factor,
//! stiffness; sweeps; validation against measured voltages and switching times.

use std::path::{Path, PathBuf};

use serde::Serialize;
use stiction_actuator::{
    TransientPhysics, compare_transients, read_measurements, read_transients, switch_effects, transient_switch_effects,
    validate,
};
use stiction_scenario::Scenario;

// The actuator's types that a front end names or prints: the array's section and model, a sweep
// and its points, the validation and transient reports and their points.
pub use stiction_actuator::{
    ArraySpec, GapClosingActuator, Sweep, SweepPoint, TransientComparison, TransientEvent, TransientReport,
    ValidationPoint, ValidationReport,
};

use crate::Error;

/// What to compute of an actuator array.
#[derive(Clone, Debug, Default)]
pub struct ActuatorRequest {
    /// The array's name (None: the scenario's only array).
    pub array: Option<String>,
    /// Also the loading and unloading sweep.
    pub sweep: bool,
    /// Top voltage of the sweep, V (default 1.3 x the pull-in voltage).
    pub sweep_max_v: Option<f64>,
    /// Voltage steps of the sweep.
    pub sweep_steps: usize,
    /// Measured pull-in and release voltages (CSV) to validate the model against.
    pub validate: Option<PathBuf>,
    /// Measured switching times (CSV) to compare the transient model with.
    pub transients: Option<PathBuf>,
    /// With `validate` or `transients`: each physics ingredient switched off in turn.
    pub switches: bool,
}

/// A finished `actuator`: the array's name, its specification, its model and the summary.
pub struct ActuatorRun {
    /// The array's name.
    pub name: String,
    /// Its specification as the scenario gives it.
    pub spec: ArraySpec,
    /// The model built from it.
    pub model: GapClosingActuator,
    /// What `--json` prints.
    pub summary: ActuatorSummary,
}

/// What `actuator --json` prints.
#[allow(missing_docs)]
#[derive(Serialize)]
pub struct ActuatorSummary {
    pub array: String,
    pub pull_in_voltage_v: f64,
    pub pull_in_travel_m: f64,
    pub pull_in_limited_by_stop: bool,
    pub release_voltage_v: Option<f64>,
    pub hysteresis_v: Option<f64>,
    /// Why `release_voltage_v`, `hysteresis_v` or `stop_travel_m` is null (absent when none is).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub release_note: Option<String>,
    pub conversion_factor_n_per_v2: f64,
    pub conversion_factor_travel_m: f64,
    pub spring_stiffness_n_per_m: f64,
    pub front_gap_m: f64,
    pub stop_travel_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sweep: Option<Sweep>,
    /// With --validate: `points`, `pull_in_mean_abs_rel_error`, `release_mean_abs_rel_error` at the top level.
    #[serde(flatten)]
    pub validation: Option<stiction_actuator::ValidationReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub switches: Option<Vec<stiction_actuator::SwitchEffect>>,
    /// With --transients: `points`, `pull_in_time_mean_abs_rel_error`, `release_time_mean_abs_rel_error`,
    /// `errors` (per event and finger length) at the top level.
    #[serde(flatten)]
    pub transients: Option<TransientReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transient_switches: Option<Vec<stiction_actuator::TransientSwitchEffect>>,
}

/// Loads a scenario and picks the named array (or the only one).
pub fn pick_array(path: &Path, name: Option<&str>, sets: &[String]) -> Result<(String, ArraySpec), Error> {
    let scenario = Scenario::load(path, sets)?;
    let names: Vec<&String> = scenario.actuators.keys().collect();
    let name = match name {
        Some(n) => n.to_string(),
        None if names.len() == 1 => names[0].clone(),
        None => return Err(format!("{}: choose an array with --array, one of {names:?}", path.display()).into()),
    };
    let spec = scenario
        .actuators
        .get(&name)
        .cloned()
        .ok_or_else(|| format!("{}: no actuator array `{name}`; the scenario has {names:?}", path.display()))?;
    Ok((name, spec))
}

/// Why the summary's release voltage (and hysteresis, and stop) is null, or `None` when it is not:
/// without a stop the plates close the gap at pull-in and no release voltage is defined; with a
/// stop reached before the pull-in travel the plates never snap, so they release where they closed.
fn release_note(has_stop: bool, limited_by_stop: bool) -> Option<String> {
    if !has_stop {
        Some("no stop: the array has no stop travel, so no release voltage or hysteresis is defined".into())
    } else if limited_by_stop {
        Some(
            "the stop is reached before the pull-in travel: the plates do not snap, so there is no separate \
             release voltage and no hysteresis"
                .into(),
        )
    } else {
        None
    }
}

/// Computes the request on the scenario file `scenario` with the overrides `sets`.
pub fn actuator(scenario: &Path, sets: &[String], req: &ActuatorRequest) -> Result<ActuatorRun, Error> {
    let (name, spec) = pick_array(scenario, req.array.as_deref(), sets)?;
    let model = spec.to_model().map_err(|e| format!("actuator `{name}`: {e}"))?;
    let pull_in = model.pull_in()?;
    let release =
        if model.stop_travel_m.is_some() && !pull_in.limited_by_stop { Some(model.release_voltage_v()?) } else { None };
    let mut summary = ActuatorSummary {
        array: name.clone(),
        pull_in_voltage_v: pull_in.voltage_v,
        pull_in_travel_m: pull_in.travel_m,
        pull_in_limited_by_stop: pull_in.limited_by_stop,
        release_voltage_v: release,
        hysteresis_v: release.map(|r| pull_in.voltage_v - r),
        release_note: release_note(model.stop_travel_m.is_some(), pull_in.limited_by_stop),
        conversion_factor_n_per_v2: model.conversion_factor_n_per_v2(spec.operating_travel),
        conversion_factor_travel_m: spec.operating_travel,
        spring_stiffness_n_per_m: model.stiffness_n_per_m(),
        front_gap_m: model.plates.front_gap_m,
        stop_travel_m: model.stop_travel_m,
        sweep: None,
        validation: None,
        switches: None,
        transients: None,
        transient_switches: None,
    };
    if req.sweep {
        let vmax = req.sweep_max_v.unwrap_or(1.3 * pull_in.voltage_v);
        summary.sweep = Some(model.sweep(vmax, req.sweep_steps)?);
    }
    if let Some(csv) = &req.validate {
        let data = read_measurements(csv)?;
        summary.validation = Some(validate(&spec, &data)?);
        if req.switches {
            summary.switches = Some(switch_effects(&spec, &data)?);
        }
    }
    if let Some(csv) = &req.transients {
        let data = read_transients(csv)?;
        let physics = TransientPhysics::default();
        summary.transients =
            Some(compare_transients(&spec, physics, &data).map_err(|e| format!("{}: {e}", csv.display()))?);
        if req.switches {
            summary.transient_switches = Some(transient_switch_effects(&spec, physics, &data)?);
        }
    }
    Ok(ActuatorRun { name, spec, model, summary })
}

/// The transient model evaluated at 24 voltages evenly over the measured range of each finger
/// length and event (at the external force of its measurements, when they share one): the model
/// curves of the figures, not straight segments between the measured voltages.
pub fn model_curves(spec: &ArraySpec, r: &TransientReport) -> Result<TransientReport, Error> {
    let mut grid = Vec::new();
    let mut keys: Vec<(u64, TransientEvent)> =
        r.points.iter().map(|p| (p.finger_length_m.to_bits(), p.event)).collect();
    keys.dedup();
    for (bits, event) in keys {
        let pts: Vec<_> = r.points.iter().filter(|p| p.finger_length_m.to_bits() == bits && p.event == event).collect();
        let force = pts[0].external_force_n;
        let (lo, hi) = pts.iter().fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.voltage_v), a.1.max(p.voltage_v)));
        if pts.iter().any(|p| p.external_force_n != force) || hi <= lo {
            continue;
        }
        grid.extend((0..24).map(|k| stiction_actuator::MeasuredTransient {
            finger_length_m: f64::from_bits(bits),
            event,
            voltage_v: lo + (hi - lo) * f64::from(k) / 23.0,
            external_force_n: force,
            times_s: vec![1e-6],
        }));
    }
    if grid.is_empty() {
        return Ok(TransientReport { points: Vec::new(), ..r.clone() });
    }
    Ok(compare_transients(spec, TransientPhysics::default(), &grid)?)
}

/// The hysteresis of `plot actuator`: the named array (else the only one, else `clamp`) of the
/// scenario file `path` with `sets`, its model and its loading and unloading sweep to 1.3 x the
/// pull-in voltage in 300 steps.
pub fn hysteresis(
    path: &Path,
    array: Option<&str>,
    sets: &[String],
) -> Result<(String, GapClosingActuator, Sweep), Error> {
    let name = array.map(str::to_string);
    let (name, spec) = match pick_array(path, name.as_deref(), sets) {
        Ok(x) => x,
        Err(_) if name.is_none() => pick_array(path, Some("clamp"), sets)?,
        Err(e) => return Err(e),
    };
    let model = spec.to_model()?;
    let vmax = 1.3 * model.pull_in()?.voltage_v;
    let sweep = model.sweep(vmax, 300)?;
    Ok((name, model, sweep))
}

/// The pull-in and release model of a validation report evaluated at 24 finger lengths spread
/// evenly over its measured range (one where all lengths are equal): the model curves of the
/// validation figure, the same model as the report's points, not straight segments between the
/// measured lengths.
pub fn validation_curves(spec: &ArraySpec, r: &ValidationReport) -> Result<ValidationReport, Error> {
    let lo = r.points.iter().map(|p| p.finger_length_m).fold(f64::INFINITY, f64::min);
    let hi = r.points.iter().map(|p| p.finger_length_m).fold(f64::NEG_INFINITY, f64::max);
    let n = if hi > lo { 24 } else { 1 };
    let grid: Vec<stiction_actuator::MeasuredPoint> = (0..n)
        .map(|k| stiction_actuator::MeasuredPoint {
            finger_length_m: if n == 1 { lo } else { lo + (hi - lo) * k as f64 / (n - 1) as f64 },
            pull_in_v: vec![1.0],
            release_v: vec![1.0],
        })
        .collect();
    Ok(validate(spec, &grid)?)
}
