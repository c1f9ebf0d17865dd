//! Quantities at the edge of stiction.
//!
//! # Internal unit system
//!
//! Everything inside stiction is SI, stored as `f64`: metres, newtons, pascals, joules per square
//! metre, volts, seconds, radians. Users may write quantities with units: scenario files and
//! command-line flags accept a bare number (taken as SI) or a string such as `"0.5 um"`, `"0.5um"`,
//! `"1.4 GPa"`, `"3 uN"`, `"0.1 J/m^2"`, `"9.1e-12 1/Pa"`, `"4e12 m^-2"`, `"100 um^2"`,
//! `"1.4e-8 N/V^2"` or `"35 %"`. [`parse_quantity`] converts such a string once, at the edge, to
//! SI, and checks that its unit has the dimension the field expects.
//!
//! Units are products and quotients of symbols (`m g s A N Pa J V W C F Hz rad deg %`) with SI
//! prefixes (`f p n u µ m c k M G T`) and integer powers (`m^2`, `m^-2`, `m2`). A `/` divides by
//! everything after it up to the next `/`; `*`, `.` or a space multiply.
//!
//! Scenario fields take such values through the serde helpers in [`de`], which also accept an
//! uncertain-parameter object (`{"value": "0.5 um", "sd": "0.3 um", "distribution": "normal"}`),
//! see [`UncertainInput`]: a nominal run takes its `value`; Monte Carlo studies sample it.

mod parse;
pub use parse::{format_quantity, parse_any, parse_quantity, parse_quantity_checked};

pub mod de;
pub mod finite;
pub mod io;
mod names;
mod quantity;
pub mod text;
mod uncertain;
pub use names::{key_with_unit, serde_name, unit_key_suffix};
pub use quantity::{Constraint, Dimension, DimensionVector, MAX_UNIT_EXPONENT, QuantityError};
pub use uncertain::{Distribution, QuantityInput, ScalarInput, UncertainInput, nominal_from_json};

#[cfg(test)]
mod name_tests {
    use super::*;

    /// Text and JSON spell an enum the same way, the way a scenario file writes it.
    #[test]
    fn display_is_the_serde_name() {
        assert_eq!(Distribution::Lognormal.to_string(), "lognormal");
        assert_eq!(serde_json::to_string(&Distribution::Lognormal).unwrap(), "\"lognormal\"");
        let back: Distribution = serde_json::from_str(&format!("\"{}\"", Distribution::Uniform)).unwrap();
        assert_eq!(back, Distribution::Uniform);
        assert_eq!(serde_name(&3), "3");
        // An uncertain parameter in an error: as written, not as a Rust value.
        let u: UncertainInput =
            serde_json::from_str(r#"{"value": "0.5 um", "sd": "0.3 um", "min": "0.6 um", "max": 7e-7}"#).unwrap();
        let e = u.nominal(Dimension::Length, Constraint::Positive).unwrap_err().to_string();
        assert!(
            e.starts_with(r#""{value: 0.5 um, sd: 0.3 um, distribution: normal, min: 0.6 um, max: 0.0000007}": value"#),
            "{e}"
        );
    }

    /// The unit suffixes of keys and columns, as the hand-written keys spell them.
    #[test]
    fn unit_suffixes() {
        for (unit, key) in [
            ("N", "n"),
            ("m^2", "m2"),
            ("N/V^2", "n_per_v2"),
            ("m^-2", "per_m2"),
            ("1/Pa", "per_pa"),
            ("J/m^2", "j_per_m2"),
            ("N s/m", "n_s_per_m"),
            ("N/m", "n_per_m"),
            ("1", ""),
            ("", ""),
        ] {
            assert_eq!(unit_key_suffix(unit), key, "{unit}");
        }
        assert_eq!(key_with_unit("surface.summit_radius", "m"), "surface.summit_radius_m");
        assert_eq!(key_with_unit("meter.slip_mu", "1"), "meter.slip_mu");
    }

    /// "expected a positive length", not "expected positive a length".
    #[test]
    fn expected_reads_as_english() {
        let e = parse_quantity_checked("-0.5 um", Dimension::Length, Constraint::Positive).unwrap_err();
        assert!(e.to_string().contains("expected a positive length such as"), "{e}");
        let e = parse_quantity_checked("-1 um^2", Dimension::Area, Constraint::NonNegative).unwrap_err();
        assert!(e.to_string().contains("expected a non-negative area such as"), "{e}");
        let e = parse_quantity_checked("1 N", Dimension::Length, Constraint::Finite).unwrap_err();
        assert!(e.to_string().contains("expected a length such as"), "{e}");
    }
}
