//! stiction-fit: from measured friction-meter voltages to physics, with honest uncertainty and a
//! choice of contact model (`stiction fit`).
//!
//! * [`data`]: the measured-voltage CSV (csv crate; BOM, CRLF, comments, quoting; errors name the
//!   file, line, column and value).
//! * [`eq10`]: eq. 10 as the paper did it, with the regression's and the calibration's
//!   uncertainty kept apart and each source's share of the variance.
//! * [`mle`]: maximum-likelihood fits of the shear strength s (and R, F_spring) per contact model
//!   on V_pull^2, profile-likelihood intervals, chi^2, AIC/BIC; [`models`] says what each model
//!   predicts.
//! * [`synth`]: labelled synthetic data made by the virtual meter (the bundled example, tests).
//!
//! [`analyse`] runs all of it on a data set and a scenario and returns the report behind
//! `stiction fit --json`.

// Comparisons are written `!(x > 0.0)` on purpose: they are true for NaN too, so a NaN is
// rejected by the same test as a non-positive value.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;
use serde_json::Value;
use stiction_scenario::Scenario;
use stiction_units::UncertainInput;

pub mod eq10;
mod error;
pub mod mle;
pub mod models;
pub mod scal;
pub mod stats;
pub mod structure;
pub mod synth;

pub use eq10::{CalibrationSource, Eq10Fit, Eq10Point, Estimate, VarianceShares};
pub use error::FitError;
pub use mle::{Free, ModelFit, Noise, ShearStrength};
pub use models::{ModelContext, ModelKind};
pub use stiction_meter::measured::{
    Dataset, Rejected, Row, VoltageCsvError, parse_measured_voltages, read_measured_voltages, select_rows,
};
pub use stiction_meter::structure_measured::{ThresholdData, parse_thresholds, read_thresholds};
pub use structure::StructureFitReport;

/// Settings of a fit.
#[derive(Debug, Clone)]
pub struct FitOptions {
    /// The models to fit.
    pub models: Vec<ModelKind>,
    /// Free parameters besides s.
    pub free: Free,
    /// Surface realisations of the explicit ensemble.
    pub surfaces: usize,
    /// Calibration Monte Carlo draws.
    pub calibration_draws: usize,
    /// Seed of the calibration Monte Carlo.
    pub seed: u64,
    /// Points of each model curve in the figures.
    pub curve_points: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            models: ModelKind::defaults(),
            free: Free::default(),
            surfaces: 100,
            calibration_draws: 4000,
            seed: 1,
            curve_points: 41,
        }
    }
}

/// Largest number of calibration draws.
pub const MAX_DRAWS: usize = 10_000_000;

/// Largest number of data rows `stiction fit` takes (the work and memory are linear in the rows:
/// about 100 bytes a row).
pub const MAX_FIT_ROWS: usize = 2_000_000;

/// Largest number of device labels in one file (each gets its own eq. 10 line).
pub const MAX_DEVICES: usize = 100_000;

/// Largest number of distinct clamp voltages among the used rows: each contact model is evaluated
/// once per distinct clamp voltage (the explicit ensemble once per voltage and surface), so this
/// bounds the models' work. A real sweep has tens; a file whose recorded clamp voltages all differ
/// (measured, not set, voltages) is refused with the advice to round them to the set points.
pub const MAX_DISTINCT_CLAMP_VOLTAGES: usize = 5_000;

/// A model that could not be fitted.
#[derive(Debug, Clone, Serialize)]
pub struct FailedModel {
    /// Model name.
    pub name: String,
    /// Why.
    pub reason: String,
}

/// Eq. 10 of one device.
#[derive(Debug, Clone, Serialize)]
pub struct DeviceFit {
    /// Device label.
    pub device: String,
    /// Rows of this device with L > 0.
    pub rows_used: usize,
    /// Its eq. 10 fit (None when it has fewer than three usable rows, with the reason).
    pub eq10: Option<Eq10Fit>,
    /// Why there is no fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The report of `stiction fit` (the `--json` contract).
#[derive(Debug, Clone, Serialize)]
pub struct FitReport {
    /// The data file.
    pub data: String,
    /// The nominal reduction (the scenario's device values).
    pub reduction: stiction_meter::Reduction,
    /// Apparent friction coefficient (eq. 10).
    pub mu_apparent: Estimate,
    /// Apparent zero-load adhesion force (eq. 10), N.
    pub apparent_adhesion_force_n: Estimate,
    /// Share of each source in the variance of mu_e,a and F_a0.
    pub variance_shares: VarianceShares,
    /// The whole eq. 10 fit (covariance, calibration Monte Carlo).
    pub eq10: Eq10Fit,
    /// Per device, when the file has several.
    pub devices: Vec<DeviceFit>,
    /// Rows used.
    pub rows_used: usize,
    /// Rows left out, with line and reason.
    pub rows_rejected: Vec<Rejected>,
    /// Where the noise level comes from, in words.
    pub noise: Noise,
    /// The same, as a sentence.
    pub noise_note: String,
    /// How the intervals of s are made, and why.
    pub interval_method: String,
    /// The fitted models, best (lowest AIC among the comparable) first.
    pub models: Vec<ModelFit>,
    /// Models that could not be fitted.
    pub models_failed: Vec<FailedModel>,
    /// Plain sentences on which models the data can and cannot tell apart.
    pub model_selection: Vec<String>,
    /// With a height-map surface: the summit statistics the statistical models (GW, discrete) use,
    /// counted on the map (the numbers `stiction topography` prints), and where they come from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub summit_statistics: Option<stiction_surface::MapSummitStatistics>,
    /// Sentences on the surface the models stand on (which statistics come from a map, which maps
    /// are tiled as periodic cells).
    pub surface_notes: Vec<String>,
}

/// The reduction's uncertain sources from the scenario's JSON tree (`actuators.clamp.conversion_factor`,
/// `actuators.pull.conversion_factor`, `meter.spring_force`), with the device's nominal values.
pub fn calibration_sources(
    json: &Value,
    device: &stiction_meter::Reduction,
) -> Result<[CalibrationSource; 3], FitError> {
    let get = |name: &str, path: &str, nominal: f64| -> Result<CalibrationSource, FitError> {
        let unit = if name == "spring_force" { "N" } else { "N/V^2" };
        let mut v = json;
        for key in path.split('.') {
            v = match v.get(key) {
                Some(x) => x,
                None => {
                    return Ok(CalibrationSource {
                        name: name.into(),
                        path: path.into(),
                        nominal,
                        unit,
                        uncertainty: None,
                    });
                }
            };
        }
        let uncertainty =
            match v {
                Value::Object(_) => Some(serde_json::from_value::<UncertainInput>(v.clone()).map_err(|e| {
                    FitError::Setting(format!("scenario `{path}`: not a valid uncertain parameter ({e})"))
                })?)
                .filter(|u| u.sd.is_some() || u.min.is_some()),
                _ => None,
            };
        Ok(CalibrationSource { name: name.into(), path: path.into(), nominal, unit, uncertainty })
    };
    Ok([
        get("a_clamp", "actuators.clamp.conversion_factor", device.a_clamp_n_per_v2)?,
        get("a_pull", "actuators.pull.conversion_factor", device.a_pull_n_per_v2)?,
        get("spring_force", "meter.spring_force", device.spring_force_n)?,
    ])
}

/// The pooled pull-voltage SD of repeated rows (same device, same clamp voltage), V, and its
/// degrees of freedom; None with fewer than two.
pub fn repeats_sigma(rows: &[&Row]) -> Option<(f64, usize)> {
    let mut groups: BTreeMap<(&str, u64), Vec<f64>> = BTreeMap::new();
    for r in rows {
        groups.entry((r.device.as_str(), r.v_clamp_v.to_bits())).or_default().push(r.v_pull_v);
    }
    let (mut ss, mut dof) = (0.0, 0usize);
    for g in groups.values().filter(|g| g.len() > 1) {
        let m = g.iter().sum::<f64>() / g.len() as f64;
        ss += g.iter().map(|v| (v - m).powi(2)).sum::<f64>();
        dof += g.len() - 1;
    }
    (dof >= 2 && ss > 0.0).then(|| ((ss / dof as f64).sqrt(), dof))
}

fn fit_data(rows: &[&Row]) -> mle::FitData {
    let mut xs: Vec<f64> = rows.iter().map(|r| r.v_clamp_v * r.v_clamp_v).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let row_unique = rows.iter().map(|r| xs.partition_point(|&x| x < r.v_clamp_v * r.v_clamp_v)).collect();
    mle::FitData {
        x_unique_v2: xs,
        row_unique,
        y_v2: rows.iter().map(|r| r.v_pull_v * r.v_pull_v).collect(),
        weight: rows.iter().map(|r| 1.0 / (2.0 * r.v_pull_v * r.v_pull_sd_v.unwrap_or(1.0)).powi(2)).collect(),
        line: rows.iter().map(|r| r.line).collect(),
    }
}

/// Fits eq. 10 and the asked models to a data set with a scenario (`json`: the scenario's JSON
/// tree, for the uncertain calibration values; `base_dir` resolves its relative paths).
pub fn analyse(
    data: &Dataset,
    scenario: &Scenario,
    json: &Value,
    base_dir: &Path,
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    if options.calibration_draws == 0 || options.calibration_draws > MAX_DRAWS {
        return Err(FitError::Setting(format!(
            "calibration draws {}: expected 1 to {MAX_DRAWS}",
            options.calibration_draws
        )));
    }
    if options.curve_points < 2 || options.curve_points > 10_000 {
        return Err(FitError::Setting(format!("curve points {}: expected 2 to 10000", options.curve_points)));
    }
    if options.surfaces == 0 || options.surfaces > models::MAX_SURFACES {
        return Err(FitError::Setting(format!(
            "--surfaces {}: expected 1 to {} surface realisations",
            options.surfaces,
            models::MAX_SURFACES
        )));
    }
    if data.rows.len() > MAX_FIT_ROWS {
        return Err(FitError::TooFewRows(format!(
            "{}: {} rows; `stiction fit` takes at most {MAX_FIT_ROWS} rows (split the file, e.g. by device)",
            data.source,
            data.rows.len()
        )));
    }
    // The rows of each device, in one pass (linear in the rows).
    let mut by_device: BTreeMap<&str, Vec<eq10::Eq10Point>> = BTreeMap::new();
    for r in data.rows.iter().filter(|r| r.v_pull_v > 0.0) {
        by_device.entry(r.device.as_str()).or_default().push(eq10::Eq10Point {
            v_clamp_v: r.v_clamp_v,
            v_pull_v: r.v_pull_v,
            v_pull_sd_v: r.v_pull_sd_v,
        });
    }
    if by_device.len() > MAX_DEVICES {
        return Err(FitError::TooFewRows(format!(
            "{}: {} device labels; `stiction fit` takes at most {MAX_DEVICES} devices in one file",
            data.source,
            by_device.len()
        )));
    }
    let ctx = ModelContext::new(scenario, base_dir)?;
    let (used, rows_rejected) = select_rows(&data.rows, &ctx.device);
    if used.len() < 3 {
        let below = rows_rejected.iter().filter(|r| r.reason.starts_with("below first contact")).count();
        let what = if below == data.rows.len() {
            format!("all {} rows are below first contact (L <= 0 with the nominal a_clamp and F_spring)", below)
        } else {
            format!("{} usable row(s) of {}", used.len(), data.rows.len())
        };
        let first: Vec<String> =
            rows_rejected.iter().take(5).map(|r| format!("line {}: {}", r.line, r.reason)).collect();
        return Err(FitError::TooFewRows(format!(
            "{}: {what}; a fit needs at least three rows with L > 0 and V_pull > 0{}",
            data.source,
            if first.is_empty() { String::new() } else { format!(" (rejected: {})", first.join("; ")) }
        )));
    }
    let distinct = {
        let mut v: Vec<u64> = used.iter().map(|r| r.v_clamp_v.to_bits()).collect();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    if distinct < 2 {
        return Err(FitError::TooFewRows(format!(
            "{}: all usable rows have the same clamp voltage; eq. 10 and the models need at least two",
            data.source
        )));
    }
    if distinct > MAX_DISTINCT_CLAMP_VOLTAGES {
        return Err(FitError::TooFewRows(format!(
            "{}: {distinct} distinct clamp voltages among the used rows; the models are evaluated once per clamp voltage and `stiction fit` takes at most {MAX_DISTINCT_CLAMP_VOLTAGES} (round the recorded clamp voltages to the set points of the sweep)",
            data.source
        )));
    }
    let sources = calibration_sources(json, &ctx.device)?;
    let all_points: Vec<eq10::Eq10Point> = data
        .rows
        .iter()
        .filter(|r| r.v_pull_v > 0.0)
        .map(|r| eq10::Eq10Point { v_clamp_v: r.v_clamp_v, v_pull_v: r.v_pull_v, v_pull_sd_v: r.v_pull_sd_v })
        .collect();
    let eq10 = eq10::fit_eq10(&all_points, &ctx.device, &sources, options.calibration_draws, options.seed)?;
    let mut devices = Vec::new();
    if by_device.len() > 1 {
        let mut used_per_device: BTreeMap<&str, usize> = BTreeMap::new();
        for r in &used {
            *used_per_device.entry(r.device.as_str()).or_default() += 1;
        }
        for (label, points) in &by_device {
            // Per device the regression alone: the calibration is common to all devices (the
            // pooled fit carries it), and a Monte Carlo per device would make the work grow as
            // devices x draws.
            let (fit, note) = match eq10::fit_eq10(points, &ctx.device, &sources, 0, options.seed) {
                Ok(f) => (Some(f), None),
                Err(e) => (None, Some(e.to_string())),
            };
            devices.push(DeviceFit {
                device: label.to_string(),
                rows_used: used_per_device.get(label).copied().unwrap_or(0),
                eq10: fit,
                note,
            });
        }
    }
    let (noise, noise_note) = if data.has_sd {
        (Noise::Column, "noise: each row's v_pull_sd_v (known; chi^2 tests the fit)".to_string())
    } else if let Some((sigma_v, dof)) = repeats_sigma(&used) {
        (
            Noise::Repeats { sigma_v, dof },
            format!(
                "noise: from the repeats, pooled pull-voltage SD {sigma_v:.3} V on {dof} degrees of freedom (chi^2 tests the fit)"
            ),
        )
    } else {
        (
            Noise::Residuals,
            "noise: from each model's residuals (no v_pull_sd_v column and no repeated clamp voltages), so chi^2 equals its dof by construction and cannot test the fit; models are ranked by their residual sum of squares through AIC".to_string(),
        )
    };
    let fd = fit_data(&used);
    let (vmin, vmax) = used.iter().fold((f64::INFINITY, 0.0f64), |a, r| (a.0.min(r.v_clamp_v), a.1.max(r.v_clamp_v)));
    let m = options.curve_points;
    let grid: Vec<f64> = (0..m)
        .map(|k| {
            let v = vmin + (vmax - vmin) * k as f64 / (m - 1) as f64;
            v * v
        })
        .collect();
    let mut models = Vec::new();
    let mut models_failed = Vec::new();
    let flat = used.iter().all(|r| r.v_pull_v == used[0].v_pull_v);
    for kind in &options.models {
        if flat {
            models_failed.push(FailedModel {
                name: kind.name(),
                reason: format!(
                    "all {} used rows have the same pull voltage ({} V): the data show no change of friction with load, so no shear strength is fitted and the models are not ranked",
                    used.len(),
                    used[0].v_pull_v
                ),
            });
            continue;
        }
        let result = match kind {
            ModelKind::ExplicitEnsemble => {
                mle::Ensemble::run(&ctx, options.surfaces, &fd, &grid).and_then(|e| e.fit(&ctx, &fd, noise, &grid))
            }
            _ => {
                let mut src = mle::Source::Build { ctx: &ctx, kind: *kind, cache: None };
                mle::fit_model(&ctx, kind.name(), &mut src, options.free, &fd, noise, &grid)
            }
        };
        let result = result.and_then(|mut f| {
            if let Some(what) = non_finite(&f) {
                return Err(FitError::Model {
                    model: kind.name(),
                    message: format!("the fit gives no finite {what} on these data; the model is not ranked"),
                });
            }
            let p = scal::propagate(
                &ctx,
                *kind,
                &f,
                &fd,
                noise,
                &sources,
                options.free,
                options.surfaces,
                options.calibration_draws,
                options.seed,
            )?;
            f.shear_strength_pa.ci95_with_calibration = p.ci95;
            f.shear_strength_pa.ci95_with_calibration_note = p.note;
            f.shear_strength_pa.variance_shares = p.shares;
            Ok(f)
        });
        match result {
            Ok(f) => models.push(f),
            Err(e) => models_failed.push(FailedModel { name: kind.name(), reason: e.to_string() }),
        }
    }
    let model_selection = rank(&mut models);
    let mut surface_notes = Vec::new();
    let mut summit_statistics = None;
    if let Some(spec) = scenario.surface.as_ref().filter(|s| s.source == stiction_surface::SurfaceSource::HeightMap) {
        let map_err = |e: stiction_surface::SurfaceError| FitError::Setting(format!("surface: {e}"));
        if options.models.iter().any(|k| k.is_cheap()) {
            let st = stiction_surface::map_summit_statistics(spec, base_dir).map_err(map_err)?;
            surface_notes.push(format!(
                "gw-dmt and discrete-nN use the {}: eta = {:.4e} m^-2, sigma = {}, R = {} ({} summits){}",
                st.source,
                st.summit_density_per_m2,
                stiction_units::format_quantity(st.summit_sd_m, stiction_units::Dimension::Length),
                stiction_units::format_quantity(
                    spec.summit_radius.unwrap_or(st.summit_radius_m),
                    stiction_units::Dimension::Length
                ),
                st.summit_count,
                if spec.summit_radius.is_some() { "; R is the given `summit_radius`, not the map's" } else { "" }
            ));
            summit_statistics = Some(st);
        }
        surface_notes.extend(stiction_surface::height_map_tiling(spec, base_dir).map_err(map_err)?);
    }
    let interval_method = "95 % intervals of s: `ci95` from the noise alone (the nominal a_clamp, a_pull and F_spring taken as exact), by profile likelihood (chi2_prof(s) - chi2_min <= t_0.975(nu)^2): exact for the linear dependence on s, follows the (s, R, F_spring) valley when those are free, and needs a few hundred model evaluations instead of the thousands of refits a bootstrap would (unaffordable for the explicit ensemble). `ci95_with_calibration` adds a_clamp, a_pull and F_spring drawn from their stated uncertainties (s refitted per draw, the noise added as se t_nu; 2.5-97.5 percentiles), with the variance shares by source. The ensemble's roughness interval is the 2.5-97.5 percentile of the s each surface alone needs.".to_string();
    Ok(FitReport {
        data: data.source.clone(),
        reduction: ctx.device,
        mu_apparent: eq10.mu_apparent.clone(),
        apparent_adhesion_force_n: eq10.apparent_adhesion_force_n.clone(),
        variance_shares: eq10.variance_shares.clone(),
        eq10,
        devices,
        rows_used: used.len(),
        rows_rejected,
        noise,
        noise_note,
        interval_method,
        models,
        models_failed,
        model_selection,
        summit_statistics,
        surface_notes,
    })
}

/// Fits eq. 10 to a structure's measured thresholds ([`structure::analyse`]) after checking the
/// counts against the limits of every fit: `draws` calibration draws (1 to [`MAX_DRAWS`]) and at
/// most [`MAX_FIT_ROWS`] rows.
pub fn analyse_structure(
    data: &ThresholdData,
    scenario: &Scenario,
    json: &Value,
    draws: usize,
    seed: u64,
) -> Result<StructureFitReport, FitError> {
    if draws == 0 || draws > MAX_DRAWS {
        return Err(FitError::Setting(format!("calibration draws {draws}: expected 1 to {MAX_DRAWS}")));
    }
    if data.rows.len() > MAX_FIT_ROWS {
        return Err(FitError::TooFewRows(format!(
            "{}: {} rows; `stiction fit` takes at most {MAX_FIT_ROWS} rows",
            data.source,
            data.rows.len()
        )));
    }
    structure::analyse(data, scenario, json, draws, seed)
}

/// The first number of a model fit that is not finite, by name (None: all are finite).
pub fn non_finite(f: &ModelFit) -> Option<&'static str> {
    let bad = |x: f64| !x.is_finite();
    let bad_ci = |c: &Option<[f64; 2]>| c.is_some_and(|[a, b]| bad(a) || bad(b));
    let s = &f.shear_strength_pa;
    if bad(s.value) {
        return Some("shear strength");
    }
    if bad_ci(&s.ci95) {
        return Some("interval of the shear strength");
    }
    if bad(f.chi2) || bad(f.aic) || bad(f.bic) || f.p_value.is_some_and(bad) || f.sigma_v.is_some_and(bad) {
        return Some("chi^2 or noise level (the model fits every row exactly or not at all)");
    }
    for p in [&f.summit_radius_m, &f.spring_force_n].into_iter().flatten() {
        if bad(p.value) || bad_ci(&p.ci95) {
            return Some("nuisance parameter");
        }
    }
    None
}

/// Orders the models by AIC (comparable ones first), fills delta AIC and Akaike weights, and
/// says in words which ones the data cannot tell apart (delta AIC < 2).
pub fn rank(models: &mut [ModelFit]) -> Vec<String> {
    models.sort_by(|a, b| b.comparable.cmp(&a.comparable).then(a.aic.total_cmp(&b.aic)));
    let mut out = Vec::new();
    let comparable: Vec<usize> =
        (0..models.len()).filter(|&i| models[i].comparable && models[i].aic.is_finite()).collect();
    if let Some(&best) = comparable.first() {
        let a0 = models[best].aic;
        let z: f64 = comparable.iter().map(|&i| (-(models[i].aic - a0) / 2.0).exp()).sum();
        for &i in &comparable {
            let d = models[i].aic - a0;
            models[i].delta_aic = Some(d);
            models[i].akaike_weight = Some((-d / 2.0).exp() / z);
        }
        let close: Vec<String> = comparable
            .iter()
            .filter(|&&i| models[i].delta_aic.unwrap_or(f64::INFINITY) < 2.0)
            .map(|&i| models[i].name.clone())
            .collect();
        if close.len() > 1 {
            out.push(format!(
                "The data cannot tell {} apart (AIC within 2 of the best): prefer none of them on these data.",
                join_names(&close)
            ));
        } else {
            out.push(format!("{} fits best; the next model's AIC is at least 2 higher.", models[best].name));
        }
        let far: Vec<String> = comparable
            .iter()
            .filter(|&&i| models[i].delta_aic.unwrap_or(0.0) > 10.0)
            .map(|&i| models[i].name.clone())
            .collect();
        if !far.is_empty() {
            out.push(format!(
                "{} {} strongly disfavoured (AIC more than 10 above the best).",
                join_names(&far),
                if far.len() > 1 { "are" } else { "is" }
            ));
        }
    }
    let odd: Vec<String> = models.iter().filter(|m| !m.comparable).map(|m| m.name.clone()).collect();
    if !odd.is_empty() {
        out.push(format!(
            "{}: no contact state at some used rows (listed under rows_without_state); fitted to the others, AIC not comparable.",
            join_names(&odd)
        ));
    }
    out
}

fn join_names(names: &[String]) -> String {
    match names {
        [] => String::new(),
        [a] => a.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// The paper's way from eq. 10 to s, over a whole load range: the shear strength for which the
/// eq. 10 line fitted to `kind`'s friction `s A_r(L)` over `loads_n` (least squares, as the lab
/// fits the measured points) has the slope `mu`; returns `(s, F_a0 of that model line)` (Pa, N).
/// (The slope at a single load, the paper's 3 uN, is
/// [`stiction_contact::discrete::DiscreteModel::shear_strength_for_slope`].) `F_f` is proportional
/// to s, so s = mu / (slope of A_r against L), and the model's F_a0 does not depend on s.
pub fn shear_strength_for_eq10_slope(
    ctx: &ModelContext,
    kind: ModelKind,
    mu: f64,
    loads_n: &[f64],
) -> Result<(f64, f64), FitError> {
    let mut m = ctx.build(kind, None, None)?;
    let parts = ctx.parts(&mut m, loads_n);
    let mut pts = Vec::with_capacity(loads_n.len());
    for (p, &l) in parts.iter().zip(loads_n) {
        let (g, h) = p.clone().map_err(|e| FitError::Model { model: kind.name(), message: e })?;
        if h != 0.0 {
            return Err(FitError::Setting(
                "this needs the shear-area or plastic slip criterion (no s-independent part)".into(),
            ));
        }
        pts.push((l, g));
    }
    let line = stats::fit_line(&pts)
        .ok_or_else(|| FitError::TooFewRows("need at least three loads to fit the model's eq. 10 line".into()))?;
    Ok((mu / line.slope, line.intercept / line.slope))
}

/// `study` with the lab's eq. 10 intervals of every experiment: the widths of the 95 % intervals
/// of mu_e,a and F_a0 that [`eq10::fit_eq10`] would give the experiment's slips, with the
/// reduction the lab used and the calibration uncertainties the scenario states for a_clamp,
/// a_pull and F_spring ([`eq10::interval_widths`], [`eq10::LAB_WIDTH_DRAWS`] joint calibration
/// draws per experiment). Every front end prepares its studies through this, so the same scenario
/// gives the same samples.
pub fn with_lab_intervals(study: stiction_study::Study) -> Result<stiction_study::Study, stiction_study::StudyError> {
    let setting = |e: String| stiction_study::StudyError::Setting(e);
    let sources = calibration_sources(study.scenario_json(), &study.reduction()).map_err(|e| setting(e.to_string()))?;
    // A release protocol's intervals come from its readings through the nominal parts
    // ([`structure::release_interval_widths`]), with the uncertain quantities under `structure`.
    let structure = match &study.nominal().structure {
        Some(spec) => Some(
            stiction_meter::structure::StructureDevice::from_spec(spec)
                .map_err(|e| setting(format!("structure: {e}")))?,
        ),
        None => None,
    };
    let json = study.scenario_json().clone();
    let to_widths = |w: eq10::IntervalWidths| stiction_study::FitIntervals {
        mu_ci95_width: w.mu,
        mu_ci95_width_with_calibration: w.mu_with_calibration,
        fa0_ci95_width_n: w.fa0_n,
        fa0_ci95_width_with_calibration_n: w.fa0_with_calibration_n,
    };
    let intervals =
        move |slips: stiction_study::Slips<'_>, reduction: &stiction_meter::Reduction, seed: u64| match slips {
            stiction_study::Slips::Voltages(slips) => {
                let points: Vec<Eq10Point> = slips
                    .iter()
                    .map(|&(v_clamp_v, v_pull_v)| Eq10Point { v_clamp_v, v_pull_v, v_pull_sd_v: None })
                    .collect();
                eq10::interval_widths(&points, reduction, &sources, eq10::LAB_WIDTH_DRAWS, seed)
                    .map(to_widths)
                    .unwrap_or_default()
            }
            stiction_study::Slips::Release(readings) => structure
                .as_ref()
                .and_then(|device| {
                    structure::release_interval_widths(readings, device, &json, eq10::LAB_WIDTH_DRAWS, seed).ok()
                })
                .map(to_widths)
                .unwrap_or_default(),
        };
    Ok(study.with_intervals(std::sync::Arc::new(intervals), eq10::LAB_WIDTH_DRAWS))
}
