//! Summits of a height map: pixels higher than their 8 neighbours.
//!
//! A pixel `(ix, iy)` not on the border is a summit when it and its 8 neighbours have heights and
//! its height is strictly greater than each neighbour's (a flat top of equal pixels has no summit).
//! Its curvature is the mean of the two second central differences,
//! `kappa = -(z_xx + z_yy) / 2`, `z_xx = (z(x+dx) - 2 z + z(x-dx)) / dx^2` (likewise y), in 1/m,
//! and its radius `R = 1 / kappa`. A strict maximum has `z_xx < 0` and `z_yy < 0`, so `kappa > 0`
//! always. The summit stands at its pixel's centre `((ix + 1/2) dx, (iy + 1/2) dy)`. A maximum
//! whose curvature is so small that its radius `1 / kappa` is not a finite number (differences of
//! subnormal heights, below about 1e-308 m) is flat, not a summit.

use crate::HeightMap;

/// The summits of a map (struct of arrays, in row-major pixel order).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Summits {
    /// Column of each summit's pixel.
    pub ix: Vec<u32>,
    /// Row of each summit's pixel.
    pub iy: Vec<u32>,
    /// Height \[m\].
    pub height_m: Vec<f64>,
    /// Curvature `kappa = -(z_xx + z_yy)/2` \[1/m\], > 0.
    pub curvature_per_m: Vec<f64>,
    /// Pixels that could hold a summit (interior pixels whose 3 x 3 neighbourhood has heights);
    /// the summit density is `len / (candidates dx dy)`.
    pub candidate_pixels: usize,
}

impl Summits {
    /// Number of summits.
    pub fn len(&self) -> usize {
        self.height_m.len()
    }

    /// True when there is no summit.
    pub fn is_empty(&self) -> bool {
        self.height_m.is_empty()
    }

    /// Radius `1 / kappa` of summit `i` \[m\].
    pub fn radius_m(&self, i: usize) -> f64 {
        1.0 / self.curvature_per_m[i]
    }
}

/// All summits of the map (border pixels excluded).
pub fn find_summits(map: &HeightMap) -> Summits {
    find_summits_in(map, 1, 1, map.nx().saturating_sub(1), map.ny().saturating_sub(1))
}

/// The summits whose pixel lies in columns `ix0..ix1` and rows `iy0..iy1` (clamped to the map's
/// interior); neighbours outside the window but inside the map are used.
pub fn find_summits_in(map: &HeightMap, ix0: usize, iy0: usize, ix1: usize, iy1: usize) -> Summits {
    let (nx, ny) = (map.nx(), map.ny());
    let (ix0, iy0) = (ix0.max(1), iy0.max(1));
    let (ix1, iy1) = (ix1.min(nx.saturating_sub(1)), iy1.min(ny.saturating_sub(1)));
    let h = map.heights_m();
    let (cx, cy) = (1.0 / (map.dx_m() * map.dx_m()), 1.0 / (map.dy_m() * map.dy_m()));
    let mut s = Summits::default();
    for iy in iy0..iy1 {
        let (up, row, down) =
            (&h[(iy - 1) * nx..iy * nx], &h[iy * nx..(iy + 1) * nx], &h[(iy + 1) * nx..(iy + 2) * nx]);
        for ix in ix0..ix1 {
            let z = row[ix];
            let n = [up[ix - 1], up[ix], up[ix + 1], row[ix - 1], row[ix + 1], down[ix - 1], down[ix], down[ix + 1]];
            // NaN compares false: a missing neighbour (or centre) makes the pixel no candidate.
            if z.is_nan() || n.iter().any(|v| v.is_nan()) {
                continue;
            }
            s.candidate_pixels += 1;
            if n.iter().all(|&v| z > v) {
                let zxx = (row[ix + 1] - 2.0 * z + row[ix - 1]) * cx;
                let zyy = (down[ix] - 2.0 * z + up[ix]) * cy;
                if !(2.0 / (zxx + zyy)).is_finite() {
                    continue;
                }
                s.ix.push(ix as u32);
                s.iy.push(iy as u32);
                s.height_m.push(z);
                s.curvature_per_m.push(-(zxx + zyy) / 2.0);
            }
        }
    }
    s
}
