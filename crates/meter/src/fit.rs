//! The straight line of eq. 10, `F_f = mu_e,a (F_a0 + L)`, fitted by least squares.

use serde::Serialize;

/// An ordinary least-squares line y = slope x + intercept with standard errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineFit {
    /// Slope (for eq. 10: mu_e,a).
    pub slope: f64,
    /// Intercept (for eq. 10: mu_e,a F_a0, N).
    pub intercept: f64,
    /// Standard error of the slope (NaN with two points).
    pub slope_se: f64,
    /// Standard error of the intercept (NaN with two points).
    pub intercept_se: f64,
    /// Coefficient of determination R^2.
    pub r_squared: f64,
    /// Number of points.
    pub points: usize,
}

impl LineFit {
    /// Fits `points` (x, y); None with fewer than two points or all x equal.
    pub fn least_squares(points: &[(f64, f64)]) -> Option<LineFit> {
        let n = points.len();
        if n < 2 {
            return None;
        }
        let nf = n as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
        if sxx <= 0.0 {
            return None;
        }
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let sse: f64 = points.iter().map(|p| (p.1 - intercept - slope * p.0).powi(2)).sum();
        let (slope_se, intercept_se) = if n > 2 {
            let s2 = sse / (nf - 2.0);
            ((s2 / sxx).sqrt(), (s2 * (1.0 / nf + mx * mx / sxx)).sqrt())
        } else {
            (f64::NAN, f64::NAN)
        };
        let r_squared = if syy > 0.0 { 1.0 - sse / syy } else { 1.0 };
        Some(LineFit { slope, intercept, slope_se, intercept_se, r_squared, points: n })
    }
}

/// Eq. 10 from (L, F_f) points: the least-squares line, mu_e,a = its slope and
/// F_a0 = intercept / slope (None without a line of positive slope).
pub fn eq10(points: &[(f64, f64)]) -> (Option<LineFit>, Option<f64>, Option<f64>) {
    let line = LineFit::least_squares(points);
    match &line {
        Some(l) if l.slope > 0.0 => (line, Some(l.slope), Some(l.intercept / l.slope)),
        _ => (line, None, None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_an_exact_line_and_rejects_degenerate_input() {
        // F_f = 0.7 (2.3e-6 + L): slope 0.7, intercept 1.61e-6 (the paper's Fig. 7 numbers).
        let pts: Vec<(f64, f64)> = (0..6)
            .map(|i| {
                let l = i as f64 * 2e-6;
                (l, 0.7 * (2.3e-6 + l))
            })
            .collect();
        let f = LineFit::least_squares(&pts).unwrap();
        assert!((f.slope - 0.7).abs() < 1e-12 && (f.intercept - 1.61e-6).abs() < 1e-18, "{f:?}");
        assert!((f.r_squared - 1.0).abs() < 1e-12);
        assert!(LineFit::least_squares(&pts[..1]).is_none());
        assert!(LineFit::least_squares(&[(1.0, 1.0), (1.0, 2.0)]).is_none());
    }

    #[test]
    fn standard_errors_match_a_hand_computed_case() {
        // Points (0,0), (1,1), (2,1): slope 0.5, intercept 1/6, residuals -1/6, 1/3, -1/6;
        // s^2 = (1/36 + 1/9 + 1/36) / 1 = 1/6, sxx = 2, se(slope) = sqrt(1/12).
        let f = LineFit::least_squares(&[(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)]).unwrap();
        assert!((f.slope - 0.5).abs() < 1e-15);
        assert!((f.intercept - 1.0 / 6.0).abs() < 1e-15);
        assert!((f.slope_se - (1.0f64 / 12.0).sqrt()).abs() < 1e-15);
    }
}
