//! The asperity (summit) model on the same height grid, for the asperity-versus-BEM comparison:
//! every summit an independent Hertz sphere under a rigid flat, no elastic interaction between
//! summits (the paper's model without adhesion, with the flat free to approach only).
//!
//! Summits are the strict 8-neighbour local maxima of the periodic grid; a summit's radius is
//! `R = 1/kappa_m` from the mean curvature `kappa_m = -(h_xx + h_yy)/2` of the 5-point finite
//! differences (Greenwood 1984's definition; summits with `kappa_m <= 0` are dropped). With the flat
//! at height `d`, summit `i` carries `P_i = (4/3) E* R_i^(1/2) delta_i^(3/2)` on the area
//! `pi R_i delta_i`, `delta_i = h_i - d > 0` (Hertz, Johnson 1985 eq. 4.22-4.23).

use crate::BemError;
use crate::error::check_positive;
use crate::grid::Grid;

/// One summit of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summit {
    /// Row-major index.
    pub index: usize,
    /// Height, m.
    pub height_m: f64,
    /// Radius of curvature, m.
    pub radius_m: f64,
}

/// Summits (strict 8-neighbour maxima with positive mean curvature) of the periodic height field.
pub fn summits(heights_m: &[f64], grid: Grid) -> Vec<Summit> {
    let (nx, ny) = (grid.nx, grid.ny);
    let at = |x: usize, y: usize| heights_m[(y % ny) * nx + (x % nx)];
    let mut out = Vec::new();
    for y in 0..ny {
        for x in 0..nx {
            let h = at(x, y);
            let (xm, xp, ym, yp) = (x + nx - 1, x + 1, y + ny - 1, y + 1);
            let nbrs = [at(xm, ym), at(x, ym), at(xp, ym), at(xm, y), at(xp, y), at(xm, yp), at(x, yp), at(xp, yp)];
            if nbrs.iter().all(|&v| h > v) {
                let hxx = (at(xp, y) - 2.0 * h + at(xm, y)) / (grid.dx_m * grid.dx_m);
                let hyy = (at(x, yp) - 2.0 * h + at(x, ym)) / (grid.dy_m * grid.dy_m);
                let km = -(hxx + hyy) / 2.0;
                if km > 0.0 {
                    out.push(Summit { index: y * nx + x, height_m: h, radius_m: 1.0 / km });
                }
            }
        }
    }
    out
}

/// State of the summit model at a load.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AsperityState {
    /// Flat height `d`, m.
    pub flat_height_m: f64,
    /// Total load, N.
    pub load_n: f64,
    /// Real contact area, m^2.
    pub contact_area_m2: f64,
    /// Summits in contact.
    pub contacts: usize,
}

fn state(summits: &[Summit], e_star_pa: f64, d: f64) -> AsperityState {
    let (mut p, mut a, mut c) = (0.0, 0.0, 0);
    for s in summits {
        let delta = s.height_m - d;
        if delta > 0.0 {
            p += 4.0 / 3.0 * e_star_pa * s.radius_m.sqrt() * delta.powf(1.5);
            a += std::f64::consts::PI * s.radius_m * delta;
            c += 1;
        }
    }
    AsperityState { flat_height_m: d, load_n: p, contact_area_m2: a, contacts: c }
}

/// The summit model at total load `load_n` (N, > 0): the flat height by bisection (100 halvings
/// of the bracket between the highest summit and a height where the load is exceeded).
pub fn at_load(summits: &[Summit], e_star_pa: f64, load_n: f64) -> Result<AsperityState, BemError> {
    check_positive("load_n", load_n, "a finite load > 0 (N)")?;
    check_positive("e_star_pa", e_star_pa, "a finite composite modulus > 0 (Pa)")?;
    let top = summits.iter().map(|s| s.height_m).fold(f64::NEG_INFINITY, f64::max);
    if !top.is_finite() {
        return Err(BemError::Value { name: "summits", value: 0.0, expected: "at least one summit" });
    }
    let mut step = summits.iter().map(|s| s.radius_m).fold(0.0, f64::max).max(1e-12) * 1e-6;
    let mut lo = top - step;
    let mut guard = 0;
    while state(summits, e_star_pa, lo).load_n < load_n {
        step *= 2.0;
        lo = top - step;
        guard += 1;
        if guard > 200 {
            return Err(BemError::Value { name: "load_n", value: load_n, expected: "a load the summits can carry" });
        }
    }
    let mut hi = top;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if state(summits, e_star_pa, mid).load_n > load_n {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(state(summits, e_star_pa, 0.5 * (lo + hi)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A single paraboloid summit `h = -r^2/(2R)` on the grid: the finite-difference radius is
    /// exact for a quadratic (to rounding, 1e-9), and the state at a load is Hertz:
    /// `a^2 = R delta`, `a^3 = 3 P R/(4 E*)` (1e-9).
    #[test]
    fn single_paraboloid_is_hertz() {
        let (n, l, r, e) = (64usize, 10e-6, 50e-6, 1e11);
        let g = Grid::new(n, n, l / n as f64, l / n as f64).unwrap();
        let h: Vec<f64> = (0..n * n)
            .map(|i| {
                let (x, y) = ((i % n) as f64 - 32.0, (i / n) as f64 - 32.0);
                -(x * x + y * y) * g.dx_m * g.dx_m / (2.0 * r)
            })
            .collect();
        let s = summits(&h, g);
        assert_eq!(s.len(), 1);
        assert!((s[0].radius_m / r - 1.0).abs() < 1e-9);
        let p = 1e-3;
        let st = at_load(&s, e, p).unwrap();
        let a_hertz = (3.0 * p * r / (4.0 * e)).cbrt();
        assert!(((st.contact_area_m2 / std::f64::consts::PI).sqrt() / a_hertz - 1.0).abs() < 1e-9);
        assert!((st.load_n / p - 1.0).abs() < 1e-9);
    }
}
