//! The non-periodic (zero-padded) Green's function: a finite patch on a half-space that goes on.
//! Held against Boussinesq's flat punch, Hertz without periodic images, and Tamaas's non-periodic
//! `dcfft` operator on the same problems (data/bem-nonperiodic-tamaas/, written by
//! scripts/bem-nonperiodic-tamaas.py).

use std::f64::consts::PI;

use stiction_bem::{BemSolver, Boundary, ContactSolution, SolverOptions};

/// Heights of an `n x n` patch of side `l` with pixel centres at `((i + 1/2) dx - l/2, ...)`.
fn field(n: usize, l: f64, f: impl Fn(f64) -> f64) -> Vec<f64> {
    let dx = l / n as f64;
    (0..n * n)
        .map(|i| {
            let (x, y) = (((i % n) as f64 + 0.5) * dx - 0.5 * l, ((i / n) as f64 + 0.5) * dx - 0.5 * l);
            f(x.hypot(y))
        })
        .collect()
}

/// The flat's height over the contact, `mean_{p > 0}(h - u)` (m): minus the approach of the shoe
/// into the undeformed wall.
fn flat_height(s: &mut BemSolver, sol: &ContactSolution) -> f64 {
    let h = s.heights_m().to_vec();
    let u = s.half_space().displacement(&sol.pressure_pa);
    let (mut sum, mut k) = (0.0, 0.0);
    for i in 0..h.len() {
        if sol.contact[i] {
            sum += h[i] - u[i];
            k += 1.0;
        }
    }
    sum / k
}

/// Boussinesq's rigid flat circular punch (Johnson 1985, sec. 3.8): `F = 2 a E* d` and
/// `p(r) = F/(2 pi a sqrt(a^2 - r^2))`, the inverse-square-root singularity at the edge. A disc of
/// radius 0.3 L on a 128^2 patch (38 pixels of radius; `a` from the pixelated disc's area), the
/// rest of the patch 1 um below it. Tolerances: the compliance within 1 % (measured -0.31 %); the
/// pressure, averaged in rings of r/a, within 2.5 % of the closed form out to r = 0.95 a (measured
/// +0.6 % at the centre to +2.0 % in [0.9, 0.95)), where it has risen to 2.6 times its centre value as
/// the singularity asks; closer to the edge a ring is one or two pixels wide and the pixel average
/// of the singular profile is not its centre value (not tested).
#[test]
fn flat_circular_punch_is_boussinesq() {
    let (n, l, e_star) = (128usize, 10e-6, 100e9);
    let dx = l / n as f64;
    let a_nominal = 0.3 * l;
    let h = field(n, l, |r| if r < a_nominal { 0.0 } else { -1e-6 });
    let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
    let p_mean = 20e6;
    let sol = s.solve_load(p_mean, &SolverOptions::default(), None).unwrap();
    let force = p_mean * l * l;
    let inside = h.iter().filter(|&&v| v == 0.0).count();
    assert_eq!(sol.contact.iter().filter(|&&c| c).count(), inside, "the whole face is in contact");
    let a = (inside as f64 / PI).sqrt() * dx;
    let d = -flat_height(&mut s, &sol);
    let ratio = force / (2.0 * a * e_star * d);
    assert!((ratio - 1.0).abs() < 0.01, "F/(2 a E* d) = {ratio}");
    let mut rings = Vec::new();
    for (lo, hi) in [(0.0, 0.2), (0.2, 0.4), (0.4, 0.6), (0.6, 0.8), (0.8, 0.9), (0.9, 0.95)] {
        let (mut num, mut den, mut exact) = (0.0, 0.0, 0.0);
        for i in 0..n * n {
            let (x, y) = (((i % n) as f64 + 0.5) * dx - 0.5 * l, ((i / n) as f64 + 0.5) * dx - 0.5 * l);
            let r = x.hypot(y) / a;
            if r >= lo && r < hi {
                let p = force / (2.0 * PI * a * a * (1.0 - r * r).sqrt());
                num += sol.pressure_pa[i];
                den += p;
                exact += 1.0;
            }
        }
        assert!((num / den - 1.0).abs() < 0.025, "r/a in [{lo}, {hi}): p / Boussinesq = {}", num / den);
        rings.push(num / exact);
    }
    let rise = rings[5] / rings[0];
    assert!(rise > 2.4, "edge ring / centre = {rise}");
}

/// Hertz (Johnson 1985, eq. 4.22-4.23) without periodic images: `a^3 = 3 P R/(4 E*)`,
/// `p0 = 2 E* a/(pi R)`, approach `d = a^2/R`. The non-periodic patch has an absolute approach
/// (the periodic cell has none: its displacement has zero mean); tolerances: radius within 1.5
/// pixels, peak within 0.5 %, approach within 0.5 % (measured -0.02 to -0.11 %). The periodic
/// cell at a/L = 0.25 shows the images: its peak is 2 % high (the neighbours' pressure lifts the
/// whole cell), the non-periodic one 0.09 % low, on the same grid.
#[test]
fn hertz_without_images() {
    let (e_star, radius) = (100e9, 200e-6);
    for (n, l) in [(64usize, 12e-6), (64, 24e-6), (128, 24e-6)] {
        let dx = l / n as f64;
        let a: f64 = 3e-6;
        let load = 4.0 * e_star * a.powi(3) / (3.0 * radius);
        let p0 = 2.0 * e_star * a / (PI * radius);
        let h = field(n, l, |r| -r * r / (2.0 * radius));
        let mut peak = Vec::new();
        for b in [Boundary::Periodic, Boundary::NonPeriodic] {
            let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, b).unwrap();
            let sol = s.solve_load(load / (l * l), &SolverOptions::default(), None).unwrap();
            let a_num = (sol.contact_area_m2 / PI).sqrt();
            assert!((a_num - a).abs() < 1.5 * dx, "{b:?} n {n}: a {a_num:e}");
            let pmax = sol.pressure_pa.iter().copied().fold(0.0, f64::max);
            peak.push(pmax / p0 - 1.0);
            if b == Boundary::NonPeriodic {
                assert!((pmax / p0 - 1.0).abs() < 0.005, "n {n} L {l:e}: peak {}", pmax / p0);
                let d = -flat_height(&mut s, &sol);
                assert!((d * radius / (a * a) - 1.0).abs() < 0.005, "n {n} L {l:e}: approach {}", d * radius / (a * a));
            }
        }
        if l == 12e-6 {
            assert!(peak[0] > 0.015 && peak[1].abs() < 0.1 * peak[0], "a/L = 0.25: peak errors {peak:?}");
        }
    }
}

/// Tamaas 2.9's non-periodic `dcfft` operator (PolonskyKeerRey, load control, tolerance 1e-12) on
/// the same three problems (48^2, E* = 100 GPa: a flat circular punch, a sphere with a quarter-patch
/// contact, a seeded rough patch), values in data/bem-nonperiodic-tamaas/reference.json written by
/// scripts/bem-nonperiodic-tamaas.py. Both use Love's pixel coefficients on the zero-padded grid,
/// so they must agree to the solver tolerance: the same contact points, the pressure within 1e-7
/// of its maximum everywhere (measured 2.3e-9 on the punch, whose edge is singular; 1e-11 and below
/// otherwise), the flat's height over the contact within 1e-8 relative (measured 4e-12).
#[test]
fn tamaas_dcfft() {
    let doc: serde_json::Value =
        serde_json::from_str(include_str!("../../../data/bem-nonperiodic-tamaas/reference.json")).unwrap();
    let n = doc["n"].as_u64().unwrap() as usize;
    let dx = doc["pixel_m"].as_f64().unwrap();
    let e_star = doc["e_star_pa"].as_f64().unwrap();
    let l = n as f64 * dx;
    let vec =
        |v: &serde_json::Value| -> Vec<f64> { v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect() };
    for name in ["punch", "hertz", "rough"] {
        let c = &doc["cases"][name];
        let h = match name {
            "punch" => {
                let a = doc["punch_radius_m"].as_f64().unwrap();
                field(n, l, |r| if r < a { 0.0 } else { -1e-6 })
            }
            "hertz" => {
                let radius = doc["sphere_radius_m"].as_f64().unwrap();
                field(n, l, |r| -r * r / (2.0 * radius))
            }
            _ => vec(&c["heights_m"]),
        };
        let p_ref = vec(&c["pressure_pa"]);
        let mut s = BemSolver::with_boundary(n, n, dx, dx, &h, e_star, Boundary::NonPeriodic).unwrap();
        let opts = SolverOptions { tolerance: 1e-12, ..Default::default() };
        let sol = s.solve_load(c["mean_pressure_pa"].as_f64().unwrap(), &opts, None).unwrap();
        let pmax = p_ref.iter().copied().fold(0.0, f64::max);
        let dev = sol.pressure_pa.iter().zip(&p_ref).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max) / pmax;
        let mismatched = sol.pressure_pa.iter().zip(&p_ref).filter(|(a, b)| (**a > 0.0) != (**b > 0.0)).count();
        let flat = flat_height(&mut s, &sol);
        let flat_ref = c["flat_height_m"].as_f64().unwrap();
        assert_eq!(mismatched, 0, "{name}: contact sets differ");
        assert_eq!(sol.contact.iter().filter(|&&c| c).count() as u64, c["contact_points"].as_u64().unwrap());
        assert!(dev < 1e-7, "{name}: max |dp|/max p = {dev:e}");
        assert!((flat - flat_ref).abs() < 1e-8 * flat_ref.abs(), "{name}: flat {flat:e} vs {flat_ref:e}");
    }
}
