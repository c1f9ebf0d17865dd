//! Length units of map files and flags (a leaf of the module graph, used by `read` and `formats`).

use stiction_units::text::{MAX_CELL_BYTES, excerpt};
use stiction_units::{Dimension, parse_quantity};

/// Parses a length unit such as `"nm"`, `"um"`, `"µm"`, `"m"` or a scale such as `"10 nm"` into
/// metres per unit.
pub fn parse_length_unit(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let q = if t.starts_with(|c: char| c.is_alphabetic()) { format!("1 {t}") } else { t.to_string() };
    if t.len() > MAX_CELL_BYTES {
        return Err(format!("unit {}: longer than {MAX_CELL_BYTES} bytes", excerpt(t)));
    }
    let v = parse_quantity(&q, Dimension::Length).map_err(|e| format!("unit {}", e.brief()))?;
    if v > 0.0 { Ok(v) } else { Err(format!("unit {} must be a positive length", excerpt(t))) }
}
