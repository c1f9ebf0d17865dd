//! Measured (V_clamp, V_pull) pairs from a real friction meter, reduced and compared with the
//! virtual one.

use std::path::Path;

use serde::Serialize;

use crate::fit::LineFit;
use crate::{Meter, MeterError, Reduction};

/// One measured slip: clamp voltage and pull voltage at the onset of slip, V.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MeasuredSlip {
    /// Clamp voltage, V.
    pub v_clamp: f64,
    /// Pull voltage at slip, V.
    pub v_pull: f64,
}

/// Reads a CSV with the header `v_clamp_v,v_pull_v` (more columns are allowed and ignored; a
/// `#` starts a comment line). Every bad line is an error naming the file, the line and the value.
pub fn read_measured_voltages(path: &Path) -> Result<Vec<MeasuredSlip>, MeterError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| MeterError::Measured(format!("cannot read {}: {e}", path.display())))?;
    parse_measured_voltages(&text, &path.display().to_string())
}

/// Parses the text of a measured-voltage CSV; `source` names it in errors.
pub fn parse_measured_voltages(text: &str, source: &str) -> Result<Vec<MeasuredSlip>, MeterError> {
    let err = |line: usize, msg: String| MeterError::Measured(format!("{source}, line {line}: {msg}"));
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let (hline, header) =
        lines.next().ok_or_else(|| err(1, "empty file; expected a header `v_clamp_v,v_pull_v`".into()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let col = |name: &str| {
        names.iter().position(|n| *n == name).ok_or_else(|| {
            err(hline + 1, format!("no column `{name}` in the header {names:?}; expected `v_clamp_v,v_pull_v`"))
        })
    };
    let (ic, ip) = (col("v_clamp_v")?, col("v_pull_v")?);
    let mut out = Vec::new();
    for (i, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let get = |k: usize, name: &str| -> Result<f64, MeterError> {
            let raw = fields
                .get(k)
                .ok_or_else(|| err(i + 1, format!("missing column `{name}` ({} fields)", fields.len())))?;
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
                _ => Err(err(i + 1, format!("{name} = {raw:?}: expected a non-negative voltage in V"))),
            }
        };
        out.push(MeasuredSlip { v_clamp: get(ic, "v_clamp_v")?, v_pull: get(ip, "v_pull_v")? });
    }
    if out.is_empty() {
        return Err(err(hline + 1, "no data lines after the header".into()));
    }
    Ok(out)
}

/// One measured slip beside the virtual meter at the same clamp voltage.
#[derive(Debug, Clone, Serialize)]
pub struct ComparedPoint {
    /// Clamp voltage, V.
    pub v_clamp: f64,
    /// Measured pull voltage at slip, V.
    pub v_pull_measured: f64,
    /// Virtual pull voltage at slip, V (None: no contact or no slip in the model).
    pub v_pull_model: Option<f64>,
    /// Measured friction and load reduced with the nominal factors, N.
    pub friction_measured_n: f64,
    /// Measured load a_clamp V_clamp^2 - F_spring, N.
    pub load_measured_n: f64,
    /// V_pull,model^2 - V_pull,measured^2, V^2.
    pub v_pull_sq_residual_v2: Option<f64>,
}

/// The measured data beside the model.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Per measured slip.
    pub points: Vec<ComparedPoint>,
    /// Root mean square of the V_pull^2 residuals over the points the model could give, V^2.
    pub rms_v_pull_sq_residual_v2: Option<f64>,
    /// Eq. 10 fitted to the measured data (L > 0), as the paper does.
    pub measured_fit: Option<LineFit>,
    /// mu_e,a of the measured data.
    pub mu_apparent_measured: Option<f64>,
    /// F_a0 of the measured data, N.
    pub apparent_adhesion_force_measured_n: Option<f64>,
}

impl Meter {
    /// Runs the virtual meter at the measured clamp voltages and compares: the pull voltages, and
    /// eq. 10 fitted to the measured data reduced with `reduction` (the lab's nominal values).
    pub fn compare(&mut self, measured: &[MeasuredSlip], reduction: Reduction) -> Result<Comparison, MeterError> {
        let voltages: Vec<f64> = measured.iter().map(|m| m.v_clamp).collect();
        let model = self.run_at(&voltages, &mut |_, _| {})?;
        let mut points = Vec::with_capacity(measured.len());
        for (m, p) in measured.iter().zip(&model.points) {
            let v_pull_model = p.v_pull;
            points.push(ComparedPoint {
                v_clamp: m.v_clamp,
                v_pull_measured: m.v_pull,
                v_pull_model,
                friction_measured_n: reduction.a_pull_n_per_v2 * m.v_pull * m.v_pull,
                load_measured_n: reduction.a_clamp_n_per_v2 * m.v_clamp * m.v_clamp - reduction.spring_force_n,
                v_pull_sq_residual_v2: v_pull_model.map(|v| v * v - m.v_pull * m.v_pull),
            });
        }
        let res: Vec<f64> = points.iter().filter_map(|p| p.v_pull_sq_residual_v2).collect();
        let rms = (!res.is_empty()).then(|| (res.iter().map(|r| r * r).sum::<f64>() / res.len() as f64).sqrt());
        let pairs: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.load_measured_n > 0.0)
            .map(|p| (p.load_measured_n, p.friction_measured_n))
            .collect();
        let (fit, mu, fa0) = crate::fit::eq10(&pairs);
        Ok(Comparison {
            points,
            rms_v_pull_sq_residual_v2: rms,
            measured_fit: fit,
            mu_apparent_measured: mu,
            apparent_adhesion_force_measured_n: fa0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_voltages_and_names_bad_lines() {
        let ok = parse_measured_voltages("# fig 5\nv_clamp_v,v_pull_v\n25,30.1\n27, 33.9\n", "m.csv").unwrap();
        assert_eq!(
            ok,
            vec![MeasuredSlip { v_clamp: 25.0, v_pull: 30.1 }, MeasuredSlip { v_clamp: 27.0, v_pull: 33.9 }]
        );
        let e = parse_measured_voltages("v_clamp_v,v_pull_v\n25,30\n26,abc\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("m.csv, line 3") && e.contains("\"abc\""), "{e}");
        let e = parse_measured_voltages("clamp,pull\n25,30\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("no column `v_clamp_v`"), "{e}");
        let e = parse_measured_voltages("v_clamp_v,v_pull_v\n25,-3\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("non-negative"), "{e}");
        assert!(parse_measured_voltages("v_clamp_v,v_pull_v\n", "m.csv").is_err());
        let e = parse_measured_voltages("v_clamp_v,v_pull_v\n25\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("missing column `v_pull_v`"), "{e}");
    }
}
