//! `stiction plot humidity`: the friction meter of a scenario over a grid of relative humidities,
//! and its three figures (mu_e,a, F_a0 and the capillary share of the adhesive load against RH).
//!
//! The composition ([`sweep`], [`charts`]) is library code that a front end other than the command
//! line can call ([`crate::api::humidity_json`]); `plot.rs` only parses flags, prints and writes.

use serde::Serialize;
use stiction_meter::{Meter, MeterResult};
use stiction_plot::{Chart, LegendPosition, Series};
use stiction_scenario::{Scenario, Warning};
use stiction_units::Dimension;

use crate::figargs::reference;
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
/// `--set` overrides; [`crate::scenario_source::ScenarioSource`]) at each relative humidity of `rhs` (from
/// [`rh_grid`]): `environment.relative_humidity` is set to each value, every other field as the
/// scenario gives it. An error of the dry point (RH = 0) is the scenario's and is returned; at a
/// humid point the meter's error becomes that point's `reason` with null values. `progress(done,
/// total)` after each humidity.
pub fn sweep(
    source: &ScenarioSource,
    rhs: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<HumiditySweep, Box<dyn std::error::Error>> {
    let name = source.name();
    let value = source.json(&[])?;
    let scenario = source.parse(&[])?;
    if let Some(conflict) = scenario.spring_force_conflict() {
        return Err(format!("{name}: {conflict}").into());
    }
    scenario.require_material().map_err(|e| format!("{name}: {e}"))?;
    let (a1, a2) = scenario.contact_angles_rad();
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

/// The figures of a sweep by file stem: `humidity-mu` (mu_e,a), `humidity-fa0` (F_a0, µN) and
/// `humidity-share` (capillary share of the adhesive load, %), each against RH in %, with the
/// measured reference as a point with its error bars at the experiment's humidity (a band over the
/// grid when the scenario states no humidity). Humidities without an eq. 10 line are named in the
/// figure's note.
pub fn charts(s: &HumiditySweep) -> Vec<(&'static str, Chart)> {
    // Percent, rounded to 12 digits so that 0.9 shows as 90, not 89.99999999999999.
    let pct = |rh: f64| (rh * 1e14).round() / 1e12;
    let x_top = s.points.last().map_or(100.0, |p| pct(p.relative_humidity));
    let x_range = (0.0, if x_top > 0.0 { x_top } else { 100.0 });
    let model_marker = stiction_plot::Marker::Circle;
    let missing: Vec<String> = s
        .points
        .iter()
        .filter(|p| p.mu_apparent.is_none())
        .map(|p| format!("{}", (pct(p.relative_humidity) * 100.0).round() / 100.0))
        .collect();
    let missing_note = (!missing.is_empty())
        .then(|| format!("no eq. 10 line at RH = {} % (reasons: humidity.csv)", missing.join(", ")));
    let model = format!("virtual meter ({})", s.contact_model);
    let x_label = "relative humidity RH (%)";
    let series = |f: &dyn Fn(&HumidityPoint) -> Option<f64>| -> Vec<(f64, f64)> {
        s.points.iter().filter_map(|p| f(p).map(|y| (pct(p.relative_humidity), y))).collect()
    };

    let mut mu = Chart::new("apparent friction coefficient against humidity", x_label, "μ_e,a (eq. 10)")
        .keys("relative_humidity_percent", "mu_apparent")
        .with(Series::markers(model.clone(), series(&|p| p.mu_apparent)).with_color(0).with_marker(model_marker));
    let mut fa0 = Chart::new("apparent adhesion force against humidity", x_label, "F_a0 (µN, eq. 10)")
        .keys("relative_humidity_percent", "apparent_adhesion_force_un")
        .with(
            Series::markers(model.clone(), series(&|p| p.apparent_adhesion_force_n.map(|f| f * 1e6)))
                .with_color(0)
                .with_marker(model_marker),
        );
    let share = Chart::new(
        "capillary share of the adhesive load against humidity",
        x_label,
        "capillary share of the adhesive load (%)",
    )
    .keys("relative_humidity_percent", "capillary_share_percent")
    .with(
        Series::markers(model.clone(), series(&|p| p.capillary_share.map(|c| c * 100.0)))
            .with_color(0)
            .with_marker(model_marker),
    );
    let mut notes: [Vec<String>; 2] = [Vec::new(), Vec::new()];
    if let Some(r) = &s.reference {
        let rf = stiction_scenario::ReferenceSpec {
            device: None,
            source: r.source.clone(),
            mu_apparent: r.mu_apparent,
            mu_apparent_uncertainty: r.mu_apparent_uncertainty,
            apparent_adhesion_force: r.apparent_adhesion_force_n,
            apparent_adhesion_force_uncertainty: r.apparent_adhesion_force_uncertainty_n,
            uncertainty_meaning: r.uncertainty_meaning.clone(),
        };
        let at = |label: String, value: f64, err: Option<f64>| -> Series {
            match r.relative_humidity {
                Some(rh) => {
                    let label = match r.relative_humidity_sd {
                        Some(sd) => format!("{label}, at RH = {} ± {} %", pct(rh), pct(sd)),
                        None => format!("{label}, at RH = {} %", pct(rh)),
                    };
                    let mut m = Series::markers(label, vec![(pct(rh), value)])
                        .with_color(4)
                        .with_marker(stiction_plot::Marker::Square);
                    if let Some(e) = err {
                        m = m.with_y_err(vec![e]);
                    }
                    if let Some(sd) = r.relative_humidity_sd {
                        m = m.with_x_err(vec![pct(sd)]);
                    }
                    m
                }
                None => {
                    let e = err.unwrap_or(0.0);
                    Series::y_range(format!("{label}, humidity not stated"), value - e, value + e).with_color(7)
                }
            }
        };
        if let (Some(m), Some(label)) = (r.mu_apparent, reference::mu_label(&rf)) {
            mu.series.push(at(label, m, r.mu_apparent_uncertainty));
        }
        if let (Some(f), Some(label)) = (r.apparent_adhesion_force_n, reference::adhesion_label(&rf)) {
            fa0.series.push(at(label, f * 1e6, r.apparent_adhesion_force_uncertainty_n.map(|u| u * 1e6)));
        }
        if let Some(n) = reference::meaning_note(&rf) {
            notes[0].push(n.clone());
            notes[1].push(n);
        }
    }
    for n in &mut notes {
        n.extend(missing_note.clone());
    }
    let [mu_notes, fa0_notes] = notes;
    let mut out = Vec::new();
    for (stem, mut chart, notes) in
        [("humidity-mu", mu, mu_notes), ("humidity-fa0", fa0, fa0_notes), ("humidity-share", share, Vec::new())]
    {
        let notes: Vec<String> =
            if stem == "humidity-share" { missing_note.clone().into_iter().collect() } else { notes };
        if !notes.is_empty() {
            chart.note = Some(notes.join("\n"));
        }
        // Margins of 3 % so that the markers at the ends of the grid are drawn whole.
        let w = x_range.1 - x_range.0;
        chart.x_range = Some((x_range.0 - 0.03 * w, x_range.1 + 0.03 * w));
        chart.legend = LegendPosition::UpperLeft;
        let (mut lo, mut hi) = (0.0_f64, if stem == "humidity-share" { 100.0_f64 } else { 0.0 });
        for se in &chart.series {
            for (i, p) in se.points.iter().enumerate() {
                let e = se.y_err.as_ref().and_then(|e| e.get(i)).copied().unwrap_or(0.0);
                let (a, b) = match se.style {
                    stiction_plot::SeriesStyle::YSpan => (p.0, p.1),
                    _ => (p.1 - e, p.1 + e),
                };
                if a.is_finite() && b.is_finite() {
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
            }
        }
        let span = if hi > lo { hi - lo } else { 1.0 };
        // From 0 (or below, for a negative value), 3 % margins, headroom for the legend; the share
        // runs to 100 % (a share cannot exceed it; the legend finds a free corner or goes below).
        let headroom = if stem == "humidity-share" { 0.03 } else { 0.35 };
        chart.y_range = Some((lo - 0.03 * span, hi + headroom * span));
        out.push((stem, chart));
    }
    out
}

/// The table of a sweep as CSV, one row per humidity (`humidity.csv`): every field of
/// [`HumidityPoint`], SI units in the column names, an empty cell for a null.
pub fn table_csv(s: &HumiditySweep) -> Result<Vec<u8>, Box<dyn std::error::Error>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for p in &s.points {
        w.serialize(p)?;
    }
    Ok(w.into_inner().map_err(|e| format!("humidity.csv: {e}"))?)
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
