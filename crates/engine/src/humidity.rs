//! `humidity` (`stiction plot humidity`, Python's `humidity`): the friction meter of a scenario
//! over a grid of relative humidities.

use serde::Serialize;
use stiction_meter::{Meter, MeterResult};
use stiction_scenario::{Scenario, Warning};
use stiction_units::Dimension;

use crate::Error;

use crate::scenario_source::ScenarioSource;

/// The default grid of `--rh`: 0 to 90 % in ten steps.
pub const DEFAULT_RH: &str = "0:0.9:10";

/// The relative humidities of `--rh` (a list `0.1,0.35` or `FROM:TO:STEPS`, each a fraction in
/// [0, 1) or a percentage, as `stiction bem --rh` takes them; default [`DEFAULT_RH`]), strictly
/// increasing, with the dry point RH = 0 put first when the list does not start there.
pub fn rh_grid(text: Option<&str>) -> Result<Vec<f64>, String> {
    let text = text.unwrap_or(DEFAULT_RH);
    dry_first(crate::rh::parse_rh(text)?, &format!("--rh {text:?}"))
}

/// The relative humidities given as numbers (a front end's list, named `rh`): each finite and in
/// [0, 1), 1 to 1000 of them, strictly increasing, with the dry point RH = 0 put first when the
/// list does not start there; the same grid as [`rh_grid`] of the same numbers written as text.
pub fn rh_grid_of(values: &[f64]) -> Result<Vec<f64>, String> {
    crate::rh::check_rh_values(values)?;
    dry_first(values.to_vec(), "rh")
}

/// `values` (non-empty) checked strictly increasing, with 0 put first when they start above it;
/// `label` names the input in the error.
fn dry_first(mut values: Vec<f64>, label: &str) -> Result<Vec<f64>, String> {
    if let Some(w) = values.windows(2).find(|w| w[1] <= w[0]) {
        return Err(format!(
            "{label}: the humidities must increase ({:?} is followed by {:?}); the dry point 0 comes first by itself",
            w[0], w[1]
        ));
    }
    if values.first().is_some_and(|&v| v > 0.0) {
        values.insert(0, 0.0);
    }
    Ok(values)
}

/// The capillary share of the adhesive load of a meter run: the capillary load over the adhesive
/// load, both summed over the clamp voltages in contact without an error (`None` without any
/// adhesive load). 0 when dry.
pub fn capillary_share(r: &MeterResult) -> Option<f64> {
    let (adh, cap) = summed_loads(r);
    // Each contact state holds 0 <= capillary <= adhesive (meter::invariants), so the share lies in
    // [0, 1]; the clamp removes the rounding of the sums (a share of 1.0000000000000002).
    (adh > 0.0).then(|| (cap / adh).clamp(0.0, 1.0))
}

/// Adhesive and capillary load, N, summed over the clamp voltages in contact without an error.
fn summed_loads(r: &MeterResult) -> (f64, f64) {
    r.points
        .iter()
        .filter(|p| p.in_contact && p.error.is_none())
        .fold((0.0, 0.0), |(a, c), p| (a + p.adhesive_load_n, c + p.capillary_load_n.unwrap_or(0.0)))
}

/// The meter at one relative humidity.
#[derive(Serialize, Debug, Clone)]
pub struct HumidityPoint {
    /// Relative humidity (fraction).
    pub relative_humidity: f64,
    /// Apparent friction coefficient mu_e,a (eq. 10); null with `reason` when there is no line.
    pub mu_apparent: Option<f64>,
    /// Standard error of mu_e,a from the regression alone (no calibration).
    pub mu_apparent_se: Option<f64>,
    /// Apparent zero-load adhesion force F_a0 (eq. 10), N; null with `reason`.
    pub apparent_adhesion_force_n: Option<f64>,
    /// R^2 of the eq. 10 fit.
    pub r_squared: Option<f64>,
    /// Adhesive load summed over the clamp voltages in contact, N.
    pub adhesive_load_summed_n: Option<f64>,
    /// Its capillary part (the water menisci), N.
    pub capillary_load_summed_n: Option<f64>,
    /// Capillary share of the adhesive load (fraction); null without adhesive load.
    pub capillary_share: Option<f64>,
    /// Kelvin radius r_K, m (null when dry or no meniscus forms).
    pub kelvin_radius_m: Option<f64>,
    /// Largest gap a meniscus bridges, h_m = r_K (cos th1 + cos th2), m.
    pub meniscus_height_m: Option<f64>,
    /// Why mu_e,a and F_a0 are null (no usable eq. 10 line, or the meter failed at this humidity).
    pub reason: Option<String>,
    /// Why the Kelvin radius, the meniscus height or the capillary share is null (null when
    /// none is; always written, so that every CSV row has the same columns).
    pub meniscus_note: Option<&'static str>,
}

/// The measured reference of the scenario, placed at the humidity of its experiment.
#[derive(Serialize, Debug, Clone)]
pub struct HumidityReference {
    /// Where the numbers come from.
    pub source: String,
    /// The relative humidity of the experiment (the scenario's `environment`), null when the
    /// scenario states none (then the reference is drawn as a band over the whole grid).
    pub relative_humidity: Option<f64>,
    /// Its standard deviation, when the scenario gives one.
    pub relative_humidity_sd: Option<f64>,
    /// Measured mu_e,a.
    pub mu_apparent: Option<f64>,
    /// Its +/- (see `uncertainty_meaning`).
    pub mu_apparent_uncertainty: Option<f64>,
    /// Measured F_a0, N.
    pub apparent_adhesion_force_n: Option<f64>,
    /// Its +/-, N.
    pub apparent_adhesion_force_uncertainty_n: Option<f64>,
    /// What the +/- is.
    pub uncertainty_meaning: String,
    /// Why a value is null: the scenario states no humidity (or no sd) of the experiment, or the
    /// reference gives no such value.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

/// The friction meter of a scenario over a grid of relative humidities.
#[derive(Serialize, Debug, Clone)]
pub struct HumiditySweep {
    /// The scenario file.
    pub scenario: String,
    /// Its description.
    pub description: String,
    /// The contact model used.
    pub contact_model: String,
    /// Temperature of the air, K (the scenario's, default 25 C).
    pub temperature_k: f64,
    /// Water contact angle of the sidewall, rad.
    pub contact_angle_rad: f64,
    /// Water contact angle of the shoe's face, rad.
    pub counter_face_contact_angle_rad: f64,
    /// The measured reference, when the scenario has one of this device.
    pub reference: Option<HumidityReference>,
    /// One point per humidity, the dry point (RH = 0) first.
    pub points: Vec<HumidityPoint>,
    /// What loading the scenario noted (a reference of another device dropped, ...).
    pub warnings: Vec<Warning>,
}

/// Runs the friction meter of the scenario `source` (a file or a tree built in memory, with its
/// `--set` overrides; [`ScenarioSource`]) at each relative humidity of `rhs` (from
/// [`rh_grid`]): `environment.relative_humidity` is set to each value, every other field as the
/// scenario gives it. An error of the dry point (RH = 0) is the scenario's and is returned; at a
/// humid point the meter's error becomes that point's `reason` with null values. `progress(done,
/// total)` after each humidity.
pub fn sweep(
    source: &ScenarioSource,
    rhs: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<HumiditySweep, Error> {
    let name = source.name();
    let value = source.json(&[])?;
    let scenario = source.parse(&[])?;
    if let Some(conflict) = scenario.spring_force_conflict() {
        return Err(format!("{name}: {conflict}").into());
    }
    let material = scenario.require_material().map_err(|e| format!("{name}: {e}"))?;
    let (a1, a2) = material.contact_angles_rad();
    let reference = scenario.reference.as_ref().map(|r| HumidityReference {
        source: r.source.clone(),
        relative_humidity: scenario.environment.as_ref().map(|e| e.relative_humidity),
        relative_humidity_sd: scenario
            .environment
            .as_ref()
            .and_then(|_| scenario.given_sd(&["environment", "relative_humidity"], Dimension::Dimensionless)),
        mu_apparent: r.mu_apparent,
        mu_apparent_uncertainty: r.mu_apparent_uncertainty,
        apparent_adhesion_force_n: r.apparent_adhesion_force,
        apparent_adhesion_force_uncertainty_n: r.apparent_adhesion_force_uncertainty,
        uncertainty_meaning: r.uncertainty_meaning.clone(),
        note: Some(
            "a null humidity or sd: the scenario states none for the experiment (the reference is then a band \
             over the grid); a null value or +/-: the reference gives none",
        ),
    });
    let mut contact_model = String::new();
    let mut points = Vec::with_capacity(rhs.len());
    for (k, &rh) in rhs.iter().enumerate() {
        let mut v = value.clone();
        if let Some(root) = v.as_object_mut() {
            let env = root.entry("environment").or_insert_with(|| serde_json::json!({}));
            if !env.is_object() {
                *env = serde_json::json!({});
            }
            env["relative_humidity"] = serde_json::json!(rh);
        }
        let at = |e: &dyn std::fmt::Display| format!("{name}: at relative humidity {rh}: {e}");
        let result = Scenario::from_value_with_sets(v, &source.origin, &source.sets)
            .map_err(|e| at(&e))
            .and_then(|s| Meter::from_scenario(&s, &source.base).map_err(|e| at(&e)))
            .and_then(|mut m| m.run(&mut |_, _| {}).map_err(|e| at(&e)));
        let point = match result {
            Ok(r) => {
                contact_model.clone_from(&r.contact_model);
                point_of(rh, &r)
            }
            // The dry point is the scenario as given: its error is the scenario's.
            Err(e) if k == 0 => return Err(e.into()),
            Err(e) => HumidityPoint {
                relative_humidity: rh,
                mu_apparent: None,
                mu_apparent_se: None,
                apparent_adhesion_force_n: None,
                r_squared: None,
                adhesive_load_summed_n: None,
                capillary_load_summed_n: None,
                capillary_share: None,
                kelvin_radius_m: None,
                meniscus_height_m: None,
                reason: Some(format!("the meter failed: {e}")),
                meniscus_note: None,
            },
        };
        points.push(point);
        progress(k + 1, rhs.len());
    }
    Ok(HumiditySweep {
        scenario: name,
        description: scenario.description.clone(),
        contact_model,
        temperature_k: scenario
            .environment
            .as_ref()
            .map_or(stiction_scenario::DEFAULT_TEMPERATURE_K, |e| e.temperature),
        contact_angle_rad: a1,
        counter_face_contact_angle_rad: a2,
        reference,
        points,
        warnings: scenario.notes.clone(),
    })
}

/// One humidity's point from the meter's result.
fn point_of(rh: f64, r: &MeterResult) -> HumidityPoint {
    let (adh, cap) = summed_loads(r);
    let share = capillary_share(r);
    let (mu, fa0) = (r.mu_apparent, r.apparent_adhesion_force_n);
    let reason = match (mu, fa0) {
        (Some(_), Some(_)) => None,
        _ => Some(
            r.fit_note
                .clone()
                .unwrap_or_else(|| "the fitted slope is not positive, so mu_e,a and F_a0 are undefined".into()),
        ),
    };
    HumidityPoint {
        relative_humidity: rh,
        mu_apparent: mu,
        mu_apparent_se: r.fit.as_ref().filter(|_| mu.is_some()).map(|f| f.slope_se),
        apparent_adhesion_force_n: fa0,
        r_squared: r.fit.as_ref().filter(|_| mu.is_some()).map(|f| f.r_squared),
        adhesive_load_summed_n: Some(adh),
        capillary_load_summed_n: Some(cap),
        capillary_share: share,
        kelvin_radius_m: r.environment.as_ref().and_then(|h| h.kelvin_radius_m),
        meniscus_height_m: r.environment.as_ref().and_then(|h| h.meniscus_height_m),
        reason,
        meniscus_note: (r.environment.as_ref().and_then(|h| h.meniscus_height_m).is_none() || share.is_none())
        .then_some("no meniscus: dry (RH 0), faces that do not condense water (cos theta_1 + cos theta_2 <= 0), or a Kelvin radius below the smallest one (min_kelvin_radius), or no adhesive load to share"),
    }
}

/// The sweep as a JSON value (what `stiction plot humidity --json` prints), every number checked
/// finite.
pub fn humidity_json(
    source: &ScenarioSource,
    rhs: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<serde_json::Value, Error> {
    Ok(crate::json::finite_value(&sweep(source, rhs, progress)?)?)
}

#[cfg(test)]
mod tests {
    use super::{rh_grid, rh_grid_of};

    #[test]
    fn the_grid_starts_dry_and_increases() {
        assert_eq!(rh_grid(Some("0.2,0.5")).unwrap(), vec![0.0, 0.2, 0.5]);
        assert_eq!(rh_grid(Some("0:0.5:3")).unwrap(), vec![0.0, 0.25, 0.5]);
        let d = rh_grid(None).unwrap();
        assert_eq!(d.len(), 10);
        assert_eq!(d[0], 0.0);
        assert!((d[9] - 0.9).abs() < 1e-15);
        for bad in ["0.5,0.2", "0.2,0.2", "0.9:0.1:5", "1.2", "x", "0:0.5:0"] {
            assert!(rh_grid(Some(bad)).is_err(), "{bad}");
        }
        // The same grid from numbers as from their text; a bad number named by its index.
        assert_eq!(rh_grid_of(&[0.2, 0.5]).unwrap(), rh_grid(Some("0.2,0.5")).unwrap());
        assert_eq!(rh_grid_of(&[0.0, 0.3]).unwrap(), vec![0.0, 0.3]);
        for (bad, names) in [
            (vec![], "rh:"),
            (vec![0.1, f64::NAN], "rh[1]"),
            (vec![1.0], "rh[0]"),
            (vec![-0.1], "rh[0]"),
            (vec![0.5, 0.2], "rh:"),
            (vec![0.1; 1001], "rh:"),
        ] {
            let e = rh_grid_of(&bad).unwrap_err();
            assert!(e.starts_with(names), "{bad:?}: {e}");
        }
    }

    /// Seeded fuzzing of `--rh` (`STICTION_FUZZ_CASES`, default 20 000; `STICTION_FUZZ_SEED`):
    /// strings of RH atoms (numbers, percentages, NaN, inf, 1e400, huge step counts, separators,
    /// signs, spaces, non-ASCII). Each gives a grid that starts at 0, increases, is finite, in
    /// [0, 1) and has at most 1001 points, or an error that names `--rh` in under 400 characters.
    #[test]
    fn hostile_rh_lists_give_a_valid_grid_or_an_error_naming_the_flag() {
        let cases: usize = std::env::var("STICTION_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(20_000);
        let mut state: u64 = std::env::var("STICTION_FUZZ_SEED").ok().and_then(|v| v.parse().ok()).unwrap_or(22) | 1;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        const ATOMS: [&str; 32] = [
            "0",
            "0.35",
            "35 %",
            "99.9 %",
            "100 %",
            "1",
            "0.999999",
            "-0.1",
            "1e-300",
            "1e400",
            "NaN",
            "inf",
            "-0",
            ",",
            ",",
            ":",
            ":",
            "10",
            "1000",
            "1001",
            "18446744073709551616",
            " ",
            "%",
            "e",
            ".",
            "µ",
            "0x1",
            "5e-1",
            "35 %%",
            "",
            "+0.2",
            "0.9",
        ];
        let (mut ok, mut refused) = (0, 0);
        for _ in 0..cases {
            let n = 1 + (next() % 7) as usize;
            let text: String = (0..n).map(|_| ATOMS[(next() % ATOMS.len() as u64) as usize]).collect();
            match rh_grid(Some(&text)) {
                Ok(g) => {
                    ok += 1;
                    assert!(!g.is_empty() && g.len() <= 1001 && g[0] == 0.0, "{text:?}: {g:?}");
                    assert!(g.iter().all(|v| v.is_finite() && (0.0..1.0).contains(v)), "{text:?}: {g:?}");
                    assert!(g.windows(2).all(|w| w[1] > w[0]), "{text:?}: {g:?}");
                }
                Err(e) => {
                    refused += 1;
                    assert!(e.starts_with("--rh") && e.len() < 400, "{text:?}: {e}");
                }
            }
        }
        assert!(ok > 0 && refused > 0, "{ok} accepted, {refused} refused");
    }
}
