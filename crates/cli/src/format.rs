//! Number formatting shared by the commands' tables and chart labels.

/// Three significant digits without trailing zeros, plain or a·10ⁿ: 0.5, 1.4, 12400, 9.1·10⁻¹².
pub fn sig3(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let trim = |t: String| if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t };
    let a = v.abs();
    if !(1e-3..1e5).contains(&a) {
        let e = a.log10().floor();
        format!("{}·10{}", trim(format!("{:.2}", v / 10f64.powf(e))), stiction_plot::superscript(e as i64))
    } else {
        let d = a.log10().floor() as i32;
        let decimals = (2 - d).clamp(0, 6) as usize;
        // Round to 3 significant digits also above 1000 (12433 -> 12400).
        let v = if d > 2 { (v / 10f64.powi(d - 2)).round() * 10f64.powi(d - 2) } else { v };
        trim(format!("{:.*}", decimals, v))
    }
}

#[cfg(test)]
mod tests {
    use super::sig3;

    #[test]
    fn three_significant_digits_without_trailing_zeros() {
        assert_eq!(sig3(2.8), "2.8");
        assert_eq!(sig3(0.5), "0.5");
        assert_eq!(sig3(1.4), "1.4");
        assert_eq!(sig3(12433.0), "12400");
        assert_eq!(sig3(0.12345), "0.123");
        assert_eq!(sig3(9.1e-12), "9.1·10⁻¹²");
    }
}
