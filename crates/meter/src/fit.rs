//! The straight line of eq. 10, `F_f = mu_e,a (F_a0 + L)`, fitted by least squares.

use serde::Serialize;

/// An ordinary least-squares line y = slope x + intercept with standard errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineFit {
    /// Slope (for eq. 10: mu_e,a).
    pub slope: f64,
    /// Intercept (for eq. 10: mu_e,a F_a0, N; JSON `intercept_n`: every LineFit of the meter is
    /// eq. 10 in newtons).
    #[serde(rename = "intercept_n")]
    pub intercept: f64,
    /// Standard error of the slope.
    pub slope_se: f64,
    /// Standard error of the intercept, N (JSON `intercept_se_n`).
    #[serde(rename = "intercept_se_n")]
    pub intercept_se: f64,
    /// Coefficient of determination R^2.
    pub r_squared: f64,
    /// Number of points.
    pub points: usize,
}

/// Relative tolerance below which two abscissae count as equal: differences below
/// 1e-9 of the largest |x| are rounding noise of the inputs, not a spread to fit a slope on.
pub const DISTINCT_X_RELATIVE_TOLERANCE: f64 = 1e-9;

/// The least number of distinct abscissae a line is fitted through: with two, the line goes
/// through both points and nothing estimates its uncertainty.
pub const MIN_DISTINCT_X: usize = 3;

/// The number of distinct abscissae of `points`: sorted x values more than
/// [`DISTINCT_X_RELATIVE_TOLERANCE`] times max |x| apart.
pub fn distinct_abscissae(points: &[(f64, f64)]) -> usize {
    let mut xs: Vec<f64> = points.iter().map(|p| p.0).collect();
    xs.sort_by(f64::total_cmp);
    let scale = xs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = DISTINCT_X_RELATIVE_TOLERANCE * scale;
    let mut count = 0;
    let mut last = f64::NEG_INFINITY;
    for x in xs {
        if count == 0 || x - last > tol {
            count += 1;
            last = x;
        }
    }
    count
}

impl LineFit {
    /// Fits `points` (x, y); None with fewer than [`MIN_DISTINCT_X`] distinct abscissae (relative
    /// spread, see [`distinct_abscissae`]), a non-finite point, or a non-finite result.
    pub fn least_squares(points: &[(f64, f64)]) -> Option<LineFit> {
        let n = points.len();
        if points.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) || distinct_abscissae(points) < MIN_DISTINCT_X {
            return None;
        }
        let nf = n as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / nf;
        let my = points.iter().map(|p| p.1).sum::<f64>() / nf;
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let syy: f64 = points.iter().map(|p| (p.1 - my).powi(2)).sum();
        if sxx.is_nan() || sxx <= 0.0 {
            return None;
        }
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let sse: f64 = points.iter().map(|p| (p.1 - intercept - slope * p.0).powi(2)).sum();
        // n >= 3 here.
        let s2 = sse / (nf - 2.0);
        let (slope_se, intercept_se) = ((s2 / sxx).sqrt(), (s2 * (1.0 / nf + mx * mx / sxx)).sqrt());
        let r_squared = if syy > 0.0 { 1.0 - sse / syy } else { 1.0 };
        let fit = LineFit { slope, intercept, slope_se, intercept_se, r_squared, points: n };
        [slope, intercept, slope_se, intercept_se, r_squared].iter().all(|v| v.is_finite()).then_some(fit)
    }
}

/// Why [`LineFit::least_squares`] gives no line for these points (None when it gives one).
pub fn no_fit_reason(points: &[(f64, f64)]) -> Option<String> {
    if LineFit::least_squares(points).is_some() {
        return None;
    }
    let d = distinct_abscissae(points);
    Some(if d < MIN_DISTINCT_X {
        format!(
            "{} point(s) with L > 0 at {d} distinct load(s): the eq. 10 fit needs at least {MIN_DISTINCT_X} distinct \
             loads (relative spread above {DISTINCT_X_RELATIVE_TOLERANCE:e})",
            points.len()
        )
    } else {
        "the eq. 10 fit has no finite result for these points (values out of range)".to_string()
    })
}

/// The least number of points an eq. 10 fit should rest on without a warning: with fewer, its
/// n - 2 degrees of freedom leave the standard error (and R^2) themselves too uncertain to judge
/// the fit by (3 points: one degree of freedom, a 95 % interval of +/- 12.7 standard errors).
pub const MIN_RECOMMENDED_POINTS: usize = 5;

/// The least fraction of the scheduled clamp voltages an eq. 10 fit should use without a warning.
pub const MIN_CLAMP_RANGE_FRACTION: f64 = 0.5;

/// Warnings about an eq. 10 fit: `few_points` (fewer than [`MIN_RECOMMENDED_POINTS`]) and
/// `partial_clamp_range` (fewer than [`MIN_CLAMP_RANGE_FRACTION`] of the `scheduled` clamp
/// voltages among the `fitted` ones; the other points say why in their `reason`).
pub fn eq10_warnings(
    line: &LineFit,
    scheduled: &[f64],
    fitted: &[f64],
    points: &[crate::MeterPoint],
) -> Vec<stiction_scenario::Warning> {
    let mut out = Vec::new();
    if line.points < MIN_RECOMMENDED_POINTS {
        out.push(stiction_scenario::Warning::new(
            "few_points",
            format!(
                "the eq. 10 fit rests on {} points (fewer than {MIN_RECOMMENDED_POINTS}): with {} degree(s) of \
                 freedom its standard error and R^2 say little about mu_e,a; measure at more clamp voltages with \
                 contact and slip",
                line.points,
                line.points.saturating_sub(2)
            ),
        ));
    }
    let range = |v: &[f64]| {
        (v.iter().cloned().fold(f64::INFINITY, f64::min), v.iter().cloned().fold(f64::NEG_INFINITY, f64::max))
    };
    if !scheduled.is_empty() && (fitted.len() as f64) < MIN_CLAMP_RANGE_FRACTION * scheduled.len() as f64 {
        let (a, b) = range(fitted);
        let (lo, hi) = range(scheduled);
        let first_reason = points.iter().find_map(|p| p.reason.clone()).unwrap_or_default();
        out.push(stiction_scenario::Warning::new(
            "partial_clamp_range",
            format!(
                "the eq. 10 fit uses {} of {} clamp voltages ({a:.2}-{b:.2} V of {lo:.2}-{hi:.2} V): mu_e,a and \
                 F_a0 describe only that part of the range; the other points have no contact, load or slip (e.g. \
                 {first_reason})",
                fitted.len(),
                scheduled.len()
            ),
        ));
    }
    out
}

/// One-sided confidence at which the eq. 10 slope must be above zero to count as a slope: 95 %.
pub const SLOPE_CONFIDENCE: f64 = 0.95;

/// Eq. 10 of a set of (L, F_f) points: the line, mu_e,a, F_a0, and why they are null when they are.
#[derive(Debug, Clone, PartialEq)]
pub struct Eq10Fit {
    /// The least-squares line, when eq. 10 is determined.
    pub line: Option<LineFit>,
    /// mu_e,a, the slope (None when eq. 10 is not determined).
    pub mu_apparent: Option<f64>,
    /// F_a0 = intercept / slope, N (None when eq. 10 is not determined).
    pub apparent_adhesion_force_n: Option<f64>,
    /// Why there is no mu_e,a (None exactly when there is one).
    pub note: Option<String>,
}

/// The number of distinct values among `v`, two values being equal when they differ by at most
/// [`DISTINCT_X_RELATIVE_TOLERANCE`] of the largest |v|.
fn distinct_values(v: impl Iterator<Item = f64>) -> usize {
    distinct_abscissae(&v.map(|x| (x, 0.0)).collect::<Vec<_>>())
}

/// The one-sided Student t quantile at [`SLOPE_CONFIDENCE`] for `dof` degrees of freedom: the
/// closed forms for 1 and 2 degrees of freedom, the Cornish-Fisher expansion about the normal
/// quantile beyond (Abramowitz & Stegun 26.7.5; within 2e-3 of their table 26.10 from 3 on).
pub fn t_one_sided_95(dof: usize) -> f64 {
    match dof {
        0 => f64::INFINITY,
        // t_1 = tan(pi (p - 1/2)), t_2 = (2p - 1) sqrt(2 / (1 - (2p - 1)^2)) at p = 0.95.
        1 => (std::f64::consts::PI * (SLOPE_CONFIDENCE - 0.5)).tan(),
        2 => {
            let a = 2.0 * SLOPE_CONFIDENCE - 1.0;
            a * (2.0 / (1.0 - a * a)).sqrt()
        }
        _ => {
            let z: f64 = 1.644_853_626_951_472_2; // the normal quantile at 0.95
            let n = dof as f64;
            let g1 = (z.powi(3) + z) / 4.0;
            let g2 = (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / 96.0;
            let g3 = (3.0 * z.powi(7) + 19.0 * z.powi(5) + 17.0 * z.powi(3) - 15.0 * z) / 384.0;
            let g4 =
                (79.0 * z.powi(9) + 776.0 * z.powi(7) + 1482.0 * z.powi(5) - 1920.0 * z.powi(3) - 945.0 * z) / 92160.0;
            z + g1 / n + g2 / (n * n) + g3 / n.powi(3) + g4 / n.powi(4)
        }
    }
}

/// Eq. 10 from (L, F_f) points, determined only when the data determine it: at least
/// [`MIN_DISTINCT_X`] distinct loads, at least two distinct frictions (a flat line, every point
/// slipping at the same pull voltage, has no slope to fit: rounding left slopes of 4e-31 and
/// F_a0 = 2.5e25 N), and a slope above zero at [`SLOPE_CONFIDENCE`] one-sided (slope > t se).
/// Then mu_e,a is the slope and F_a0 = intercept / slope; otherwise all three are None and
/// `note` says why.
pub fn eq10(points: &[(f64, f64)]) -> Eq10Fit {
    let none =
        |note: String| Eq10Fit { line: None, mu_apparent: None, apparent_adhesion_force_n: None, note: Some(note) };
    let Some(line) = LineFit::least_squares(points) else {
        return none(no_fit_reason(points).unwrap_or_default());
    };
    if distinct_values(points.iter().map(|p| p.1)) < 2 {
        return none(format!(
            "every one of the {} points has the same friction F_f = {:.6} uN (the same pull voltage at slip): the \
             line is flat and eq. 10 has no slope to fit; the pull ramp does not resolve how friction changes \
             with load",
            points.len(),
            points[0].1 * 1e6
        ));
    }
    let t = t_one_sided_95(line.points.saturating_sub(2));
    // Not above zero at the confidence (a NaN slope is not above either).
    if line.slope.is_nan() || line.slope <= t * line.slope_se {
        return none(format!(
            "the slope {:.4e} +/- {:.2e} (standard error) is not above zero at {:.0} % confidence (t = {:.3} for \
             {} degrees of freedom): the data do not determine mu_e,a",
            line.slope,
            line.slope_se,
            SLOPE_CONFIDENCE * 100.0,
            t,
            line.points.saturating_sub(2)
        ));
    }
    Eq10Fit {
        line: Some(line),
        mu_apparent: Some(line.slope),
        apparent_adhesion_force_n: Some(line.intercept / line.slope),
        note: None,
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
        // Two points fit exactly but have no standard error: refused (was "+/- NaN").
        assert!(LineFit::least_squares(&pts[..2]).is_none());
        // Seven equal loads with rounding noise are one abscissa, not a spread (was R^2 = 1).
        let equal: Vec<(f64, f64)> =
            (0..7).map(|i| (4.2e-6 * (1.0 + i as f64 * 1e-16), 3e-6 + i as f64 * 1e-9)).collect();
        assert_eq!(distinct_abscissae(&equal), 1);
        assert!(LineFit::least_squares(&equal).is_none());
        assert!(no_fit_reason(&equal).unwrap().contains("1 distinct"));
        assert!(LineFit::least_squares(&[(0.0, 0.0), (1.0, f64::NAN), (2.0, 1.0)]).is_none());
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

    /// The t quantile against tables (t_0.95 for 1, 2, 3, 5, 10, 30 degrees of freedom: 6.314,
    /// 2.920, 2.353, 2.015, 1.812, 1.697; Abramowitz & Stegun table 26.10) within 2e-3.
    #[test]
    fn t_quantiles_match_the_tables() {
        for (dof, table) in [(1, 6.314), (2, 2.920), (3, 2.353), (5, 2.015), (10, 1.812), (30, 1.697)] {
            assert!((t_one_sided_95(dof) - table).abs() < 2e-3, "{dof}: {}", t_one_sided_95(dof));
        }
    }

    /// Eq. 10 is determined only when the data determine it: a flat line (every point at one pull
    /// voltage, a rounding slope of 4e-31) and a slope within its noise are null with a reason; a
    /// clean line gives mu_e,a and F_a0 and no note.
    #[test]
    fn undetermined_lines_are_null_with_a_reason() {
        let flat: Vec<(f64, f64)> = (0..6).map(|i| (1e-6 * (1 + i) as f64, 2.5e-6)).collect();
        let f = eq10(&flat);
        assert!(f.mu_apparent.is_none() && f.line.is_none() && f.note.as_deref().unwrap().contains("flat"), "{f:?}");
        // Rounding noise on a flat line: y differs in the last bits only.
        let noisy: Vec<(f64, f64)> =
            (0..6).map(|i| (1e-6 * (1 + i) as f64, 2.5e-6 * (1.0 + (i % 2) as f64 * 1e-16))).collect();
        assert!(eq10(&noisy).note.unwrap().contains("flat"));
        // A slope of 0.01 under noise of 1 uN on 4 points: not above zero at 95 %.
        let weak = [(1e-6, 3e-6), (2e-6, 2e-6), (3e-6, 4e-6), (4e-6, 3.04e-6)];
        let w = eq10(&weak);
        assert!(w.mu_apparent.is_none() && w.note.as_deref().unwrap().contains("not above zero"), "{w:?}");
        let down = [(1e-6, 4e-6), (2e-6, 3e-6), (3e-6, 2e-6)];
        assert!(eq10(&down).note.unwrap().contains("not above zero"));
        let line: Vec<(f64, f64)> = (0..6).map(|i| (1e-6 * i as f64, 0.7 * (2.3e-6 + 1e-6 * i as f64))).collect();
        let g = eq10(&line);
        assert!(g.note.is_none() && (g.mu_apparent.unwrap() - 0.7).abs() < 1e-12, "{g:?}");
        assert!((g.apparent_adhesion_force_n.unwrap() - 2.3e-6).abs() < 1e-17);
    }
}
