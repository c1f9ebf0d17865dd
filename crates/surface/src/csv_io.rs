//! CSV export and import of a summit list: columns `x_m,y_m,height_m,radius_m` in SI units.

use std::io::{Read, Write};
use std::path::Path;

use crate::{Radii, Surface, SurfaceError};

/// The header line of a surface CSV file.
pub const CSV_HEADER: [&str; 4] = ["x_m", "y_m", "height_m", "radius_m"];

impl Surface {
    /// Writes the summits as CSV: a header `x_m,y_m,height_m,radius_m` and one row per summit in
    /// SI units (metres), in summit order. Numbers use the shortest representation that reads back
    /// to the same value, so [`Surface::read_csv`] restores the surface bit for bit.
    pub fn write_csv<W: Write>(&self, writer: W) -> Result<(), SurfaceError> {
        let mut w = csv::Writer::from_writer(writer);
        w.write_record(CSV_HEADER)?;
        for i in 0..self.len() {
            w.write_record([
                self.xs_m()[i].to_string(),
                self.ys_m()[i].to_string(),
                self.height_m(i).to_string(),
                self.radius_m(i).to_string(),
            ])?;
        }
        w.flush().map_err(|e| SurfaceError::Io { path: "<csv writer>".into(), message: e.to_string() })?;
        Ok(())
    }

    /// Writes the CSV to a file atomically (see [`Surface::write_csv`] and
    /// [`stiction_units::io::write_atomic`]: a temporary file renamed over the target, never
    /// through a symbolic link).
    pub fn write_csv_file(&self, path: &Path) -> Result<(), SurfaceError> {
        let mut bytes = Vec::new();
        self.write_csv(&mut bytes)?;
        stiction_units::io::write_atomic(path, &bytes)
            .map_err(|e| SurfaceError::Io { path: path.display().to_string(), message: e.to_string() })
    }

    /// Reads a summit list from CSV with the columns `x_m,y_m,height_m,radius_m` (any order, all
    /// four required, no others) over the apparent area `[0, apparent_length_m] x [0, apparent_width_m]`.
    ///
    /// Every error names the line of the file, the column and the value: a missing column, a
    /// malformed or non-finite number, a radius <= 0, a position outside the apparent area.
    pub fn read_csv<R: Read>(
        reader: R,
        apparent_length_m: f64,
        apparent_width_m: f64,
    ) -> Result<Surface, SurfaceError> {
        crate::surface::check_positive("apparent_length", apparent_length_m, "m")?;
        crate::surface::check_positive("apparent_width", apparent_width_m, "m")?;
        // Fields are trimmed by hand (`trim_ascii`) and read as bytes: the csv crate's `Trim::All`
        // and UTF-8 checks of every field cost about a third of the time at 1e6 rows (issue 16).
        let mut r = csv::ReaderBuilder::new().has_headers(true).from_reader(reader);
        let headers = r.headers()?.clone();
        let mut col = [usize::MAX; 4];
        for (k, h) in headers.iter().enumerate() {
            let h = h.trim();
            match CSV_HEADER.iter().position(|c| *c == h) {
                Some(c) if col[c] == usize::MAX => col[c] = k,
                Some(_) => {
                    return Err(SurfaceError::Csv { line: 1, message: format!("column `{h}` appears twice") });
                }
                None => {
                    return Err(SurfaceError::Csv {
                        line: 1,
                        message: format!("unknown column `{h}`: expected the columns x_m, y_m, height_m, radius_m"),
                    });
                }
            }
        }
        if let Some(c) = col.iter().position(|&k| k == usize::MAX) {
            return Err(SurfaceError::Csv {
                line: 1,
                message: format!(
                    "missing column `{}`: expected the columns x_m, y_m, height_m, radius_m",
                    CSV_HEADER[c]
                ),
            });
        }
        let (mut xs, mut ys, mut hs, mut rs) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut rec = csv::ByteRecord::new();
        loop {
            match r.read_byte_record(&mut rec) {
                Ok(false) => break,
                Ok(true) => {}
                Err(e) => {
                    let line = e.position().map_or(0, |p| p.line());
                    return Err(SurfaceError::Csv { line, message: e.to_string() });
                }
            }
            let line = rec.position().map_or(0, |p| p.line());
            let get = |c: usize| -> Result<f64, SurfaceError> {
                let bytes = rec.get(col[c]).unwrap_or(b"").trim_ascii();
                match std::str::from_utf8(bytes).ok().and_then(|t| t.parse::<f64>().ok()) {
                    Some(v) if v.is_finite() => Ok(v),
                    parsed => {
                        let text = String::from_utf8_lossy(bytes);
                        let what =
                            if parsed.is_some() { "is not finite" } else { "is not a number (expected SI metres)" };
                        Err(SurfaceError::Csv { line, message: format!("column `{}`: `{text}` {what}", CSV_HEADER[c]) })
                    }
                }
            };
            let (x, y, h, rad) = (get(0)?, get(1)?, get(2)?, get(3)?);
            if !(0.0..=apparent_length_m).contains(&x) {
                return Err(SurfaceError::Csv {
                    line,
                    message: format!("column `x_m`: {x} lies outside the apparent length [0, {apparent_length_m}] m"),
                });
            }
            if !(0.0..=apparent_width_m).contains(&y) {
                return Err(SurfaceError::Csv {
                    line,
                    message: format!("column `y_m`: {y} lies outside the apparent width [0, {apparent_width_m}] m"),
                });
            }
            if rad <= 0.0 {
                return Err(SurfaceError::Csv { line, message: format!("column `radius_m`: {rad} must be > 0 m") });
            }
            if xs.len() >= crate::MAX_SUMMITS {
                return Err(SurfaceError::Csv { line, message: format!("more than {} summits", crate::MAX_SUMMITS) });
            }
            xs.push(round_inside(x, apparent_length_m));
            ys.push(round_inside(y, apparent_width_m));
            hs.push(h);
            rs.push(rad);
        }
        if xs.is_empty() {
            return Err(SurfaceError::Csv {
                line: 1,
                message: "no summit rows after the header: expected at least one summit".into(),
            });
        }
        let radii = match rs.first() {
            Some(&r0) if rs.iter().all(|&r| r == r0) => Radii::Uniform(r0),
            Some(_) => Radii::PerSummit(rs),
            None => Radii::Uniform(1.0),
        };
        Surface::new(apparent_length_m, apparent_width_m, xs, ys, hs, radii)
    }

    /// Reads a summit list from a CSV file (see [`Surface::read_csv`]); errors name the path.
    pub fn read_csv_file(path: &Path, apparent_length_m: f64, apparent_width_m: f64) -> Result<Surface, SurfaceError> {
        // A regular file of at most 1 GiB (no FIFO, no /dev/zero), BOM removed.
        let text = stiction_units::io::read_input_text(path, stiction_units::io::DEFAULT_INPUT_LIMIT_BYTES)
            .map_err(|e| SurfaceError::Io { path: path.display().to_string(), message: e.to_string() })?;
        Surface::read_csv(text.as_bytes(), apparent_length_m, apparent_width_m).map_err(|e| match e {
            SurfaceError::Csv { line, message } => {
                SurfaceError::CsvFile { path: path.display().to_string(), line, message }
            }
            other => other,
        })
    }
}

fn round_inside(v: f64, lim: f64) -> f32 {
    let mut f = v as f32;
    while f64::from(f) > lim {
        f = f.next_down();
    }
    f
}
