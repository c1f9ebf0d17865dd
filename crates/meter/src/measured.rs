//! Measured (V_clamp, V_pull) pairs from a real friction meter: the one reader of
//! measured-voltage CSVs (`stiction run` with a `measured` section and `stiction fit` read files
//! through it, so they accept the same files with the same messages), the rows an analysis leaves
//! out with their reasons, and the comparison with the virtual meter.
//!
//! Columns (units in the names): `v_clamp_v` and `v_pull_v` (required), `v_pull_sd_v` (optional,
//! the standard deviation of each pull voltage, V) and `device` (optional, a label; several devices
//! in one file each get their own eq. 10 fit in `stiction fit`). Other columns are ignored. Fields
//! are separated by commas, semicolons or tabs (the one the header line uses). A UTF-8
//! byte-order mark, CRLF line ends, `#` comment lines, quoted fields and blanks around fields are
//! accepted. A bad cell is an error naming the file, line, column and value; rows that are readable
//! but cannot be used (below first contact, no slip recorded) are listed by [`select_rows`] with
//! their line and reason.

use std::path::Path;

use serde::Serialize;

use crate::fit::LineFit;
use crate::{Meter, MeterError, Reduction};

/// Largest measured-voltage CSV read, bytes (512 MiB: about 25 million rows of two voltages).
pub const MAX_MEASURED_CSV_BYTES: u64 = 512 << 20;
/// Largest number of data rows accepted.
pub const MAX_MEASURED_ROWS: usize = 20_000_000;

/// The column names the reader accepts (units in the names: volts).
pub const ACCEPTED_COLUMNS: [&str; 4] = ["v_clamp_v", "v_pull_v", "v_pull_sd_v", "device"];

/// Why a measured-voltage file cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum VoltageCsvError {
    /// The file cannot be read (not a regular file, too large, unreadable).
    #[error(transparent)]
    File(#[from] stiction_units::io::FileError),
    /// The file is wrong at a line (and column).
    #[error("{file}, line {line}{}: {message}", column.as_ref().map(|c| format!(", column `{c}`")).unwrap_or_default())]
    Data {
        /// File.
        file: String,
        /// Line (1-based).
        line: u64,
        /// Column name.
        column: Option<String>,
        /// What is wrong and what was expected.
        message: String,
    },
}

/// One measured slip.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// Line of the file where the row starts (1-based).
    pub line: u64,
    /// Device label ("" when the file has no `device` column).
    pub device: String,
    /// Clamp voltage, V.
    pub v_clamp_v: f64,
    /// Pull voltage at the onset of slip, V.
    pub v_pull_v: f64,
    /// Standard deviation of the pull voltage, V (from the `v_pull_sd_v` column).
    pub v_pull_sd_v: Option<f64>,
}

/// The rows of a measured-voltage file.
#[derive(Debug, Clone, Serialize)]
pub struct Dataset {
    /// Where the rows came from (file name, for messages).
    pub source: String,
    /// The rows in file order.
    pub rows: Vec<Row>,
    /// Whether the file has a `v_pull_sd_v` column.
    pub has_sd: bool,
    /// Whether the file has a `device` column.
    pub has_device: bool,
}

/// A row left out of an analysis, with its line and the reason.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Rejected {
    /// File line.
    pub line: u64,
    /// Why.
    pub reason: String,
}

/// Splits the rows into used ones (L > 0 with the nominal values, V_pull > 0) and rejected ones,
/// each with its line and reason. `stiction fit` and the comparison of `stiction run` use the
/// same rule.
pub fn select_rows<'a>(rows: &'a [Row], reduction: &Reduction) -> (Vec<&'a Row>, Vec<Rejected>) {
    let mut used = Vec::with_capacity(rows.len());
    let mut rejected = Vec::new();
    for r in rows {
        let load = reduction.a_clamp_n_per_v2 * r.v_clamp_v * r.v_clamp_v - reduction.spring_force_n;
        if load.is_nan() || load <= 0.0 {
            rejected.push(Rejected {
                line: r.line,
                reason: format!(
                    "below first contact: L = a_clamp V_clamp^2 - F_spring = {} <= 0 with the nominal values",
                    stiction_units::format_quantity(load, stiction_units::Dimension::Force)
                ),
            });
        } else if r.v_pull_v <= 0.0 {
            rejected.push(Rejected { line: r.line, reason: "V_pull = 0 V: no slip recorded".into() });
        } else {
            used.push(r);
        }
    }
    (used, rejected)
}

/// Reads a measured-voltage CSV through [`stiction_units::io::read_input`] (regular files only,
/// at most [`MAX_MEASURED_CSV_BYTES`]).
pub fn read_measured_voltages(path: &Path) -> Result<Dataset, VoltageCsvError> {
    let bytes = stiction_units::io::read_input(path, MAX_MEASURED_CSV_BYTES)?;
    parse_measured_voltages(&bytes, &path.display().to_string())
}

fn is_voltage_name_without_unit(name: &str) -> bool {
    let stem = ["v_clamp", "vclamp", "clamp", "v_pull", "vpull", "pull", "v_pull_sd", "pull_sd", "sd"];
    stem.contains(&name) || (name.starts_with("v_clamp") || name.starts_with("v_pull")) && !name.ends_with("_v")
}

/// Parses the bytes of a measured-voltage CSV; `source` names it in errors. One pass with the `csv`
/// crate: linear in the size.
pub fn parse_measured_voltages(bytes: &[u8], source: &str) -> Result<Dataset, VoltageCsvError> {
    let table = CsvText::new(bytes);
    let empty = |message: String| VoltageCsvError::Data { file: source.into(), line: 1, column: None, message };
    if table.is_blank() {
        return Err(empty(format!(
            "the file is empty; expected a header line with the columns `v_clamp_v,v_pull_v` (optional {:?})",
            &ACCEPTED_COLUMNS[2..]
        )));
    }
    let separator = table.separator;
    let mut reader = table.reader();
    let mut record = csv::ByteRecord::new();
    let line_of = |r: &csv::ByteRecord| table.line_of(r);
    let Some(header_line) = table.header(&mut reader, &mut record, source)? else {
        return Err(empty("only comments or blank lines; expected a header `v_clamp_v,v_pull_v`".into()));
    };
    let header_err =
        |message: String| VoltageCsvError::Data { file: source.into(), line: header_line, column: None, message };
    let names: Vec<String> =
        record.iter().map(|f| String::from_utf8_lossy(f).trim().to_ascii_lowercase()).collect::<Vec<_>>();
    let mut col = [None::<usize>; 4];
    for (k, name) in names.iter().enumerate() {
        if let Some(which) = ACCEPTED_COLUMNS.iter().position(|a| a == name) {
            if let Some(first) = col[which] {
                return Err(header_err(format!(
                    "column `{name}` appears twice (columns {} and {}); each column may appear once",
                    first + 1,
                    k + 1
                )));
            }
            col[which] = Some(k);
        } else if is_voltage_name_without_unit(name) {
            return Err(header_err(format!(
                "column {} gives no unit (read with the separator {}); accepted names (unit in the name, volts): {ACCEPTED_COLUMNS:?}",
                stiction_units::text::excerpt(name),
                separator_name(separator)
            )));
        }
    }
    let (Some(ic), Some(ip)) = (col[0], col[1]) else {
        let missing: Vec<&str> =
            [(col[0], "v_clamp_v"), (col[1], "v_pull_v")].iter().filter(|c| c.0.is_none()).map(|c| c.1).collect();
        return Err(header_err(format!(
            "missing column(s) {missing:?} in the header {} (read with the separator {}); accepted names (unit in the name, volts): {ACCEPTED_COLUMNS:?}; accepted separators: comma, semicolon, tab",
            header_excerpt(&names),
            separator_name(separator)
        )));
    };
    let (isd, idev) = (col[2], col[3]);
    let mut rows = Vec::with_capacity(table.line_count().min(MAX_MEASURED_ROWS));
    while reader.read_byte_record(&mut record).map_err(|e| csv_error(source, &e))? {
        if record.len() == 1 && record[0].is_empty() {
            continue;
        }
        let line = line_of(&record);
        if rows.len() >= MAX_MEASURED_ROWS {
            return Err(VoltageCsvError::Data {
                file: source.into(),
                line,
                column: None,
                message: format!("more than {MAX_MEASURED_ROWS} data rows; split the file"),
            });
        }
        let cell = |k: usize, name: &str| -> Result<&[u8], VoltageCsvError> {
            record.get(k).ok_or_else(|| VoltageCsvError::Data {
                file: source.into(),
                line,
                column: Some(name.into()),
                message: format!("missing: the row has {} field(s), the header {}", record.len(), names.len()),
            })
        };
        let number = |k: usize, name: &str, positive: bool| -> Result<f64, VoltageCsvError> {
            let raw = cell(k, name)?;
            let text = std::str::from_utf8(raw).unwrap_or("");
            let bad = |what: &str| VoltageCsvError::Data {
                file: source.into(),
                line,
                column: Some(name.into()),
                message: format!("value {:?}: {what}", crate::short(&String::from_utf8_lossy(raw))),
            };
            let x: f64 = text.parse().map_err(|_| {
                if separator != b',' && text.contains(',') {
                    bad("expected a number in volts with a decimal point (the file's separator is a semicolon or tab; a decimal comma is not read)")
                } else {
                    bad("expected a number in volts")
                }
            })?;
            if !x.is_finite() {
                return Err(bad("expected a finite number in volts (NaN and infinity are not voltages)"));
            }
            if positive && x <= 0.0 {
                return Err(bad("expected a standard deviation > 0 V"));
            }
            if x < 0.0 {
                return Err(bad("expected a voltage >= 0 V (the reduction uses V^2; record magnitudes)"));
            }
            if x > MAX_MEASURED_VOLTAGE_V {
                return Err(bad(&format!("expected a voltage of at most {MAX_MEASURED_VOLTAGE_V:e} V")));
            }
            Ok(x)
        };
        let v_clamp_v = number(ic, "v_clamp_v", false)?;
        let v_pull_v = number(ip, "v_pull_v", false)?;
        let v_pull_sd_v = isd.map(|k| number(k, "v_pull_sd_v", true)).transpose()?;
        let device = match idev {
            Some(k) => String::from_utf8_lossy(cell(k, "device")?).into_owned(),
            None => String::new(),
        };
        rows.push(Row { line, device, v_clamp_v, v_pull_v, v_pull_sd_v });
    }
    if rows.is_empty() {
        return Err(header_err("no data rows after the header".into()));
    }
    Ok(Dataset { source: source.into(), rows, has_sd: isd.is_some(), has_device: idev.is_some() })
}

/// The text of a CSV as the readers of measured data take it: a UTF-8 byte-order mark dropped,
/// `#` comment lines blanked byte for byte (so the byte offsets the csv crate reports still map to
/// the file's lines; its own line counter skips comments), the separator detected
/// ([`detect_separator`]). Shared by the measured-voltage reader and the structure-threshold reader
/// ([`crate::structure_measured`]).
pub(crate) struct CsvText {
    owned: Vec<u8>,
    newlines: Vec<usize>,
    blank: bool,
    /// The field separator.
    pub separator: u8,
}

impl CsvText {
    /// Prepares `bytes`.
    pub fn new(bytes: &[u8]) -> CsvText {
        let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        let blank = bytes.iter().all(|b| b.is_ascii_whitespace());
        let mut owned = bytes.to_vec();
        let mut start = 0;
        while start < owned.len() {
            let end = owned[start..].iter().position(|&b| b == b'\n').map_or(owned.len(), |k| start + k);
            if owned[start] == b'#' {
                owned[start..end].fill(b' ');
            }
            start = end + 1;
        }
        let separator = detect_separator(&owned);
        let newlines = owned.iter().enumerate().filter(|(_, b)| **b == b'\n').map(|(i, _)| i).collect();
        CsvText { owned, newlines, blank, separator }
    }

    /// Whether the file holds only blanks (before comments are blanked).
    pub fn is_blank(&self) -> bool {
        self.blank
    }

    /// The number of line ends (a bound on the rows).
    pub fn line_count(&self) -> usize {
        self.newlines.len()
    }

    /// A csv reader over the text: no headers, the detected separator, fields trimmed, rows of
    /// any length.
    pub fn reader(&self) -> csv::Reader<&[u8]> {
        csv::ReaderBuilder::new()
            .has_headers(false)
            .delimiter(self.separator)
            .trim(csv::Trim::All)
            .flexible(true)
            .from_reader(&self.owned[..])
    }

    /// The 1-based line of a record (from its byte offset; a record's offset may point at the end
    /// of the previous line's CRLF, so line ends are skipped first).
    pub fn line_of(&self, r: &csv::ByteRecord) -> u64 {
        let Some(p) = r.position() else { return 0 };
        let mut b = p.byte() as usize;
        while b < self.owned.len() && (self.owned[b] == b'\n' || self.owned[b] == b'\r') {
            b += 1;
        }
        1 + self.newlines.partition_point(|&i| i < b) as u64
    }

    /// Reads up to the header, the first record that is not blank, into `record`: its line, or
    /// None when the file has only comments or blank lines.
    pub fn header(
        &self,
        reader: &mut csv::Reader<&[u8]>,
        record: &mut csv::ByteRecord,
        source: &str,
    ) -> Result<Option<u64>, VoltageCsvError> {
        loop {
            if !reader.read_byte_record(record).map_err(|e| csv_error(source, &e))? {
                return Ok(None);
            }
            if !(record.len() == 1 && record[0].is_empty()) {
                return Ok(Some(self.line_of(record)));
            }
        }
    }
}

/// The field separator of the file: the one of comma, semicolon and tab that occurs in the first
/// line that is not blank (comment lines are blank by then); comma when the line has a comma or
/// none of them.
fn detect_separator(bytes: &[u8]) -> u8 {
    let first = bytes.split(|&b| b == b'\n').find(|l| !l.iter().all(|b| b.is_ascii_whitespace())).unwrap_or_default();
    let count = |c: u8| first.iter().filter(|&&b| b == c).count();
    if count(b',') > 0 {
        b','
    } else if count(b';') > 0 {
        b';'
    } else if count(b'\t') > 0 {
        b'\t'
    } else {
        b','
    }
}

pub(crate) fn separator_name(sep: u8) -> &'static str {
    match sep {
        b';' => "semicolon `;`",
        b'\t' => "tab",
        _ => "comma `,`",
    }
}

pub(crate) fn csv_error(source: &str, e: &csv::Error) -> VoltageCsvError {
    let line = e.position().map(|p| p.line()).unwrap_or(0);
    VoltageCsvError::Data {
        file: source.into(),
        line,
        column: None,
        message: format!("not readable as CSV: {}", crate::short(&e.to_string())),
    }
}

/// Highest voltage accepted in a measured CSV, V (the scenario's limit, see
/// [`stiction_scenario::MAX_VOLTAGE_V`]).
pub const MAX_MEASURED_VOLTAGE_V: f64 = stiction_scenario::MAX_VOLTAGE_V;

/// One measured slip beside the virtual meter at the same clamp voltage.
#[derive(Debug, Clone, Serialize)]
pub struct ComparedPoint {
    /// Line of the measured file.
    pub line: u64,
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
    /// Why the model gives no pull voltage here (its point's reason: no contact, no slip, ...).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_note: Option<String>,
}

/// The measured data beside the model.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// Per measured slip.
    pub points: Vec<ComparedPoint>,
    /// Root mean square of the V_pull^2 residuals over the points the model could give, V^2.
    pub rms_v_pull_sq_residual_v2: Option<f64>,
    /// Rows left out of the measured eq. 10 fit, with their line and reason (the rule of
    /// [`select_rows`], as in `stiction fit`); the model still runs at their clamp voltages.
    pub rows_rejected: Vec<Rejected>,
    /// Eq. 10 fitted to the measured data (rows with L > 0 and V_pull > 0), as the paper does.
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
    pub fn compare(&mut self, data: &Dataset, reduction: Reduction) -> Result<Comparison, MeterError> {
        let measured = &data.rows;
        let limit = self.protocol.max_clamp_voltages.unwrap_or(stiction_scenario::DEFAULT_MAX_CLAMP_VOLTAGES);
        if measured.len() as u64 > limit {
            return Err(MeterError::Measured(format!(
                "{} measured rows: the virtual meter runs once per row and the limit is {limit} clamp voltages \
                 (`meter.max_clamp_voltages`, default {}); raise `meter.max_clamp_voltages` if you mean it",
                measured.len(),
                stiction_scenario::DEFAULT_MAX_CLAMP_VOLTAGES
            )));
        }
        let voltages: Vec<f64> = measured.iter().map(|m| m.v_clamp_v).collect();
        let model = self.run_at(&voltages, &mut |_, _| {})?;
        let mut points = Vec::with_capacity(measured.len());
        for (m, p) in measured.iter().zip(&model.points) {
            let v_pull_model = p.v_pull;
            let model_reason = p.reason.clone();
            points.push(ComparedPoint {
                line: m.line,
                v_clamp: m.v_clamp_v,
                v_pull_measured: m.v_pull_v,
                v_pull_model,
                friction_measured_n: reduction.a_pull_n_per_v2 * m.v_pull_v * m.v_pull_v,
                load_measured_n: reduction.a_clamp_n_per_v2 * m.v_clamp_v * m.v_clamp_v - reduction.spring_force_n,
                v_pull_sq_residual_v2: v_pull_model.map(|v| v * v - m.v_pull_v * m.v_pull_v),
                model_note: v_pull_model.is_none().then(|| {
                    model_reason.clone().unwrap_or_else(|| "the model has no slip at this clamp voltage".into())
                }),
            });
        }
        let res: Vec<f64> = points.iter().filter_map(|p| p.v_pull_sq_residual_v2).collect();
        let rms = (!res.is_empty()).then(|| (res.iter().map(|r| r * r).sum::<f64>() / res.len() as f64).sqrt());
        let (used, rows_rejected) = select_rows(measured, &reduction);
        let pairs: Vec<(f64, f64)> = used
            .iter()
            .map(|m| {
                let load = reduction.a_clamp_n_per_v2 * m.v_clamp_v * m.v_clamp_v - reduction.spring_force_n;
                (load, reduction.a_pull_n_per_v2 * m.v_pull_v * m.v_pull_v)
            })
            .collect();
        let eq10 = crate::fit::eq10(&pairs);
        Ok(Comparison {
            points,
            rms_v_pull_sq_residual_v2: rms,
            rows_rejected,
            measured_fit: eq10.line,
            mu_apparent_measured: eq10.mu_apparent,
            apparent_adhesion_force_measured_n: eq10.apparent_adhesion_force_n,
            measured_fit_note: eq10.note,
        })
    }
}

/// The header's names as an error quotes them: at most four, each a short sanitised excerpt, never
/// a whole line of a file that is not a voltage CSV (`/etc/passwd`'s first line).
pub(crate) fn header_excerpt(names: &[String]) -> String {
    let shown: Vec<String> = names.iter().take(4).map(|n| stiction_units::text::excerpt(n)).collect();
    let more = names.len().saturating_sub(4);
    if more > 0 { format!("[{}, and {more} more]", shown.join(", ")) } else { format!("[{}]", shown.join(", ")) }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(text: &str) -> String {
        parse_measured_voltages(text.as_bytes(), "m.csv").unwrap_err().to_string()
    }

    #[test]
    fn reads_bom_crlf_comments_quotes_and_extra_columns() {
        let text = "\u{feff}# synthetic\r\nnote,\"v_clamp_v\",v_pull_v,device\r\n\"a, b\",25,30.5,\"d1\"\r\n\r\n# mid\r\nx, 26 ,31,d2\r\n";
        let d = parse_measured_voltages(text.as_bytes(), "m.csv").unwrap();
        assert_eq!(d.rows.len(), 2);
        assert_eq!(d.rows[0], Row { line: 3, device: "d1".into(), v_clamp_v: 25.0, v_pull_v: 30.5, v_pull_sd_v: None });
        assert_eq!(d.rows[1].line, 6);
        assert_eq!(d.rows[1].v_clamp_v, 26.0);
        assert!(d.has_device && !d.has_sd);
    }

    #[test]
    fn bad_files_are_errors_naming_line_column_and_value() {
        assert!(msg("").contains("empty"));
        assert!(msg("# only a comment\n").contains("header"));
        assert!(msg("v_clamp_v,v_pull_v\n").contains("no data rows"));
        let e = msg("v_clamp_v,v_pull_v\n25,30\n26,abc\n");
        assert!(e.contains("m.csv, line 3") && e.contains("v_pull_v") && e.contains("\"abc\""), "{e}");
        let e = msg("v_clamp_v,v_pull_v\n25,-3\n");
        assert!(e.contains("line 2") && e.contains(">= 0"), "{e}");
        for bad in ["NaN", "inf", "-inf"] {
            let e = msg(&format!("v_clamp_v,v_pull_v\n{bad},3\n"));
            assert!(e.contains("finite") && e.contains("v_clamp_v"), "{e}");
        }
        let e = msg("v_clamp_v,v_pull_v,v_clamp_v\n1,2,3\n");
        assert!(e.contains("twice"), "{e}");
        let e = msg("v_clamp_v,x\n1,2\n");
        assert!(e.contains("missing column") && e.contains("v_pull_v"), "{e}");
        let e = msg("v_clamp,v_pull\n1,2\n");
        assert!(e.contains("gives no unit") && e.contains("v_clamp_v"), "{e}");
        // A file that is not a voltage CSV is never echoed: each header name is quoted through a
        // 20-character excerpt, at most four of them.
        let secret = "root:x:0:0:root:/root:/bin/bash,daemon:x:1:1:daemon,bin:x:2:2,sys:x:3:3,sync:x:4:65534";
        let e = msg(&format!("{secret}\n1,2\n"));
        assert!(!e.contains("/bin/bash") && e.contains("(31 bytes)") && e.contains("and 1 more"), "{e}");
        let e = msg("v_clamp_v,v_pull_v\n25\n");
        assert!(e.contains("line 2") && e.contains("v_pull_v") && e.contains("missing"), "{e}");
        let e = msg("v_clamp_v,v_pull_v,v_pull_sd_v\n25,30,0\n");
        assert!(e.contains("v_pull_sd_v") && e.contains("> 0"), "{e}");
        let e = msg("v_clamp_v,v_pull_v\n25,1e200\n");
        assert!(e.contains("line 2") && e.contains("at most"), "{e}");
    }

    /// Semicolon- and tab-separated files read like comma-separated ones (the separator of the
    /// header line); a decimal comma in a semicolon file is named in the error.
    #[test]
    fn semicolon_and_tab_separators_are_detected() {
        for sep in [";", "\t"] {
            let text =
                format!("# lab export\nv_clamp_v{sep}v_pull_v{sep}device\n25{sep}30.5{sep}d1\n26{sep}31{sep}d2\n");
            let d = parse_measured_voltages(text.as_bytes(), "m.csv").unwrap();
            assert_eq!(d.rows.len(), 2, "separator {sep:?}");
            assert_eq!((d.rows[0].v_clamp_v, d.rows[0].v_pull_v, d.rows[1].device.as_str()), (25.0, 30.5, "d2"));
            assert_eq!(d.rows[0].line, 3);
        }
        let e = msg("v_clamp_v;v_pull_v\n25,5;30\n");
        assert!(e.contains("line 2") && e.contains("decimal point"), "{e}");
        let e = msg("v_clamp_v|v_pull_v\n25|30\n");
        assert!(e.contains("separator comma") && e.contains("semicolon, tab"), "{e}");
    }

    /// The rows an analysis leaves out: L <= 0 with the nominal reduction, or no slip.
    #[test]
    fn rows_below_contact_or_without_slip_are_rejected_with_their_line() {
        let d = parse_measured_voltages(b"v_clamp_v,v_pull_v\n10,5\n25,0\n26,31\n", "m.csv").unwrap();
        // The paper's reduction: first contact at V_clamp = sqrt(7e-6 / 1.4e-8) = 22.4 V.
        let red = Reduction { a_clamp_n_per_v2: 1.4e-8, a_pull_n_per_v2: 3.8e-9, spring_force_n: 7e-6 };
        let (used, rejected) = select_rows(&d.rows, &red);
        assert_eq!(used.len(), 1);
        assert_eq!(used[0].line, 4);
        assert_eq!(rejected.len(), 2);
        assert!(rejected[0].line == 2 && rejected[0].reason.contains("below first contact"), "{rejected:?}");
        assert!(rejected[1].line == 3 && rejected[1].reason.contains("no slip"), "{rejected:?}");
    }
}
