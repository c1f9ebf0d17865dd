//! The height map: a regular grid of heights in metres.

use crate::TopographyError;
use crate::error::check_positive;

/// Largest grid accepted anywhere in this crate: 2^25 = 33,554,432 pixels (4096 x 8192, 5792^2),
/// checked before any grid is allocated. At 8 bytes per height that is 256 MiB per map.
pub const MAX_PIXELS: u64 = 1 << 25;

/// A height map: `nx` columns (along x) by `ny` rows (along y) of heights on a regular grid.
///
/// * Pixel `(ix, iy)` (column `ix < nx`, row `iy < ny`) covers `[ix dx, (ix+1) dx) x [iy dy, (iy+1) dy)`
///   and its height stands for its centre `((ix + 1/2) dx, (iy + 1/2) dy)`.
/// * Heights are metres, stored row-major: the height of pixel `(ix, iy)` is
///   `heights_m()[iy * nx + ix]`. A missing (masked) pixel is `NaN`; infinities are refused.
/// * Pixel sizes `dx_m`, `dy_m` are metres, finite and > 0.
///
/// This type is the hand-over point between the readers, the generator, the analysis of this crate
/// and other solvers (for example a boundary-element contact solver); it is deliberately plain.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    nx: usize,
    ny: usize,
    dx_m: f64,
    dy_m: f64,
    heights_m: Vec<f64>,
}

/// Checks `nx x ny` against [`MAX_PIXELS`] (and that both are at least 2) before allocating.
pub fn check_grid_size(origin: &str, nx: u64, ny: u64) -> Result<(), TopographyError> {
    if nx < 2 || ny < 2 {
        return Err(TopographyError::format(
            origin,
            0,
            format!("a {nx} x {ny} grid is too small: at least 2 x 2 pixels are needed"),
        ));
    }
    match nx.checked_mul(ny) {
        Some(n) if n <= MAX_PIXELS => Ok(()),
        _ => Err(TopographyError::TooLarge { origin: origin.into(), nx, ny, limit: MAX_PIXELS }),
    }
}

impl HeightMap {
    /// A map from its parts. Errors when `heights_m.len() != nx * ny`, when the grid is smaller
    /// than 2 x 2 or larger than [`MAX_PIXELS`], when a pixel size is not finite and > 0, or when a
    /// height is infinite (NaN marks a missing pixel and is allowed).
    pub fn new(nx: usize, ny: usize, dx_m: f64, dy_m: f64, heights_m: Vec<f64>) -> Result<Self, TopographyError> {
        check_grid_size("height map", nx as u64, ny as u64)?;
        check_positive("pixel_size_x", dx_m, "m")?;
        check_positive("pixel_size_y", dy_m, "m")?;
        if heights_m.len() != nx * ny {
            return Err(TopographyError::invalid(
                "heights",
                format!("{} values", heights_m.len()),
                format!("{nx} x {ny} = {} values", nx * ny),
            ));
        }
        if let Some(k) = heights_m.iter().position(|h| h.is_infinite()) {
            return Err(TopographyError::invalid(
                "heights",
                format!("{} at column {}, row {}", heights_m[k], k % nx, k / nx),
                "finite heights (NaN for a missing pixel)",
            ));
        }
        Ok(HeightMap { nx, ny, dx_m, dy_m, heights_m })
    }

    /// [`HeightMap::new`] for heights the caller has checked to be finite or NaN (the readers'
    /// one pass over them does): the same checks of the grid and pixel sizes, no second pass.
    pub(crate) fn from_checked_heights(
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
        heights_m: Vec<f64>,
    ) -> Result<Self, TopographyError> {
        check_grid_size("height map", nx as u64, ny as u64)?;
        check_positive("pixel_size_x", dx_m, "m")?;
        check_positive("pixel_size_y", dy_m, "m")?;
        if heights_m.len() != nx * ny {
            return Err(TopographyError::invalid(
                "heights",
                format!("{} values", heights_m.len()),
                format!("{nx} x {ny} = {} values", nx * ny),
            ));
        }
        debug_assert!(!heights_m.iter().any(|h| h.is_infinite()));
        Ok(HeightMap { nx, ny, dx_m, dy_m, heights_m })
    }

    /// Columns (pixels along x).
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Rows (pixels along y).
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Pixel size along x \[m\].
    pub fn dx_m(&self) -> f64 {
        self.dx_m
    }

    /// Pixel size along y \[m\].
    pub fn dy_m(&self) -> f64 {
        self.dy_m
    }

    /// Size of the map along x, `nx dx` \[m\].
    pub fn length_x_m(&self) -> f64 {
        self.nx as f64 * self.dx_m
    }

    /// Size of the map along y, `ny dy` \[m\].
    pub fn length_y_m(&self) -> f64 {
        self.ny as f64 * self.dy_m
    }

    /// All heights \[m\], row-major (`iy * nx + ix`), NaN where missing.
    pub fn heights_m(&self) -> &[f64] {
        &self.heights_m
    }

    /// The height of pixel `(ix, iy)` \[m\] (NaN if missing). Panics out of range, like slice indexing.
    pub fn at(&self, ix: usize, iy: usize) -> f64 {
        self.heights_m[iy * self.nx + ix]
    }

    /// Row `iy` of heights \[m\].
    pub fn row(&self, iy: usize) -> &[f64] {
        &self.heights_m[iy * self.nx..(iy + 1) * self.nx]
    }

    /// Number of pixels with a height (not NaN).
    pub fn valid_count(&self) -> usize {
        self.heights_m.iter().filter(|h| !h.is_nan()).count()
    }

    /// The heights, consuming the map.
    pub fn into_heights_m(self) -> Vec<f64> {
        self.heights_m
    }

    /// Mutable access for in-place processing within the crate (keeps the invariants: the caller
    /// never writes an infinity).
    pub(crate) fn heights_mut(&mut self) -> &mut [f64] {
        &mut self.heights_m
    }

    /// The sub-map of `nx x ny` pixels whose first pixel is `(ix0, iy0)`.
    pub fn crop(&self, ix0: usize, iy0: usize, nx: usize, ny: usize) -> Result<HeightMap, TopographyError> {
        if ix0.checked_add(nx).is_none_or(|e| e > self.nx) || iy0.checked_add(ny).is_none_or(|e| e > self.ny) {
            return Err(TopographyError::invalid(
                "crop",
                format!("{nx} x {ny} pixels from ({ix0}, {iy0})"),
                format!("a window inside the {} x {} map", self.nx, self.ny),
            ));
        }
        let mut h = Vec::with_capacity(nx * ny);
        for iy in iy0..iy0 + ny {
            h.extend_from_slice(&self.row(iy)[ix0..ix0 + nx]);
        }
        HeightMap::new(nx, ny, self.dx_m, self.dy_m, h)
    }

    /// Adds `other` pixel by pixel (a composite of two faces); the grids must match in size and
    /// pixel size (relative difference <= 1e-9).
    pub fn add(&self, other: &HeightMap) -> Result<HeightMap, TopographyError> {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs());
        if self.nx != other.nx || self.ny != other.ny || !close(self.dx_m, other.dx_m) || !close(self.dy_m, other.dy_m)
        {
            return Err(TopographyError::invalid(
                "height map sum",
                format!("{} x {} pixels of {} m x {} m", other.nx, other.ny, other.dx_m, other.dy_m),
                format!("the same grid as {} x {} pixels of {} m x {} m", self.nx, self.ny, self.dx_m, self.dy_m),
            ));
        }
        let h = self.heights_m.iter().zip(&other.heights_m).map(|(a, b)| a + b).collect();
        HeightMap::new(self.nx, self.ny, self.dx_m, self.dy_m, h)
    }
}
