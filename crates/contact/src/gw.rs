//! Greenwood-Williamson statistics of a Gaussian summit-height distribution (section 3.1-3.2):
//! the probability integrals `F_n(h)` (eq. 6), the GW relations (eq. 5, 7) and the GW+DMT load
//! (eq. 8) with Fuller and Tabor's adhesion parameter `theta` (eq. 9).
//!
//! # Probability integrals (eq. 6)
//! `F_n(h) = 1/sqrt(2 pi) int_h^inf (y - h)^n exp(-y^2/2) dy = phi(h) G_n(h)`, with
//! `phi(h) = exp(-h^2/2)/sqrt(2 pi)` and the scaled integral `G_n(h) = int_0^inf t^n exp(-h t - t^2/2) dt`
//! (`G_n = Gamma(n+1) exp(h^2/4) U(n + 1/2, h)` with Whittaker's parabolic cylinder function `U`).
//! `G_n` is smooth and of moderate size for every `h >= 0` (`~ Gamma(n+1)/h^(n+1)` for large `h`),
//! so the far tail is computed in log space: `ln F_n = -h^2/2 - ln sqrt(2 pi) + ln G_n`, with `h^2`
//! split exactly (fused multiply-add) so that `ln F_n` carries an absolute error of a few ulp of
//! its own magnitude (relative error of `F_n` <= 1e-10 for `|h| <= 1000`).
//!
//! Methods (relative accuracy of `G_n` about 1e-14, checked in the tests against an independent
//! adaptive Gauss-Kronrod quadrature and 30-digit mpmath values):
//! * `n = 0`: `G_0 = sqrt(pi/2) erfcx(h/sqrt 2)` (erfc of `libm`, a port of FreeBSD's msun, < 1 ulp;
//!   `exp(x^2)` with the rounding error of `x^2` compensated); `h < 0`: `F_0 = erfc(h/sqrt 2)/2`.
//! * `n = 1`: `G_1 = 1 - h G_0` (`h < 12`, cancellation at most a factor `h^2`);
//!   `h < 0`: `F_1 = phi(h) + |h| F_0(h)`.
//! * any `n >= 0`, `h >= 12`: the asymptotic series
//!   `G_n = sum_k (-1)^k Gamma(n + 2k + 1)/(2^k k!) h^-(n+2k+1)`, summed while its terms fall
//!   (the smallest term is below 1e-20 of the sum for `h >= 12`, `n <= 6`).
//! * other `n`, `0 <= h < 12`: double-exponential (exp-sinh) quadrature of `G_n`, step halved until
//!   two levels agree to 1e-9 (the error then is near 1e-16); `h < 0`: `F_n` directly, split at the peak `t = -h` (tanh-sinh on
//!   `[0, -h]`, exp-sinh beyond).
//!
//! # GW and GW+DMT (eq. 5, 7, 8, 9)
//! With `eta` the summit density (1/m^2), `R` the summit radius, `sigma` the SD of summit heights,
//! `D` the compliance, `A_a` the apparent area and `h = d/sigma` the normalised separation:
//! `N* = N/(eta A_a) = F_0(h)` (5a), `A* = A_r/(eta R sigma A_a) = pi F_1(h)` (5b),
//! `L* = D L/(eta A_a R^(1/2) sigma^(3/2)) = F_3/2(h) - (2 pi/theta) F_0(h)` (5c, 8),
//! `theta = sigma^(3/2) R^(1/2)/(D dgamma R)` (9) (`theta = inf`: no adhesion), and the mean real
//! elastic pressure `p_e = sqrt(sigma/R) F_3/2/(D pi F_1)` (7).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::error::{ContactError, check_finite, check_nonnegative, check_positive};

/// `ln sqrt(2 pi)`.
const LN_SQRT_2PI: f64 = 0.918_938_533_204_672_8;
/// Separation above which the asymptotic series is used.
const H_ASYMPTOTIC: f64 = 12.0;

// ---------------------------------------------------------------------------------------------
// Special functions
// ---------------------------------------------------------------------------------------------

/// `h^2` as an unevaluated sum `hi + lo` (exact).
#[inline]
fn square_split(h: f64) -> (f64, f64) {
    let hi = h * h;
    let lo = h.mul_add(h, -hi);
    (hi, lo)
}

/// `exp(x^2) erfc(x)` for `0 <= x <= 9` (relative error a few ulp).
fn erfcx_small(x: f64) -> f64 {
    let (hi, lo) = square_split(x);
    hi.exp() * (1.0 + lo) * libm::erfc(x)
}

/// Standard normal density `phi(h) = exp(-h^2/2)/sqrt(2 pi)` (relative error a few ulp for all h).
pub fn normal_pdf(h: f64) -> f64 {
    let (hi, lo) = square_split(h);
    (-0.5 * hi).exp() * (-0.5 * lo).exp() * (-LN_SQRT_2PI).exp()
}

/// `ln phi(h) = -h^2/2 - ln sqrt(2 pi)` with `h^2` split exactly.
pub fn ln_normal_pdf(h: f64) -> f64 {
    let (hi, lo) = square_split(h);
    (-0.5 * hi - LN_SQRT_2PI) - 0.5 * lo
}

/// Trapezoidal sums of a double-exponentially decaying integrand `g(u)` on `[u_lo, u_hi]`,
/// step halved from 1/2 until two levels agree to `1e-9` relative (at least step 1/8, at most
/// 2^-9). The error of the trapezoidal rule of such an integrand roughly squares with each halving,
/// so that agreement leaves an error near 1e-16.
fn de_sum(g: impl Fn(f64) -> f64, u_lo: f64, u_hi: f64) -> f64 {
    let mut step = 0.5;
    let k_lo = (u_lo / step).ceil() as i64;
    let k_hi = (u_hi / step).floor() as i64;
    let mut sum: f64 = (k_lo..=k_hi).map(|k| g(k as f64 * step)).sum();
    let mut est = sum * step;
    for level in 1..=8 {
        step *= 0.5;
        // new points: odd multiples of the new step
        let j_lo = ((u_lo / step - 1.0) / 2.0).ceil() as i64;
        let j_hi = ((u_hi / step - 1.0) / 2.0).floor() as i64;
        sum += (j_lo..=j_hi).map(|j| g((2 * j + 1) as f64 * step)).sum::<f64>();
        let new = sum * step;
        let converged = (new - est).abs() <= 1e-9 * new.abs();
        est = new;
        if converged && level >= 2 {
            break;
        }
    }
    est
}

/// `G_n(h) = int_0^inf t^n exp(-h t - t^2/2) dt` for `h >= 0` by exp-sinh quadrature with
/// `t = exp(pi/2 sinh u)/(1 + h)`.
fn g_n_quadrature(n: f64, h: f64) -> f64 {
    let scale = 1.0 / (1.0 + h);
    let ln_scale = scale.ln();
    let g = |u: f64| {
        let ln_t = ln_scale + 0.5 * PI * u.sinh();
        let t = ln_t.exp();
        let e = (n + 1.0) * ln_t - h * t - 0.5 * t * t;
        e.exp() * 0.5 * PI * u.cosh()
    };
    // Truncate where the integrand is below e^-50 of its scale: t^(n+1) < e^-50 on the left,
    // h t + t^2/2 - (n+1) ln t > 50 on the right (G_n >= G_n(12) ~ 1e-2 here, so the neglected
    // parts are below 1e-19 relative).
    let ln_t_lo = -50.0 / (n + 1.0);
    let mut t_hi: f64 = 10.0;
    for _ in 0..4 {
        let rhs = 50.0 + (n + 1.0) * t_hi.max(1.0).ln();
        t_hi = -h + (h * h + 2.0 * rhs).sqrt();
    }
    let u_of = |ln_t: f64| ((ln_t - ln_scale) * 2.0 / PI).asinh();
    de_sum(g, u_of(ln_t_lo).max(-5.0), u_of(t_hi.ln()).min(4.5))
}

/// `F_n(h)` for `h < 0`: `1/sqrt(2 pi) [int_0^b t^n e^{-(t-b)^2/2} dt + int_0^inf (b+u)^n e^{-u^2/2} du]`,
/// `b = -h`.
fn f_n_negative(n: f64, h: f64) -> f64 {
    let b = -h;
    // tanh-sinh on [0, b]: t = b/(1+e^{-v}), b - t = b/(1+e^{v}), v = pi sinh u
    let i1 = de_sum(
        |u: f64| {
            let v = PI * u.sinh();
            let t = b / (1.0 + (-v).exp());
            let bt = b / (1.0 + v.exp());
            let w = b * PI * u.cosh() / (2.0 * (1.0 + v.cosh()));
            if t <= 0.0 || !w.is_finite() {
                return 0.0;
            }
            (n * t.ln() - 0.5 * bt * bt).exp() * w
        },
        -4.0,
        4.0,
    );
    // exp-sinh on [0, inf): u' = exp(pi/2 sinh u)
    let i2 = de_sum(
        |u: f64| {
            let x = (0.5 * PI * u.sinh()).exp();
            let e = n * (b + x).ln() - 0.5 * x * x + x.ln();
            e.exp() * 0.5 * PI * u.cosh()
        },
        // x < e^-50 on the left, x^2/2 - n ln(1 + x/b) > 50 on the right (the integral is >= b^n)
        -((2.0 / PI) * 50.0_f64).asinh(),
        ((2.0 / PI) * (100.0 + 2.0 * n * (1.0 + 12.0 / b.max(1e-300)).ln()).sqrt().ln()).asinh().min(4.5),
    );
    (i1 + i2) * (-LN_SQRT_2PI).exp()
}

/// Asymptotic series of `G_n(h)` for large `h`; `None` if it does not reach full accuracy.
fn g_n_asymptotic(n: f64, h: f64) -> Option<f64> {
    let inv_h2 = 1.0 / (h * h);
    let mut term = 1.0;
    let mut sum = 1.0;
    let mut k = 0.0;
    loop {
        let ratio = -(n + 2.0 * k + 1.0) * (n + 2.0 * k + 2.0) * inv_h2 / (2.0 * (k + 1.0));
        let next = term * ratio;
        if next.abs() >= term.abs() {
            return None;
        }
        term = next;
        sum += term;
        k += 1.0;
        if term.abs() <= 1e-17 * sum.abs() {
            break;
        }
    }
    // Gamma(n+1) / h^(n+1) * sum
    Some(((libm::lgamma(n + 1.0)) - (n + 1.0) * h.ln()).exp() * sum)
}

/// Scaled integral `G_n(h) = F_n(h)/phi(h) = int_0^inf t^n exp(-h t - t^2/2) dt` for `h >= 0`.
fn g_n_nonneg(n: f64, h: f64) -> f64 {
    if h >= H_ASYMPTOTIC
        && let Some(g) = g_n_asymptotic(n, h)
    {
        return g;
    }
    if n == 0.0 {
        (0.5 * PI).sqrt() * erfcx_small(h * std::f64::consts::FRAC_1_SQRT_2)
    } else if n == 1.0 {
        1.0 - h * (0.5 * PI).sqrt() * erfcx_small(h * std::f64::consts::FRAC_1_SQRT_2)
    } else {
        g_n_quadrature(n, h)
    }
}

/// `F_n(h)` for `h < 0` (no underflow there).
fn f_n_neg(n: f64, h: f64) -> f64 {
    let f0 = 0.5 * libm::erfc(h * std::f64::consts::FRAC_1_SQRT_2);
    if n == 0.0 {
        f0
    } else if n == 1.0 {
        normal_pdf(h) - h * f0
    } else {
        f_n_negative(n, h)
    }
}

fn check_n_h(n: f64, h: f64) -> Result<(), ContactError> {
    check_nonnegative("n", n, "a finite order n >= 0")?;
    check_finite("h", h, "a finite normalised separation h")?;
    Ok(())
}

/// Probability integral `F_n(h)` of eq. 6 (dimensionless), any order `n >= 0`, any finite `h`.
/// Underflows to 0 for `h` above about 38; use [`ln_f_n`] / [`log10_f_n`] there.
pub fn f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    check_n_h(n, h)?;
    Ok(if h < 0.0 { f_n_neg(n, h) } else { normal_pdf(h) * g_n_nonneg(n, h) })
}

/// Scaled integral `G_n(h) = F_n(h)/phi(h)` (finite for all `h >= 0`; overflows for `h < -37`).
pub fn scaled_f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    check_n_h(n, h)?;
    Ok(if h < 0.0 { (f_n_neg(n, h).ln() - ln_normal_pdf(h)).exp() } else { g_n_nonneg(n, h) })
}

/// Natural logarithm of `F_n(h)` (eq. 6), finite for every finite `h` (e.g. `ln F_0(190) = -18 058.6`).
pub fn ln_f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    check_n_h(n, h)?;
    Ok(ln_f_n_unchecked(n, h))
}

fn ln_f_n_unchecked(n: f64, h: f64) -> f64 {
    if h < 0.0 { f_n_neg(n, h).ln() } else { ln_normal_pdf(h) + g_n_nonneg(n, h).ln() }
}

/// `ln G_n(h) = ln F_n(h) - ln phi(h)` for any finite `h`.
fn ln_g_n(n: f64, h: f64) -> f64 {
    if h < 0.0 { f_n_neg(n, h).ln() - ln_normal_pdf(h) } else { g_n_nonneg(n, h).ln() }
}

/// Base-10 logarithm of `F_n(h)` (e.g. `log10 F_0(190) = -7843.0`).
pub fn log10_f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    Ok(ln_f_n(n, h)? / std::f64::consts::LN_10)
}

// ---------------------------------------------------------------------------------------------
// Root finding
// ---------------------------------------------------------------------------------------------

/// Brent's method for `f(x) = 0` on `[a, b]` with `f(a) f(b) <= 0`.
fn brent(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, what: &'static str) -> Result<f64, ContactError> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.signum() == fb.signum() || fa.is_nan() || fb.is_nan() {
        return Err(ContactError::NoConvergence { what, iterations: 0 });
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol = 2.0 * f64::EPSILON * b.abs() + 1e-300;
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * m * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol { d } else { tol * m.signum() };
        fb = f(b);
    }
    Err(ContactError::NoConvergence { what, iterations: 200 })
}

/// Find `h` with `g(h) = 0` for a function decreasing in `h`, searching from `start` downwards
/// (doubling steps) for a lower bracket; `upper` is a known point with `g(upper) <= 0`.
fn solve_decreasing_below(g: impl Fn(f64) -> f64, upper: f64, what: &'static str) -> Result<f64, ContactError> {
    let mut step = 1.0;
    let mut lo = upper.min(0.0) - step;
    while g(lo) < 0.0 {
        step *= 2.0;
        lo -= step;
        if lo < -1e8 {
            return Err(ContactError::NoConvergence { what, iterations: 0 });
        }
    }
    brent(g, lo, upper, what)
}

// ---------------------------------------------------------------------------------------------
// GW and GW+DMT in normalised form
// ---------------------------------------------------------------------------------------------

/// `ln(G_3/2(h)/G_0(h))`, decreasing in `h`.
fn ln_ratio_32_0(h: f64) -> f64 {
    ln_g_n(1.5, h) - ln_g_n(0.0, h)
}

/// The pull-off (minimum load) point of GW+DMT for a finite adhesion parameter.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct GwPullOff {
    /// Normalised separation at pull-off, `dL*/dh = 0`: `G_1/2(h) = 4 pi/(3 theta)`.
    pub h: f64,
    /// Minimum normalised load `L*` (negative; may underflow to -0 for large theta).
    pub l_star: f64,
    /// `log10 |L*|` at pull-off (finite even where `L*` underflows).
    pub log10_abs_l_star: f64,
    /// `N* = F_0(h)` at pull-off.
    pub n_star: f64,
    /// `log10 N*` at pull-off.
    pub log10_n_star: f64,
    /// `A* = pi F_1(h)` at pull-off.
    pub a_star: f64,
    /// `log10 A*` at pull-off.
    pub log10_a_star: f64,
}

/// A GW (or GW+DMT) equilibrium on the stable branch (the one with most contact).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct GwState {
    /// Adhesion parameter `theta` (eq. 9); `None` = infinity (no adhesion, plain GW).
    pub theta: Option<f64>,
    /// Normalised separation `h = d/sigma`.
    pub h: f64,
    /// Normalised applied load `L*` (eq. 5c / 8).
    pub l_star: f64,
    /// Fraction of summits in contact `N* = F_0(h)` (eq. 5a).
    pub n_star: f64,
    /// `log10 N*`.
    pub log10_n_star: f64,
    /// Normalised real area `A* = pi F_1(h)` (eq. 5b).
    pub a_star: f64,
    /// `log10 A*`.
    pub log10_a_star: f64,
    /// Normalised elastic (Hertzian) load `F_3/2(h)`.
    pub elastic_l_star: f64,
    /// Normalised adhesive load `(2 pi/theta) F_0(h)` (0 without adhesion).
    pub adhesive_l_star: f64,
    /// Normalised mean real elastic pressure `F_3/2/(pi F_1)`, so that
    /// `p_e = sqrt(sigma/R)/D * elastic_pressure_star` (eq. 7).
    pub elastic_pressure_star: f64,
    /// Normalised applied load per real area `L*/A*` (equals `elastic_pressure_star` without adhesion).
    pub applied_pressure_star: f64,
    /// Pull-off point (`None` without adhesion).
    pub pull_off: Option<GwPullOff>,
}

/// GW / GW+DMT model for one adhesion parameter, with its pull-off point precomputed.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct GwModel {
    theta: Option<f64>,
    pull_off: Option<GwPullOff>,
    /// Normalised separation where `L* = 0` (finite theta only).
    zero_load_h: Option<f64>,
}

/// Adhesion parameter `theta = sigma^(3/2) R^(1/2)/(D dgamma R)` (eq. 9), dimensionless;
/// `None` (infinity) when `dgamma = 0`.
pub fn adhesion_parameter(
    summit_sd_m: f64,
    summit_radius_m: f64,
    compliance_per_pa: f64,
    work_of_adhesion_j_per_m2: f64,
) -> Result<Option<f64>, ContactError> {
    check_positive("summit_sd_m", summit_sd_m, "a finite summit-height SD > 0 (m)")?;
    check_positive("summit_radius_m", summit_radius_m, "a finite summit radius > 0 (m)")?;
    check_positive("compliance_per_pa", compliance_per_pa, "a finite compliance > 0 (1/Pa)")?;
    check_nonnegative(
        "work_of_adhesion_j_per_m2",
        work_of_adhesion_j_per_m2,
        "a finite work of adhesion >= 0 (J/m^2)",
    )?;
    if work_of_adhesion_j_per_m2 == 0.0 {
        return Ok(None);
    }
    Ok(Some(
        summit_sd_m.powf(1.5) * summit_radius_m.sqrt()
            / (compliance_per_pa * work_of_adhesion_j_per_m2 * summit_radius_m),
    ))
}

impl GwModel {
    /// Model for adhesion parameter `theta` (finite, > 0) or `None` (= infinity, plain GW).
    pub fn new(theta: Option<f64>) -> Result<Self, ContactError> {
        let Some(t) = theta else {
            return Ok(GwModel { theta: None, pull_off: None, zero_load_h: None });
        };
        check_positive("theta", t, "a finite adhesion parameter > 0, or none for infinity")?;
        let c = 2.0 * PI / t;
        // pull-off: G_1/2(h) = 2c/3 (ln G_1/2 decreasing in h)
        let target = (2.0 * c / 3.0).ln();
        let g = |h: f64| ln_g_n(0.5, h) - target;
        let h_m = bracket_decreasing(&g, "GW+DMT pull-off separation")?;
        // zero load: ln(G_3/2/G_0) = ln c, below h_m
        let lc = c.ln();
        let h0 = solve_decreasing_below(|h| ln_ratio_32_0(h) - lc, h_m, "GW+DMT zero-load separation")?;
        let (ln_abs, l_star) = if h_m < 0.0 {
            let v = f_n_neg(0.0, h_m) * c - f_n_neg(1.5, h_m);
            (v.ln(), -v)
        } else {
            let v = c * g_n_nonneg(0.0, h_m) - g_n_nonneg(1.5, h_m);
            let ln_abs = ln_normal_pdf(h_m) + v.ln();
            (ln_abs, -normal_pdf(h_m) * v)
        };
        let ln_n = ln_f_n_unchecked(0.0, h_m);
        let ln_a = PI.ln() + ln_f_n_unchecked(1.0, h_m);
        let pull_off = GwPullOff {
            h: h_m,
            l_star,
            log10_abs_l_star: ln_abs / std::f64::consts::LN_10,
            n_star: ln_n.exp(),
            log10_n_star: ln_n / std::f64::consts::LN_10,
            a_star: ln_a.exp(),
            log10_a_star: ln_a / std::f64::consts::LN_10,
        };
        Ok(GwModel { theta, pull_off: Some(pull_off), zero_load_h: Some(h0) })
    }

    /// The adhesion parameter (`None` = infinity).
    pub fn theta(&self) -> Option<f64> {
        self.theta
    }

    /// The pull-off point (`None` without adhesion).
    pub fn pull_off(&self) -> Option<GwPullOff> {
        self.pull_off
    }

    /// Normalised separation at zero applied load (`None` without adhesion: `h = inf`).
    pub fn zero_load_h(&self) -> Option<f64> {
        self.zero_load_h
    }

    /// The state at normalised separation `h` (any `h`, also on the unstable branch).
    pub fn state_at_h(&self, h: f64) -> Result<GwState, ContactError> {
        check_finite("h", h, "a finite normalised separation")?;
        let c = self.theta.map_or(0.0, |t| 2.0 * PI / t);
        let ln_n = ln_f_n_unchecked(0.0, h);
        let ln_f1 = ln_f_n_unchecked(1.0, h);
        let ln_f32 = ln_f_n_unchecked(1.5, h);
        let (g0, g1, g32) = (ln_g_n(0.0, h), ln_g_n(1.0, h), ln_g_n(1.5, h));
        let l_star =
            if h < 0.0 { f_n_neg(1.5, h) - c * f_n_neg(0.0, h) } else { normal_pdf(h) * (g32.exp() - c * g0.exp()) };
        let ln_a = PI.ln() + ln_f1;
        Ok(GwState {
            theta: self.theta,
            h,
            l_star,
            n_star: ln_n.exp(),
            log10_n_star: ln_n / std::f64::consts::LN_10,
            a_star: ln_a.exp(),
            log10_a_star: ln_a / std::f64::consts::LN_10,
            elastic_l_star: ln_f32.exp(),
            adhesive_l_star: c * ln_n.exp(),
            elastic_pressure_star: (g32 - g1).exp() / PI,
            applied_pressure_star: ((g32 - g1).exp() - c * (g0 - g1).exp()) / PI,
            pull_off: self.pull_off,
        })
    }

    /// Separation `h` on the stable branch (most contact) for normalised load `l_star` (eq. 5c / 8).
    /// Without adhesion `l_star` must be > 0. Below the pull-off load: `Err(NoEquilibrium)`
    /// (for large theta the pull-off `|L*|` is below the f64 range, so every negative load is).
    pub fn solve_h(&self, l_star: f64) -> Result<f64, ContactError> {
        check_finite("l_star", l_star, "a finite normalised load L*")?;
        let Some(theta) = self.theta else {
            if l_star <= 0.0 {
                return Err(ContactError::InvalidParameter {
                    field: "l_star",
                    value: l_star,
                    expected: "L* > 0 without adhesion (theta = inf; L* = 0 means no contact)",
                });
            }
            let target = l_star.ln();
            return bracket_decreasing(&|h: f64| ln_f_n_unchecked(1.5, h) - target, "GW separation from load");
        };
        let c = 2.0 * PI / theta;
        let (Some(po), Some(h0)) = (self.pull_off, self.zero_load_h) else {
            return Err(ContactError::NoConvergence { what: "GW+DMT model", iterations: 0 });
        };
        if l_star == 0.0 {
            return Ok(h0);
        }
        if l_star > 0.0 {
            let target = l_star.ln();
            // ln L*(h) for h < h0 (where L* > 0); beyond, a huge negative stand-in for -inf
            let ln_l = |h: f64| -> f64 {
                let (v, ln_scale) = if h < 0.0 {
                    (f_n_neg(1.5, h) - c * f_n_neg(0.0, h), 0.0)
                } else {
                    (g_n_nonneg(1.5, h) - c * g_n_nonneg(0.0, h), ln_normal_pdf(h))
                };
                if v > 0.0 { ln_scale + v.ln() } else { -1e300 }
            };
            return solve_decreasing_below(|h| ln_l(h) - target, h0, "GW+DMT separation from load");
        }
        // L*_min <= L* < 0: h in (h0, h_m], -L* increasing there
        let target = (-l_star).ln();
        if target > po.log10_abs_l_star * std::f64::consts::LN_10 {
            let pull = if po.l_star != 0.0 {
                format!("L* = {:e}", po.l_star)
            } else {
                format!("L* = -10^{:.3}", po.log10_abs_l_star)
            };
            return Err(ContactError::NoEquilibrium { quantity: "l_star", value: l_star, pull_off: pull });
        }
        // ln(-L*(h)) for h > h0 (where L* < 0); below, a huge negative stand-in for -inf
        let ln_neg = |h: f64| -> f64 {
            let (v, ln_scale) = if h < 0.0 {
                (c * f_n_neg(0.0, h) - f_n_neg(1.5, h), 0.0)
            } else {
                (c * g_n_nonneg(0.0, h) - g_n_nonneg(1.5, h), ln_normal_pdf(h))
            };
            if v > 0.0 { ln_scale + v.ln() } else { -1e300 }
        };
        // increasing in h on (h0, h_m]: solve ln(-L*) - target = 0
        brent(|h| ln_neg(h) - target, h0, po.h, "GW+DMT separation from tensile load").or_else(|e| {
            // target equal to the pull-off within rounding
            if (ln_neg(po.h) - target).abs() <= 1e-12 * target.abs().max(1.0) { Ok(po.h) } else { Err(e) }
        })
    }

    /// The stable-branch state for normalised load `l_star`; see [`GwModel::solve_h`].
    pub fn solve(&self, l_star: f64) -> Result<GwState, ContactError> {
        let h = self.solve_h(l_star)?;
        let mut st = self.state_at_h(h)?;
        if l_star != 0.0 && st.l_star.abs() < f64::MIN_POSITIVE {
            st.l_star = l_star;
        }
        Ok(st)
    }
}

/// Root of a decreasing function of `h` on the whole line (bracket found by doubling steps
/// around 0).
fn bracket_decreasing(g: &dyn Fn(f64) -> f64, what: &'static str) -> Result<f64, ContactError> {
    let g0 = g(0.0);
    if g0 == 0.0 {
        return Ok(0.0);
    }
    let dir = if g0 > 0.0 { 1.0 } else { -1.0 };
    let mut prev = 0.0;
    let mut step = 1.0;
    loop {
        let next = prev + dir * step;
        let gn = g(next);
        if gn == 0.0 {
            return Ok(next);
        }
        if gn.signum() != g0.signum() {
            let (a, b) = if dir > 0.0 { (prev, next) } else { (next, prev) };
            return brent(g, a, b, what);
        }
        prev = next;
        step *= 2.0;
        if step > 1e9 {
            return Err(ContactError::NoConvergence { what, iterations: 0 });
        }
    }
}

/// Fraction of summits in contact `N*` at zero applied load (`L* = 0`) against the adhesion
/// parameter: `points` values of theta log-spaced over `[theta_min, theta_max]` (Fig. 2).
pub fn fig2_series(theta_min: f64, theta_max: f64, points: usize) -> Result<Vec<(f64, f64)>, ContactError> {
    check_positive("theta_min", theta_min, "a finite adhesion parameter > 0")?;
    check_positive("theta_max", theta_max, "a finite adhesion parameter > 0")?;
    if theta_max <= theta_min || points < 2 {
        return Err(ContactError::InvalidParameter {
            field: "theta_max",
            value: theta_max,
            expected: "theta_max > theta_min and at least 2 points",
        });
    }
    (0..points)
        .map(|i| {
            let t = theta_min * (theta_max / theta_min).powf(i as f64 / (points - 1) as f64);
            let st = GwModel::new(Some(t))?.solve(0.0)?;
            Ok((t, st.n_star))
        })
        .collect()
}

/// `A*` against `L*` on the stable branch for one theta (`None` = infinity), `points` loads evenly
/// spaced over `[l_star_min, l_star_max]` (Fig. 3). With adhesion the curve starts at the
/// pull-off load if `l_star_min` is below it (the pull-off point is then the first point);
/// without adhesion `l_star_min` must be > 0 (else `Err`).
pub fn fig3_series(
    theta: Option<f64>,
    l_star_min: f64,
    l_star_max: f64,
    points: usize,
) -> Result<Vec<(f64, f64)>, ContactError> {
    check_finite("l_star_min", l_star_min, "a finite normalised load")?;
    check_finite("l_star_max", l_star_max, "a finite normalised load")?;
    if l_star_max <= l_star_min || points < 2 {
        return Err(ContactError::InvalidParameter {
            field: "l_star_max",
            value: l_star_max,
            expected: "l_star_max > l_star_min and at least 2 points",
        });
    }
    let model = GwModel::new(theta)?;
    let start = match model.pull_off() {
        Some(po) if po.l_star > l_star_min => po.l_star,
        _ => l_star_min,
    };
    let mut out = Vec::with_capacity(points);
    if let Some(po) = model.pull_off()
        && po.l_star > l_star_min
    {
        out.push((po.l_star, po.a_star));
    }
    let first = out.len();
    for i in first..points {
        let l = start + (l_star_max - start) * i as f64 / (points - 1) as f64;
        let st = model.solve(l)?;
        out.push((l, st.a_star));
    }
    Ok(out)
}

// ---------------------------------------------------------------------------------------------
// Dimensional wrapper
// ---------------------------------------------------------------------------------------------

/// A nominally flat rough contact in the GW picture (composite values of both surfaces).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct GwSurface {
    /// Summit density `eta`, 1/m^2.
    pub summit_density_per_m2: f64,
    /// Summit radius `R`, m.
    pub summit_radius_m: f64,
    /// Standard deviation of the summit heights `sigma`, m.
    pub summit_sd_m: f64,
    /// Compliance `D` (eq. 3), 1/Pa.
    pub compliance_per_pa: f64,
    /// Work of adhesion `dgamma`, J/m^2 (0: plain GW).
    pub work_of_adhesion_j_per_m2: f64,
    /// Apparent contact area `A_a`, m^2.
    pub apparent_area_m2: f64,
}

/// A dimensional GW / GW+DMT equilibrium.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct GwContact {
    /// The normalised state.
    pub normalized: GwState,
    /// Separation `d = h sigma`, m.
    pub separation_m: f64,
    /// Applied load `L`, N.
    pub load_n: f64,
    /// Expected number of summits in contact `N = eta A_a N*`.
    pub contacts: f64,
    /// `log10 N`.
    pub log10_contacts: f64,
    /// Real contact area `A_r = eta R sigma A_a A*`, m^2.
    pub real_area_m2: f64,
    /// `log10 (A_r / 1 m^2)`.
    pub log10_real_area_m2: f64,
    /// Total adhesive load `(2 pi dgamma R) N`, N.
    pub adhesive_load_n: f64,
    /// Mean real elastic contact pressure `p_e` (eq. 7), Pa.
    pub mean_elastic_pressure_pa: f64,
}

impl GwSurface {
    /// The paper's Table 1: eta = 4e12 1/m^2, R = 0.5 um, sigma = 0.04 um, D = 9.1e-12 1/Pa,
    /// dgamma = 0.1 J/m^2, A_a = 100 um^2.
    pub fn table1() -> Self {
        GwSurface {
            summit_density_per_m2: 4e12,
            summit_radius_m: 0.5e-6,
            summit_sd_m: 0.04e-6,
            compliance_per_pa: 9.1e-12,
            work_of_adhesion_j_per_m2: 0.1,
            apparent_area_m2: 100e-12,
        }
    }

    /// Check every field (all finite and > 0, work of adhesion >= 0).
    pub fn validate(&self) -> Result<(), ContactError> {
        check_positive("summit_density_per_m2", self.summit_density_per_m2, "a finite summit density > 0 (1/m^2)")?;
        check_positive("apparent_area_m2", self.apparent_area_m2, "a finite area > 0 (m^2)")?;
        adhesion_parameter(
            self.summit_sd_m,
            self.summit_radius_m,
            self.compliance_per_pa,
            self.work_of_adhesion_j_per_m2,
        )?;
        Ok(())
    }

    /// Adhesion parameter theta (eq. 9); `None` = infinity (no adhesion).
    pub fn adhesion_parameter(&self) -> Result<Option<f64>, ContactError> {
        self.validate()?;
        adhesion_parameter(
            self.summit_sd_m,
            self.summit_radius_m,
            self.compliance_per_pa,
            self.work_of_adhesion_j_per_m2,
        )
    }

    /// Load scale `eta A_a R^(1/2) sigma^(3/2)/D` (N): `L = L* * scale` (eq. 5c).
    pub fn load_scale_n(&self) -> f64 {
        self.summit_density_per_m2 * self.apparent_area_m2 * self.summit_radius_m.sqrt() * self.summit_sd_m.powf(1.5)
            / self.compliance_per_pa
    }

    /// Area scale `eta R sigma A_a` (m^2): `A_r = A* * scale` (eq. 5b).
    pub fn area_scale_m2(&self) -> f64 {
        self.summit_density_per_m2 * self.summit_radius_m * self.summit_sd_m * self.apparent_area_m2
    }

    /// Pressure scale `sqrt(sigma/R)/D` (Pa): `p_e = scale * F_3/2/(pi F_1)` (eq. 7).
    pub fn pressure_scale_pa(&self) -> f64 {
        (self.summit_sd_m / self.summit_radius_m).sqrt() / self.compliance_per_pa
    }

    /// The stable-branch equilibrium under applied load `load_n` (N), with DMT adhesion if the
    /// work of adhesion is > 0 (`with_adhesion = false` forces plain GW).
    pub fn solve_load(&self, load_n: f64, with_adhesion: bool) -> Result<GwContact, ContactError> {
        check_finite("load_n", load_n, "a finite load (N)")?;
        let theta = if with_adhesion {
            self.adhesion_parameter()?
        } else {
            self.validate()?;
            None
        };
        let model = GwModel::new(theta)?;
        let st = model.solve(load_n / self.load_scale_n())?;
        Ok(self.dimensional(st, load_n))
    }

    fn dimensional(&self, st: GwState, load_n: f64) -> GwContact {
        let n_scale = self.summit_density_per_m2 * self.apparent_area_m2;
        let contacts = n_scale * st.n_star;
        GwContact {
            normalized: st,
            separation_m: st.h * self.summit_sd_m,
            load_n,
            contacts,
            log10_contacts: st.log10_n_star + n_scale.log10(),
            real_area_m2: st.a_star * self.area_scale_m2(),
            log10_real_area_m2: st.log10_a_star + self.area_scale_m2().log10(),
            adhesive_load_n: if st.theta.is_some() {
                2.0 * PI * self.work_of_adhesion_j_per_m2 * self.summit_radius_m * contacts
            } else {
                0.0
            },
            mean_elastic_pressure_pa: self.pressure_scale_pa() * st.elastic_pressure_star,
        }
    }
}
