//! Validation against measured pull-in and release voltages of a gap-closing actuator (Rauf et
//! al., JMEMS 31(1) 29-36, 2022, data in `data/gca-pullin-release/`).
//!
//! The swept variable is the drawn finger (overlap) length; every other input comes from the
//! [`ArraySpec`]. No per-point fitting: the model is evaluated with the same spec at every length.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::ActuatorError;
use crate::protocol::{PullInProtocol, Shuttle, step_pull_in};
use crate::spec::ArraySpec;

/// One measured finger length with its repeats.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeasuredPoint {
    /// Drawn finger (overlap) length (m).
    pub finger_length_m: f64,
    /// Pull-in voltage repeats (V).
    pub pull_in_v: Vec<f64>,
    /// Release voltage repeats (V).
    pub release_v: Vec<f64>,
}

/// Largest measured-voltage file read (bytes), checked before reading.
pub const MAX_VALIDATION_FILE_BYTES: u64 = 16 << 20;

/// Reads a measured-data CSV file through [`stiction_units::io::read_input_text`] (regular files
/// only, at most [`MAX_VALIDATION_FILE_BYTES`], checked before reading), see [`parse_measurements`].
pub fn read_measurements(path: &Path) -> Result<Vec<MeasuredPoint>, ActuatorError> {
    let text = stiction_units::io::read_input_text(path, MAX_VALIDATION_FILE_BYTES)
        .map_err(|e| ActuatorError::Data { path: path.display().to_string(), line: 0, message: e.to_string() })?;
    parse_measurements(&text, &path.display().to_string())
}

/// Parses measured data: a header `finger_length_drawn_um,pull_in_v_1,...,release_v[,...]`
/// (first column the drawn finger length in um, then any number of columns whose names start
/// with `pull_in_v` and `release_v`, at least one of each), then one row per length. Values must
/// be finite and positive, lengths at most [`crate::transients::MAX_FINGER_LENGTH_UM`] and voltages
/// at most [`crate::transients::MAX_TRANSIENT_VOLTAGE_V`]. Blank lines and lines starting with `#`
/// are comments; no line may be longer than [`stiction_units::text::MAX_LINE_BYTES`]. Errors carry
/// the 1-based line number and quote a cell only through [`stiction_units::text::excerpt`].
pub fn parse_measurements(text: &str, source: &str) -> Result<Vec<MeasuredPoint>, ActuatorError> {
    use stiction_units::text::excerpt;
    let err = |line: usize, message: String| ActuatorError::Data { path: source.to_string(), line, message };
    stiction_units::text::check_lines(text, stiction_units::text::MAX_LINE_BYTES)
        .map_err(|e| err(e.line as usize, e.to_string()))?;
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (hline, header) = lines.next().ok_or_else(|| err(0, "empty file: expected a header line".into()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    if names[0] != "finger_length_drawn_um" {
        return Err(err(
            hline + 1,
            format!("first column is {}, expected `finger_length_drawn_um`", excerpt(names[0])),
        ));
    }
    let mut kinds = Vec::with_capacity(names.len());
    for (k, n) in names.iter().enumerate().skip(1) {
        if n.starts_with("pull_in_v") {
            kinds.push(true);
        } else if n.starts_with("release_v") {
            kinds.push(false);
        } else {
            return Err(err(
                hline + 1,
                format!(
                    "column {}: unknown column {}: expected names starting with `pull_in_v` or `release_v`",
                    k + 1,
                    excerpt(n)
                ),
            ));
        }
    }
    if !kinds.iter().any(|&k| k) || !kinds.iter().any(|&k| !k) {
        return Err(err(hline + 1, "need at least one `pull_in_v*` and one `release_v*` column".into()));
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(err(
                i + 1,
                format!("{} values, expected {} (one per header column)", cells.len(), names.len()),
            ));
        }
        let mut vals = Vec::with_capacity(cells.len());
        for (k, (c, name)) in cells.iter().zip(&names).enumerate() {
            let v: f64 = c
                .parse()
                .map_err(|_| err(i + 1, format!("column {}: {} is not a number", excerpt(name), excerpt(c))))?;
            let limit = if k == 0 {
                crate::transients::MAX_FINGER_LENGTH_UM
            } else {
                crate::transients::MAX_TRANSIENT_VOLTAGE_V
            };
            let min = limit * crate::transients::MEASURED_MIN_FRACTION;
            if !(v.is_finite() && v >= min && v <= limit) {
                return Err(err(
                    i + 1,
                    format!("column {}: {v:e} must be finite and in [{min:e}, {limit:e}]", excerpt(name)),
                ));
            }
            vals.push(v);
        }
        let mut p = MeasuredPoint { finger_length_m: vals[0] * 1e-6, pull_in_v: vec![], release_v: vec![] };
        for (&k, &v) in kinds.iter().zip(&vals[1..]) {
            if k { p.pull_in_v.push(v) } else { p.release_v.push(v) }
        }
        out.push(p);
    }
    if out.is_empty() {
        return Err(err(0, "no data rows".into()));
    }
    Ok(out)
}

/// Model beside measurement at one finger length.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ValidationPoint {
    /// Drawn finger length (m).
    pub finger_length_m: f64,
    /// Mean of the measured pull-in repeats (V).
    #[serde(rename = "pull_in_measured_v")]
    pub pull_in_v_measured: f64,
    /// Sample standard deviation of the pull-in repeats (V), 0 for one repeat.
    #[serde(rename = "pull_in_spread_v")]
    pub pull_in_v_spread: f64,
    /// Model pull-in voltage (V).
    #[serde(rename = "pull_in_model_v")]
    pub pull_in_v_model: f64,
    /// `model / measured - 1`.
    pub pull_in_rel_error: f64,
    /// Mean of the measured release repeats (V).
    #[serde(rename = "release_measured_v")]
    pub release_v_measured: f64,
    /// Sample standard deviation of the release repeats (V), 0 for one repeat.
    #[serde(rename = "release_spread_v")]
    pub release_v_spread: f64,
    /// Model release voltage (V).
    #[serde(rename = "release_model_v")]
    pub release_v_model: f64,
    /// `model / measured - 1`.
    pub release_rel_error: f64,
}

/// Validation of a spec against measured data.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ValidationReport {
    /// Process undercut used (m per edge).
    pub undercut_m: f64,
    /// Stop contact standoff used (m).
    pub stop_contact_standoff_m: f64,
    /// One entry per measured length.
    pub points: Vec<ValidationPoint>,
    /// Mean of `|pull_in_rel_error|`.
    pub pull_in_mean_abs_rel_error: f64,
    /// Mean of `|release_rel_error|`.
    pub release_mean_abs_rel_error: f64,
}

fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    if v.len() < 2 {
        return (m, 0.0);
    }
    (m, (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt())
}

/// Predicts pull-in and release at every measured finger length (the spec's `overlap_length`
/// replaced by the drawn finger length) and compares. The spec needs a stop. Pull-in follows the
/// spec's `pull_in_protocol` (quasi-static, or the step pull-in of [`step_pull_in`] with the
/// shuttle's mass and damping at that length); release is always quasi-static.
pub fn validate(spec: &ArraySpec, data: &[MeasuredPoint]) -> Result<ValidationReport, ActuatorError> {
    if data.is_empty() {
        return Err(ActuatorError::NotAvailable("no measured points to validate against".into()));
    }
    let mut points = Vec::with_capacity(data.len());
    for d in data {
        let mut s = spec.clone();
        s.overlap_length = d.finger_length_m;
        let m = s.to_model()?;
        let mut h = m.hysteresis()?;
        if s.pull_in_protocol == PullInProtocol::Step {
            let step = step_pull_in(&m, &Shuttle::from_spec(&s)?)?;
            h.pull_in_voltage_v = step.voltage_v;
        }
        let (pm, ps) = mean_sd(&d.pull_in_v);
        let (rm, rs) = mean_sd(&d.release_v);
        points.push(ValidationPoint {
            finger_length_m: d.finger_length_m,
            pull_in_v_measured: pm,
            pull_in_v_spread: ps,
            pull_in_v_model: h.pull_in_voltage_v,
            pull_in_rel_error: h.pull_in_voltage_v / pm - 1.0,
            release_v_measured: rm,
            release_v_spread: rs,
            release_v_model: h.release_voltage_v,
            release_rel_error: h.release_voltage_v / rm - 1.0,
        });
    }
    let n = points.len() as f64;
    Ok(ValidationReport {
        undercut_m: spec.undercut,
        stop_contact_standoff_m: spec.stop.as_ref().map_or(0.0, |s| s.contact_standoff),
        pull_in_mean_abs_rel_error: points.iter().map(|p| p.pull_in_rel_error.abs()).sum::<f64>() / n,
        release_mean_abs_rel_error: points.iter().map(|p| p.release_rel_error.abs()).sum::<f64>() / n,
        points,
    })
}

/// The one global fit: the stop contact standoff `delta` (m) minimising the release mean
/// absolute relative error, golden-section search on `[0, min(1 um, x_s/2)]`. Pull-in does not
/// depend on it (the instability happens before the stop), so pull-in stays a pure prediction.
pub fn fit_stop_contact_standoff(
    spec: &ArraySpec,
    data: &[MeasuredPoint],
) -> Result<(f64, ValidationReport), ActuatorError> {
    let stop = spec
        .stop
        .as_ref()
        .ok_or_else(|| ActuatorError::NotAvailable("fitting the stop standoff needs `stop`".into()))?;
    let upper = (1e-6f64).min(0.5 * (stop.travel + 2.0 * spec.undercut));
    // Release does not depend on the pull-in protocol: the search runs quasi-static (fast).
    let mut quasi = spec.clone();
    quasi.pull_in_protocol = PullInProtocol::QuasiStatic;
    let cost = |d: f64| -> Result<f64, ActuatorError> {
        let mut s = quasi.clone();
        if let Some(st) = s.stop.as_mut() {
            st.contact_standoff = d;
        }
        Ok(validate(&s, data)?.release_mean_abs_rel_error)
    };
    let (mut a, mut b) = (0.0, upper);
    let r = 0.5 * (5f64.sqrt() - 1.0);
    while b - a > 1e-12 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if cost(c)? < cost(d)? {
            b = d;
        } else {
            a = c;
        }
    }
    let best = 0.5 * (a + b);
    let mut s = spec.clone();
    if let Some(st) = s.stop.as_mut() {
        st.contact_standoff = best;
    }
    Ok((best, validate(&s, data)?))
}

/// Effect of one physics switch: mean absolute relative errors with the switch changed from
/// the spec's setting.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SwitchEffect {
    /// What was changed.
    pub switch: String,
    /// Pull-in mean |relative error| with the change.
    pub pull_in_mean_abs_rel_error: f64,
    /// Release mean |relative error| with the change.
    pub release_mean_abs_rel_error: f64,
    /// Mean signed pull-in relative error (sign shows the direction).
    pub pull_in_mean_rel_error: f64,
    /// Mean signed release relative error.
    pub release_mean_rel_error: f64,
}

/// Runs the validation with each physics switch of the spec toggled, one at a time: the spec
/// itself, no back gap, fringing off, fringing Palmer, fringing cross_section (with and without
/// the substrate, when the spec has a `comb`), plane-stress beams (when a Poisson ratio is given),
/// no undercut, the other pull-in protocol (when the spec has a `shuttle`), finger bending on/off (when
/// the spec has bending inputs), no stop contact standoff, no stop (release then not defined and
/// left out), plus the rigid parallel-plate baseline (quasi-static, no fringing, no bending, no
/// standoff: the data README's orientation).
pub fn switch_effects(spec: &ArraySpec, data: &[MeasuredPoint]) -> Result<Vec<SwitchEffect>, ActuatorError> {
    let mut variants: Vec<(String, ArraySpec)> = vec![("as specified".into(), spec.clone())];
    let mut s = spec.clone();
    s.back_gap = None;
    variants.push(("no back gap".into(), s));
    for (name, fr) in
        [("fringing off", crate::plates::Fringing::Off), ("fringing palmer", crate::plates::Fringing::Palmer)]
    {
        if spec.fringing != fr {
            let mut s = spec.clone();
            s.fringing = fr;
            variants.push((name.into(), s));
        }
    }
    if let Some(comb) = &spec.comb {
        if spec.fringing != crate::plates::Fringing::CrossSection {
            let mut s = spec.clone();
            s.fringing = crate::plates::Fringing::CrossSection;
            variants.push(("fringing cross_section".into(), s));
        }
        if comb.substrate.is_some() {
            let mut s = spec.clone();
            s.fringing = crate::plates::Fringing::CrossSection;
            if let Some(c) = s.comb.as_mut() {
                c.substrate = None;
            }
            variants.push(("fringing cross_section, no substrate".into(), s));
        }
    }
    if spec.spring.beams.as_ref().is_some_and(|b| b.poisson_ratio.is_some()) {
        let mut s = spec.clone();
        if let Some(b) = s.spring.beams.as_mut() {
            b.poisson_ratio = None;
        }
        variants.push(("plane-stress beams (E, not E/(1-nu^2))".into(), s));
    }
    let mut s = spec.clone();
    s.undercut = 0.0;
    variants.push(("no undercut".into(), s));
    if spec.shuttle.is_some() {
        let mut s = spec.clone();
        let name = match spec.pull_in_protocol {
            PullInProtocol::QuasiStatic => {
                s.pull_in_protocol = PullInProtocol::Step;
                "pull-in protocol step (dynamic, squeeze-film damping)"
            }
            PullInProtocol::Step => {
                s.pull_in_protocol = PullInProtocol::QuasiStatic;
                "pull-in protocol quasi_static"
            }
        };
        variants.push((name.into(), s));
    }
    if let Some(b) = &spec.finger_bending {
        let mut s = spec.clone();
        if let Some(bb) = s.finger_bending.as_mut() {
            bb.enabled = !b.enabled;
        }
        variants.push((if b.enabled { "finger bending off" } else { "finger bending on" }.into(), s));
    }
    if spec.stop.as_ref().is_some_and(|st| st.contact_standoff > 0.0) {
        let mut s = spec.clone();
        if let Some(st) = s.stop.as_mut() {
            st.contact_standoff = 0.0;
        }
        variants.push(("no stop contact standoff".into(), s));
    }
    let mut base = spec.clone();
    base.pull_in_protocol = PullInProtocol::QuasiStatic;
    base.fringing = crate::plates::Fringing::Off;
    if let Some(b) = base.finger_bending.as_mut() {
        b.enabled = false;
    }
    if let Some(st) = base.stop.as_mut() {
        st.contact_standoff = 0.0;
    }
    variants.push(("rigid parallel plate (baseline)".into(), base));
    let mut out = Vec::new();
    for (name, s) in variants {
        let r = validate(&s, data)?;
        let n = r.points.len() as f64;
        out.push(SwitchEffect {
            switch: name,
            pull_in_mean_abs_rel_error: r.pull_in_mean_abs_rel_error,
            release_mean_abs_rel_error: r.release_mean_abs_rel_error,
            pull_in_mean_rel_error: r.points.iter().map(|p| p.pull_in_rel_error).sum::<f64>() / n,
            release_mean_rel_error: r.points.iter().map(|p| p.release_rel_error).sum::<f64>() / n,
        });
    }
    Ok(out)
}
