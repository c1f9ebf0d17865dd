//! The non-periodic (free-boundary) Green's function: a finite patch on a half-space that goes on.
//!
//! The periodic operator of [`crate::HalfSpace`] makes the grid one cell of an infinite array. A
//! shoe pressed on a wall is a finite punch on a half-space that extends beyond it: the traction
//! lives on the `nx x ny` patch, is zero outside, and the displacement it causes has no images.
//! That is the linear (not circular) convolution of the traction with the influence coefficients
//! of a uniformly loaded pixel, evaluated by the FFT after zero padding to `2nx x 2ny` (Hockney
//! 1970; the "DC-FFT" of Liu, Wang & Liu, Wear 243 (2000) 101, and Tamaas's non-periodic
//! operator): the kernel is laid out on the doubled grid at offsets `-nx..nx` (wrapped), the
//! traction fills one quarter, and the product of the two spectra gives, on that quarter, the
//! exact sum `u_i = sum_j K(x_i - x_j) p_j` without wrap-around.
//!
//! Influence coefficient (Love 1929; Johnson 1985, eq. 3.25, with `(1 - nu^2)/E` of one body
//! replaced by the composite `1/E*`): the surface displacement at `(x, y)` from the centre of a
//! pixel `2a x 2b` carrying a unit uniform pressure is
//!
//! ```text
//! K(x, y) = 1/(pi E*) [ (x+a) ln((y+b + r(x+a, y+b)) / (y-b + r(x+a, y-b)))
//!                     + (y+b) ln((x+a + r(x+a, y+b)) / (x-a + r(x-a, y+b)))
//!                     + (x-a) ln((y-b + r(x-a, y-b)) / (y+b + r(x-a, y+b)))
//!                     + (y-b) ln((x-a + r(x-a, y-b)) / (x+a + r(x+a, y-b))) ]   (m/Pa)
//! ```
//!
//! with `r(u, v) = sqrt(u^2 + v^2)`. Unlike the periodic operator it has a zero mode: a uniform
//! pressure `P` on a circle of radius `a` sinks it by `2 P a/E*` at the centre, so the displacement
//! is absolute and the rigid approach of the shoe is measured from the undeformed wall.
//!
//! Only the compliance (traction to displacement) is available: its inverse is not diagonal in
//! Fourier space, so the mean-gap (dual) solves and the Dugdale solver that runs on them need the
//! periodic operator; load control (Polonsky-Keer) and the load-controlled cohesive solve
//! (`BemSolver::adhesive_at_load`) work with either.

use rayon::prelude::*;
use realfft::num_complex::Complex;

use crate::fft::Fft2;
use std::sync::Arc;

use crate::grid::{Grid, MAX_POINTS};

/// Largest non-periodic grid, in points: a quarter of [`MAX_POINTS`], since the operator works on
/// the grid padded to four times its size.
pub const MAX_POINTS_NON_PERIODIC: usize = MAX_POINTS / 4;

/// Bytes per grid point that the padded operator adds to [`crate::BYTES_PER_POINT`]: the two
/// padded complex half spectra (2 x 2 x 16 bytes), the real multiplier (2 x 8 bytes) and the
/// real-space influence coefficients at the patch's offsets (8 bytes, for the solves on a set of
/// points, [`crate::restricted`]) = 88 bytes per point of the patch.
pub const PADDED_BYTES_PER_POINT: usize = 88;

/// Which Green's function a [`crate::HalfSpace`] uses (scenario `contact.bem.boundary`:
/// "non_periodic" or "periodic").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Boundary {
    /// The grid is one periodic cell (a statistically homogeneous interface).
    #[default]
    Periodic,
    /// The grid is a finite patch on an unbounded half-space (zero padding, no images): a shoe
    /// face on a wall that goes on.
    NonPeriodic,
}

/// Displacement at `(x, y)` (m) of a unit uniform pressure on a `2a x 2b` pixel centred at the
/// origin, times `pi E*` (m): Love's solution (module docs).
pub fn love_coefficient(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let r = |u: f64, v: f64| u.hypot(v);
    // ln(num/den) where both are sums of a coordinate and a distance; each term is finite for a
    // point off the pixel's edges' extensions, and its prefactor vanishes where a ratio is 0/0.
    let term =
        |c: f64, num: f64, den: f64| if c == 0.0 || num <= 0.0 || den <= 0.0 { 0.0 } else { c * (num / den).ln() };
    let (xp, xm, yp, ym) = (x + a, x - a, y + b, y - b);
    let (rpp, rpm, rmp, rmm) = (r(xp, yp), r(xp, ym), r(xm, yp), r(xm, ym));
    term(xp, yp + rpp, ym + rpm)
        + term(yp, xp + rpp, xm + rmp)
        + term(xm, ym + rmm, yp + rmp)
        + term(ym, xm + rmm, xp + rpm)
}

/// The padded operator's data for one grid and modulus: the multiplier (the kernel's spectrum)
/// and the influence coefficients at the patch's offsets.
struct Kernel {
    /// `(nx, ny, dx, dy, E*)`, the floats by their bits.
    key: (usize, usize, u64, u64, u64),
    multiplier: Vec<f64>,
    /// The influence coefficients `K(i dx, j dy)` (m/Pa) at the offsets `0 <= i < nx`,
    /// `0 <= j < ny` (row-major, `j nx + i`); `K` is even in both, so this is every offset
    /// between two points of the patch.
    table: Vec<f64>,
}

/// Largest patch (points) whose kernel is kept for the next operator of the same grid and modulus
/// ([`LAST_KERNEL`]): 2^18 points, 6 MB.
const KEPT_POINTS: usize = 1 << 18;

/// The last kernel built of at most [`KEPT_POINTS`] points: a study builds the same shoe's
/// operator once per experiment, and the kernel (Love's coefficients and their FFT) is a function
/// of the grid and the modulus only, so it is built once.
static LAST_KERNEL: std::sync::Mutex<Option<Arc<Kernel>>> = std::sync::Mutex::new(None);

/// The zero-padded compliance operator on an `nx x ny` patch.
pub(crate) struct Padded {
    nx: usize,
    ny: usize,
    fft: Fft2,
    kernel: Arc<Kernel>,
    rows: Vec<Complex<f64>>,
    spec: Vec<Complex<f64>>,
}

impl std::fmt::Debug for Padded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Padded {{ nx: {}, ny: {} }}", self.nx, self.ny)
    }
}

impl Kernel {
    /// The kernel of `grid` for `E*` (Pa), planned with `fft` (the doubled grid's).
    fn new(grid: Grid, e_star_pa: f64, fft: &Fft2, key: (usize, usize, u64, u64, u64)) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let (mx, my) = (2 * nx, 2 * ny);
        let (a, b) = (0.5 * grid.dx_m, 0.5 * grid.dy_m);
        let c = 1.0 / (std::f64::consts::PI * e_star_pa);
        // The coefficients at the offsets 0..=nx, 0..=ny (K is even in x and in y).
        let mut quarter = vec![0.0; (nx + 1) * (ny + 1)];
        quarter.par_chunks_mut(nx + 1).enumerate().for_each(|(j, row)| {
            let y = j as f64 * grid.dy_m;
            for (i, k) in row.iter_mut().enumerate() {
                *k = c * love_coefficient(i as f64 * grid.dx_m, y, a, b);
            }
        });
        // Kernel on the doubled grid, offsets wrapped: index i <-> offset i (i <= nx) or i - 2nx.
        let offset = |i: usize, n: usize| if i <= n { i } else { 2 * n - i };
        let mut kernel = vec![0.0; mx * my];
        kernel.par_chunks_mut(mx).enumerate().for_each(|(j, row)| {
            let q = &quarter[offset(j, ny) * (nx + 1)..(offset(j, ny) + 1) * (nx + 1)];
            for (i, k) in row.iter_mut().enumerate() {
                *k = q[offset(i, nx)];
            }
        });
        let table: Vec<f64> = (0..ny).flat_map(|j| quarter[j * (nx + 1)..j * (nx + 1) + nx].iter().copied()).collect();
        let n = fft.spectrum_len();
        let mut rows = vec![Complex::default(); n];
        let mut spec = vec![Complex::default(); n];
        fft.forward(&mut kernel, &mut rows, &mut spec);
        // The kernel is real and even in x and y, so its spectrum is real (the imaginary parts are
        // rounding); the inverse transform is unnormalised, hence 1/(4 nx ny).
        let norm = 1.0 / (mx * my) as f64;
        let multiplier = spec.iter().map(|s| s.re * norm).collect();
        Kernel { key, multiplier, table }
    }
}

impl Padded {
    /// The operator of `grid` (already checked against [`MAX_POINTS_NON_PERIODIC`]) for `E*` (Pa).
    pub(crate) fn new(grid: Grid, e_star_pa: f64) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let fft = Fft2::new(2 * nx, 2 * ny);
        let key = (nx, ny, grid.dx_m.to_bits(), grid.dy_m.to_bits(), e_star_pa.to_bits());
        // A poisoned lock (a panic elsewhere while it was held) only loses the reuse.
        let kept = LAST_KERNEL.lock().ok().and_then(|k| k.as_ref().filter(|k| k.key == key).cloned());
        let kernel = kept.unwrap_or_else(|| {
            let k = Arc::new(Kernel::new(grid, e_star_pa, &fft, key));
            if grid.len() <= KEPT_POINTS
                && let Ok(mut last) = LAST_KERNEL.lock()
            {
                *last = Some(k.clone());
            }
            k
        });
        let n = fft.spectrum_len();
        Padded { nx, ny, fft, kernel, rows: vec![Complex::default(); n], spec: vec![Complex::default(); n] }
    }

    /// The influence coefficients at the offsets `(i, j)`, `0 <= i < nx`, `0 <= j < ny` (m/Pa,
    /// row-major `j nx + i`): every offset between two points of the patch (`K` is even).
    pub(crate) fn table(&self) -> &[f64] {
        &self.kernel.table
    }

    /// `out = K[input]` on the patch: the traction padded with zeros, convolved, and the
    /// displacement read back on the patch ([`Fft2::convolve_sub`]).
    pub(crate) fn compliance(&mut self, input: &[f64], out: &mut [f64]) {
        self.fft.convolve_sub(input, self.nx, self.ny, &self.kernel.multiplier, &mut self.rows, &mut self.spec, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The centre of a square pixel of side 2a under unit pressure sinks by
    /// `(1/(pi E*)) int dA/r = (8 a/(pi E*)) ln(1 + sqrt 2)` (the integral in polar coordinates
    /// over the eight right triangles of the square): `K(0,0) pi E* = 8 a asinh(1)`.
    /// Far away it is a point load: `K -> (2a)(2b)/(pi E* r)` (Boussinesq), to O((a/r)^2).
    #[test]
    fn love_coefficient_centre_and_far_field() {
        let a = 0.5;
        let centre = love_coefficient(0.0, 0.0, a, a);
        assert!((centre - 8.0 * a * 1f64.asinh()).abs() < 1e-14, "{centre}");
        let far = love_coefficient(40.0, 30.0, a, a);
        assert!((far / (1.0 / 50.0) - 1.0).abs() < 1e-4, "{far}");
        // Symmetric in x and y.
        let (k1, k2) = (love_coefficient(3.0, -2.0, a, 0.7), love_coefficient(-3.0, 2.0, a, 0.7));
        assert!((k1 - k2).abs() < 1e-14 * k1, "{k1} {k2}");
    }

    /// The padded convolution equals the direct sum `u_i = sum_j K(x_i - x_j) p_j` (no images).
    #[test]
    fn padded_convolution_is_the_direct_sum() {
        let grid = Grid::new(7, 5, 1.0, 1.3).unwrap();
        let mut op = Padded::new(grid, 2.0);
        let p: Vec<f64> = (0..35).map(|i| ((i * 37 % 11) as f64) - 3.0).collect();
        let mut u = vec![0.0; 35];
        op.compliance(&p, &mut u);
        let c = 1.0 / (std::f64::consts::PI * 2.0);
        for (i, ui) in u.iter().enumerate() {
            let (xi, yi) = ((i % 7) as f64, (i / 7) as f64 * 1.3);
            let direct: f64 = (0..35)
                .map(|j| {
                    let (xj, yj) = ((j % 7) as f64, (j / 7) as f64 * 1.3);
                    c * love_coefficient(xi - xj, yi - yj, 0.5, 0.65) * p[j]
                })
                .sum();
            assert!((ui - direct).abs() < 1e-12 * direct.abs().max(1.0), "{i}: {ui} vs {direct}");
        }
    }
}
