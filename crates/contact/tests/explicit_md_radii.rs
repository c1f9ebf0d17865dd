//! Maugis-Dugdale with a radius per summit (lognormal radii, Table 1's R = 0.5 +/- 0.3 um):
//! the explicit solver interpolates normalised Maugis-Dugdale tables between a grid of radii
//! (docs/explicit-solver.md). Checked against the uniform-radius path, against the exact law of
//! `single::summit_response` for each radius, and for equilibrium on a Table 1 surface.

use std::f64::consts::PI;

use stiction_contact::explicit::*;
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch, branch_limits, summit_response};
use stiction_surface::*;

const L_A: f64 = 20e-6;
const W_A: f64 = 5e-6;

fn layout(seed: u64) -> Layout {
    Layout { apparent_length_m: L_A, apparent_width_m: W_A, placement: Placement::Poisson, seed }
}

/// Table 1 face (eta = 4e12 m^-2, sigma = 0.04 um), radii lognormal with mean 0.5 um, SD 0.3 um.
fn table1_lognormal(seed: u64) -> Surface {
    let face = FaceParams {
        radius_sd_m: 0.3e-6,
        radius_distribution: RadiusDistribution::Lognormal,
        ..FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)
    };
    generate(&layout(seed), &face).unwrap()
}

#[test]
fn equal_per_summit_radii_reproduce_the_uniform_radius_path() {
    // All radii equal: one table, the exact Maugis-Dugdale law; the per-summit path must give the
    // same equilibria as the uniform-radius path (SummitModel) along a whole load history.
    // Tolerance 1e-9 relative (both converge to 1e-9 of the load scale from the same start).
    let p = AsperityParams::table1();
    let base = generate(&layout(5), &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).unwrap();
    let n = base.len();
    let per = Surface::new(
        L_A,
        W_A,
        base.xs_m().to_vec(),
        base.ys_m().to_vec(),
        base.heights_m().to_vec(),
        Radii::PerSummit(vec![0.5e-6; n]),
    )
    .unwrap();
    let cfg = SolverConfig::default();
    let mut uni = ExplicitSolver::new(base, AdhesionLaw::MaugisDugdale, p, cfg).unwrap();
    let mut psr = ExplicitSolver::new(per, AdhesionLaw::MaugisDugdale, p, cfg).unwrap();
    let po_u = uni.pull_off(0.0, 1e-6).unwrap();
    let po_p = psr.pull_off(0.0, 1e-6).unwrap();
    let adh = PI * 0.1 * 0.5e-6;
    assert!((po_u.load_n - po_p.load_n).abs() < 1e-9 * adh, "pull-off {} vs {}", po_u.load_n, po_p.load_n);
    let loads: Vec<f64> = (0..=40).map(|k| po_u.load_n + k as f64 * 0.25e-6).collect();
    let su = uni.sweep(&loads, Branch::Loading).unwrap();
    let sp = psr.sweep(&loads, Branch::Loading).unwrap();
    assert_eq!(su.points.len(), sp.points.len());
    for (a, b) in su.points.iter().zip(&sp.points) {
        assert_eq!(a.contact_indices, b.contact_indices, "L = {}", a.load_n);
        let scale = a.load_n.abs().max(a.elastic_load_n).max(adh);
        assert!((a.real_area_m2 / b.real_area_m2 - 1.0).abs() < 1e-9, "L = {}", a.load_n);
        assert!((a.elastic_load_n - b.elastic_load_n).abs() < 1e-9 * scale);
        // Separation: 1e-9 of the height SD.
        assert!((a.separation_m - b.separation_m).abs() < 1e-9 * 0.04e-6, "L = {}", a.load_n);
    }
}

/// Largest error, over a range of normalised interferences, of the solver's load and contact
/// radius for one summit of radius `r` on a surface whose other summits (far below the shoe)
/// span the radii 0.1-3 um, against the exact law `summit_response`. Returns
/// (max |dP| / (pi dgamma R), max |da| / (pi dgamma R^2 D)^(1/3)) over the contact branch.
fn single_summit_error(r: f64) -> (f64, f64) {
    let p = AsperityParams::table1();
    let pr = AsperityParams { radius_m: r, ..p };
    let lim = branch_limits(AdhesionLaw::MaugisDugdale, &pr).unwrap();
    let ds = pr.interference_scale_m();
    let ls = pr.load_scale_n();
    // The summit under test at the load point, two summits 1 mm lower fixing the radius range.
    let s = Surface::new(
        L_A,
        W_A,
        vec![10e-6, 1e-6, 19e-6],
        vec![2.5e-6, 1e-6, 4e-6],
        vec![0.0, -1e-3, -1e-3],
        Radii::PerSummit(vec![r, 0.1e-6, 3e-6]),
    )
    .unwrap();
    let cfg = SolverConfig { mode: ShoeMode::Flat, ..Default::default() };
    let mut sol = ExplicitSolver::new(s, AdhesionLaw::MaugisDugdale, p, cfg).unwrap();
    let rs = pr.radius_scale_m();
    // Jump-in: out of contact 1e-4 interference scales below the exact jump-in, in contact above
    // (the interpolated jump-in interference is within 1e-4 scales of the exact one).
    let z_in = lim.jump_in_interference_m;
    assert_eq!(sol.evaluate_pose(-(z_in - 1e-4 * ds), 0.0, 0.0).contacts, 0, "R = {r}");
    assert_eq!(sol.evaluate_pose(-(z_in + 1e-4 * ds), 0.0, 0.0).contacts, 1, "R = {r}");
    let (mut e_p, mut e_a) = (0.0f64, 0.0f64);
    for k in 1..=200 {
        // Interference from the jump-in value to 30 interference scales (P ~ 160 pi dgamma R).
        let z = z_in + (k as f64 / 200.0).powi(2) * 30.0 * ds;
        let exact = summit_response(AdhesionLaw::MaugisDugdale, &pr, z, Branch::Loading);
        let eq = sol.evaluate_pose(-z, 0.0, 0.0);
        assert!(exact.in_contact, "R = {r}, z = {z}");
        assert_eq!(eq.contacts, 1, "R = {r}, z = {z}");
        e_p = e_p.max((eq.load_n - exact.load_n).abs() / ls);
        e_a = e_a.max((eq.summits[0].contact_radius_m - exact.contact_radius_m).abs() / rs);
    }
    (e_p, e_a)
}

#[test]
fn single_summits_follow_the_exact_maugis_dugdale_law_within_the_interpolation_error() {
    // Radii 0.1-3 um (lognormal R = 0.5 +/- 0.3 um: 99.9 % inside), 25 log-spaced radii (most of
    // them between table nodes) plus the range ends, which are nodes and so exact (1e-12).
    let mut worst = (0.0f64, 0.0f64);
    for k in 0..=24 {
        let r = 0.1e-6 * 30f64.powf(k as f64 / 24.0 + 0.013 * f64::from(k % 3));
        let r = r.min(3e-6);
        let (e_p, e_a) = single_summit_error(r);
        eprintln!("R = {:.4} um: max |dP|/(pi dgamma R) = {e_p:.2e}, max |da|/a_scale = {e_a:.2e}", r * 1e6);
        worst = (worst.0.max(e_p), worst.1.max(e_a));
    }
    eprintln!("worst: {worst:?}");
    // Measured worst case with table step 0.05 in ln R (docs/explicit-solver.md): load 4.5e-5 of
    // pi dgamma R, contact radius 2.1e-4 of (pi dgamma R^2 D)^(1/3), largest near R = 2 um
    // (lambda ~ 0.55). Bounds: 1e-4 and 3e-4.
    assert!(worst.0 < 1e-4 && worst.1 < 3e-4, "{worst:?}");
    for r in [0.1e-6, 3e-6] {
        let (e_p, e_a) = single_summit_error(r);
        assert!(e_p < 1e-12 && e_a < 1e-12, "node radius {r}: {e_p} {e_a}");
    }
}

#[test]
fn lognormal_table1_surface_balances_forces_and_moments_on_loading_and_unloading() {
    // Tilt free, residuals below 1e-9 of the load scale max(|L|, sum |P_i|, 2 pi dgamma R) along
    // loading from pull-off to 10 uN and unloading back to pull-off; every contact on its branch.
    let p = AsperityParams::table1();
    let ell = 0.5 * L_A.hypot(W_A);
    for seed in [0u64, 1, 2] {
        let s = table1_lognormal(seed);
        let r_max = s.stats().radius_max_m;
        let mut sol = ExplicitSolver::new(s, AdhesionLaw::MaugisDugdale, p, SolverConfig::default()).unwrap();
        let curve = sol.loading_curve(10e-6, 41).unwrap();
        let down: Vec<f64> = (0..=200).map(|k| 10e-6 - k as f64 * 0.1e-6).collect();
        let unload = sol.sweep(&down, Branch::Unloading).unwrap();
        assert!(matches!(unload.events.last(), Some(SweepEvent::PullOff { .. })), "seed {seed}: ends in pull-off");
        assert!(curve.points.len() == 41 && unload.points.len() > 100);
        for e in curve.points.iter().chain(&unload.points) {
            let sum_abs: f64 = e.summits.iter().map(|c| c.load_n.abs()).sum();
            let scale = e.load_n.abs().max(sum_abs).max(2.0 * PI * 0.1 * 0.5e-6);
            assert!(e.force_residual_n.abs() < 1e-9 * scale, "seed {seed} L={}: {e:?}", e.load_n);
            assert!(e.moment_residual_x_n_m.abs() < 1e-9 * scale * ell);
            assert!(e.moment_residual_y_n_m.abs() < 1e-9 * scale * ell);
            assert!(e.contacts >= 3, "seed {seed} L={}: {} contacts", e.load_n, e.contacts);
            for c in &e.summits {
                // On the contact branch: at or above the release interference of its radius.
                let pr = AsperityParams { radius_m: c.radius_m, ..p };
                let lim = branch_limits(AdhesionLaw::MaugisDugdale, &pr).unwrap();
                assert!(c.interference_m >= lim.pull_off_interference_m - 1e-4 * pr.interference_scale_m());
                assert!(c.radius_m <= r_max);
            }
        }
    }
}
