//! Measured friction-meter voltages: a CSV read with the `csv` crate.
//!
//! Columns (units in the names): `v_clamp_v` and `v_pull_v` (required), `v_pull_sd_v` (optional,
//! the standard deviation of each pull voltage, V) and `device` (optional, a label; several devices
//! in one file each get their own eq. 10 fit). Other columns are ignored. A UTF-8 byte-order mark,
//! CRLF line ends, `#` comment lines, quoted fields and blanks around fields are accepted. A bad
//! cell is an error naming the file, line, column and value; rows that are readable but cannot be
//! used (below first contact, no slip recorded) are listed by [`crate::select_rows`] with their
//! line and reason.

use std::path::Path;

use serde::Serialize;

use crate::FitError;

/// Largest data file read, bytes (about 25 million rows of two voltages).
pub const DATA_LIMIT_BYTES: u64 = 512 << 20;
/// Largest number of data rows accepted.
pub const MAX_ROWS: usize = 20_000_000;

/// The names the reader accepts (units in the names: volts).
pub const ACCEPTED_COLUMNS: [&str; 4] = ["v_clamp_v", "v_pull_v", "v_pull_sd_v", "device"];

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

/// Reads a measured-voltage CSV through [`stiction_units::io::read_input`] (regular files only,
/// at most [`DATA_LIMIT_BYTES`]).
pub fn read_voltages(path: &Path) -> Result<Dataset, FitError> {
    let bytes = stiction_units::io::read_input(path, DATA_LIMIT_BYTES)?;
    parse_voltages(&bytes, &path.display().to_string())
}

fn is_voltage_name_without_unit(name: &str) -> bool {
    let stem = ["v_clamp", "vclamp", "clamp", "v_pull", "vpull", "pull", "v_pull_sd", "pull_sd", "sd"];
    stem.contains(&name) || (name.starts_with("v_clamp") || name.starts_with("v_pull")) && !name.ends_with("_v")
}

/// Parses the bytes of a measured-voltage CSV; `source` names it in errors.
pub fn parse_voltages(bytes: &[u8], source: &str) -> Result<Dataset, FitError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let empty = |message: String| FitError::Data { file: source.into(), line: 1, column: None, message };
    if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(empty(format!(
            "the file is empty; expected a header line with the columns `v_clamp_v,v_pull_v` (optional {:?})",
            &ACCEPTED_COLUMNS[2..]
        )));
    }
    // Comment lines (`#` first) are blanked in a copy, byte for byte, so that the byte offsets the
    // csv crate reports still map to the file's lines (its own line counter skips comments).
    let mut owned = bytes.to_vec();
    let mut start = 0;
    while start < owned.len() {
        let end = owned[start..].iter().position(|&b| b == b'\n').map_or(owned.len(), |k| start + k);
        if owned[start] == b'#' {
            owned[start..end].fill(b' ');
        }
        start = end + 1;
    }
    let bytes = &owned[..];
    let mut reader =
        csv::ReaderBuilder::new().has_headers(false).trim(csv::Trim::All).flexible(true).from_reader(bytes);
    let mut record = csv::ByteRecord::new();
    // The csv crate's own line counter skips comment lines, so lines come from byte offsets.
    let newlines: Vec<usize> = bytes.iter().enumerate().filter(|(_, b)| **b == b'\n').map(|(i, _)| i).collect();
    // A record's offset may point at the end of the previous line's CRLF: skip line ends first.
    let line_at = |byte: u64| {
        let mut b = byte as usize;
        while b < owned.len() && (owned[b] == b'\n' || owned[b] == b'\r') {
            b += 1;
        }
        1 + newlines.partition_point(|&i| i < b) as u64
    };
    let line_of = |r: &csv::ByteRecord| r.position().map_or(0, |p| line_at(p.byte()));
    // The header: the first record that is not blank.
    let header_line;
    loop {
        let more = reader.read_byte_record(&mut record).map_err(|e| csv_error(source, &e))?;
        if !more {
            return Err(empty("only comments or blank lines; expected a header `v_clamp_v,v_pull_v`".into()));
        }
        if !(record.len() == 1 && record[0].is_empty()) {
            header_line = line_of(&record);
            break;
        }
    }
    let header_err = |message: String| FitError::Data { file: source.into(), line: header_line, column: None, message };
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
                "column `{name}` gives no unit; accepted names (unit in the name, volts): {ACCEPTED_COLUMNS:?}"
            )));
        }
    }
    let (Some(ic), Some(ip)) = (col[0], col[1]) else {
        let missing: Vec<&str> =
            [(col[0], "v_clamp_v"), (col[1], "v_pull_v")].iter().filter(|c| c.0.is_none()).map(|c| c.1).collect();
        return Err(header_err(format!(
            "missing column(s) {missing:?} in the header {names:?}; accepted names (unit in the name, volts): {ACCEPTED_COLUMNS:?}"
        )));
    };
    let (isd, idev) = (col[2], col[3]);
    let mut rows = Vec::with_capacity(newlines.len().min(MAX_ROWS));
    while reader.read_byte_record(&mut record).map_err(|e| csv_error(source, &e))? {
        if record.len() == 1 && record[0].is_empty() {
            continue;
        }
        let line = line_of(&record);
        if rows.len() >= MAX_ROWS {
            return Err(FitError::Data {
                file: source.into(),
                line,
                column: None,
                message: format!("more than {MAX_ROWS} data rows; split the file"),
            });
        }
        let cell = |k: usize, name: &str| -> Result<&[u8], FitError> {
            record.get(k).ok_or_else(|| FitError::Data {
                file: source.into(),
                line,
                column: Some(name.into()),
                message: format!("missing: the row has {} field(s), the header {}", record.len(), names.len()),
            })
        };
        let number = |k: usize, name: &str, positive: bool| -> Result<f64, FitError> {
            let raw = cell(k, name)?;
            let text = std::str::from_utf8(raw).unwrap_or("");
            let bad = |what: &str| FitError::Data {
                file: source.into(),
                line,
                column: Some(name.into()),
                message: format!("value {:?}: {what}", String::from_utf8_lossy(raw)),
            };
            let x: f64 = text.parse().map_err(|_| bad("expected a number in volts"))?;
            if !x.is_finite() {
                return Err(bad("expected a finite number in volts (NaN and infinity are not voltages)"));
            }
            if positive && x <= 0.0 {
                return Err(bad("expected a standard deviation > 0 V"));
            }
            if x < 0.0 {
                return Err(bad("expected a voltage >= 0 V (the reduction uses V^2; record magnitudes)"));
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

fn csv_error(source: &str, e: &csv::Error) -> FitError {
    let line = e.position().map(|p| p.line()).unwrap_or(0);
    FitError::Data { file: source.into(), line, column: None, message: format!("not readable as CSV: {e}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(text: &str) -> String {
        parse_voltages(text.as_bytes(), "m.csv").unwrap_err().to_string()
    }

    #[test]
    fn reads_bom_crlf_comments_quotes_and_extra_columns() {
        let text = "\u{feff}# synthetic\r\nnote,\"v_clamp_v\",v_pull_v,device\r\n\"a, b\",25,30.5,\"d1\"\r\n\r\n# mid\r\nx, 26 ,31,d2\r\n";
        let d = parse_voltages(text.as_bytes(), "m.csv").unwrap();
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
        let e = msg("v_clamp_v,v_pull_v\n25\n");
        assert!(e.contains("line 2") && e.contains("v_pull_v") && e.contains("missing"), "{e}");
        let e = msg("v_clamp_v,v_pull_v,v_pull_sd_v\n25,30,0\n");
        assert!(e.contains("v_pull_sd_v") && e.contains("> 0"), "{e}");
    }
}
