//! Evenly spaced paths of a quantity as typed request fields: where a path starts and ends (SI,
//! the unit in the field name) and its number of steps. A front end parses them at its edge from
//! its own inputs (the command line from `--sweep FROM:TO:STEPS`, Python from its argument of the
//! same text), naming its own flag or argument in errors; the engine takes the typed value.

use stiction_units::{Constraint, Dimension, parse_quantity_checked};

/// Most steps of one path (`limits::BEM_MAX_PATH_STEPS`).
pub const MAX_PATH_STEPS: usize = 10_000;

/// The values of a path from `from` to `to` in `steps` (>= 1) evenly spaced steps, both ends
/// included; one step is `from` alone.
fn path_values(from: f64, to: f64, steps: usize) -> Vec<f64> {
    if steps <= 1 {
        return vec![from];
    }
    (0..steps).map(|k| from + (to - from) * k as f64 / (steps - 1) as f64).collect()
}

/// Parses FROM:TO:STEPS of quantities of `dim` (each > 0) with 1 to [`MAX_PATH_STEPS`] steps;
/// `name` (a flag or an argument) names the text in errors.
fn parse_positive_path(text: &str, dim: Dimension, name: &str) -> Result<(f64, f64, usize), String> {
    let parts: Vec<&str> = text.split(':').collect();
    if parts.len() != 3 {
        return Err(format!("{name} {text:?}: expected FROM:TO:STEPS"));
    }
    let f = |s: &str| parse_quantity_checked(s, dim, Constraint::Positive).map_err(|e| format!("{name}: {e}"));
    let (a, b) = (f(parts[0])?, f(parts[1])?);
    let steps: usize =
        parts[2].trim().parse().ok().filter(|s| (1..=MAX_PATH_STEPS).contains(s)).ok_or_else(|| {
            format!("{name} {text:?}: STEPS {:?} must be an integer in 1..={MAX_PATH_STEPS}", parts[2])
        })?;
    Ok((a, b, steps))
}

/// Checks a typed path: both ends finite and > 0, 1 to [`MAX_PATH_STEPS`] steps; `name` names
/// the path in errors.
fn check_positive_path(from: f64, to: f64, steps: usize, unit: &str, name: &str) -> Result<(), String> {
    if !(from.is_finite() && from > 0.0 && to.is_finite() && to > 0.0) {
        return Err(format!("{name}: from {from} {unit} to {to} {unit}: expected finite values > 0"));
    }
    if !(1..=MAX_PATH_STEPS).contains(&steps) {
        return Err(format!("{name}: {steps} steps: expected 1 to {MAX_PATH_STEPS}"));
    }
    Ok(())
}

/// A path of mean pressures (`bem --sweep`), each solved from the previous state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PressureRange {
    /// First mean pressure, Pa (> 0).
    pub from_pa: f64,
    /// Last mean pressure, Pa (> 0).
    pub to_pa: f64,
    /// Number of pressures, 1 to [`MAX_PATH_STEPS`] (one: `from_pa` alone).
    pub steps: usize,
}

impl PressureRange {
    /// Parses FROM:TO:STEPS ("1MPa:20MPa:3"), named `name` in errors.
    pub fn parse(text: &str, name: &str) -> Result<PressureRange, String> {
        let (from_pa, to_pa, steps) = parse_positive_path(text, Dimension::Pressure, name)?;
        Ok(PressureRange { from_pa, to_pa, steps })
    }

    /// Checks the range (a request built without [`PressureRange::parse`]), named `name`.
    pub fn check(&self, name: &str) -> Result<(), String> {
        check_positive_path(self.from_pa, self.to_pa, self.steps, "Pa", name)
    }

    /// The mean pressures, Pa, evenly spaced from `from_pa` to `to_pa`.
    pub fn values_pa(&self) -> Vec<f64> {
        path_values(self.from_pa, self.to_pa, self.steps)
    }
}

/// A path of mean gaps (`bem --gap-sweep`), each solved from the previous state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GapRange {
    /// First mean gap, m (> 0).
    pub from_m: f64,
    /// Last mean gap, m (> 0).
    pub to_m: f64,
    /// Number of gaps, 1 to [`MAX_PATH_STEPS`] (one: `from_m` alone).
    pub steps: usize,
}

impl GapRange {
    /// Parses FROM:TO:STEPS ("20nm:1nm:4"), named `name` in errors.
    pub fn parse(text: &str, name: &str) -> Result<GapRange, String> {
        let (from_m, to_m, steps) = parse_positive_path(text, Dimension::Length, name)?;
        Ok(GapRange { from_m, to_m, steps })
    }

    /// Checks the range (a request built without [`GapRange::parse`]), named `name`.
    pub fn check(&self, name: &str) -> Result<(), String> {
        check_positive_path(self.from_m, self.to_m, self.steps, "m", name)
    }

    /// The mean gaps, m, evenly spaced from `from_m` to `to_m`.
    pub fn values_m(&self) -> Vec<f64> {
        path_values(self.from_m, self.to_m, self.steps)
    }
}

/// A sweep of normal loads (`contact --sweep`), each solved from the previous equilibrium; a
/// front end hands the engine its loads ([`LoadRange::values_n`], `ContactRequest::loads_n`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadRange {
    /// First load, N (compressive positive), in the domain of `load`.
    pub from_n: f64,
    /// Last load, N, in the domain of `load`.
    pub to_n: f64,
    /// Number of loads, >= 2.
    pub steps: usize,
}

impl LoadRange {
    /// Parses FROM:TO:STEPS ("0uN:10uN:21"): loads in the domain of `load`, 2 to `max_steps`
    /// steps (checked before any load is made); `name` (a flag or an argument) names the text in
    /// errors, and `advice` says how to raise the limit ("raise it with --max-sweep-steps if you
    /// mean it").
    pub fn parse(text: &str, name: &str, max_steps: usize, advice: &str) -> Result<LoadRange, String> {
        let parts: Vec<&str> = text.split(':').collect();
        if parts.len() != 3 {
            return Err(format!("{name} {text:?}: expected FROM:TO:STEPS, like \"0uN:10uN:21\""));
        }
        let f = |s: &str, what: &str| {
            let v = parse_quantity_checked(s, Dimension::Force, Constraint::Finite)
                .map_err(|e| format!("{name} {what}: {e}"))?;
            stiction_scenario::domain::check_value("load", "load", v)
                .map_err(|e| format!("{name} {what}: {}", e.message))?;
            Ok::<f64, String>(v)
        };
        let (from_n, to_n) = (f(parts[0], "FROM")?, f(parts[1], "TO")?);
        let steps: usize = parts[2]
            .trim()
            .parse()
            .ok()
            .filter(|n| *n >= 2)
            .ok_or_else(|| format!("{name} STEPS {:?}: expected a whole number >= 2", parts[2]))?;
        if steps > max_steps {
            return Err(format!(
                "{name} STEPS {steps}: more than the limit of {max_steps} steps (one equilibrium solve and about 100 \
                 bytes of output each: {:.1e} bytes); {advice}",
                steps as f64 * 100.0
            ));
        }
        Ok(LoadRange { from_n, to_n, steps })
    }

    /// The loads, N, evenly spaced from `from_n` to `to_n`.
    pub fn values_n(&self) -> Vec<f64> {
        path_values(self.from_n, self.to_n, self.steps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_is_its_ends_and_evenly_spaced_steps() {
        // 1, 10.5, 20 MPa: the middle one is the mean of the ends (exact in binary for these).
        let r = PressureRange::parse("1MPa:20MPa:3", "--sweep").unwrap();
        assert_eq!(r, PressureRange { from_pa: 1e6, to_pa: 20e6, steps: 3 });
        assert_eq!(r.values_pa(), vec![1e6, 10.5e6, 20e6]);
        // A falling gap path keeps its order; one step is FROM alone.
        let g = GapRange::parse("20nm:1nm:4", "--gap-sweep").unwrap();
        let v = g.values_m();
        assert_eq!(v.len(), 4);
        // The ends are the parsed quantities (a unit conversion: a few ulps, 1e-12 relative).
        assert!((v[0] / 20e-9 - 1.0).abs() < 1e-12 && (v[3] / 1e-9 - 1.0).abs() < 1e-12, "{v:?}");
        // Equal steps of (1 - 20) / 3 nm, to rounding (1e-12 relative).
        for w in v.windows(2) {
            assert!(((w[1] - w[0]) / (-19e-9 / 3.0) - 1.0).abs() < 1e-12, "evenly spaced: {v:?}");
        }
        assert_eq!(GapRange::parse("5nm:9nm:1", "gap_sweep").unwrap().values_m(), vec![5e-9]);
    }

    #[test]
    fn a_load_sweep_is_its_ends_and_evenly_spaced_loads_named_as_given() {
        // 0, 5, 10 uN: the middle one the mean of the ends (1e-12 relative: one unit conversion).
        let r = LoadRange::parse("0uN:10uN:3", "--sweep", 10, "").unwrap();
        assert_eq!(r.steps, 3);
        let v = r.values_n();
        assert!(v[0] == 0.0 && (v[1] / 5e-6 - 1.0).abs() < 1e-12 && (v[2] / 10e-6 - 1.0).abs() < 1e-12, "{v:?}");
        let e = LoadRange::parse("0uN:10uN", "sweep", 10, "").unwrap_err();
        assert_eq!(e, "sweep \"0uN:10uN\": expected FROM:TO:STEPS, like \"0uN:10uN:21\"");
        let e = LoadRange::parse("0uN:10uN:1", "--sweep", 10, "").unwrap_err();
        assert_eq!(e, "--sweep STEPS \"1\": expected a whole number >= 2");
        let e = LoadRange::parse("0uN:1m:3", "sweep", 10, "").unwrap_err();
        assert!(e.starts_with("sweep TO: "), "{e}");
        let e = LoadRange::parse("0uN:1uN:11", "sweep", 10, "raise it with max_sweep_steps=N").unwrap_err();
        assert!(e.starts_with("sweep STEPS 11: more than the limit of 10") && e.ends_with("max_sweep_steps=N"), "{e}");
    }

    #[test]
    fn errors_name_the_flag_or_argument_given() {
        let e = PressureRange::parse("1MPa:2MPa", "--sweep").unwrap_err();
        assert_eq!(e, "--sweep \"1MPa:2MPa\": expected FROM:TO:STEPS");
        let e = GapRange::parse("1nm:2nm:0", "gap_sweep").unwrap_err();
        assert_eq!(e, "gap_sweep \"1nm:2nm:0\": STEPS \"0\" must be an integer in 1..=10000");
        let e = PressureRange::parse("-1MPa:2MPa:3", "sweep").unwrap_err();
        assert!(e.starts_with("sweep: "), "{e}");
        // A pressure where a gap is expected is a unit error naming the argument.
        assert!(GapRange::parse("1MPa:2MPa:3", "gap_sweep").unwrap_err().starts_with("gap_sweep: "));
        // A typed range outside the domain is refused by its check.
        assert!(PressureRange { from_pa: f64::NAN, to_pa: 1.0, steps: 2 }.check("sweep").is_err());
        assert!(GapRange { from_m: 1e-9, to_m: 2e-9, steps: 0 }.check("gap_sweep").is_err());
        assert!(GapRange { from_m: 1e-9, to_m: 2e-9, steps: 10_001 }.check("gap_sweep").is_err());
        assert!(GapRange { from_m: 1e-9, to_m: 2e-9, steps: 10_000 }.check("gap_sweep").is_ok());
    }
}
