//! Tests of the solver internals: the fast pass on every instruction set, the linear last step
//! against a fresh pass, the shortcuts within the tolerance, the LDL^T direction.

use nalgebra::Matrix3;
use stiction_surface::{FaceParams, Layout, Placement, generate};

use super::direction::newton_ldlt;
use super::eval::Eval;
use super::pass::evaluate;
use super::*;
use crate::single::Branch;

/// The fast pass gives the same bits on the baseline instruction set and on the best one of
/// this machine (AVX2+FMA on most x86-64): fixed lanes, no contraction, exact sqrt; dry and
/// with menisci.
#[test]
fn fast_pass_has_the_same_bits_on_every_instruction_set() {
    let layout = Layout { apparent_length_m: 40e-6, apparent_width_m: 10e-6, placement: Placement::Poisson, seed: 7 };
    for (mode, hardness) in [(ShoeMode::TiltFree, None), (ShoeMode::Flat, None), (ShoeMode::TiltFree, Some(2e9))] {
        let surface = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
        let cfg = SolverConfig { mode, hardness_pa: hardness, ..Default::default() };
        let mut s = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver");
        s.solve(0.1).expect("solve");
        let LawImpl::HertzDmt { inv_d, two_pi_dgamma } = s.imp else { panic!("DMT law expected") };
        let (x0, y0, inv_ell) = s.geom.uv.expect("fast pass");
        let radius = s.geom.radius(0);
        let a_hard = s.geom.hardness * std::f64::consts::PI * radius / (1.5 * inv_d);
        // A pose slightly off the equilibrium (members past release, summits touching).
        let q = [s.state.q[0] - 1e-9, s.state.q[1] + 4e-9, s.state.q[2] - 4e-9];
        // Dry, and with menisci (water at 35 %: f R = 0.45 uN, h_m = 1 nm), each without and
        // with the linear step's data.
        for (lin, cap_f, hm) in [(false, 0.0, 0.0), (true, 0.0, 0.0), (false, 0.45e-6, 1e-9), (true, 0.45e-6, 1e-9)] {
            let k = fast::Kernel {
                q,
                x0,
                y0,
                inv_ell,
                radius,
                inv_d,
                c0: two_pi_dgamma * radius + cap_f,
                allow_touch: true,
                a_hard,
                z_hard: a_hard * a_hard / radius,
                lin,
                cap_f,
                hm,
                inv_hm: if hm > 0.0 { 1.0 / hm } else { 0.0 },
            };
            let end = s.geom.hs.len();
            let (mut t1, mut t2) = (Vec::new(), Vec::new());
            let e1 = fast::evaluate_with(pulp::Arch::Scalar, &s.geom, &s.state, &k, end, 0.1, &mut t1);
            let e2 = fast::evaluate_with(pulp::Arch::new(), &s.geom, &s.state, &k, end, 0.1, &mut t2);
            assert!(e1.contacts > 100 && e1.releases > 0 && !t1.is_empty(), "{e1:?}");
            assert_eq!(e1.lin.is_some(), lin);
            assert_eq!(format!("{e1:?}"), format!("{e2:?}"), "{mode:?}");
            assert_eq!(t1, t2);
        }
    }
}

/// A solver for `summits` summits of the Table 1 statistics (4:1 face).
fn table1_solver(summits: f64, mode: ShoeMode, hardness_pa: Option<f64>) -> ExplicitSolver {
    let width = (summits / 4e12 / 4.0).sqrt();
    let layout =
        Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed: 3 };
    let surface = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
    let cfg = SolverConfig { mode, hardness_pa, detail: Detail::Summary, ..Default::default() };
    ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver")
}

/// Load at L* = 0.1 (eq. 5c) for `m` summits of the Table 1 statistics \[N\].
fn load_star_01(m: usize) -> f64 {
    0.1 * m as f64 * 0.5e-6f64.sqrt() * 0.04e-6f64.powf(1.5) / 9.1e-12
}

/// After every solve of a loading curve (pull-off, then 40 points to L* = 0.1), a fresh pass at
/// the final pose confirms what the solve reported, also where its last Newton step was a
/// linear one (no pass): the same contacts (no summit touching, none past release), force
/// and moment residuals below the tolerance (the remainder bound of `linear_step` holds),
/// real area and elastic load equal to rounding, the largest pressure and the count over the
/// hardness exactly. Tilt free, flat, and tilt free with a hardness.
#[test]
fn linear_steps_agree_with_a_pass_at_the_final_pose() {
    for (mode, hardness) in [(ShoeMode::TiltFree, None), (ShoeMode::Flat, None), (ShoeMode::TiltFree, Some(3e9))] {
        let mut s = table1_solver(3e4, mode, hardness);
        let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
        let l_max = load_star_01(s.len());
        let mut linear = 0;
        for k in 0..40 {
            let load = po + (l_max - po) * f64::from(k) / 39.0;
            let passes = s.work().passes;
            let eq = s.solve(load).expect("solve");
            linear += usize::from(s.work().passes - passes < eq.iterations as u64);
            let law =
                HertzDmt { inv_d: 1.0 / 9.1e-12, two_pi_dgamma: 0.2 * std::f64::consts::PI, radii: &s.geom.radii };
            let mut touch = Vec::new();
            let ev = evaluate(&s.geom, &law, &s.state, &s.state.q, load, true, true, &mut touch);
            let scale = load.abs().max(ev.force_abs).max(s.adhesion_ref);
            let tol = s.config.relative_tolerance * scale;
            assert!(touch.is_empty() && ev.releases == 0, "{mode:?} point {k}: contact set changed");
            assert_eq!(ev.contacts, eq.contacts, "{mode:?} point {k}");
            assert!(ev.g[..s.geom.ndof].iter().all(|g| g.abs() <= tol), "{mode:?} point {k}: {:?} > {tol:e}", ev.g);
            let ell = 1.0 / s.geom.uv.expect("fast pass").2;
            for (a, b, what) in [
                (eq.force_residual_n, load - ev.force, "force residual"),
                (eq.moment_residual_x_n_m / ell, ev.moment_x / ell, "moment x"),
                (eq.moment_residual_y_n_m / ell, ev.moment_y / ell, "moment y"),
                (eq.elastic_load_n, ev.elastic, "elastic load"),
            ] {
                assert!((a - b).abs() <= tol, "{mode:?} point {k}: {what} {a:e} against {b:e}");
            }
            assert!((eq.real_area_m2 - ev.area).abs() <= 1e-12 * ev.area, "{mode:?} point {k}: area");
            assert_eq!(eq.max_pressure_pa, ev.q0_max, "{mode:?} point {k}");
            assert_eq!(eq.summits_over_elastic_limit, ev.over_limit, "{mode:?} point {k}");
        }
        // The shortcut is taken on most points of the curve.
        assert!(linear >= 20, "{mode:?}: {linear} linear last steps of 40");
    }
}

/// The same with menisci (water at 35 %: f R = 0.45 uN, h_m = 1 nm): a fresh pass at every
/// final pose confirms the contacts (solid and wetted), the residuals, the capillary load and
/// the elastic load to the tolerance, and the real area to rounding, also where the last step
/// was a linear one with the tails in it. Tilt free and flat.
#[test]
fn linear_steps_with_menisci_agree_with_a_pass_at_the_final_pose() {
    let men = Meniscus { force_per_radius_n_per_m: 0.45e-6 / 0.5e-6, height_m: 1e-9 };
    for mode in [ShoeMode::TiltFree, ShoeMode::Flat] {
        let mut s = table1_solver(3e4, mode, None);
        s.set_meniscus(Some(men)).expect("meniscus");
        let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
        let l_max = load_star_01(s.len());
        let mut linear = 0;
        for k in 0..40 {
            let load = po + (l_max - po) * f64::from(k) / 39.0;
            let passes = s.work().passes;
            let eq = s.solve(load).expect("solve");
            linear += usize::from(s.work().passes - passes < eq.iterations as u64);
            let dry =
                HertzDmt { inv_d: 1.0 / 9.1e-12, two_pi_dgamma: 0.2 * std::f64::consts::PI, radii: &s.geom.radii };
            let law = Wet {
                dry: &dry,
                radii: &s.geom.radii,
                solid: &s.solid,
                force_per_radius_n_per_m: men.force_per_radius_n_per_m,
                height_m: men.height_m,
            };
            let mut touch = Vec::new();
            let ev = evaluate(&s.geom, &law, &s.state, &s.state.q, load, true, true, &mut touch);
            let scale = load.abs().max(ev.force_abs).max(s.adhesion_ref);
            let tol = s.config.relative_tolerance * scale;
            assert!(touch.is_empty() && ev.releases == 0, "{mode:?} point {k}: contact set changed");
            assert_eq!(ev.contacts, eq.wetted_summits, "{mode:?} point {k}");
            assert_eq!(ev.solid, eq.contacts, "{mode:?} point {k}");
            assert!(ev.g[..s.geom.ndof].iter().all(|g| g.abs() <= tol), "{mode:?} point {k}: {:?} > {tol:e}", ev.g);
            let ell = 1.0 / s.geom.uv.expect("fast pass").2;
            for (a, b, what) in [
                (eq.force_residual_n, load - ev.force, "force residual"),
                (eq.moment_residual_x_n_m / ell, ev.moment_x / ell, "moment x"),
                (eq.moment_residual_y_n_m / ell, ev.moment_y / ell, "moment y"),
                (eq.elastic_load_n, ev.elastic, "elastic load"),
                (eq.capillary_load_n, ev.capillary, "capillary load"),
            ] {
                assert!((a - b).abs() <= tol, "{mode:?} point {k}: {what} {a:e} against {b:e}");
            }
            assert!((eq.real_area_m2 - ev.area).abs() <= 1e-12 * ev.area, "{mode:?} point {k}: area");
            assert_eq!(eq.max_pressure_pa, ev.q0_max, "{mode:?} point {k}");
        }
        // The shortcut is taken with menisci too.
        assert!(linear >= 10, "{mode:?}: {linear} linear last steps of 40");
    }
}

/// The shortcuts (extrapolated first step, linear last step) change the equilibria of a loading
/// curve only within the solver tolerance: same contact counts at every point, elastic load
/// within 1e-9 of the load scale, separation within that load over the contact stiffness; and
/// off, the iteration takes every step with a pass (more passes).
#[test]
fn shortcuts_change_the_curve_only_within_the_tolerance() {
    for mode in [ShoeMode::TiltFree, ShoeMode::Flat] {
        let run = |shortcuts: bool| {
            let mut s = table1_solver(3e4, mode, None);
            s.set_shortcuts(shortcuts);
            let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            let l_max = load_star_01(s.len());
            let loads: Vec<f64> = (0..40).map(|k| po + (l_max - po) * f64::from(k) / 39.0).collect();
            let sweep = s.sweep(&loads, Branch::Loading).expect("sweep");
            (sweep.points, s.work().passes)
        };
        let (fast, fast_passes) = run(true);
        let (exact, exact_passes) = run(false);
        assert!(fast_passes < exact_passes, "{mode:?}: {fast_passes} passes against {exact_passes}");
        for (k, (a, b)) in fast.iter().zip(&exact).enumerate() {
            let scale = a.load_n.abs().max(b.elastic_load_n).max(2.0 * std::f64::consts::PI * 0.1 * 0.5e-6);
            assert_eq!(a.contacts, b.contacts, "{mode:?} point {k}");
            assert!((a.elastic_load_n - b.elastic_load_n).abs() <= 1e-9 * scale, "{mode:?} point {k}: {a:?} {b:?}");
            // Separation: the load scale's tolerance over the stiffness (> 1e3 N/m here); the
            // area pi R sum z+ moves by at most pi R n times that.
            let sep_tol = 1e-9 * scale / 1e3;
            assert!((a.separation_m - b.separation_m).abs() <= sep_tol, "{mode:?} point {k}");
            let area_tol = 1e-8 * b.real_area_m2 + std::f64::consts::PI * 0.5e-6 * b.contacts as f64 * sep_tol;
            assert!((a.real_area_m2 - b.real_area_m2).abs() <= area_tol, "{mode:?} point {k}: {a:?} {b:?}");
        }
    }
}

/// The LDL^T Newton direction agrees with the eigen-decomposition (to rounding) on a positive
/// definite Hessian, and declines a singular one.
#[test]
fn ldlt_direction_matches_the_eigen_direction() {
    let h = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
    let ev = Eval { g: [1.0, -2.0, 0.5], h, ..Default::default() };
    let d = newton_ldlt(&ev.h, &ev.g, 3).expect("positive definite");
    let m = Matrix3::from_fn(|i, j| h[i][j]);
    let x = m.try_inverse().expect("regular") * nalgebra::Vector3::new(-1.0, 2.0, -0.5);
    for j in 0..3 {
        assert!((d[j] - x[j]).abs() <= 1e-14 * x.norm(), "{d:?} {x:?}");
    }
    let singular = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    assert!(newton_ldlt(&singular, &ev.g, 3).is_none());
    // Flat mode: one degree of freedom.
    let d1 = newton_ldlt(&h, &[2.0, 9.0, 9.0], 1).expect("k > 0");
    assert_eq!(d1, [-0.5, 0.0, 0.0]);
}
