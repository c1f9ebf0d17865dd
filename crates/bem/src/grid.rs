//! The periodic grid of the boundary-element solution ([`Grid`]), its size limits
//! ([`MAX_POINTS`], [`BYTES_PER_POINT`]) and the block sums that keep every total independent of
//! the thread count.

use rayon::prelude::*;
use serde::Serialize;

use crate::error::{BemError, check_positive};

/// Largest grid, in points (4096 x 4096): about 1.3 GB of solver state at
/// [`BYTES_PER_POINT`].
pub const MAX_POINTS: usize = 1 << 24;

/// Bytes of solver state per grid point during a non-adhesive solve: persistent, the heights
/// (8 bytes), the two real multipliers (`(nx/2+1) ny` values each, ~4 bytes per point each) and
/// the two complex half spectra (~8 bytes per point each) = 32 bytes (the FFTs' other work
/// buffers are per row or column and per thread); per solve, the unknown, the data, the residual,
/// `A x`, the direction and its image (6 x 8) = 48 bytes; in all 80 bytes. The returned solution
/// adds its pressure and gap fields and contact flags (17 bytes); an adhesive solve adds the zone
/// and the shifted data (+9 bytes). Measured: 110 MB maximum resident for the 1024 x 1024 timing
/// example (105 bytes per point, with the example's own copy of the heights and the solution).
pub const BYTES_PER_POINT: usize = 80;

/// Block length of the deterministic sums.
pub(super) const SUM_BLOCK: usize = 8192;

/// Runs `f` on a worker of the current rayon pool (the global pool when called from outside
/// any): a solve's many short parallel passes are then forked from a worker and stolen by the
/// others, instead of each being handed from the calling thread to the pool and back.
pub(super) fn in_pool<R: Send, F: FnOnce() -> R + Send>(f: F) -> R {
    if rayon::current_thread_index().is_some() { f() } else { rayon::scope(|_| f()) }
}

/// Deterministic parallel sum of `f` over fixed blocks of `0..n`, added in block order.
pub(crate) fn block_sum<F: Fn(std::ops::Range<usize>) -> f64 + Sync>(n: usize, f: F) -> f64 {
    let nb = n.div_ceil(SUM_BLOCK);
    let parts: Vec<f64> = (0..nb).into_par_iter().map(|b| f(b * SUM_BLOCK..((b + 1) * SUM_BLOCK).min(n))).collect();
    parts.iter().sum()
}

/// Deterministic parallel sums of two quantities.
pub(super) fn block_sum2<F: Fn(std::ops::Range<usize>) -> (f64, f64) + Sync>(n: usize, f: F) -> (f64, f64) {
    let nb = n.div_ceil(SUM_BLOCK);
    let parts: Vec<(f64, f64)> =
        (0..nb).into_par_iter().map(|b| f(b * SUM_BLOCK..((b + 1) * SUM_BLOCK).min(n))).collect();
    parts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1))
}

/// A periodic grid: `nx` columns (the fast index) by `ny` rows of `dx_m x dy_m` pixels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Grid {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Pixel size along x, m.
    pub dx_m: f64,
    /// Pixel size along y, m.
    pub dy_m: f64,
}

impl Grid {
    /// A checked grid: `2 <= nx, ny`, `nx ny <= MAX_POINTS`, pixel sizes finite and > 0.
    pub fn new(nx: usize, ny: usize, dx_m: f64, dy_m: f64) -> Result<Self, BemError> {
        if nx < 2 || ny < 2 || nx.checked_mul(ny).is_none_or(|n| n > MAX_POINTS) {
            return Err(BemError::GridSize { nx, ny, limit: MAX_POINTS });
        }
        check_positive("dx_m", dx_m, "a finite pixel size > 0 (m)")?;
        check_positive("dy_m", dy_m, "a finite pixel size > 0 (m)")?;
        Ok(Grid { nx, ny, dx_m, dy_m })
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false (a grid has at least 4 points); for clippy's `len` convention.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Nominal (cell) area `A0 = nx dx ny dy`, m^2.
    pub fn area_m2(&self) -> f64 {
        self.nx as f64 * self.dx_m * self.ny as f64 * self.dy_m
    }

    /// Magnitude of the wave vector (rad/m) at spectrum index (`kx` in `0..=nx/2`, `ky` in `0..ny`).
    pub(crate) fn wavenumber(&self, kx: usize, ky: usize) -> f64 {
        let fy = if ky <= self.ny / 2 { ky as f64 } else { ky as f64 - self.ny as f64 };
        let qx = 2.0 * std::f64::consts::PI * kx as f64 / (self.nx as f64 * self.dx_m);
        let qy = 2.0 * std::f64::consts::PI * fy / (self.ny as f64 * self.dy_m);
        qx.hypot(qy)
    }
}
