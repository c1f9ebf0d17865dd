//! Names of values in text and JSON: an enum's serde name ([`serde_name`], and `Display` from it
//! by [`display_serde_name!`](crate::display_serde_name)), and keys that carry a unit
//! ([`key_with_unit`], [`unit_key_suffix`]).

use serde::Serialize;

/// The name serde gives a value: for a unit enum variant the string the scenario files and every
/// JSON output spell it with (`"maugis-dugdale"`, `"tilt"`); anything else its compact JSON.
///
/// Text output uses the same names as JSON through [`display_serde_name!`](crate::display_serde_name),
/// so each enum is spelled one way everywhere and the spelling lives only in its serde attributes.
pub fn serde_name<T: Serialize + ?Sized>(value: &T) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(other) => other.to_string(),
        Err(e) => format!("<{e}>"),
    }
}

/// The suffix that names an SI unit in a JSON key or CSV column (`name_unit`, as `load_n`,
/// `real_area_m2`): "N/V^2" -> "n_per_v2", "m^-2" -> "per_m2", "1/Pa" -> "per_pa",
/// "N s/m" -> "n_s_per_m"; "" or "1" (a pure number) -> "" (no suffix).
pub fn unit_key_suffix(si_unit: &str) -> String {
    let unit = si_unit.trim();
    if unit.is_empty() || unit == "1" {
        return String::new();
    }
    // Terms with a negative power move behind "per": "m^-2" is "per m^2".
    let (num, den) = unit.split_once('/').unwrap_or((unit, ""));
    let mut over: Vec<String> = Vec::new();
    let mut under: Vec<String> = Vec::new();
    for term in num.split([' ', '*', '.']).filter(|t| !t.is_empty() && *t != "1") {
        match term.split_once("^-") {
            Some((base, power)) => under.push(format!("{base}{power}")),
            None => over.push(term.replace('^', "")),
        }
    }
    for term in den.split([' ', '*', '.']).filter(|t| !t.is_empty()) {
        under.push(term.replace('^', ""));
    }
    let mut key = over.join("_");
    if !under.is_empty() {
        key =
            if key.is_empty() { format!("per_{}", under.join("_")) } else { format!("{key}_per_{}", under.join("_")) };
    }
    key.to_lowercase()
}

/// `name` with the unit suffix of [`unit_key_suffix`]: ("surface.summit_radius", "m") ->
/// "surface.summit_radius_m"; a pure number keeps its bare name.
pub fn key_with_unit(name: &str, si_unit: &str) -> String {
    match unit_key_suffix(si_unit) {
        s if s.is_empty() => name.to_string(),
        s => format!("{name}_{s}"),
    }
}

/// Implements `Display` for enums with their serde names (see [`serde_name`]):
/// `stiction_units::display_serde_name!(AdhesionLaw, Branch);` makes `AdhesionLaw::MaugisDugdale`
/// print as `maugis-dugdale`, as it is written in a scenario file and in JSON.
#[macro_export]
macro_rules! display_serde_name {
    ($($t:ty),+ $(,)?) => {
        $(
            impl ::std::fmt::Display for $t {
                fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                    f.write_str(&$crate::serde_name(self))
                }
            }
        )+
    };
}
