//! Checks of a request's fields against the physical domains of `stiction_scenario::domain`,
//! naming each field as the front end calls it.

/// A value outside its usual range: a code and a message naming the field.
pub use stiction_scenario::Warning;

use crate::Error;

/// How a front end names a request field in a message: the command line gives its flag
/// (`radius_m` -> `--radius`), Python its keyword argument (`radius`).
pub type Names<'a> = dyn Fn(&str) -> String + 'a;

/// A request field's own name (for tests and front ends that name fields as the request does).
pub fn field_names(field: &str) -> String {
    field.to_string()
}

/// Checks `value` of the request field `field` against the domain of the scenario quantity
/// `path`: outside it, an error naming the field; outside the usual range, a warning pushed to
/// `warnings`.
pub fn domain(warnings: &mut Vec<Warning>, names: &Names, field: &str, path: &str, value: f64) -> Result<(), Error> {
    match stiction_scenario::domain::check_value(path, &names(field), value) {
        Ok(Some(w)) => warnings.push(w),
        Ok(None) => {}
        // The field as the front end names it, then the value, the domain and its reason.
        Err(e) => return Err(e.to_string().into()),
    }
    Ok(())
}

/// Checks `value` of the scenario quantity `path`, given as `name` (a flag, an argument), against
/// its domain (`stiction_scenario::domain`): outside it, the message naming `name` with the domain
/// and its reason; outside the usual range, the warning.
pub fn domain_value(path: &str, name: &str, value: f64) -> Result<Option<Warning>, String> {
    stiction_scenario::domain::check_value(path, name, value).map_err(|e| e.message)
}
