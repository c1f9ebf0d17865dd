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
//! transform, so the result does not depend on the thread count (bit for bit). A convolution is
//! one call ([`Fft2::convolve`]): the column transforms, the multiplication and the inverse column
//! transforms are one pass over each block of columns.

use std::sync::Arc;

use rayon::prelude::*;
use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};

/// Least rows (or columns) per rayon task in the transforms and transposes.
const BLOCK: usize = 16;

/// Least values per rayon task in the transforms (2^12: a 64 x 64 grid is one task; from 256
/// points a side, [`BLOCK`] rows, so that a worker can take over the blocks of one that the
/// machine has descheduled).
const MIN_TASK_POINTS: usize = 1 << 12;

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
        let c2r = &*self.c2r;
        rows.par_chunks_mut(nxc * BLOCK).zip(real.par_chunks_mut(nx * BLOCK)).for_each_init(
            || c2r.make_scratch_vec(),
            |scratch, (rin, rout)| {
                for (a, b) in rin.chunks_mut(nxc).zip(rout.chunks_mut(nx)) {
                    row_inverse(c2r, a, b, scratch);
                }
            },
        );
    }

    /// Rows (or columns) of `len` values per rayon task: at least [`BLOCK`], and at least
    /// [`MIN_TASK_POINTS`] values, so a small grid runs as a few tasks (each row or column is an
    /// independent transform, so the grouping does not change a bit of the result).
    fn per_task(len: usize) -> usize {
        BLOCK.max(MIN_TASK_POINTS / len.max(1))
    }

    /// The periodic convolution `out = IFFT(m * FFT(input))` (unnormalised: `m` carries the
    /// `1/(nx ny)`), with `m` laid out as the spectrum (`[kx][ky]`, length `nxc*ny`), `rows` and
    /// `spec` (length `nxc*ny`) as work space. Five parallel passes: rows forward, a transpose,
    /// each column forward, multiplied and inverse, a transpose, rows inverse.
    pub fn convolve(
        &self,
        input: &[f64],
        m: &[f64],
        rows: &mut [Complex<f64>],
        spec: &mut [Complex<f64>],
        out: &mut [f64],
    ) {
        let (nx, nxc) = (self.nx, self.nxc);
        debug_assert_eq!(input.len(), nx * self.ny);
        let r2c = &self.r2c;
        let rb = Self::per_task(nx);
        input.par_chunks(nx * rb).zip(rows.par_chunks_mut(nxc * rb)).for_each_init(
            || (r2c.make_scratch_vec(), vec![0.0; nx]),
            |(scratch, row), (rin, rout)| {
                for (a, b) in rin.chunks(nx).zip(rout.chunks_mut(nxc)) {
                    // The transform destroys its input: it works on a copy of the row.
                    row.copy_from_slice(a);
                    // Lengths are right by construction, so the transform cannot fail.
                    r2c.process_with_scratch(row, b, scratch).expect("row r2c lengths");
                }
            },
        );
        self.multiply_and_back(m, rows, spec, out);
    }

    /// [`Fft2::convolve`] of `field` after `prepare(offset, block)` has rewritten each block of
    /// its rows in place (`offset`: index of the block's first value), in the same pass as the
    /// rows' transforms: the solver builds its search direction this way.
    pub fn convolve_prepared<P: Fn(usize, &mut [f64]) + Sync>(
        &self,
        field: &mut [f64],
        prepare: P,
        m: &[f64],
        rows: &mut [Complex<f64>],
        spec: &mut [Complex<f64>],
        out: &mut [f64],
    ) {
        let (nx, nxc) = (self.nx, self.nxc);
        debug_assert_eq!(field.len(), nx * self.ny);
        let r2c = &self.r2c;
        let rb = Self::per_task(nx);
        field.par_chunks_mut(nx * rb).zip(rows.par_chunks_mut(nxc * rb)).enumerate().for_each_init(
            || (r2c.make_scratch_vec(), vec![0.0; nx]),
            |(scratch, row), (blk, (rin, rout))| {
                prepare(blk * nx * rb, rin);
                for (a, b) in rin.chunks(nx).zip(rout.chunks_mut(nxc)) {
                    row.copy_from_slice(a);
                    r2c.process_with_scratch(row, b, scratch).expect("row r2c lengths");
                }
            },
        );
        self.multiply_and_back(m, rows, spec, out);
    }

    /// The convolution of a field that vanishes outside its first `ny_in` rows and `nx_in`
    /// columns, given there (`input`, row-major `ny_in x nx_in`), read back on the same sub-grid
    /// (`out`, the same layout): the zero-padded operator of [`crate::green`]. Equal to
    /// [`Fft2::convolve`] of the padded field read on the sub-grid; the rows that are zero are not
    /// transformed forward, nor the rows outside the sub-grid back.
    #[allow(clippy::too_many_arguments)]
    pub fn convolve_sub(
        &self,
        input: &[f64],
        nx_in: usize,
        ny_in: usize,
        m: &[f64],
        rows: &mut [Complex<f64>],
        spec: &mut [Complex<f64>],
        out: &mut [f64],
    ) {
        let (nx, nxc) = (self.nx, self.nxc);
        debug_assert!(nx_in <= nx && ny_in <= self.ny && input.len() == nx_in * ny_in && out.len() == input.len());
        let r2c = &self.r2c;
        let rb = Self::per_task(nx);
        rows.par_chunks_mut(nxc * rb).enumerate().for_each_init(
            || (r2c.make_scratch_vec(), vec![0.0; nx]),
            |(scratch, row), (blk, rout)| {
                for (k, b) in rout.chunks_mut(nxc).enumerate() {
                    let j = blk * rb + k;
                    if j < ny_in {
                        row[..nx_in].copy_from_slice(&input[j * nx_in..(j + 1) * nx_in]);
                        row[nx_in..].fill(0.0);
                        r2c.process_with_scratch(row, b, scratch).expect("row r2c lengths");
                    } else {
                        b.fill(Complex::default());
                    }
                }
            },
        );
        self.multiply_and_back_sub(m, rows, spec, out, nx_in, ny_in);
    }

    /// The rest of a convolution from the rows' spectra in `rows`.
    fn multiply_and_back(&self, m: &[f64], rows: &mut [Complex<f64>], spec: &mut [Complex<f64>], out: &mut [f64]) {
        self.multiply_and_back_sub(m, rows, spec, out, self.nx, self.ny);
    }

    /// [`Self::multiply_and_back`] read back on the first `ny_out` rows and `nx_out` columns
    /// (`out` row-major `ny_out x nx_out`).
    fn multiply_and_back_sub(
        &self,
        m: &[f64],
        rows: &mut [Complex<f64>],
        spec: &mut [Complex<f64>],
        out: &mut [f64],
        nx_out: usize,
        ny_out: usize,
    ) {
        let (nx, ny, nxc) = (self.nx, self.ny, self.nxc);
        debug_assert_eq!(m.len(), nxc * ny);
        transpose(rows, spec, ny, nxc);
        let (fwd, inv) = (&self.col_fwd, &self.col_inv);
        let cb = Self::per_task(ny);
        spec.par_chunks_mut(ny * cb).zip(m.par_chunks(ny * cb)).for_each_init(
            || vec![Complex::default(); fwd.get_inplace_scratch_len().max(inv.get_inplace_scratch_len())],
            |scratch, (c, m)| {
                for (c, m) in c.chunks_mut(ny).zip(m.chunks(ny)) {
                    fwd.process_with_scratch(c, scratch);
                    for (s, m) in c.iter_mut().zip(m) {
                        *s *= *m;
                    }
                    inv.process_with_scratch(c, scratch);
                }
            },
        );
        transpose(spec, rows, nxc, ny);
        let c2r = &*self.c2r;
        let rb = Self::per_task(nx);
        if nx_out == nx {
            rows[..nxc * ny_out].par_chunks_mut(nxc * rb).zip(out.par_chunks_mut(nx * rb)).for_each_init(
                || c2r.make_scratch_vec(),
                |scratch, (rin, rout)| {
                    for (a, b) in rin.chunks_mut(nxc).zip(rout.chunks_mut(nx)) {
                        row_inverse(c2r, a, b, scratch);
                    }
                },
            );
        } else {
            rows[..nxc * ny_out].par_chunks_mut(nxc * rb).zip(out.par_chunks_mut(nx_out * rb)).for_each_init(
                || (c2r.make_scratch_vec(), vec![0.0; nx]),
                |(scratch, row), (rin, rout)| {
                    for (a, b) in rin.chunks_mut(nxc).zip(rout.chunks_mut(nx_out)) {
                        row_inverse(c2r, a, row, scratch);
                        b.copy_from_slice(&row[..nx_out]);
                    }
                },
            );
        }
    }
}

/// One row's inverse real transform of the half spectrum `a` (length `nx/2 + 1`) into `b` (length
/// `nx`). The multipliers are real and even, so the imaginary parts of the zero and (even `nx`)
/// Nyquist terms are rounding noise of a real field: they are cleared, as the real transform
/// requires.
fn row_inverse(c2r: &dyn ComplexToReal<f64>, a: &mut [Complex<f64>], b: &mut [f64], scratch: &mut [Complex<f64>]) {
    a[0].im = 0.0;
    if b.len().is_multiple_of(2) {
        let last = a.len() - 1;
        a[last].im = 0.0;
    }
    c2r.process_with_scratch(a, b, scratch).expect("row c2r lengths");
}

/// Transpose `src` (`rows x cols`, row-major) into `dst` (`cols x rows`), in parallel over blocks
/// of destination rows.
fn transpose(src: &[Complex<f64>], dst: &mut [Complex<f64>], rows: usize, cols: usize) {
    let per = Fft2::per_task(rows);
    dst.par_chunks_mut(rows * per).enumerate().for_each(|(blk, out)| {
        let c0 = blk * per;
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
