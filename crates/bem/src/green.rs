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
use crate::grid::{Grid, MAX_POINTS, SUM_BLOCK};

/// Largest non-periodic grid, in points: a quarter of [`MAX_POINTS`], since the operator works on
/// the grid padded to four times its size.
pub const MAX_POINTS_NON_PERIODIC: usize = MAX_POINTS / 4;

/// Bytes per grid point that the padded operator adds to [`crate::BYTES_PER_POINT`]: the padded
/// real work field (4 points x 8 bytes), the two padded complex half spectra (2 x 2 x 16 bytes),
/// the real multiplier (2 x 8 bytes) and the real-space influence coefficients at the patch's
/// offsets (8 bytes, for the solves on a set of points, [`crate::restricted`]) = 120 bytes per
/// point of the patch.
pub const PADDED_BYTES_PER_POINT: usize = 120;

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
    term(xp, yp + r(xp, yp), ym + r(xp, ym))
        + term(yp, xp + r(xp, yp), xm + r(xm, yp))
        + term(xm, ym + r(xm, ym), yp + r(xm, yp))
        + term(ym, xm + r(xm, ym), xp + r(xp, ym))
}

/// The zero-padded compliance operator on an `nx x ny` patch.
pub(crate) struct Padded {
    nx: usize,
    ny: usize,
    fft: Fft2,
    multiplier: Vec<f64>,
    rows: Vec<Complex<f64>>,
    spec: Vec<Complex<f64>>,
    work: Vec<f64>,
    /// The influence coefficients `K(i dx, j dy)` (m/Pa) at the offsets `0 <= i < nx`,
    /// `0 <= j < ny` (row-major, `j nx + i`); `K` is even in both, so this is every offset
    /// between two points of the patch.
    table: Vec<f64>,
}

impl std::fmt::Debug for Padded {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Padded {{ nx: {}, ny: {} }}", self.nx, self.ny)
    }
}

impl Padded {
    /// The operator of `grid` (already checked against [`MAX_POINTS_NON_PERIODIC`]) for `E*` (Pa).
    pub(crate) fn new(grid: Grid, e_star_pa: f64) -> Self {
        let (nx, ny) = (grid.nx, grid.ny);
        let (mx, my) = (2 * nx, 2 * ny);
        let fft = Fft2::new(mx, my);
        let (a, b) = (0.5 * grid.dx_m, 0.5 * grid.dy_m);
        let c = 1.0 / (std::f64::consts::PI * e_star_pa);
        // Kernel on the doubled grid, offsets wrapped: index i <-> offset i (i <= nx) or i - 2nx.
        let offset = |i: usize, n: usize| if i <= n { i as f64 } else { i as f64 - 2.0 * n as f64 };
        let mut kernel = vec![0.0; mx * my];
        kernel.par_chunks_mut(mx).enumerate().for_each(|(j, row)| {
            let y = offset(j, ny) * grid.dy_m;
            for (i, k) in row.iter_mut().enumerate() {
                *k = c * love_coefficient(offset(i, nx) * grid.dx_m, y, a, b);
            }
        });
        let table: Vec<f64> = (0..ny).flat_map(|j| kernel[j * mx..j * mx + nx].iter().copied()).collect();
        let n = fft.spectrum_len();
        let mut rows = vec![Complex::default(); n];
        let mut spec = vec![Complex::default(); n];
        fft.forward(&mut kernel, &mut rows, &mut spec);
        // The kernel is real and even in x and y, so its spectrum is real (the imaginary parts are
        // rounding); the inverse transform is unnormalised, hence 1/(4 nx ny).
        let norm = 1.0 / (mx * my) as f64;
        let multiplier = spec.iter().map(|s| s.re * norm).collect();
        Padded { nx, ny, fft, multiplier, rows, spec, work: vec![0.0; mx * my], table }
    }

    /// The influence coefficient of the offset `(di, dj)` pixels (m/Pa), `|di| < nx`, `|dj| < ny`.
    pub(crate) fn table(&self) -> &[f64] {
        &self.table
    }

    /// `out = K[input]` on the patch: the traction is padded with zeros, convolved, and the
    /// displacement read back on the patch.
    pub(crate) fn compliance(&mut self, input: &[f64], out: &mut [f64]) {
        let (nx, mx) = (self.nx, 2 * self.nx);
        self.work.par_chunks_mut(mx).enumerate().for_each(|(j, row)| {
            if j < self.ny {
                row[..nx].copy_from_slice(&input[j * nx..(j + 1) * nx]);
                row[nx..].fill(0.0);
            } else {
                row.fill(0.0);
            }
        });
        self.fft.forward(&mut self.work, &mut self.rows, &mut self.spec);
        self.spec.par_chunks_mut(SUM_BLOCK).zip(self.multiplier.par_chunks(SUM_BLOCK)).for_each(|(s, m)| {
            for (s, m) in s.iter_mut().zip(m) {
                *s *= *m;
            }
        });
        self.fft.inverse(&mut self.spec, &mut self.rows, &mut self.work);
        out.par_chunks_mut(nx).enumerate().for_each(|(j, o)| o.copy_from_slice(&self.work[j * mx..j * mx + nx]));
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
