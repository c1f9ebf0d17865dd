//! The capillary cohesive zone of the boundary-element solver (condensed water wherever the gap is
//! below the meniscus height h_m = r_K (cos th1 + cos th2), traction gamma / r_K there) against
//! closed forms. Water at 25 C and RH = 35 %: gamma = 0.07197 N/m, r_K = 0.50 nm (from
//! `stiction_contact::capillary`).

use std::f64::consts::PI;

use stiction_bem::{BemSolver, ContactSolution, Dugdale, SolverOptions};
use stiction_contact::capillary::{Capillarity, Liquid};

fn water(rh: f64, angle_deg: f64) -> Capillarity {
    let t = 298.15;
    let a = angle_deg.to_radians();
    Capillarity::new(Liquid::water(t), t, rh, a, a).unwrap().unwrap()
}

fn zone(c: &Capillarity) -> Dugdale {
    Dugdale::capillary(c.surface_tension_n_per_m, c.kelvin_radius_m, c.cos_angle_sum).unwrap()
}

#[test]
fn the_zone_carries_the_laplace_pressure_over_the_meniscus_height() {
    // Energy balance of the zone: traction x h_m = gamma/r_K x r_K (cos th1 + cos th2)
    // = 2 gamma cos theta per unit area (relative 1e-15: rounding), for two humidities and angles.
    for (rh, angle) in [(0.35, 0.0), (0.8, 40.0)] {
        let c = water(rh, angle);
        let z = zone(&c);
        assert!((z.stress_pa / c.laplace_pressure_pa() - 1.0).abs() < 1e-15);
        assert!((z.range_m / c.meniscus_height_m() - 1.0).abs() < 1e-15);
        let two_gamma_cos = 2.0 * c.surface_tension_n_per_m * angle.to_radians().cos();
        assert!((z.work_of_adhesion_j_per_m2() / two_gamma_cos - 1.0).abs() < 1e-14);
    }
    assert!(Dugdale::capillary(0.072, 0.5e-9, 0.0).is_err());
    assert!(Dugdale::capillary(f64::NAN, 0.5e-9, 2.0).is_err());
}

#[test]
fn separating_a_flat_wetted_interface_takes_two_gamma_cos_theta() {
    // Two flats (a 1 pm sinusoid so the solver has a scale): retraction from a 0.1 nm mean gap to
    // separation. Work of separation sigma0 h_m = 2 gamma cos theta to within the trapezoid's
    // error at the jump, sigma0 step / 2 = 0.5 % with step = h_m / 100; pull-off pressure -gamma / r_K
    // within 1e-6.
    let n = 32;
    let dx = 10e-9;
    let h: Vec<f64> = (0..n * n).map(|i| 1e-12 * (2.0 * PI * (i % n) as f64 / n as f64).cos()).collect();
    // Stiff (E* = 10 TPa): where the zone covers part of the cell its uneven tension would lift the
    // surface (by ~0.2 nm at 85 GPa over this 320 nm cell) and hold the zone past h_m.
    let mut s = BemSolver::new(n, n, dx, dx, &h, 1e13).unwrap();
    let c = water(0.35, 20.0);
    let z = zone(&c);
    let opts = SolverOptions { tolerance: 1e-8, ..Default::default() };
    let sep = s.work_of_separation(&[z], 0.5e-12, z.range_m / 100.0, &opts).unwrap();
    let expected = 2.0 * c.surface_tension_n_per_m * 20f64.to_radians().cos();
    println!("flat: Gamma = {:.6} J/m^2, 2 gamma cos theta = {expected:.6}", sep.adhesion_energy_j_per_m2);
    assert!((sep.adhesion_energy_j_per_m2 / expected - 1.0).abs() < 0.005);
    assert!((sep.pull_off_pressure_pa / -c.laplace_pressure_pa() - 1.0).abs() < 1e-6);
}

/// A paraboloid `h = -r^2/(2R)` centred on grid point (n/2, n/2) with pixels dx.
fn paraboloid(n: usize, dx: f64, radius: f64) -> Vec<f64> {
    (0..n * n)
        .map(|i| {
            let (x, y) = ((i % n) as f64 - (n / 2) as f64, (i / n) as f64 - (n / 2) as f64);
            -(x * x + y * y) * dx * dx / (2.0 * radius)
        })
        .collect()
}

#[test]
fn a_wetted_sphere_pulls_off_at_four_pi_r_gamma_cos_theta() {
    // Sphere R = 0.5 um (paraboloid) on a stiff half-space (E* = 10 TPa: Maugis parameter of the
    // zone 0.005, the rigid limit) against a flat, 128 x 128 pixels of 2 nm: the meniscus zone
    // radius sqrt(2 R h_m) = 31.6 nm spans 16 pixels. Pull-off (most tensile load on a mean-gap
    // retraction through contact) = 4 pi R gamma cos theta (Israelachvili, Intermolecular and
    // Surface Forces, 3rd ed. 2011, ch. 17, r_K << R) within 2.5 % (the zone is counted in whole
    // pixels: 777 inside the circle of 784.8 pixel areas, -1 %); with a van der Waals Dugdale zone added (w = 0.1 J/m^2, range 0.5 nm) the two pulls
    // add: 2 pi R (w + 2 gamma cos theta), within 3 %.
    let (n, dx, radius) = (128, 2e-9, 0.5e-6);
    let h = paraboloid(n, dx, radius);
    let mut s = BemSolver::new(n, n, dx, dx, &h, 1e13).unwrap();
    let c = water(0.35, 0.0);
    let cap = zone(&c);
    let vdw = Dugdale::from_work_and_range(0.1, 0.5e-9).unwrap();
    let touch = -h.iter().sum::<f64>() / (n * n) as f64;
    let opts = SolverOptions { tolerance: 1e-7, ..Default::default() };
    let area = (n as f64 * dx).powi(2);
    for (laws, expected) in [
        (vec![cap], 4.0 * PI * radius * c.surface_tension_n_per_m),
        (vec![vdw, cap], 2.0 * PI * radius * (0.1 + 2.0 * c.surface_tension_n_per_m)),
    ] {
        let mut warm: Option<ContactSolution> = None;
        let mut pull_off: f64 = 0.0;
        let reach = cap.range_m;
        // From contact to separation, finely just past contact where the pull is largest.
        for d in [-0.2, -0.1, 0.0, 1e-3, 3e-3, 0.01, 0.03, 0.1, 0.3, 0.6, 1.0, 1.2] {
            let gbar = touch + d * reach;
            let sol = s.solve_cohesive_mean_gap(gbar, &laws, &opts, warm.as_ref()).unwrap();
            pull_off = pull_off.min(sol.mean_pressure_pa * area);
            warm = Some(sol);
        }
        println!("{} laws: pull-off {:.5e} N, closed form {expected:.5e} N", laws.len(), -pull_off);
        assert!((-pull_off / expected - 1.0).abs() < 0.025, "{} vs {expected}", -pull_off);
    }
}

#[test]
fn one_law_through_the_general_solver_is_the_dugdale_solver_to_the_bit() {
    let (n, dx, radius) = (32, 4e-9, 0.5e-6);
    let h = paraboloid(n, dx, radius);
    let law = Dugdale::from_work_and_range(0.1, 1e-9).unwrap();
    let opts = SolverOptions::default();
    let touch = -h.iter().sum::<f64>() / (n * n) as f64;
    let mut a = BemSolver::new(n, n, dx, dx, &h, 85e9).unwrap();
    let mut b = BemSolver::new(n, n, dx, dx, &h, 85e9).unwrap();
    let x = a.solve_adhesive_mean_gap(touch - 0.5e-9, &law, &opts, None).unwrap();
    let y = b.solve_cohesive_mean_gap(touch - 0.5e-9, &[law], &opts, None).unwrap();
    assert_eq!(x, y);
}
