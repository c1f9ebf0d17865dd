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
    #[serde(rename = "v_clamp_v")]
    pub v_clamp: f64,
    /// Pull voltage at slip, V.
    #[serde(rename = "v_pull_v")]
    pub v_pull: f64,
}

/// Largest measured-voltage CSV read, bytes (256 MiB: about 10 million rows).
pub const MAX_MEASURED_CSV_BYTES: u64 = 256 << 20;

/// Reads a CSV with the header `v_clamp_v,v_pull_v` (more columns are allowed and ignored; a
/// `#` starts a comment line). The file must be a regular file of at most
/// [`MAX_MEASURED_CSV_BYTES`]. Every bad line is an error naming the file, the line and the value.
pub fn read_measured_voltages(path: &Path) -> Result<Vec<MeasuredSlip>, MeterError> {
    let text = stiction_units::io::read_input_text(path, MAX_MEASURED_CSV_BYTES)
        .map_err(|e| MeterError::Measured(e.to_string()))?;
    parse_measured_voltages(&text, &path.display().to_string())
}

/// Parses the text of a measured-voltage CSV; `source` names it in errors. One pass with the
/// `csv` crate (quoting, CRLF; a byte-order mark is removed by the file reader): linear in the size.
pub fn parse_measured_voltages(text: &str, source: &str) -> Result<Vec<MeasuredSlip>, MeterError> {
    let err = |line: u64, msg: String| MeterError::Measured(format!("{source}, line {line}: {msg}"));
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .comment(Some(b'#'))
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let csv_err = |e: csv::Error| {
        let line = e.position().map_or(0, |p| p.line());
        err(line, crate::short(&e.to_string()))
    };
    let header = r.headers().map_err(csv_err)?.clone();
    let hline = header.position().map_or(1, |p| p.line());
    if header.is_empty() || header.iter().all(str::is_empty) {
        return Err(err(1, "empty file; expected a header `v_clamp_v,v_pull_v`".into()));
    }
    let col = |name: &str| -> Result<usize, MeterError> {
        let found: Vec<usize> = header.iter().enumerate().filter(|(_, n)| *n == name).map(|(i, _)| i).collect();
        match found.as_slice() {
            [k] => Ok(*k),
            [] => Err(err(
                hline,
                format!(
                    "no column `{name}` in the header {}; expected `v_clamp_v,v_pull_v`",
                    crate::short(&format!("{:?}", header.iter().collect::<Vec<_>>()))
                ),
            )),
            _ => Err(err(hline, format!("column `{name}` appears {} times; expected it once", found.len()))),
        }
    };
    let (ic, ip) = (col("v_clamp_v")?, col("v_pull_v")?);
    let mut out = Vec::new();
    let mut rec = csv::StringRecord::new();
    while r.read_record(&mut rec).map_err(csv_err)? {
        let line = rec.position().map_or(0, |p| p.line());
        if rec.iter().all(str::is_empty) {
            continue;
        }
        let get = |k: usize, name: &str| -> Result<f64, MeterError> {
            let raw = rec.get(k).ok_or_else(|| err(line, format!("missing column `{name}` ({} fields)", rec.len())))?;
            match raw.parse::<f64>() {
                Ok(v) if v.is_finite() && (0.0..=MAX_MEASURED_VOLTAGE_V).contains(&v) => Ok(v),
                _ => Err(err(
                    line,
                    format!(
                        "{name} = {:?}: expected a non-negative voltage in V, at most {MAX_MEASURED_VOLTAGE_V:e} V",
                        crate::short(raw)
                    ),
                )),
            }
        };
        out.push(MeasuredSlip { v_clamp: get(ic, "v_clamp_v")?, v_pull: get(ip, "v_pull_v")? });
    }
    if out.is_empty() {
        return Err(err(hline, "no data lines after the header".into()));
    }
    Ok(out)
}

/// Highest voltage accepted in a measured CSV, V (the scenario's limit, see
/// [`stiction_scenario::MAX_VOLTAGE_V`]).
pub const MAX_MEASURED_VOLTAGE_V: f64 = stiction_scenario::MAX_VOLTAGE_V;

/// One measured slip beside the virtual meter at the same clamp voltage.
#[derive(Debug, Clone, Serialize)]
pub struct ComparedPoint {
    /// Clamp voltage, V (JSON `v_clamp_v`).
    #[serde(rename = "v_clamp_v")]
    pub v_clamp: f64,
    /// Measured pull voltage at slip, V (JSON `v_pull_measured_v`).
    #[serde(rename = "v_pull_measured_v")]
    pub v_pull_measured: f64,
    /// Virtual pull voltage at slip, V (None: no contact or no slip in the model; JSON `v_pull_model_v`).
    #[serde(rename = "v_pull_model_v")]
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
    /// Why the measured data have no eq. 10 fit, when they have none (fewer than three distinct
    /// loads above zero).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured_fit_note: Option<String>,
}

impl Meter {
    /// Runs the virtual meter at the measured clamp voltages and compares: the pull voltages, and
    /// eq. 10 fitted to the measured data reduced with `reduction` (the lab's nominal values).
    pub fn compare(&mut self, measured: &[MeasuredSlip], reduction: Reduction) -> Result<Comparison, MeterError> {
        let limit = self.protocol.max_clamp_voltages.unwrap_or(stiction_scenario::DEFAULT_MAX_CLAMP_VOLTAGES);
        if measured.len() as u64 > limit {
            return Err(MeterError::Measured(format!(
                "{} measured rows: the virtual meter runs once per row and the limit is {limit} clamp voltages \
                 (`meter.max_clamp_voltages`, default {}); raise `meter.max_clamp_voltages` if you mean it",
                measured.len(),
                stiction_scenario::DEFAULT_MAX_CLAMP_VOLTAGES
            )));
        }
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
            measured_fit_note: crate::fit::no_fit_reason(&pairs),
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
        let e = parse_measured_voltages("v_clamp_v,v_pull_v,v_pull_v\n25,1,2\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("`v_pull_v` appears 2 times"), "{e}");
        let e = parse_measured_voltages("v_clamp_v,v_pull_v\n25,1e200\n", "m.csv").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("at most"), "{e}");
        // Quoting, CRLF and a BOM as a spreadsheet writes them.
        let ok = parse_measured_voltages("\u{feff}\"v_clamp_v\",v_pull_v\r\n\"25\",30\r\n", "m.csv").unwrap();
        assert_eq!(ok, vec![MeasuredSlip { v_clamp: 25.0, v_pull: 30.0 }]);
    }
}
