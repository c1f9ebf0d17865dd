//! Two-dimensional real-to-complex FFT on a row-major `ny x nx` grid, built from `realfft` (rows)
//! and `rustfft` (columns).
//!
//! Forward: a real-to-complex transform of each row (length `nx`, giving `nxc = nx/2 + 1` complex
//! values), a transpose to column-major order `[kx][y]`, then a complex transform of each column
//! (length `ny`). The spectrum is kept in that transposed layout `[kx][ky]` (length `nxc * ny`): a
//! convolution multiplies it by a multiplier laid out the same way and runs the steps backwards, so
//! it never needs the second transpose. Transforms are unnormalised (forward then inverse multiplies
//! by `nx * ny`); the multipliers carry the `1/(nx ny)`.
//!
//! Rows and columns are transformed in parallel with rayon; each row or column is an independent
//! transform, so the result does not depend on the thread count (bit for bit).

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// Rows (or columns) per rayon task in the transforms and transposes.
const BLOCK: usize = 16;

/// Plans and sizes of a 2-D real FFT on an `ny x nx` grid.
pub struct Fft2 {
    nx: usize,
    ny: usize,
    nxc: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_fwd: Arc<dyn Fft<f64>>,
    col_inv: Arc<dyn Fft<f64>>,
}

impl std::fmt::Debug for Fft2 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Fft2 {{ nx: {}, ny: {} }}", self.nx, self.ny)
    }
}

impl Fft2 {
    /// Plans for a grid of `nx` columns (fast index) and `ny` rows.
    pub fn new(nx: usize, ny: usize) -> Self {
        let mut rp = RealFftPlanner::<f64>::new();
        let mut cp = FftPlanner::<f64>::new();
        Fft2 {
            nx,
            ny,
            nxc: nx / 2 + 1,
            r2c: rp.plan_fft_forward(nx),
            c2r: rp.plan_fft_inverse(nx),
            col_fwd: cp.plan_fft_forward(ny),
            col_inv: cp.plan_fft_inverse(ny),
        }
    }

    /// Number of complex values in the (transposed) half spectrum: `(nx/2 + 1) * ny`.
    pub fn spectrum_len(&self) -> usize {
        self.nxc * self.ny
    }

    /// Number of kept `kx` values, `nx/2 + 1`.
    pub fn nxc(&self) -> usize {
        self.nxc
    }

    /// Forward transform of `real` (row-major, length `nx*ny`; used as scratch and left garbage)
    /// into `spec` (layout `[kx][ky]`), with `rows` (length `nxc*ny`) as work space.
    pub fn forward(&self, real: &mut [f64], rows: &mut [Complex<f64>], spec: &mut [Complex<f64>]) {
        let (nx, ny, nxc) = (self.nx, self.ny, self.nxc);
        debug_assert_eq!(real.len(), nx * ny);
        let r2c = &self.r2c;
        real.par_chunks_mut(nx * BLOCK).zip(rows.par_chunks_mut(nxc * BLOCK)).for_each_init(
            || r2c.make_scratch_vec(),
            |scratch, (rin, rout)| {
                for (a, b) in rin.chunks_mut(nx).zip(rout.chunks_mut(nxc)) {
                    // Lengths are right by construction, so the transform cannot fail.
                    r2c.process_with_scratch(a, b, scratch).expect("row r2c lengths");
                }
            },
        );
        transpose(rows, spec, ny, nxc);
        let col = &self.col_fwd;
        spec.par_chunks_mut(ny * BLOCK).for_each_init(
            || vec![Complex::default(); col.get_inplace_scratch_len()],
            |scratch, c| col.process_with_scratch(c, scratch),
        );
    }

    /// Inverse transform of `spec` (layout `[kx][ky]`; used as scratch and left garbage) into
    /// `real` (row-major), with `rows` (length `nxc*ny`) as work space. Unnormalised.
    pub fn inverse(&self, spec: &mut [Complex<f64>], rows: &mut [Complex<f64>], real: &mut [f64]) {
        let (nx, ny, nxc) = (self.nx, self.ny, self.nxc);
        let col = &self.col_inv;
        spec.par_chunks_mut(ny * BLOCK).for_each_init(
            || vec![Complex::default(); col.get_inplace_scratch_len()],
            |scratch, c| col.process_with_scratch(c, scratch),
        );
        transpose(spec, rows, nxc, ny);
        let c2r = &self.c2r;
        let even = nx.is_multiple_of(2);
        rows.par_chunks_mut(nxc * BLOCK).zip(real.par_chunks_mut(nx * BLOCK)).for_each_init(
            || c2r.make_scratch_vec(),
            |scratch, (rin, rout)| {
                for (a, b) in rin.chunks_mut(nxc).zip(rout.chunks_mut(nx)) {
                    // The multipliers are real and even, so these imaginary parts are rounding
                    // noise of a real field; clear them as the real transform requires.
                    a[0].im = 0.0;
                    if even {
                        a[nxc - 1].im = 0.0;
                    }
                    c2r.process_with_scratch(a, b, scratch).expect("row c2r lengths");
                }
            },
        );
    }
}

/// Transpose `src` (`rows x cols`, row-major) into `dst` (`cols x rows`), in parallel over blocks
/// of destination rows.
fn transpose(src: &[Complex<f64>], dst: &mut [Complex<f64>], rows: usize, cols: usize) {
    dst.par_chunks_mut(rows * BLOCK).enumerate().for_each(|(blk, out)| {
        let c0 = blk * BLOCK;
        let nc = out.len() / rows;
        // Tiles of 32 source rows keep the reads in cache.
        for r0 in (0..rows).step_by(32) {
            let r1 = (r0 + 32).min(rows);
            for dc in 0..nc {
                let c = c0 + dc;
                let o = &mut out[dc * rows..(dc + 1) * rows];
                for r in r0..r1 {
                    o[r] = src[r * cols + c];
                }
            }
        }
    });
}
