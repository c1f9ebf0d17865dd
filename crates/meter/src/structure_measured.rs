//! Measured thresholds of a test structure built from parts (`stiction fit` with a scenario that
//! has a `structure`): one row per slip, the normal side and the tangential side each given by one
//! column, and the forces the structure's parts imply.
//!
//! | column | the structure's part | force |
//! |---|---|---|
//! | `v_normal_v` | normal comb or plate electrode voltage at the point | `L = a_n V^2 - F_0` |
//! | `normal_load_n` | the normal load itself, N | `L` |
//! | `v_tangential_v` | tangential comb voltage at slip (ramp) or held (lower_normal) | `F_f = a_t V^2` |
//! | `displacement_m` | released spring: the largest displacement that sticks (release) | `F_f = k x` |
//! | `tangential_load_n` | the tangential load at slip, N | `F_f` |
//!
//! Exactly one normal and one tangential column (one source of truth: two columns for one side are
//! refused, naming both). A voltage column must fit the part (`v_tangential_v` needs a tangential
//! comb, `displacement_m` a released spring). The file's text rules are those of the
//! measured-voltage reader ([`crate::measured`]: BOM, CRLF, `#` comments, quoted fields, comma,
//! semicolon or tab); a bad cell is an error naming the file, line, column and value. Rows that are
//! readable but carry no friction reading are listed by [`select_thresholds`] with their line and
//! reason: below contact (`L <= 0`), at or past the normal comb's side pull-in voltage (its load is
//! not `a_n V^2 - F_0` there), or a zero tangential reading (no slip, or a slip at the first step).

use serde::Serialize;

use crate::measured::{CsvText, Rejected, VoltageCsvError, csv_error, header_excerpt, separator_name};
use crate::structure::{NormalPart, StructureDevice, TangentialPart};

/// The columns the reader accepts (units in the names).
pub const THRESHOLD_COLUMNS: [&str; 5] =
    ["v_normal_v", "normal_load_n", "v_tangential_v", "displacement_m", "tangential_load_n"];

/// The normal side of a row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NormalReading {
    /// The normal part's voltage, V.
    VoltageV(f64),
    /// The normal load, N.
    LoadN(f64),
}

/// The tangential side of a row.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TangentialReading {
    /// The tangential comb's voltage, V.
    VoltageV(f64),
    /// The released spring's displacement, m.
    DisplacementM(f64),
    /// The tangential load, N.
    LoadN(f64),
}

/// One measured threshold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThresholdRow {
    /// Line of the file (1-based).
    pub line: u64,
    /// The normal reading.
    pub normal: NormalReading,
    /// The tangential reading.
    pub tangential: TangentialReading,
}

/// The rows of a threshold file.
#[derive(Debug, Clone, Serialize)]
pub struct ThresholdData {
    /// Where the rows came from (file name, for messages).
    pub source: String,
    /// The normal column's name.
    pub normal_column: &'static str,
    /// The tangential column's name.
    pub tangential_column: &'static str,
    /// The rows in file order.
    pub rows: Vec<ThresholdRow>,
}

/// Largest number of data rows.
pub const MAX_THRESHOLD_ROWS: usize = crate::measured::MAX_MEASURED_ROWS;

/// Largest force accepted in a cell, N (the `load` domain: beyond a newton no MEMS actuator pushes).
pub const MAX_THRESHOLD_FORCE_N: f64 = 1.0;

/// Largest displacement accepted in a cell, m (the domain of `structure.protocol.displacement_max`).
pub const MAX_THRESHOLD_DISPLACEMENT_M: f64 = 1e-3;

fn unit_word(column: &str) -> &'static str {
    if column.ends_with("_v") {
        "volts"
    } else if column.ends_with("_n") {
        "newtons"
    } else {
        "metres"
    }
}

fn limit(column: &str) -> f64 {
    if column.ends_with("_v") {
        crate::measured::MAX_MEASURED_VOLTAGE_V
    } else if column.ends_with("_n") {
        MAX_THRESHOLD_FORCE_N
    } else {
        MAX_THRESHOLD_DISPLACEMENT_M
    }
}

fn is_name_without_unit(name: &str) -> bool {
    let stems = [
        "v_normal",
        "normal_voltage",
        "normal_load",
        "load",
        "v_tangential",
        "tangential_voltage",
        "displacement",
        "tangential_load",
        "friction",
    ];
    stems.contains(&name)
}

/// Reads a threshold CSV through [`stiction_units::io::read_input`] (regular files only, at most
/// [`crate::measured::MAX_MEASURED_CSV_BYTES`]).
pub fn read_thresholds(path: &std::path::Path) -> Result<ThresholdData, VoltageCsvError> {
    let bytes = stiction_units::io::read_input(path, crate::measured::MAX_MEASURED_CSV_BYTES)?;
    parse_thresholds(&bytes, &path.display().to_string())
}

/// Parses the bytes of a threshold CSV; `source` names it in errors. One pass, linear in the size.
pub fn parse_thresholds(bytes: &[u8], source: &str) -> Result<ThresholdData, VoltageCsvError> {
    let table = CsvText::new(bytes);
    let at = |line: u64, column: Option<&str>, message: String| VoltageCsvError::Data {
        file: source.into(),
        line,
        column: column.map(str::to_string),
        message,
    };
    let expected = "a header with one normal column (`v_normal_v` or `normal_load_n`) and one tangential column \
                    (`v_tangential_v`, `displacement_m` or `tangential_load_n`)";
    if table.is_blank() {
        return Err(at(1, None, format!("the file is empty; expected {expected}")));
    }
    let mut reader = table.reader();
    let mut record = csv::ByteRecord::new();
    let Some(header_line) = table.header(&mut reader, &mut record, source)? else {
        return Err(at(1, None, format!("only comments or blank lines; expected {expected}")));
    };
    let names: Vec<String> = record.iter().map(|f| String::from_utf8_lossy(f).trim().to_ascii_lowercase()).collect();
    let mut col = [None::<usize>; 5];
    for (k, name) in names.iter().enumerate() {
        if let Some(which) = THRESHOLD_COLUMNS.iter().position(|a| a == name) {
            if let Some(first) = col[which] {
                return Err(at(
                    header_line,
                    None,
                    format!(
                        "column `{name}` appears twice (columns {} and {}); each column may appear once",
                        first + 1,
                        k + 1
                    ),
                ));
            }
            col[which] = Some(k);
        } else if is_name_without_unit(name) {
            return Err(at(
                header_line,
                None,
                format!(
                    "column {} gives no unit (read with the separator {}); accepted names (unit in the name): \
                     {THRESHOLD_COLUMNS:?}",
                    stiction_units::text::excerpt(name),
                    separator_name(table.separator)
                ),
            ));
        } else if name == "device" {
            return Err(at(
                header_line,
                Some("device"),
                "a structure's thresholds are fitted as one device (one eq. 10 line); split the file by device".into(),
            ));
        }
    }
    let pick = |idx: &[usize], side: &str| -> Result<(usize, usize), VoltageCsvError> {
        let given: Vec<usize> = idx.iter().copied().filter(|&i| col[i].is_some()).collect();
        match given.as_slice() {
            [one] => Ok((*one, col[*one].unwrap_or(0))),
            [] => Err(at(
                header_line,
                None,
                format!(
                    "missing the {side} column: one of {:?} in the header {} (read with the separator {}); accepted \
                     separators: comma, semicolon, tab",
                    idx.iter().map(|&i| THRESHOLD_COLUMNS[i]).collect::<Vec<_>>(),
                    header_excerpt(&names),
                    separator_name(table.separator)
                ),
            )),
            many => Err(at(
                header_line,
                None,
                format!(
                    "the {side} side is given twice, by {}: give one column (one source of truth; the other follows \
                     from the structure's parts)",
                    many.iter().map(|&i| format!("`{}`", THRESHOLD_COLUMNS[i])).collect::<Vec<_>>().join(" and ")
                ),
            )),
        }
    };
    let (normal_which, normal_col) = pick(&[0, 1], "normal")?;
    let (tangential_which, tangential_col) = pick(&[2, 3, 4], "tangential")?;
    let (normal_name, tangential_name) = (THRESHOLD_COLUMNS[normal_which], THRESHOLD_COLUMNS[tangential_which]);
    let mut rows = Vec::with_capacity(table.line_count().min(MAX_THRESHOLD_ROWS));
    while reader.read_byte_record(&mut record).map_err(|e| csv_error(source, &e))? {
        if record.len() == 1 && record[0].is_empty() {
            continue;
        }
        let line = table.line_of(&record);
        if rows.len() >= MAX_THRESHOLD_ROWS {
            return Err(at(line, None, format!("more than {MAX_THRESHOLD_ROWS} data rows; split the file")));
        }
        let number = |k: usize, name: &str| -> Result<f64, VoltageCsvError> {
            let raw = record.get(k).ok_or_else(|| {
                at(
                    line,
                    Some(name),
                    format!("missing: the row has {} field(s), the header {}", record.len(), names.len()),
                )
            })?;
            let text = std::str::from_utf8(raw).unwrap_or("");
            let unit = unit_word(name);
            let bad = |what: String| {
                at(line, Some(name), format!("value {:?}: {what}", crate::short(&String::from_utf8_lossy(raw))))
            };
            let x: f64 = text.parse().map_err(|_| {
                if table.separator != b',' && text.contains(',') {
                    bad(format!(
                        "expected a number in {unit} with a decimal point (the file's separator is a semicolon or \
                         tab; a decimal comma is not read)"
                    ))
                } else {
                    bad(format!("expected a number in {unit}"))
                }
            })?;
            if !x.is_finite() {
                return Err(bad(format!("expected a finite number in {unit} (NaN and infinity are not readings)")));
            }
            if x < 0.0 {
                return Err(bad(format!(
                    "expected a value >= 0 {unit} (record magnitudes: the reduction uses V^2, and a load, a \
                     displacement or a tangential load at slip is a magnitude)"
                )));
            }
            if x > limit(name) {
                return Err(bad(format!("expected at most {:e} {unit}", limit(name))));
            }
            Ok(x)
        };
        let n = number(normal_col, normal_name)?;
        let t = number(tangential_col, tangential_name)?;
        let normal = if normal_which == 0 { NormalReading::VoltageV(n) } else { NormalReading::LoadN(n) };
        let tangential = match tangential_which {
            2 => TangentialReading::VoltageV(t),
            3 => TangentialReading::DisplacementM(t),
            _ => TangentialReading::LoadN(t),
        };
        rows.push(ThresholdRow { line, normal, tangential });
    }
    if rows.is_empty() {
        return Err(at(header_line, None, "no data rows after the header".into()));
    }
    Ok(ThresholdData { source: source.into(), normal_column: normal_name, tangential_column: tangential_name, rows })
}

/// The force a threshold row implies through the structure's parts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ThresholdPoint {
    /// Line of the file.
    pub line: u64,
    /// Normal load L, N (`a_n V^2 - F_0`, or the file's load).
    pub load_n: f64,
    /// Friction at slip F_f, N (`a_t V^2`, `k x`, or the file's tangential load).
    pub friction_n: f64,
}

/// Checks that the file's columns fit the structure's parts: `v_tangential_v` needs a tangential
/// comb, `displacement_m` a released spring. The error names the column and the part.
pub fn check_columns(data: &ThresholdData, device: &StructureDevice) -> Result<(), String> {
    match (data.tangential_column, device.tangential) {
        ("v_tangential_v", TangentialPart::Spring(_)) => Err(format!(
            "{}: column `v_tangential_v` is a tangential comb's voltage, but `structure.tangential` is a \
             released_spring: give `displacement_m` (the largest displacement that sticks) or `tangential_load_n`",
            data.source
        )),
        ("displacement_m", TangentialPart::Comb(_)) => Err(format!(
            "{}: column `displacement_m` is a released spring's displacement, but `structure.tangential` is a \
             lateral_comb: give `v_tangential_v` (its voltage) or `tangential_load_n`",
            data.source
        )),
        _ => Ok(()),
    }
}

/// Splits the rows into points with a friction reading (their load and friction through the parts'
/// nominal force laws) and rejected rows, each with its line and reason: below contact
/// (`L <= 0`), at or past the normal comb's side pull-in voltage at the wall (there the comb's
/// fingers snap sideways and `a_n V^2 - F_0` is not the load), or a zero tangential reading (no
/// slip, or a slip at the first step: not a measured friction).
pub fn select_thresholds(data: &ThresholdData, device: &StructureDevice) -> (Vec<ThresholdPoint>, Vec<Rejected>) {
    let a_n = device.normal.conversion_factor_n_per_v2();
    let f0 = device.normal.spring_force_n();
    let side = device.normal.side_pull_in_voltage_v();
    let mut used = Vec::with_capacity(data.rows.len());
    let mut rejected = Vec::new();
    for r in &data.rows {
        let reject = |reason: String| Rejected { line: r.line, reason };
        let load = match r.normal {
            NormalReading::VoltageV(v) => {
                if let Some(v_side) = side.filter(|s| v >= *s) {
                    rejected.push(reject(format!(
                        "v_normal_v = {v} V is at or past the normal comb's side pull-in voltage {v_side:.3} V at the \
                         wall: its fingers snap sideways there, so the load is not a_n V^2 - F_0; no load is implied"
                    )));
                    continue;
                }
                a_n * v * v - f0
            }
            NormalReading::LoadN(l) => l,
        };
        if load.is_nan() || load <= 0.0 {
            let how = match (r.normal, &device.normal) {
                (NormalReading::LoadN(_), _) => "normal_load_n = 0: no load".to_string(),
                (NormalReading::VoltageV(_), NormalPart::Comb { .. }) => format!(
                    "below contact: L = a_n V^2 - F_0 = {} <= 0 (the comb's spring holds it off the wall)",
                    stiction_units::format_quantity(load, stiction_units::Dimension::Force)
                ),
                (NormalReading::VoltageV(_), NormalPart::Plate(_)) => format!(
                    "below contact: L = a_n V^2 - F_0 = {} <= 0 (the plate leaves the substrate)",
                    stiction_units::format_quantity(load, stiction_units::Dimension::Force)
                ),
            };
            rejected.push(reject(how));
            continue;
        }
        let friction = match (r.tangential, device.tangential) {
            (TangentialReading::VoltageV(v), TangentialPart::Comb(c)) => c.conversion_factor_n_per_v2() * v * v,
            (TangentialReading::DisplacementM(x), TangentialPart::Spring(s)) => s.stiffness_n_per_m * x,
            (TangentialReading::LoadN(f), _) => f,
            // check_columns refuses the other pairs first.
            _ => f64::NAN,
        };
        if friction.is_nan() || friction <= 0.0 {
            rejected.push(reject(match r.tangential {
                TangentialReading::DisplacementM(_) => {
                    "displacement_m = 0: it slipped at the first displacement (the friction is below one step, not \
                     measured)"
                        .into()
                }
                _ => "zero tangential reading: no slip recorded".into(),
            }));
            continue;
        }
        used.push(ThresholdPoint { line: r.line, load_n: load, friction_n: friction });
    }
    (used, rejected)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(text: &str) -> String {
        parse_thresholds(text.as_bytes(), "t.csv").unwrap_err().to_string()
    }

    #[test]
    fn reads_each_pair_of_columns() {
        let d =
            parse_thresholds(b"\xEF\xBB\xBF# release\r\nv_normal_v;displacement_m;note\r\n1.1;2.5e-7;a\r\n", "t.csv")
                .unwrap();
        assert_eq!(
            d.rows,
            vec![ThresholdRow {
                line: 3,
                normal: NormalReading::VoltageV(1.1),
                tangential: TangentialReading::DisplacementM(2.5e-7)
            }]
        );
        let d = parse_thresholds(b"tangential_load_n,normal_load_n\n1e-6,3e-6\n", "t.csv").unwrap();
        assert_eq!((d.normal_column, d.tangential_column), ("normal_load_n", "tangential_load_n"));
        assert_eq!(d.rows[0].normal, NormalReading::LoadN(3e-6));
    }

    #[test]
    fn bad_files_name_line_and_column() {
        assert!(msg("").contains("empty"));
        assert!(msg("v_normal_v,v_tangential_v\n").contains("no data rows"));
        let e = msg("v_normal_v,v_tangential_v\n40,12\n41,x\n");
        assert!(e.contains("t.csv, line 3") && e.contains("`v_tangential_v`") && e.contains("\"x\""), "{e}");
        let e = msg("v_normal_v,displacement_m\n40,-1e-7\n");
        assert!(e.contains("line 2") && e.contains("displacement_m") && e.contains(">= 0 metres"), "{e}");
        let e = msg("v_normal_v,normal_load_n,displacement_m\n1,1e-6,1e-7\n");
        assert!(e.contains("`v_normal_v` and `normal_load_n`") && e.contains("one source of truth"), "{e}");
        let e = msg("v_normal_v,displacement_m,tangential_load_n\n1,1e-7,1e-6\n");
        assert!(e.contains("`displacement_m` and `tangential_load_n`"), "{e}");
        let e = msg("v_normal_v,x\n1,2\n");
        assert!(e.contains("missing the tangential column"), "{e}");
        let e = msg("v_normal,displacement\n1,2\n");
        assert!(e.contains("gives no unit"), "{e}");
        let e = msg("v_normal_v,displacement_m\n1,2\n");
        assert!(e.contains("at most 1e-3 metres"), "{e}");
        let e = msg("v_normal_v,tangential_load_n,device\n1,1e-6,a\n");
        assert!(e.contains("`device`") && e.contains("split the file"), "{e}");
        for bad in ["NaN", "inf"] {
            let e = msg(&format!("normal_load_n,tangential_load_n\n{bad},1e-6\n"));
            assert!(e.contains("finite") && e.contains("normal_load_n"), "{e}");
        }
        let e = msg("v_normal_v,v_tangential_v\n40\n");
        assert!(e.contains("line 2") && e.contains("missing"), "{e}");
    }
}
