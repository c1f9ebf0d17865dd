//! `stiction fit` for a test structure built from parts (a scenario with a `structure` section):
//! measured thresholds (the file of [`stiction_meter::structure_measured`]) turned into forces by
//! the structure's parts, and eq. 10 fitted to them.
//!
//! * **Forces.** `L = a_n V_n^2 - F_0` (comb: `a_n = alpha N eps0 t / g`, `F_0 = k_x x_c`; plate:
//!   `a_n = eps0 A / (2 (g_c + sum t_i/eps_r,i)^2)`, `F_0 = k_z g0`) or the file's load;
//!   `F_f = a_t V_t^2` (tangential comb), `k x` (released spring) or the file's tangential load.
//! * **Eq. 10.** `F_f = mu_e,a (F_a0 + L)` by ordinary least squares in (L, F_f), determined only
//!   where [`stiction_meter::fit::eq10`] says the data determine it (at least three distinct loads,
//!   two distinct frictions, a slope above zero at 95 % one-sided); otherwise mu_e,a and F_a0 are
//!   null with the reason. The line is unweighted: a release threshold is known to one displacement
//!   step, an error of the same size at every load, and a comb's force error grows only as the
//!   voltage does.
//! * **Regression intervals.** `t_{n-2}` on mu_e,a; Fieller's interval of `intercept / slope` for
//!   F_a0 (null with the reason when the slope is not significantly positive).
//! * **Calibration.** Every uncertain quantity under `structure` (a comb's fringing factor, a
//!   spring's stiffness or its resonance, a dielectric's permittivity ...) is drawn (the rules of
//!   `stiction study`, ChaCha8 stream 0 of the seed), the parts rebuilt, the same rows reduced with
//!   the drawn parts and the line refitted; each draw also draws the regression's slope and
//!   intercept from their joint normal distribution. `ci95_with_calibration` is the 2.5-97.5
//!   percentile range, `sd_calibration` the robust SD of the calibration-only draws.
//! * **Release resolution.** A release threshold lies in `[k x, k (x + dx))` with `dx` the
//!   scenario's `displacement_step`; the lab reports `k x`, so F_a0 may lie up to `k dx / mu_e,a`
//!   below the contact's (said in `resolution_note`).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use serde::Serialize;
use serde_json::Value;
use stiction_meter::fit::LineFit;
use stiction_meter::measured::Rejected;
use stiction_meter::structure::{LabCoefficient, StructureDevice, StructureReport, TangentialPart, lab_coefficient};
use stiction_meter::structure_measured::{
    ThresholdData, ThresholdPoint, ThresholdRow, check_columns, select_thresholds,
};
use stiction_scenario::Scenario;
use stiction_scenario::structure::{ProtocolSpec, StructureSpec};

use crate::eq10::Estimate;
use crate::error::FitError;
use crate::stats::{fieller, fit_line, percentile, robust_sd, t975};

/// The report of `stiction fit` for a structure (the `--json` contract).
#[derive(Debug, Clone, Serialize)]
pub struct StructureFitReport {
    /// The data file.
    pub data: String,
    /// The structure's parts as the reduction uses them (nominal factors, spring force, stiffness).
    pub structure: StructureReport,
    /// The file's normal column.
    pub normal_column: &'static str,
    /// The file's tangential column.
    pub tangential_column: &'static str,
    /// The rows used, with the load and friction their parts imply.
    pub points: Vec<ThresholdPoint>,
    /// Rows used.
    pub rows_used: usize,
    /// Rows left out, with line and reason.
    pub rows_rejected: Vec<Rejected>,
    /// Apparent friction coefficient mu_e,a (eq. 10).
    pub mu_apparent: Estimate,
    /// Apparent zero-load adhesion force F_a0 (eq. 10), N.
    pub apparent_adhesion_force_n: Estimate,
    /// The least-squares line in (L, F_f) behind them (null with the reason in `fit_note`).
    pub fit: Option<LineFit>,
    /// Why eq. 10 is not determined by these data, when it is not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fit_note: Option<String>,
    /// The number the laboratory reports by the scenario's `structure.lab_reduction`, on the
    /// measured points.
    pub lab_coefficient: LabCoefficient,
    /// The calibration Monte Carlo.
    pub calibration: StructureCalibration,
    /// The release protocol's resolution (null for the other protocols, reason beside).
    pub resolution_note: Option<String>,
    /// Why there is no resolution note.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resolution_note_reason: Option<&'static str>,
    /// How the intervals are made, in words.
    pub interval_method: &'static str,
}

/// The calibration Monte Carlo of a structure fit.
#[derive(Debug, Clone, Serialize)]
pub struct StructureCalibration {
    /// Draws.
    pub draws: usize,
    /// Seed (ChaCha8, stream 0).
    pub seed: u64,
    /// The uncertain quantities under `structure` that were drawn: (JSON path, SI unit).
    pub sources: Vec<(String, String)>,
    /// Draws whose parts could not be built or whose line had no positive slope (left out).
    pub failed_draws: usize,
    /// Why there was no Monte Carlo, when there was none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// How the intervals of a structure fit are made.
pub const STRUCTURE_INTERVAL_METHOD: &str = "eq. 10 by ordinary least squares in (L, F_f) with the forces the \
structure's parts imply; `ci95`: t with n - 2 degrees of freedom on mu_e,a, Fieller's interval of intercept / slope \
on F_a0 (the regression alone, the parts' nominal values taken as exact); `ci95_with_calibration`: every uncertain \
quantity under `structure` drawn from its stated distribution, the parts rebuilt, the same rows reduced and the line \
refitted, with the slope and intercept drawn from their joint normal distribution in each draw (2.5-97.5 \
percentiles)";

/// The structure's parts from the scenario, or an error naming what is missing.
pub fn device_of(scenario: &Scenario) -> Result<StructureDevice, FitError> {
    let spec =
        scenario.structure.as_ref().ok_or_else(|| FitError::Setting("the scenario has no `structure`".into()))?;
    Ok(StructureDevice::from_spec(spec)?)
}

/// Eq. 10 of (L, F_f) points with its regression intervals: (mu_e,a, F_a0, line, note).
fn regression(points: &[(f64, f64)]) -> (Estimate, Estimate, Option<LineFit>, Option<String>) {
    let empty = |note: Option<String>| Estimate {
        value: None,
        value_note: note,
        stderr: None,
        ci95: None,
        ci95_note: None,
        ci95_with_calibration: None,
        ci95_with_calibration_note: None,
        sd_calibration: None,
    };
    let eq10 = stiction_meter::fit::eq10(points);
    let (Some(line), Some(mu), Some(fa0)) = (eq10.line, eq10.mu_apparent, eq10.apparent_adhesion_force_n) else {
        return (empty(eq10.note.clone()), empty(eq10.note.clone()), None, eq10.note);
    };
    let Some(l) = fit_line(points) else {
        return (empty(eq10.note.clone()), empty(eq10.note.clone()), None, eq10.note);
    };
    let t = t975(l.dof as f64);
    let mu_ci = t.map(|t| [mu - t * line.slope_se, mu + t * line.slope_se]);
    let fa0_ci = t.and_then(|t| fieller(l.intercept, l.slope, l.var_intercept, l.var_slope, l.cov, t));
    // Delta method: Var(a/b) = (Var a - 2 (a/b) Cov + (a/b)^2 Var b) / b^2.
    let r = l.intercept / l.slope;
    let fa0_se = ((l.var_intercept - 2.0 * r * l.cov + r * r * l.var_slope) / (l.slope * l.slope)).max(0.0).sqrt();
    let mu_e = Estimate {
        value: Some(mu),
        value_note: None,
        stderr: Some(line.slope_se),
        ci95: mu_ci,
        ci95_note: mu_ci.is_none().then(|| "fewer than three points: no t quantile".to_string()),
        ci95_with_calibration: None,
        ci95_with_calibration_note: None,
        sd_calibration: None,
    };
    let fa0_e = Estimate {
        value: Some(fa0),
        value_note: None,
        stderr: fa0_se.is_finite().then_some(fa0_se),
        ci95: fa0_ci,
        ci95_note: fa0_ci.is_none().then(|| {
            "Fieller's interval is unbounded: the slope is not significantly above zero at 95 % two-sided".to_string()
        }),
        ci95_with_calibration: None,
        ci95_with_calibration_note: None,
        sd_calibration: None,
    };
    (mu_e, fa0_e, Some(line), None)
}

/// The apparent area of the scenario's surface, m^2 (for the parts' report).
fn apparent_area_m2(scenario: &Scenario) -> f64 {
    scenario.surface.as_ref().map_or(0.0, |s| s.apparent_length * s.apparent_width)
}

/// Fits eq. 10 to a structure's measured thresholds (`json`: the scenario's JSON tree, for the
/// uncertain quantities of its parts); the counts are checked by [`crate::analyse_structure`].
pub fn analyse(
    data: &ThresholdData,
    scenario: &Scenario,
    json: &Value,
    draws: usize,
    seed: u64,
) -> Result<StructureFitReport, FitError> {
    let device = device_of(scenario)?;
    check_columns(data, &device).map_err(FitError::Setting)?;
    let (points, rows_rejected) = select_thresholds(data, &device);
    if points.len() < 3 {
        let first: Vec<String> =
            rows_rejected.iter().take(5).map(|r| format!("line {}: {}", r.line, r.reason)).collect();
        return Err(FitError::TooFewRows(format!(
            "{}: {} usable row(s) of {}; a fit needs at least three rows with L > 0 and a friction reading{}",
            data.source,
            points.len(),
            data.rows.len(),
            if first.is_empty() { String::new() } else { format!(" (rejected: {})", first.join("; ")) }
        )));
    }
    let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p.load_n, p.friction_n)).collect();
    let spec =
        scenario.structure.as_ref().ok_or_else(|| FitError::Setting("the scenario has no `structure`".into()))?;
    let lab = lab_coefficient(&spec.lab_reduction, &pairs, &stiction_meter::fit::eq10(&pairs));
    let StructureEq10 { mu_apparent: mu, apparent_adhesion_force_n: fa0, fit: line, fit_note, calibration } =
        structure_eq10(&data.rows, &device, json, draws, seed)?;
    let (resolution_note, resolution_note_reason) = match (&spec.protocol, device.tangential) {
        (ProtocolSpec::Release { displacement_step, .. }, TangentialPart::Spring(s))
            if data.tangential_column == "displacement_m" =>
        {
            let step_n = s.stiffness_n_per_m * displacement_step;
            let bound = mu.value.map_or(String::new(), |m| {
                format!(
                    "; F_a0 may lie up to k dx / mu_e,a = {} below the contact's",
                    stiction_units::format_quantity(step_n / m, stiction_units::Dimension::Force)
                )
            });
            (
                Some(format!(
                    "each release threshold lies in [k x, k (x + dx)) with dx = {} (structure.protocol.\
                     displacement_step), k dx = {}; the friction is reported as k x, as the lab reports it{bound}",
                    stiction_units::format_quantity(*displacement_step, stiction_units::Dimension::Length),
                    stiction_units::format_quantity(step_n, stiction_units::Dimension::Force),
                )),
                None,
            )
        }
        _ => (None, Some("not a release protocol read as displacements: the readings are not quantised by a step")),
    };
    Ok(StructureFitReport {
        data: data.source.clone(),
        structure: device.report(apparent_area_m2(scenario)),
        normal_column: data.normal_column,
        tangential_column: data.tangential_column,
        rows_used: points.len(),
        points,
        rows_rejected,
        mu_apparent: mu,
        apparent_adhesion_force_n: fa0,
        fit: line,
        fit_note,
        lab_coefficient: lab,
        calibration,
        resolution_note,
        resolution_note_reason,
        interval_method: STRUCTURE_INTERVAL_METHOD,
    })
}

/// Eq. 10 of a structure's threshold rows with its intervals.
#[derive(Debug, Clone)]
pub struct StructureEq10 {
    /// mu_e,a with its intervals.
    pub mu_apparent: Estimate,
    /// F_a0 with its intervals, N.
    pub apparent_adhesion_force_n: Estimate,
    /// The line in (L, F_f), when eq. 10 is determined.
    pub fit: Option<LineFit>,
    /// Why eq. 10 is not determined, when it is not.
    pub fit_note: Option<String>,
    /// The calibration Monte Carlo.
    pub calibration: StructureCalibration,
}

/// Eq. 10 of threshold `rows` through the `nominal` parts ([`select_thresholds`]'s rows), with the
/// regression intervals and, over the uncertain quantities of the scenario tree `json`'s
/// `structure`, the calibration intervals (`draws` draws, stream 0 of `seed`).
pub fn structure_eq10(
    rows: &[ThresholdRow],
    nominal: &StructureDevice,
    json: &Value,
    draws: usize,
    seed: u64,
) -> Result<StructureEq10, FitError> {
    let data = ThresholdData { source: String::new(), normal_column: "", tangential_column: "", rows: rows.to_vec() };
    let (points, _) = select_thresholds(&data, nominal);
    let used_lines: std::collections::BTreeSet<u64> = points.iter().map(|p| p.line).collect();
    let used: Vec<&ThresholdRow> = rows.iter().filter(|r| used_lines.contains(&r.line)).collect();
    let pairs: Vec<(f64, f64)> = points.iter().map(|p| (p.load_n, p.friction_n)).collect();
    let (mut mu, mut fa0, fit, fit_note) = regression(&pairs);
    let calibration = calibrate(&used, json, &pairs, fit.is_some(), draws, seed, &mut mu, &mut fa0)?;
    Ok(StructureEq10 { mu_apparent: mu, apparent_adhesion_force_n: fa0, fit, fit_note, calibration })
}

/// The widths of a structure experiment's four 95 % intervals (as [`crate::eq10::interval_widths`]
/// for the paper's meter): the release protocol's (normal voltage, displacement that sticks)
/// readings through the `nominal` parts, [`structure_eq10`] with `draws` calibration draws.
pub fn release_interval_widths(
    readings: &[(f64, f64)],
    nominal: &StructureDevice,
    json: &Value,
    draws: usize,
    seed: u64,
) -> Result<crate::eq10::IntervalWidths, FitError> {
    use stiction_meter::structure_measured::{NormalReading, TangentialReading};
    let rows: Vec<ThresholdRow> = readings
        .iter()
        .enumerate()
        .map(|(i, &(v, x))| ThresholdRow {
            line: i as u64 + 1,
            normal: NormalReading::VoltageV(v),
            tangential: TangentialReading::DisplacementM(x),
        })
        .collect();
    let e = structure_eq10(&rows, nominal, json, draws, seed)?;
    let width = |c: Option<[f64; 2]>| c.map(|[lo, hi]| hi - lo).filter(|w| w.is_finite());
    Ok(crate::eq10::IntervalWidths {
        mu: width(e.mu_apparent.ci95),
        mu_with_calibration: width(e.mu_apparent.ci95_with_calibration),
        fa0_n: width(e.apparent_adhesion_force_n.ci95),
        fa0_with_calibration_n: width(e.apparent_adhesion_force_n.ci95_with_calibration),
    })
}

/// The calibration Monte Carlo over the uncertain quantities under `structure` (see the module
/// docs); fills `ci95_with_calibration` and `sd_calibration` of `mu` and `fa0`.
#[allow(clippy::too_many_arguments)]
fn calibrate(
    rows: &[&ThresholdRow],
    json: &Value,
    pairs: &[(f64, f64)],
    determined: bool,
    draws: usize,
    seed: u64,
    mu: &mut Estimate,
    fa0: &mut Estimate,
) -> Result<StructureCalibration, FitError> {
    let subtree = json.get("structure").cloned().unwrap_or(Value::Null);
    let wrapped = serde_json::json!({ "structure": subtree });
    let sources = stiction_study::uncertain_parameters(&wrapped).map_err(|e| FitError::Setting(e.to_string()))?;
    let mut run = StructureCalibration { draws, seed, sources: sources.clone(), failed_draws: 0, note: None };
    let no_mc = |why: String, mu: &mut Estimate, fa0: &mut Estimate| {
        for e in [mu, fa0] {
            e.ci95_with_calibration_note = Some(why.clone());
        }
        why
    };
    if !determined {
        run.note = Some(no_mc("eq. 10 is not determined by these data: no calibration Monte Carlo".into(), mu, fa0));
        return Ok(run);
    }
    if sources.is_empty() {
        run.note = Some(no_mc(
            "no quantity under `structure` is given with an uncertainty: the parts are taken as exact and `ci95` is \
             the whole interval"
                .into(),
            mu,
            fa0,
        ));
        return Ok(run);
    }
    let Some(line) = fit_line(pairs) else {
        run.note = Some(no_mc("no line through the rows".into(), mu, fa0));
        return Ok(run);
    };
    let (sb, cz, rest) = {
        let sb = line.var_slope.max(0.0).sqrt();
        if sb > 0.0 {
            (sb, line.cov / sb, (line.var_intercept - line.cov * line.cov / line.var_slope).max(0.0).sqrt())
        } else {
            (0.0, 0.0, line.var_intercept.max(0.0).sqrt())
        }
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(0);
    let (mut mus, mut fas, mut mus_cal, mut fas_cal) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for _ in 0..draws {
        let mut tree = wrapped.clone();
        stiction_study::sample_tree(&mut tree, &mut rng).map_err(|e| FitError::Setting(e.to_string()))?;
        let (z1, z2): (f64, f64) = (StandardNormal.sample(&mut rng), StandardNormal.sample(&mut rng));
        let drawn = serde_json::from_value::<StructureSpec>(tree["structure"].take())
            .ok()
            .and_then(|spec| StructureDevice::from_spec(&spec).ok());
        let Some(device) = drawn else {
            run.failed_draws += 1;
            continue;
        };
        // The drawn parts reduce every row the nominal parts used (they slipped, whatever the true
        // parts); a row the drawn parts put below contact still counts with its (negative) load.
        let pts: Vec<(f64, f64)> = rows.iter().filter_map(|r| load_friction(r, &device)).collect();
        let Some(l) = fit_line(&pts).filter(|l| l.slope > 0.0) else {
            run.failed_draws += 1;
            continue;
        };
        let (b, a) = (l.slope, l.intercept);
        mus_cal.push(b);
        fas_cal.push(a / b);
        let (bj, aj) = (b + sb * z1, a + cz * z1 + rest * z2);
        if bj > 0.0 {
            mus.push(bj);
            fas.push(aj / bj);
        }
    }
    let ci = |v: &mut Vec<f64>| -> Option<[f64; 2]> {
        v.retain(|x| x.is_finite());
        v.sort_by(f64::total_cmp);
        Some([percentile(v, 0.025)?, percentile(v, 0.975)?])
    };
    mu.ci95_with_calibration = ci(&mut mus);
    fa0.ci95_with_calibration = ci(&mut fas);
    mu.sd_calibration = robust_sd(&mus_cal);
    fa0.sd_calibration = robust_sd(&fas_cal);
    for e in [mu, fa0] {
        if e.ci95_with_calibration.is_none() {
            e.ci95_with_calibration_note = Some(format!("none of the {draws} draws gave a line with a positive slope"));
        }
    }
    Ok(run)
}

/// The (L, F_f) of one row through `device`'s parts, without the side pull-in and contact tests of
/// [`select_thresholds`] (a drawn device reduces the rows the nominal one used).
fn load_friction(r: &ThresholdRow, device: &StructureDevice) -> Option<(f64, f64)> {
    use stiction_meter::structure_measured::{NormalReading, TangentialReading};
    let load = match r.normal {
        NormalReading::VoltageV(v) => {
            device.normal.conversion_factor_n_per_v2() * v * v - device.normal.spring_force_n()
        }
        NormalReading::LoadN(l) => l,
    };
    let friction = match (r.tangential, device.tangential) {
        (TangentialReading::VoltageV(v), TangentialPart::Comb(c)) => c.conversion_factor_n_per_v2() * v * v,
        (TangentialReading::DisplacementM(x), TangentialPart::Spring(s)) => s.stiffness_n_per_m * x,
        (TangentialReading::LoadN(f), _) => f,
        _ => return None,
    };
    (load.is_finite() && friction.is_finite()).then_some((load, friction))
}
