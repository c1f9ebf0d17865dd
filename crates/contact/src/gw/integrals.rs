//! The probability integrals `F_n(h)` of eq. 6 for a Gaussian height distribution, their logarithms
//! and the normal density, by the methods of the [module docs](super) (erfc forms, asymptotic and
//! Taylor series from the mpmath table `gw_taylor.rs`, double-exponential quadrature).

use std::f64::consts::PI;

use super::taylor;
use crate::error::{ContactError, check_finite, check_nonnegative};

// ---------------------------------------------------------------------------------------------
// Special functions
// ---------------------------------------------------------------------------------------------

/// `ln sqrt(2 pi)`.
pub(super) const LN_SQRT_2PI: f64 = 0.918_938_533_204_672_8;
/// Separation above which the asymptotic series is used.
pub(super) const H_ASYMPTOTIC: f64 = 12.0;

/// `h^2` as an unevaluated sum `hi + lo` (exact).
#[inline]
pub(super) fn square_split(h: f64) -> (f64, f64) {
    let hi = h * h;
    let lo = h.mul_add(h, -hi);
    (hi, lo)
}

/// `exp(x^2) erfc(x)` for `0 <= x <= 9` (relative error a few ulp).
pub(super) fn erfcx_small(x: f64) -> f64 {
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
pub(super) fn de_sum(g: impl Fn(f64) -> f64, u_lo: f64, u_hi: f64) -> f64 {
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
pub(super) fn g_n_quadrature(n: f64, h: f64) -> f64 {
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
pub(super) fn f_n_negative(n: f64, h: f64) -> f64 {
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
pub(super) fn g_n_asymptotic(n: f64, h: f64) -> Option<f64> {
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

/// `G_n(h)` from the Taylor tables (`n = 1/2, 3/2`, `-10 <= h < 12`); `None` elsewhere.
#[inline]
pub(super) fn g_n_taylor(n: f64, h: f64) -> Option<f64> {
    let table = if n == 0.5 {
        &taylor::HALF
    } else if n == 1.5 {
        &taylor::THREE_HALVES
    } else {
        return None;
    };
    let x = (h - taylor::H_LO) / taylor::STEP;
    if !(x >= 0.0 && x < taylor::N_CENTRES as f64) {
        return None;
    }
    let i = (x as usize).min(taylor::N_CENTRES - 1);
    let c = taylor::H_LO + (i as f64 + 0.5) * taylor::STEP;
    let d = c - h;
    let (g0, a) = &table[i];
    let mut acc = 0.0;
    for &ak in a.iter().rev() {
        acc = acc * d + ak;
    }
    Some(g0 * acc)
}

/// `(ln b^n, S)` with `F_n(-b) = b^n S` by the asymptotic series for `b >= 10`; `None` if it does
/// not reach full accuracy.
pub(super) fn f_n_neg_asymptotic(n: f64, b: f64) -> Option<(f64, f64)> {
    if b < 10.0 {
        return None;
    }
    let inv_b2 = 1.0 / (b * b);
    let (mut term, mut sum, mut k) = (1.0f64, 1.0f64, 0.0f64);
    loop {
        let next = term * (n - 2.0 * k) * (n - 2.0 * k - 1.0) / (2.0 * k + 2.0) * inv_b2;
        if next == 0.0 {
            break;
        }
        if k > 0.0 && next.abs() >= term.abs() {
            return None;
        }
        term = next;
        sum += term;
        k += 1.0;
        if term.abs() <= 1e-17 * sum.abs() {
            break;
        }
    }
    Some((n * b.ln(), sum))
}

/// Scaled integral `G_n(h) = F_n(h)/phi(h) = int_0^inf t^n exp(-h t - t^2/2) dt` for `h >= 0`.
pub(super) fn g_n_nonneg(n: f64, h: f64) -> f64 {
    if let Some(g) = g_n_taylor(n, h) {
        return g;
    }
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
pub(super) fn f_n_neg(n: f64, h: f64) -> f64 {
    if let Some(g) = g_n_taylor(n, h) {
        return normal_pdf(h) * g;
    }
    if n != 0.0
        && n != 1.0
        && let Some((ln_bn, s)) = f_n_neg_asymptotic(n, -h)
    {
        return ln_bn.exp() * s;
    }
    let f0 = 0.5 * libm::erfc(h * std::f64::consts::FRAC_1_SQRT_2);
    if n == 0.0 {
        f0
    } else if n == 1.0 {
        normal_pdf(h) - h * f0
    } else {
        f_n_negative(n, h)
    }
}

pub(super) fn check_n_h(n: f64, h: f64) -> Result<(), ContactError> {
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
    if let Some(g) = g_n_taylor(n, h) {
        return Ok(g);
    }
    Ok(if h < 0.0 { (ln_f_n_neg(n, h) - ln_normal_pdf(h)).exp() } else { g_n_nonneg(n, h) })
}

/// Natural logarithm of `F_n(h)` (eq. 6), finite for every finite `h` (e.g. `ln F_0(190) = -18 058.6`).
pub fn ln_f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    check_n_h(n, h)?;
    Ok(ln_f_n_unchecked(n, h))
}

pub(super) fn ln_f_n_unchecked(n: f64, h: f64) -> f64 {
    if h < 0.0 { ln_f_n_neg(n, h) } else { ln_normal_pdf(h) + g_n_nonneg(n, h).ln() }
}

/// `ln F_n(h)` for `h < 0`, in log space where `F_n` would overflow (`|h|^n` beyond 1e308).
pub(super) fn ln_f_n_neg(n: f64, h: f64) -> f64 {
    if h < -10.0
        && let Some((ln_bn, s)) = f_n_neg_asymptotic(n, -h)
    {
        return ln_bn + s.ln();
    }
    f_n_neg(n, h).ln()
}

/// `ln G_n(h) = ln F_n(h) - ln phi(h)` for any finite `h`.
pub(super) fn ln_g_n(n: f64, h: f64) -> f64 {
    if let Some(g) = g_n_taylor(n, h) {
        return g.ln();
    }
    if h < 0.0 { ln_f_n_neg(n, h) - ln_normal_pdf(h) } else { g_n_nonneg(n, h).ln() }
}

/// Base-10 logarithm of `F_n(h)` (e.g. `log10 F_0(190) = -7843.0`).
pub fn log10_f_n(n: f64, h: f64) -> Result<f64, ContactError> {
    Ok(ln_f_n(n, h)? / std::f64::consts::LN_10)
}
