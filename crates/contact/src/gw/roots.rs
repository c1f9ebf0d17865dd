//! Root finding for the GW relations: Brent's method on a bracket, and the search for a bracket
//! below a known point of a decreasing function.

use crate::error::ContactError;

/// Brent's method for `f(x) = 0` on `[a, b]` with `f(a) f(b) <= 0`.
pub(super) fn brent(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, what: &'static str) -> Result<f64, ContactError> {
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
pub(super) fn solve_decreasing_below(
    g: impl Fn(f64) -> f64,
    upper: f64,
    what: &'static str,
) -> Result<f64, ContactError> {
    let mut step = 1.0;
    let mut lo = upper.min(0.0) - step;
    while g(lo) < 0.0 {
        step *= 2.0;
        lo -= step;
        if lo.is_nan() || lo <= -1e300 {
            return Err(ContactError::NoConvergence { what, iterations: 0 });
        }
    }
    brent(g, lo, upper, what)
}
