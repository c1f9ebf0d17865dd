//! Small statistics helpers: quantiles of Student's t and chi^2 (statrs), percentiles, an
//! ordinary least-squares line with the slope/intercept covariance, and Fieller's interval for a
//! ratio.

use statrs::distribution::{ChiSquared, ContinuousCDF, StudentsT};

/// The two-sided 95 % quantile of Student's t with `dof` degrees of freedom (1.96 for infinite
/// `dof`, None for `dof` < 1).
pub fn t975(dof: f64) -> Option<f64> {
    if dof.is_infinite() {
        return Some(1.959_963_984_540_054);
    }
    if !(dof >= 1.0) {
        return None;
    }
    StudentsT::new(0.0, 1.0, dof).ok().map(|t| t.inverse_cdf(0.975))
}

/// Upper-tail probability of chi^2 with `dof` degrees of freedom at `x` (None for `dof` < 1).
pub fn chi2_sf(x: f64, dof: f64) -> Option<f64> {
    if !(dof >= 1.0) || !x.is_finite() {
        return None;
    }
    ChiSquared::new(dof).ok().map(|c| 1.0 - c.cdf(x))
}

/// The `p`-quantile (0..1) of sorted finite values by linear interpolation.
pub fn percentile(sorted: &[f64], p: f64) -> Option<f64> {
    if sorted.is_empty() {
        return None;
    }
    let h = p.clamp(0.0, 1.0) * (sorted.len() - 1) as f64;
    let (i, f) = (h.floor() as usize, h - h.floor());
    let j = (i + 1).min(sorted.len() - 1);
    Some(sorted[i] + f * (sorted[j] - sorted[i]))
}

/// Mean and sample standard deviation (None with fewer than two values).
pub fn mean_sd(v: &[f64]) -> Option<(f64, f64)> {
    if v.len() < 2 {
        return None;
    }
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    Some((m, (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()))
}

/// A robust standard deviation: half the 15.87-84.13 percentile range (equal to the SD for a
/// normal distribution, insensitive to long tails). None with fewer than two values.
pub fn robust_sd(v: &[f64]) -> Option<f64> {
    if v.len() < 2 {
        return None;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    Some(0.5 * (percentile(&s, 0.841_344_746)? - percentile(&s, 0.158_655_254)?))
}

/// A least-squares line `y = intercept + slope x` with its covariance.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Line {
    /// Slope.
    pub slope: f64,
    /// Intercept.
    pub intercept: f64,
    /// Variance of the slope (residual variance / S_xx).
    pub var_slope: f64,
    /// Variance of the intercept, s^2 (1/n + mean_x^2 / S_xx).
    pub var_intercept: f64,
    /// Covariance of slope and intercept, -mean_x s^2 / S_xx.
    pub cov: f64,
    /// Number of points.
    pub points: usize,
    /// Residual degrees of freedom, n - 2.
    pub dof: usize,
    /// Coefficient of determination.
    pub r_squared: f64,
}

/// Running sums of a point set, so that a line can be fitted from them in O(1).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Sums {
    /// Count.
    pub n: f64,
    /// Sum of x.
    pub x: f64,
    /// Sum of y.
    pub y: f64,
    /// Sum of x^2.
    pub xx: f64,
    /// Sum of x y.
    pub xy: f64,
    /// Sum of y^2.
    pub yy: f64,
}

impl Sums {
    /// Adds a point.
    pub fn add(&mut self, x: f64, y: f64) {
        self.n += 1.0;
        self.x += x;
        self.y += y;
        self.xx += x * x;
        self.xy += x * y;
        self.yy += y * y;
    }

    /// The difference of two running sums (the points of `self` not in `other`).
    pub fn minus(&self, o: &Sums) -> Sums {
        Sums {
            n: self.n - o.n,
            x: self.x - o.x,
            y: self.y - o.y,
            xx: self.xx - o.xx,
            xy: self.xy - o.xy,
            yy: self.yy - o.yy,
        }
    }

    /// The least-squares line (None with fewer than 3 points or all x equal). Centred sums are
    /// formed from raw sums; the callers centre x and y near their means first to keep the
    /// cancellation small.
    pub fn line(&self) -> Option<Line> {
        if self.n < 3.0 {
            return None;
        }
        let mx = self.x / self.n;
        let my = self.y / self.n;
        let sxx = self.xx - self.n * mx * mx;
        let sxy = self.xy - self.n * mx * my;
        let syy = self.yy - self.n * my * my;
        if !(sxx > 1e-12 * self.xx.abs().max(f64::MIN_POSITIVE)) {
            return None;
        }
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let sse = (syy - slope * sxy).max(0.0);
        let dof = self.n - 2.0;
        let s2 = sse / dof;
        Some(Line {
            slope,
            intercept,
            var_slope: s2 / sxx,
            var_intercept: s2 * (1.0 / self.n + mx * mx / sxx),
            cov: -mx * s2 / sxx,
            points: self.n as usize,
            dof: dof as usize,
            r_squared: if syy > 0.0 { 1.0 - sse / syy } else { 1.0 },
        })
    }
}

/// Fits a line to points directly (two-pass, centred).
pub fn fit_line(points: &[(f64, f64)]) -> Option<Line> {
    let n = points.len() as f64;
    if points.len() < 3 {
        return None;
    }
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let mut s = Sums::default();
    for p in points {
        s.add(p.0 - mx, p.1 - my);
    }
    let mut l = s.line()?;
    // Shift back: y - my = b (x - mx) + a'  =>  intercept = a' + my - b mx.
    let a_c = l.intercept;
    l.intercept = a_c + my - l.slope * mx;
    // Var(intercept) at x = 0 from the centred fit: Var(a') + mx^2 Var(b) - 2 mx Cov(a', b).
    let var_c = l.var_intercept;
    let cov_c = l.cov;
    l.var_intercept = var_c + mx * mx * l.var_slope - 2.0 * mx * cov_c;
    l.cov = cov_c - mx * l.var_slope;
    Some(l)
}

/// A weighted least-squares line through `(x, y, w)` points (`w` proportional to 1 / Var(y)),
/// with the scale of the variances estimated from the weighted residuals:
/// `s^2 = sum w (y - a - b x)^2 / (n - 2)`, `Var(b) = s^2 / S_xx`, `Var(a) = s^2 (1 / W + m_x^2 /
/// S_xx)`, `Cov(a, b) = -m_x s^2 / S_xx` with `W = sum w`, `m_x = sum w x / W`,
/// `S_xx = sum w (x - m_x)^2` (two-pass, centred). With equal weights this is [`fit_line`]. None
/// with fewer than three points, all x equal or a weight that is not finite and positive.
pub fn weighted_line(points: &[(f64, f64, f64)]) -> Option<Line> {
    if points.len() < 3 || points.iter().any(|p| !(p.2 > 0.0 && p.2.is_finite())) {
        return None;
    }
    let w: f64 = points.iter().map(|p| p.2).sum();
    let mx = points.iter().map(|p| p.2 * p.0).sum::<f64>() / w;
    let my = points.iter().map(|p| p.2 * p.1).sum::<f64>() / w;
    let (mut sxx, mut sxy, mut syy, mut xx) = (0.0, 0.0, 0.0, 0.0);
    for &(x, y, wi) in points {
        let (dx, dy) = (x - mx, y - my);
        sxx += wi * dx * dx;
        sxy += wi * dx * dy;
        syy += wi * dy * dy;
        xx += wi * x * x;
    }
    if !(sxx > 1e-12 * xx.max(f64::MIN_POSITIVE)) {
        return None;
    }
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let sse = points.iter().map(|&(x, y, wi)| wi * (y - intercept - slope * x).powi(2)).sum::<f64>();
    let dof = points.len() - 2;
    let s2 = sse / dof as f64;
    Some(Line {
        slope,
        intercept,
        var_slope: s2 / sxx,
        var_intercept: s2 * (1.0 / w + mx * mx / sxx),
        cov: -mx * s2 / sxx,
        points: points.len(),
        dof,
        r_squared: if syy > 0.0 { (1.0 - sse / syy).max(0.0) } else { 1.0 },
    })
}

/// Fieller's 95 % interval for the ratio `a / b` of two jointly normal estimates with variances
/// `vaa`, `vbb`, covariance `vab` and quantile `t`: the set of `r` with
/// `(a - r b)^2 <= t^2 (vaa - 2 r vab + r^2 vbb)`. Bounded only when `b` is significantly
/// different from zero (`b^2 > t^2 vbb`); otherwise None.
pub fn fieller(a: f64, b: f64, vaa: f64, vbb: f64, vab: f64, t: f64) -> Option<[f64; 2]> {
    let t2 = t * t;
    let qa = b * b - t2 * vbb;
    let qb = -2.0 * (a * b - t2 * vab);
    let qc = a * a - t2 * vaa;
    if !(qa > 0.0) {
        return None;
    }
    let disc = qb * qb - 4.0 * qa * qc;
    if !(disc >= 0.0) {
        return None;
    }
    let r = disc.sqrt();
    let (x1, x2) = ((-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa));
    Some([x1.min(x2), x1.max(x2)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_tables() {
        // Student's t table: t_0.975(10) = 2.228, t_0.975(2) = 4.303; chi^2(1) at 3.841: 0.05.
        assert!((t975(10.0).unwrap() - 2.228).abs() < 1e-3);
        assert!((t975(2.0).unwrap() - 4.303).abs() < 1e-3);
        assert!((chi2_sf(3.841, 1.0).unwrap() - 0.05).abs() < 1e-4);
        assert!(t975(0.5).is_none());
    }

    #[test]
    fn line_covariance_matches_hand_computation() {
        // (0,0), (1,1), (2,1): slope 0.5, intercept 1/6, s^2 = 1/6, S_xx = 2, mean x = 1:
        // var(slope) = 1/12, var(intercept) = 1/6 (1/3 + 1/2) = 5/36, cov = -1/12.
        let l = fit_line(&[(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)]).unwrap();
        assert!((l.slope - 0.5).abs() < 1e-14 && (l.intercept - 1.0 / 6.0).abs() < 1e-14);
        assert!((l.var_slope - 1.0 / 12.0).abs() < 1e-14);
        assert!((l.var_intercept - 5.0 / 36.0).abs() < 1e-14, "{l:?}");
        assert!((l.cov + 1.0 / 12.0).abs() < 1e-14);
    }

    #[test]
    fn weighted_line_matches_hand_computation() {
        // Equal weights: the same line and covariance as the unweighted fit above.
        let l = weighted_line(&[(0.0, 0.0, 2.0), (1.0, 1.0, 2.0), (2.0, 1.0, 2.0)]).unwrap();
        let u = fit_line(&[(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)]).unwrap();
        assert!((l.slope - u.slope).abs() < 1e-14 && (l.intercept - u.intercept).abs() < 1e-14);
        // Scaling all weights by 2 scales s^2 by 2 and S_xx by 2: the variances are unchanged.
        assert!((l.var_slope - u.var_slope).abs() < 1e-14 && (l.var_intercept - u.var_intercept).abs() < 1e-14);
        assert!((l.cov - u.cov).abs() < 1e-14);
        // A weight of 4 on (2, 1): W = 6, m_x = (1 + 8) / 6 = 1.5, m_y = (1 + 4) / 6 = 5/6,
        // S_xx = 2.25 + 0.25 + 4 * 0.25 = 3.5, S_xy = 1.5 * 5/6 + 0.5 * (-1/6) + 4 * 0.5 * (1/6) = 1.5,
        // slope = 3/7, intercept = 5/6 - 1.5 * 3/7 = 4/21.
        let l = weighted_line(&[(0.0, 0.0, 1.0), (1.0, 1.0, 1.0), (2.0, 1.0, 4.0)]).unwrap();
        assert!((l.slope - 3.0 / 7.0).abs() < 1e-14 && (l.intercept - 4.0 / 21.0).abs() < 1e-14, "{l:?}");
        assert!(weighted_line(&[(0.0, 0.0, 1.0), (1.0, 1.0, 0.0), (2.0, 1.0, 1.0)]).is_none());
    }

    #[test]
    fn fieller_reduces_to_the_scaled_interval_when_the_denominator_is_exact() {
        // b exact (vbb = vab = 0): interval (a -/+ t sd_a) / b.
        let i = fieller(2.0, 4.0, 0.01, 0.0, 0.0, 2.0).unwrap();
        assert!((i[0] - (2.0 - 0.2) / 4.0).abs() < 1e-12 && (i[1] - (2.2 / 4.0)).abs() < 1e-12, "{i:?}");
        assert!(fieller(1.0, 0.1, 0.01, 0.01, 0.0, 2.0).is_none());
    }
}
