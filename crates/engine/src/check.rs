//! Checks of a request's fields against the physical domains of `stiction_scenario::domain`,
//! naming each field as the front end calls it.

use stiction_scenario::Warning;

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

#[cfg(test)]
mod tests {
    use crate::contact::ContactRequest;
    use crate::discrete::DiscreteRequest;

    fn discrete() -> DiscreteRequest {
        // Table 1 of the paper: R = 0.5 um, dgamma = 0.1 J/m^2, D = 9.1e-12 1/Pa, s = 1.4 GPa.
        DiscreteRequest {
            contacts: 3,
            radius_m: 0.5e-6,
            work_of_adhesion_j_per_m2: 0.1,
            compliance_per_pa: 9.1e-12,
            shear_strength_pa: 1.4e9,
            load_n: 3e-6,
            law: stiction_contact::single::AdhesionLaw::Dmt,
            equilibrium_spacing_m: 0.3e-9,
            target_slope: None,
        }
    }

    /// A request outside the physical domain of `stiction_scenario::domain` is refused naming the
    /// field as the front end calls it (Python's argument, the command line's flag), with the
    /// value and the domain; the paper's Table 1 values pass. (Deliberate bug caught: the field's
    /// name dropped from the message, seen failing.)
    #[test]
    fn a_request_outside_its_domain_names_the_front_ends_field() {
        let python = |f: &str| f.trim_end_matches("_m").trim_end_matches("_n").to_string();
        let flag = |f: &str| format!("--{}", f.trim_end_matches("_m").replace('_', "-"));
        assert!(discrete().validate(&python).unwrap().is_empty());
        let bad = DiscreteRequest { radius_m: -1e-6, ..discrete() };
        let e = bad.validate(&python).unwrap_err().to_string();
        assert!(e.starts_with("radius: ") && e.contains("outside the physical domain"), "{e}");
        let e = bad.validate(&flag).unwrap_err().to_string();
        assert!(e.starts_with("--radius: "), "{e}");
        let e = DiscreteRequest { contacts: 4, ..discrete() }.validate(&python).unwrap_err().to_string();
        assert!(e.starts_with("contacts 4: expected 1 to 3"), "{e}");
        let e = DiscreteRequest { load_n: f64::NAN, ..discrete() }.validate(&python).unwrap_err().to_string();
        assert!(e.starts_with("load: "), "{e}");
        let e = ContactRequest { load_n: Some(f64::INFINITY), ..ContactRequest::default() }
            .validate(&python)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("load: "), "{e}");
        assert!(ContactRequest { load_n: Some(2e-6), ..ContactRequest::default() }.validate(&python).is_ok());
    }
}
