//! The explicit solver on a large Gaussian surface in flat mode against Greenwood-Williamson
//! (eq. 5a-c) and GW + DMT (eq. 8): N, A_r and L at fixed separations within 3 standard errors.
//!
//! For M summits with iid Gaussian heights (SD sigma) and separation d = h sigma, each summit
//! contributes X = g((y - h)_+) with y ~ N(0, 1); E[X] and Var[X] follow from the probability
//! integrals F_n(h) (eq. 6): N: F_0, F_0 (1 - F_0); A_r: pi R sigma F_1, (pi R sigma)^2 (F_2 - F_1^2);
//! L (DMT, kappa = R^1/2 sigma^3/2 / D, c = 2 pi dgamma R): kappa F_3/2 - c F_0 and
//! kappa^2 F_3 - 2 kappa c F_3/2 + c^2 F_0 - mean^2. The standard error of the sum is sqrt(M Var).
//! F_n is computed here by an independent quadrature (u = sqrt(y - h), Simpson, 40000 panels).

use std::f64::consts::PI;

use stiction_contact::explicit::*;
use stiction_contact::single::{AdhesionLaw, AsperityParams};
use stiction_surface::*;

/// F_n(h) = 1/sqrt(2 pi) int_h^inf (y - h)^n exp(-y^2/2) dy with y = h + u^2.
fn f_n(n: f64, h: f64) -> f64 {
    let f = |u: f64| 2.0 * u.powf(2.0 * n + 1.0) * (-(h + u * u).powi(2) / 2.0).exp();
    let (a, b, m) = (0.0, 7.0, 40_000);
    let dx = (b - a) / m as f64;
    let mut s = f(a) + f(b);
    for k in 1..m {
        s += f(a + k as f64 * dx) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * dx / 3.0 / (2.0 * PI).sqrt()
}

#[test]
fn quadrature_matches_known_values() {
    // F_0(h) = Q(h): Q(0) = 1/2, Q(1) = 0.158655253931457; F_1(0) = 1/sqrt(2 pi).
    assert!((f_n(0.0, 0.0) - 0.5).abs() < 1e-12);
    assert!((f_n(0.0, 1.0) - 0.158_655_253_931_457).abs() < 1e-12);
    assert!((f_n(1.0, 0.0) - 1.0 / (2.0 * PI).sqrt()).abs() < 1e-12);
}

#[test]
fn flat_mode_matches_gw_and_gw_dmt_within_three_standard_errors() {
    // Table 1 surface parameters over 1 mm x 0.25 mm: about 1e6 summits.
    let (eta, sigma, r, d, dg) = (4e12, 0.04e-6, 0.5e-6f64, 9.1e-12, 0.1);
    let layout =
        Layout { apparent_length_m: 1e-3, apparent_width_m: 0.25e-3, placement: Placement::Poisson, seed: 2024 };
    let surface = generate(&layout, &FaceParams::gaussian_fixed(eta, sigma, r)).unwrap();
    let m = surface.len() as f64;
    assert!(m > 0.99e6);
    let kappa = r.sqrt() * sigma.powf(1.5) / d;
    for (law, c) in [(AdhesionLaw::Hertz, 0.0), (AdhesionLaw::Dmt, 2.0 * PI * dg * r)] {
        let cfg = SolverConfig { mode: ShoeMode::Flat, detail: Detail::Summary, ..Default::default() };
        let mut sol = ExplicitSolver::new(surface.clone(), law, AsperityParams::table1(), cfg).unwrap();
        for h in [0.0, 0.5, 1.0, 2.0, 3.0] {
            let e = sol.evaluate_pose(h * sigma, 0.0, 0.0);
            let (f0, f1, f15, f2, f3) = (f_n(0.0, h), f_n(1.0, h), f_n(1.5, h), f_n(2.0, h), f_n(3.0, h));
            let checks = [
                ("N (eq. 5a)", e.contacts as f64, m * f0, (m * f0 * (1.0 - f0)).sqrt()),
                (
                    "A_r (eq. 5b)",
                    e.real_area_m2,
                    m * PI * r * sigma * f1,
                    (m * (PI * r * sigma).powi(2) * (f2 - f1 * f1)).sqrt(),
                ),
                (
                    "L (eq. 5c / 8)",
                    e.load_n,
                    m * (kappa * f15 - c * f0),
                    (m * (kappa * kappa * f3 - 2.0 * kappa * c * f15 + c * c * f0 - (kappa * f15 - c * f0).powi(2)))
                        .sqrt(),
                ),
            ];
            for (what, obs, mean, se) in checks {
                let zs = (obs - mean) / se;
                println!("{law:?} h = {h}: {what} explicit {obs:.6e} GW {mean:.6e} ({zs:+.2} SE)");
                assert!(zs.abs() < 3.0, "{law:?} h = {h}: {what} explicit {obs:e} vs GW {mean:e} is {zs:.2} SE off");
            }
        }
        // Equilibrium in flat mode at the GW load for h = 1 lands at that separation (within the
        // spacing of summit heights near d: a small fraction of sigma).
        let target = sol.evaluate_pose(sigma, 0.0, 0.0);
        let e = sol.solve(target.load_n).unwrap();
        assert!((e.separation_m / sigma - 1.0).abs() < 1e-3, "{law:?}: d/sigma = {}", e.separation_m / sigma);
        assert!(e.force_residual_n.abs() < 1e-9 * e.elastic_load_n);
    }
}
