//! Parsing "number unit" strings into SI values.

use crate::{Constraint, Dimension, DimensionVector, QuantityError};

/// A unit symbol: its SI factor and dimension (m, kg, s, A).
struct Symbol {
    name: &'static str,
    factor: f64,
    dims: [i8; 5],
    /// Whether SI prefixes may be put in front of it.
    prefixable: bool,
}

const SYMBOLS: &[Symbol] = &[
    Symbol { name: "m", factor: 1.0, dims: [1, 0, 0, 0, 0], prefixable: true },
    Symbol { name: "g", factor: 1e-3, dims: [0, 1, 0, 0, 0], prefixable: true },
    Symbol { name: "s", factor: 1.0, dims: [0, 0, 1, 0, 0], prefixable: true },
    Symbol { name: "A", factor: 1.0, dims: [0, 0, 0, 1, 0], prefixable: true },
    Symbol { name: "N", factor: 1.0, dims: [1, 1, -2, 0, 0], prefixable: true },
    Symbol { name: "Pa", factor: 1.0, dims: [-1, 1, -2, 0, 0], prefixable: true },
    Symbol { name: "J", factor: 1.0, dims: [2, 1, -2, 0, 0], prefixable: true },
    Symbol { name: "W", factor: 1.0, dims: [2, 1, -3, 0, 0], prefixable: true },
    Symbol { name: "V", factor: 1.0, dims: [2, 1, -3, -1, 0], prefixable: true },
    Symbol { name: "C", factor: 1.0, dims: [0, 0, 1, 1, 0], prefixable: true },
    Symbol { name: "F", factor: 1.0, dims: [-2, -1, 4, 2, 0], prefixable: true },
    Symbol { name: "Hz", factor: 1.0, dims: [0, 0, -1, 0, 0], prefixable: true },
    Symbol { name: "rad", factor: 1.0, dims: [0, 0, 0, 0, 0], prefixable: true },
    Symbol { name: "deg", factor: std::f64::consts::PI / 180.0, dims: [0, 0, 0, 0, 0], prefixable: false },
    Symbol { name: "%", factor: 0.01, dims: [0, 0, 0, 0, 0], prefixable: false },
    Symbol { name: "ppm", factor: 1e-6, dims: [0, 0, 0, 0, 0], prefixable: false },
    Symbol { name: "1", factor: 1.0, dims: [0, 0, 0, 0, 0], prefixable: false },
    Symbol { name: "mol", factor: 1.0, dims: [0, 0, 0, 0, 1], prefixable: true },
];

const PREFIXES: &[(&str, f64)] = &[
    ("f", 1e-15),
    ("p", 1e-12),
    ("n", 1e-9),
    ("u", 1e-6),
    ("µ", 1e-6),
    ("μ", 1e-6),
    ("m", 1e-3),
    ("c", 1e-2),
    ("k", 1e3),
    ("M", 1e6),
    ("G", 1e9),
    ("T", 1e12),
];

/// Parses `text` as a quantity of dimension `dim` and returns its SI value.
///
/// A bare number is taken as SI. Non-finite values (NaN, inf) are rejected. Equivalent to
/// [`parse_quantity_checked`] with [`Constraint::Finite`].
pub fn parse_quantity(text: &str, dim: Dimension) -> Result<f64, QuantityError> {
    parse_quantity_checked(text, dim, Constraint::Finite)
}

/// Parses `text` as a quantity of dimension `dim`, in SI, and checks its sign.
pub fn parse_quantity_checked(text: &str, dim: Dimension, constraint: Constraint) -> Result<f64, QuantityError> {
    let err = |problem: String| QuantityError::new(text, problem, dim, constraint);
    let trimmed = text.trim();
    if trimmed.is_empty() {
        return Err(err("empty value".into()));
    }
    let (number_text, unit_text) = split_number(trimmed);
    if number_text.is_empty() {
        return Err(err("no number at the start".into()));
    }
    let number: f64 = number_text.parse().map_err(|_| err(format!("`{number_text}` is not a number")))?;
    // "9.1e-12.5 1/Pa", "1.2.3 um": the number runs on into digits or dots.
    if unit_text.starts_with(|c: char| c == '.' || c.is_ascii_digit()) {
        let word = trimmed.split_whitespace().next().unwrap_or(trimmed);
        return Err(err(format!("`{word}` is not a number")));
    }
    let unit_text = unit_text.trim();
    let (factor, dims) =
        if unit_text.is_empty() { (1.0, DimensionVector::default()) } else { parse_unit(unit_text).map_err(err)? };
    let expected = dim.vector();
    // A bare number is SI in whatever dimension the field has.
    if !unit_text.is_empty() && dims != expected {
        return Err(err(format!("unit `{unit_text}` is {}", describe(dims))));
    }
    if (dim == Dimension::Angle) && unit_text == "%" {
        return Err(err("a percentage is not an angle".into()));
    }
    // Angles are pure numbers in SI, but a pure-number field (a humidity, a ratio, a coefficient)
    // is never an angle: "35 deg" as a relative humidity would be read as 0.61.
    if dim == Dimension::Dimensionless && !unit_text.is_empty() && unit_text != "%" {
        return Err(err(format!("unit `{unit_text}`: a pure number takes no unit but `%`")));
    }
    let value = number * factor;
    check_value(value, text, dim, constraint)
}

/// Parses `text` with whatever unit it carries and returns its SI value and dimension, without
/// checking against a field (used to sample uncertain parameters before the typed parse).
pub fn parse_any(text: &str) -> Result<(f64, DimensionVector), String> {
    let trimmed = text.trim();
    let (number_text, unit_text) = split_number(trimmed);
    let number: f64 = number_text.parse().map_err(|_| format!("{text:?}: `{number_text}` is not a number"))?;
    let unit_text = unit_text.trim();
    let (factor, dims) = if unit_text.is_empty() {
        (1.0, DimensionVector::default())
    } else {
        parse_unit(unit_text).map_err(|e| format!("{text:?}: {e}"))?
    };
    Ok((number * factor, dims))
}

/// Checks a parsed SI value against the constraint (finite, sign).
pub(crate) fn check_value(
    value: f64,
    text: &str,
    dim: Dimension,
    constraint: Constraint,
) -> Result<f64, QuantityError> {
    let err = |problem: &str| QuantityError::new(text, problem, dim, constraint);
    if value.is_nan() {
        return Err(err("not a number (NaN)"));
    }
    if value.is_infinite() {
        return Err(err("not finite"));
    }
    match constraint {
        Constraint::Positive if value <= 0.0 => Err(err(if value == 0.0 { "zero" } else { "negative" })),
        Constraint::NonNegative if value < 0.0 => Err(err("negative")),
        _ => Ok(value),
    }
}

/// Splits "1.5e-3 um" into ("1.5e-3", " um"). Accepts "nan"/"inf" words so they can be
/// rejected with a clear message rather than as unknown units.
fn split_number(text: &str) -> (&str, &str) {
    let lower = text.to_ascii_lowercase();
    for word in ["-infinity", "+infinity", "infinity", "-inf", "+inf", "inf", "nan"] {
        if lower.starts_with(word) {
            return text.split_at(word.len());
        }
    }
    let bytes = text.as_bytes();
    let mut i = 0;
    if i < bytes.len() && (bytes[i] == b'+' || bytes[i] == b'-') {
        i += 1;
    }
    let digits_start = i;
    while i < bytes.len() && (bytes[i].is_ascii_digit() || bytes[i] == b'.') {
        i += 1;
    }
    if i == digits_start {
        return ("", text);
    }
    // Exponent: e or E followed by an optional sign and at least one digit.
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        let mut j = i + 1;
        if j < bytes.len() && (bytes[j] == b'+' || bytes[j] == b'-') {
            j += 1;
        }
        let exp_start = j;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        if j > exp_start {
            i = j;
        }
    }
    text.split_at(i)
}

/// Parses a unit expression into its SI factor and dimension.
fn parse_unit(unit: &str) -> Result<(f64, DimensionVector), String> {
    let mut factor = 1.0;
    let mut dims = DimensionVector::default();
    for (group_index, group) in unit.split('/').enumerate() {
        let sign: i8 = if group_index == 0 { 1 } else { -1 };
        let group = group.trim();
        if group.is_empty() && group_index == 0 {
            // "/um^2": nothing above the line means 1.
            continue;
        }
        if group.is_empty() {
            return Err(format!("unit `{unit}` has an empty part around `/`"));
        }
        for token in group.split(['*', ' ', '·']).filter(|t| !t.is_empty()) {
            let (f, d) = parse_factor(token).map_err(|e| format!("in unit `{unit}`: {e}"))?;
            factor *= f.powi(sign as i32);
            dims = dims
                .mul(d, sign)
                .ok_or_else(|| format!("unit `{unit}` has a power beyond +/-{}", crate::MAX_UNIT_EXPONENT))?;
        }
    }
    Ok((factor, dims))
}

/// Parses one factor such as `um^2`, `m^-2`, `m2`, `Pa`.
fn parse_factor(token: &str) -> Result<(f64, DimensionVector), String> {
    let (base, power) = match token.find('^') {
        Some(pos) => {
            let p: i8 =
                token[pos + 1..].parse().map_err(|_| format!("`{}` is not an integer power", &token[pos + 1..]))?;
            (&token[..pos], p)
        }
        None => {
            // Trailing digits as a power: "m2", "m-2"; but "1" alone is the number one.
            let split = token.trim_end_matches(|c: char| c.is_ascii_digit() || c == '-');
            if split.is_empty() || split.len() == token.len() {
                (token, 1)
            } else {
                let p: i8 = token[split.len()..].parse().map_err(|_| format!("`{token}` has a malformed power"))?;
                (split, p)
            }
        }
    };
    let (f, d) = lookup(base).ok_or_else(|| format!("unknown unit `{base}`"))?;
    let dims = DimensionVector::default()
        .mul(d, power)
        .ok_or_else(|| format!("`{token}`: the power {power} is beyond +/-{}", crate::MAX_UNIT_EXPONENT))?;
    Ok((f.powi(power as i32), dims))
}

fn lookup(base: &str) -> Option<(f64, DimensionVector)> {
    if let Some(sym) = SYMBOLS.iter().find(|s| s.name == base) {
        return Some((sym.factor, DimensionVector(sym.dims)));
    }
    for (prefix, pf) in PREFIXES {
        if let Some(rest) = base.strip_prefix(prefix)
            && let Some(sym) = SYMBOLS.iter().find(|s| s.name == rest && s.prefixable)
        {
            return Some((pf * sym.factor, DimensionVector(sym.dims)));
        }
    }
    None
}

fn describe(d: DimensionVector) -> String {
    for dim in [
        Dimension::Length,
        Dimension::Area,
        Dimension::Force,
        Dimension::Pressure,
        Dimension::SurfaceEnergy,
        Dimension::Compliance,
        Dimension::ArealDensity,
        Dimension::ForcePerVoltageSquared,
        Dimension::Voltage,
        Dimension::Dimensionless,
        Dimension::Time,
        Dimension::Mass,
        Dimension::Damping,
        Dimension::MolarVolume,
    ] {
        if dim.vector() == d {
            return dim.description().to_string();
        }
    }
    let names = ["m", "kg", "s", "A", "mol"];
    let parts: Vec<String> = names.iter().zip(d.0).filter(|(_, p)| *p != 0).map(|(n, p)| format!("{n}^{p}")).collect();
    format!("of dimension {}", parts.join(" "))
}

/// Formats an SI value with an SI prefix and the unit of `dim`, with 4 significant digits:
/// `format_quantity(5e-7, Dimension::Length)` is `"500 nm"`.
pub fn format_quantity(value: f64, dim: Dimension) -> String {
    let unit = dim.si_unit();
    let prefixable = matches!(
        dim,
        Dimension::Length | Dimension::Force | Dimension::Pressure | Dimension::Voltage | Dimension::Time
    );
    if !value.is_finite() || value == 0.0 || !prefixable {
        return format!("{} {unit}", sig4(value)).trim_end().to_string();
    }
    let exp3 = ((value.abs().log10() / 3.0).floor() as i32).clamp(-5, 4);
    let prefix = match exp3 {
        -5 => "f",
        -4 => "p",
        -3 => "n",
        -2 => "u",
        -1 => "m",
        0 => "",
        1 => "k",
        2 => "M",
        3 => "G",
        _ => "T",
    };
    format!("{} {prefix}{unit}", sig4(value / 10f64.powi(3 * exp3)))
}

fn sig4(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let mag = x.abs().log10().floor() as i32;
    if !(-3..6).contains(&mag) {
        return format!("{x:.3e}");
    }
    let decimals = (3 - mag).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs()
    }

    #[test]
    fn the_issue_examples_convert_to_si() {
        // Every example string of issue 2, with its SI value worked out by hand.
        let cases: &[(&str, Dimension, f64)] = &[
            ("0.5 um", Dimension::Length, 0.5e-6),
            ("0.5um", Dimension::Length, 0.5e-6),
            ("1.4 GPa", Dimension::Pressure, 1.4e9),
            ("3 uN", Dimension::Force, 3e-6),
            ("0.1 J/m^2", Dimension::SurfaceEnergy, 0.1),
            ("9.1e-12 1/Pa", Dimension::Compliance, 9.1e-12),
            ("4e12 m^-2", Dimension::ArealDensity, 4e12),
            ("100 um^2", Dimension::Area, 100e-12),
            ("1.4e-8 N/V^2", Dimension::ForcePerVoltageSquared, 1.4e-8),
            ("35 %", Dimension::Dimensionless, 0.35),
            ("169 GPa", Dimension::Pressure, 169e9),
            ("2.5 N/m", Dimension::Stiffness, 2.5),
            ("40 nm", Dimension::Length, 40e-9),
            ("3e-6", Dimension::Force, 3e-6),
            ("12 V", Dimension::Voltage, 12.0),
            ("0.1 N/m", Dimension::SurfaceEnergy, 0.1),
            ("1 mrad", Dimension::Angle, 1e-3),
            ("107 ng", Dimension::Mass, 107e-12),
            ("2.1e-7 N s/m", Dimension::Damping, 2.1e-7),
            ("2.1e-7 N*s/m", Dimension::Damping, 2.1e-7),
            ("180 deg", Dimension::Angle, std::f64::consts::PI),
            ("1 /um^2", Dimension::ArealDensity, 1e12),
            ("5 mm", Dimension::Length, 5e-3),
            // 1-pentanol at 25 C: 88.148 g/mol / 0.8108 g/cm^3 = 108.7 cm^3/mol = 1.087e-4 m^3/mol.
            ("108.7 cm^3/mol", Dimension::MolarVolume, 108.7e-6),
            ("18.07e-6 m^3/mol", Dimension::MolarVolume, 18.07e-6),
            ("1.087e-4", Dimension::MolarVolume, 1.087e-4),
        ];
        for (text, dim, want) in cases {
            let got = parse_quantity(text, *dim).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!(close(got, *want), "{text}: got {got}, want {want}");
        }
    }

    #[test]
    fn unit_exponents_never_wrap() {
        // 4 x 64 = 256 wraps an i8 to 0: the unit must not silently become dimensionless.
        let e = parse_quantity_checked("0.5 N^64 N^64 N^64 N^64 um", Dimension::Length, Constraint::Positive);
        assert!(e.unwrap_err().to_string().contains("beyond"));
        assert!(parse_quantity("1 m^127", Dimension::Length).is_err());
        assert!(parse_quantity("1 m^-128", Dimension::Length).is_err());
    }

    /// A pure-number field takes a bare number or a percentage, never an angle (an angle is a
    /// pure number in SI: "35 deg" as a relative humidity was read as 0.61).
    #[test]
    fn a_pure_number_is_never_an_angle() {
        use crate::{Constraint, Dimension};
        for text in ["35 deg", "0.6 rad", "1 mrad", "2 m/m"] {
            let e = parse_quantity_checked(text, Dimension::Dimensionless, Constraint::NonNegative).unwrap_err();
            assert!(e.to_string().contains("no unit but `%`"), "{text}: {e}");
        }
        let pct = parse_quantity_checked("35 %", Dimension::Dimensionless, Constraint::NonNegative).unwrap();
        assert!((pct - 0.35).abs() < 1e-16, "{pct}");
        assert_eq!(parse_quantity_checked("0.35", Dimension::Dimensionless, Constraint::NonNegative).unwrap(), 0.35);
        let deg = parse_quantity_checked("35 deg", Dimension::Angle, Constraint::NonNegative).unwrap();
        assert!((deg - 35f64.to_radians()).abs() < 1e-15);
    }

    #[test]
    fn wrong_unit_names_value_and_expectation() {
        let e = parse_quantity("0.5 N", Dimension::Length).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("0.5 N") && msg.contains("a force") && msg.contains("expected a length"), "{msg}");
    }

    #[test]
    fn malformed_nan_inf_and_sign_are_rejected() {
        for (text, needle) in [
            ("abc", "no number"),
            ("1.2.3 um", "not a number"),
            ("NaN", "NaN"),
            ("inf um", "not finite"),
            ("-inf", "not finite"),
            ("0.5 furlong", "unknown unit `furlong`"),
            ("", "empty"),
        ] {
            let msg = parse_quantity(text, Dimension::Length).unwrap_err().to_string();
            assert!(msg.contains(needle), "{text:?} -> {msg}");
        }
        let msg = parse_quantity_checked("-0.5 um", Dimension::Length, Constraint::Positive).unwrap_err().to_string();
        assert!(
            msg.contains("negative") && msg.contains("a positive length") || msg.contains("expected a positive"),
            "{msg}"
        );
        assert!(parse_quantity_checked("0 um", Dimension::Length, Constraint::NonNegative).is_ok());
        assert!(parse_quantity_checked("0 um", Dimension::Length, Constraint::Positive).is_err());
    }

    #[test]
    fn formatting_picks_a_prefix() {
        assert_eq!(format_quantity(5e-7, Dimension::Length), "500 nm");
        assert_eq!(format_quantity(1.4e9, Dimension::Pressure), "1.4 GPa");
        assert_eq!(format_quantity(2.3e-6, Dimension::Force), "2.3 uN");
        // Round trip through the parser.
        let v = 1.234e-6;
        let back = parse_quantity(&format_quantity(v, Dimension::Force), Dimension::Force).unwrap();
        assert!(close(back, v));
    }
}

#[cfg(test)]
mod properties {
    use proptest::prelude::*;

    use super::*;

    proptest! {
        /// Any finite SI value written with the formatter's prefix parses back within the
        /// formatter's 4 significant digits (relative 5e-4 by rounding).
        #[test]
        fn format_then_parse_round_trips(mantissa in 1.0f64..10.0, exp in -14i32..12, negative in any::<bool>()) {
            let value = if negative { -1.0 } else { 1.0 } * mantissa * 10f64.powi(exp);
            for dim in [Dimension::Length, Dimension::Force, Dimension::Pressure, Dimension::Voltage] {
                let text = format_quantity(value, dim);
                let back = parse_quantity(&text, dim).unwrap();
                prop_assert!((back - value).abs() <= 5e-4 * value.abs(), "{} -> {} -> {}", value, text, back);
            }
        }

        /// A number with a unit of another dimension is always rejected, never misread.
        #[test]
        fn a_force_is_never_a_length(x in 1e-3f64..1e3) {
            let text = format!("{x} uN");
            prop_assert!(parse_quantity(&text, Dimension::Length).is_err());
            prop_assert!((parse_quantity(&text, Dimension::Force).unwrap() - x * 1e-6).abs() <= 1e-15 * x);
        }
    }
}
