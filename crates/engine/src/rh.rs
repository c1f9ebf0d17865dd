//! The relative humidities of `--rh` (`stiction bem`, `stiction plot humidity`) and of a front
//! end's list, checked alike.

use stiction_units::{Constraint, Dimension, parse_quantity_checked};

/// Most humidities of one run.
const MAX_RH: usize = 1000;

/// The relative humidities of `--rh`: a comma-separated list or FROM:TO:STEPS, each a fraction
/// in [0, 1) ("0.35" or "35 %").
pub fn parse_rh(text: &str) -> Result<Vec<f64>, String> {
    parse_rh_as(text, "--rh")
}

/// [`parse_rh`] of the text a front end calls `name` (a flag, an argument), named so in errors.
pub fn parse_rh_as(text: &str, name: &str) -> Result<Vec<f64>, String> {
    let one = |s: &str| -> Result<f64, String> {
        let v = parse_quantity_checked(s.trim(), Dimension::Dimensionless, Constraint::NonNegative)
            .map_err(|e| format!("{name} {s:?}: {e}"))?;
        if v < 1.0 { Ok(v) } else { Err(format!("{name} {s:?}: expected a relative humidity in [0, 1) (0 to 99.9 %)")) }
    };
    let parts: Vec<&str> = text.split(':').collect();
    let values = match parts.len() {
        1 => text.split(',').map(one).collect::<Result<Vec<f64>, String>>()?,
        3 => {
            let (a, b) = (one(parts[0])?, one(parts[1])?);
            let steps: usize =
                parts[2].trim().parse().ok().filter(|&s| (1..=MAX_RH).contains(&s)).ok_or_else(|| {
                    format!("{name} {text:?}: STEPS {:?} must be an integer in 1..={MAX_RH}", parts[2])
                })?;
            if steps == 1 { vec![a] } else { (0..steps).map(|k| a + (b - a) * k as f64 / (steps - 1) as f64).collect() }
        }
        _ => return Err(format!("{name} {text:?}: expected a list (0.1,0.35) or FROM:TO:STEPS")),
    };
    if values.is_empty() || values.len() > MAX_RH {
        return Err(format!("{name} {text:?}: expected 1 to {MAX_RH} humidities"));
    }
    Ok(values)
}

/// Relative humidities given as numbers (a front end's list, named `rh`): 1 to 1000 of them,
/// each finite and in [0, 1), as [`parse_rh`] takes them as text.
pub fn check_rh_values(values: &[f64]) -> Result<(), String> {
    if values.is_empty() || values.len() > MAX_RH {
        return Err(format!("rh: expected 1 to {MAX_RH} humidities, got {}", values.len()));
    }
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !(v.is_finite() && (0.0..1.0).contains(*v))) {
        return Err(format!("rh[{i}] = {v}: expected a relative humidity in [0, 1) (0 to 99.9 %)"));
    }
    Ok(())
}
