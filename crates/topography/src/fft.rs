//! Two-dimensional complex FFTs with rustfft (row transforms, a blocked transpose, row transforms).
//!
//! `portable` plans use rustfft's scalar planner, so the arithmetic does not depend on the CPU's
//! SIMD features: the generator's output is the same bytes on every x86-64 or ARM machine (given
//! the same `sin`/`cos` of the platform's libm for the twiddle factors). The statistics use the
//! SIMD planner.

use std::sync::Arc;

use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner, FftPlannerScalar};

/// Plans a 1-D transform of length `n`.
pub(crate) fn plan(n: usize, inverse: bool, portable: bool) -> Arc<dyn Fft<f64>> {
    match (portable, inverse) {
        (true, false) => FftPlannerScalar::new().plan_fft_forward(n),
        (true, true) => FftPlannerScalar::new().plan_fft_inverse(n),
        (false, false) => FftPlanner::new().plan_fft_forward(n),
        (false, true) => FftPlanner::new().plan_fft_inverse(n),
    }
}

/// Transposes a `rows x cols` row-major matrix into `cols x rows` (32 x 32 blocks).
pub(crate) fn transpose(src: &[Complex64], rows: usize, cols: usize) -> Vec<Complex64> {
    let mut dst = vec![Complex64::new(0.0, 0.0); src.len()];
    const B: usize = 32;
    for r0 in (0..rows).step_by(B) {
        for c0 in (0..cols).step_by(B) {
            for r in r0..(r0 + B).min(rows) {
                for c in c0..(c0 + B).min(cols) {
                    dst[c * rows + r] = src[r * cols + c];
                }
            }
        }
    }
    dst
}

/// Forward 2-D DFT (unnormalised) of a `ny x nx` row-major grid. Returns the spectrum in
/// transposed layout: `X[kx * ny + ky]`.
pub(crate) fn forward_2d(mut buf: Vec<Complex64>, nx: usize, ny: usize, portable: bool) -> Vec<Complex64> {
    plan(nx, false, portable).process(&mut buf);
    let mut t = transpose(&buf, ny, nx);
    drop(buf);
    plan(ny, false, portable).process(&mut t);
    t
}

/// Inverse 2-D DFT (unnormalised: divide by `nx ny`) of a spectrum in transposed layout
/// `X[kx * ny + ky]`; returns the `ny x nx` row-major grid.
pub(crate) fn inverse_2d(mut spec: Vec<Complex64>, nx: usize, ny: usize, portable: bool) -> Vec<Complex64> {
    plan(ny, true, portable).process(&mut spec);
    let mut g = transpose(&spec, nx, ny);
    drop(spec);
    plan(nx, true, portable).process(&mut g);
    g
}

/// Signed frequency index of DFT bin `k` of `n`: `k` for `k <= n/2`, else `k - n`.
pub(crate) fn signed_index(k: usize, n: usize) -> f64 {
    if k <= n / 2 { k as f64 } else { k as f64 - n as f64 }
}
