//! Explicit solver against closed forms: one summit must follow the single-asperity law exactly,
//! and the fixed-contacts mode with N = 1, 2, 3 must reproduce the discrete model, eq. 12.

use std::f64::consts::PI;

use stiction_contact::explicit::*;
use stiction_contact::single::{AdhesionLaw, AsperityParams, contact_radius_from_load};
use stiction_surface::*;

fn one_summit(x: f32, y: f32, h: f64) -> Surface {
    Surface::new(20e-6, 5e-6, vec![x], vec![y], vec![h], Radii::Uniform(0.5e-6)).unwrap()
}

fn table1_surface(seed: u64) -> Surface {
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed };
    generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).unwrap()
}

#[test]
fn one_summit_follows_hertz_and_dmt_exactly() {
    // Eq. 3b / 4b: P + 2 pi dgamma R = R^1/2 z^3/2 / D, a^2 = R z. Table 1 summit.
    let p = AsperityParams::table1();
    let c = 2.0 * PI * 0.1 * 0.5e-6;
    for (law, adh) in [(AdhesionLaw::Dmt, c), (AdhesionLaw::Hertz, 0.0)] {
        for mode in [ShoeMode::Flat, ShoeMode::TiltFree] {
            // The load acts exactly above the summit (positions are stored as f32).
            let lp = (f64::from(7e-6f32), f64::from(2e-6f32));
            let cfg = SolverConfig { mode, load_point_m: Some(lp), ..Default::default() };
            let mut s = ExplicitSolver::new(one_summit(7e-6, 2e-6, 3e-8), law, p, cfg).unwrap();
            for load in [-0.5 * adh, 0.0, 1e-7, 1e-6, 1e-5] {
                if law == AdhesionLaw::Hertz && load <= 0.0 {
                    continue;
                }
                let e = s.solve(load).unwrap();
                let z = ((load + adh) * 9.1e-12 / 0.5e-6f64.sqrt()).powf(2.0 / 3.0);
                assert_eq!(e.contacts, 1);
                // Interference: relative 1e-9 (the solver converges to 1e-10 of the load scale).
                assert!(((3e-8 - e.separation_m) / z - 1.0).abs() < 1e-9, "{law:?} {mode:?} L={load}");
                assert!((e.real_area_m2 / (PI * 0.5e-6 * z) - 1.0).abs() < 1e-9);
                assert!((e.adhesive_load_n - adh).abs() < 1e-9 * (adh + load.abs()));
                let q0 = 1.5 * (0.5e-6 * z).sqrt() / (PI * 9.1e-12 * 0.5e-6);
                assert!((e.max_pressure_pa / q0 - 1.0).abs() < 1e-9);
                assert!(e.force_residual_n.abs() < 1e-9 * (load.abs() + adh));
            }
        }
    }
}

#[test]
fn one_summit_follows_jkr_and_maugis_dugdale() {
    // The contact radius at load L equals the single-asperity law's (load-controlled stable branch).
    let p = AsperityParams::table1();
    let scale = PI * 0.1 * 0.5e-6;
    for law in [AdhesionLaw::Jkr, AdhesionLaw::MaugisDugdale] {
        let lp = (f64::from(10e-6f32), f64::from(2.5e-6f32));
        let cfg = SolverConfig { load_point_m: Some(lp), ..Default::default() };
        let mut s = ExplicitSolver::new(one_summit(10e-6, 2.5e-6, 0.0), law, p, cfg).unwrap();
        for lbar in [-1.0, 0.0, 1.0, 5.0, 30.0] {
            let e = s.solve(lbar * scale).unwrap();
            let a = contact_radius_from_load(law, &p, lbar * scale).unwrap();
            let a_exp = e.summits[0].contact_radius_m;
            // MD goes through a tabulated curve: 1e-6 relative; JKR exact to 1e-9.
            let tol = if law == AdhesionLaw::Jkr { 1e-9 } else { 1e-6 };
            assert!((a_exp / a - 1.0).abs() < tol, "{law:?} L/(pi dgamma R) = {lbar}: a {a_exp} vs {a}");
            assert!(e.force_residual_n.abs() < 1e-9 * scale.max(lbar.abs() * scale));
        }
    }
}

#[test]
fn fixed_contacts_reproduce_eq12() {
    // Eq. 12: F_f = s N pi R [ D / (N R^1/2) (L + N 2 pi dgamma R) ]^(2/3), N = 1, 2, 3; the N
    // highest summits of a Table 1 surface, load at their centroid, so each carries L/N exactly.
    let p = AsperityParams::table1();
    let (r, d, c, s) = (0.5e-6f64, 9.1e-12, 2.0 * PI * 0.1 * 0.5e-6, 1.4e9);
    for n in 1..=3usize {
        let cfg = SolverConfig { mode: ShoeMode::FixedContacts { count: n }, ..Default::default() };
        let mut sol = ExplicitSolver::new(table1_surface(4), AdhesionLaw::Dmt, p, cfg).unwrap();
        for load in [0.0, 1e-6, 3e-6, 10e-6] {
            let e = sol.solve(load).unwrap();
            let nf = n as f64;
            let eq12 = s * nf * PI * r * (d / (nf * r.sqrt()) * (load + nf * c)).powf(2.0 / 3.0);
            assert_eq!(e.contacts, n);
            assert!(
                (e.friction_capacity_n / eq12 - 1.0).abs() < 1e-9,
                "N={n} L={load}: {} vs {eq12}",
                e.friction_capacity_n
            );
            for sc in &e.summits {
                assert!((sc.load_n - load / nf).abs() < 1e-9 * (load + c), "equal sharing");
            }
        }
    }
}

#[test]
fn tilt_free_residuals_are_below_1e_minus_9_of_the_load_scale() {
    let p = AsperityParams::table1();
    let mut sol = ExplicitSolver::new(table1_surface(8), AdhesionLaw::Dmt, p, SolverConfig::default()).unwrap();
    let ell = 0.5 * 20e-6f64.hypot(5e-6);
    for load in [0.0, 0.5e-6, 1e-6, 3e-6, 10e-6, 30e-6, 100e-6] {
        let e = sol.solve(load).unwrap();
        let scale = load.max(e.elastic_load_n);
        assert!(e.force_residual_n.abs() < 1e-9 * scale, "L={load}: {e:?}");
        assert!(e.moment_residual_x_n_m.abs() < 1e-9 * scale * ell);
        assert!(e.moment_residual_y_n_m.abs() < 1e-9 * scale * ell);
        assert!(e.contacts >= 3, "a tilt-free shoe rests on at least 3 summits, got {}", e.contacts);
        for sc in &e.summits {
            assert!(sc.interference_m > 0.0, "DMT contacts have z > 0");
        }
    }
}

#[test]
fn sweeps_report_jump_in_and_pull_off_and_unloading_is_hysteretic() {
    let p = AsperityParams::table1();
    let mut sol = ExplicitSolver::new(table1_surface(3), AdhesionLaw::Dmt, p, SolverConfig::default()).unwrap();
    let up: Vec<f64> = (0..=40).map(|k| k as f64 * 5e-6).collect();
    let sw = sol.sweep(&up, stiction_contact::single::Branch::Loading).unwrap();
    assert_eq!(sw.points.len(), up.len());
    assert!(sw.events.iter().any(|e| matches!(e, SweepEvent::JumpIn { .. })), "contacts grow up to 200 uN");
    let down: Vec<f64> = (0..=440).map(|k| 200e-6 - k as f64 * 0.5e-6).collect();
    let sw2 = sol.sweep(&down, stiction_contact::single::Branch::Unloading).unwrap();
    let Some(SweepEvent::PullOff { load_n, last_stable_load_n: Some(last_stable_load_n), .. }) =
        sw2.events.last().cloned()
    else {
        panic!("unloading to -inf must end in pull-off: {:?}", sw2.events.last());
    };
    assert!(last_stable_load_n < 0.0 && load_n < last_stable_load_n);
    // Pull-off force of a few contacts: between one and (contacts) DMT summit adhesions.
    let c = 2.0 * PI * 0.1 * 0.5e-6;
    assert!(-last_stable_load_n < 10.0 * c, "{last_stable_load_n}");
    // Rejects a non-monotone load list, naming the field.
    let e = sol.sweep(&[1e-6, 0.0], stiction_contact::single::Branch::Loading).unwrap_err().to_string();
    assert!(e.contains("loads_n"), "{e}");
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let p = AsperityParams::table1();
    let mut sol = ExplicitSolver::new(table1_surface(1), AdhesionLaw::Dmt, p, SolverConfig::default()).unwrap();
    assert!(sol.solve(f64::NAN).unwrap_err().to_string().contains("load_n"));
    // Far below pull-off from the fresh state: the shoe separates.
    assert!(matches!(sol.solve(-1e-3), Err(SolveError::NoEquilibrium { .. })));
    let cfg = SolverConfig { mode: ShoeMode::FixedContacts { count: 0 }, ..Default::default() };
    let e = ExplicitSolver::new(table1_surface(1), AdhesionLaw::Dmt, p, cfg).err().unwrap().to_string();
    assert!(e.contains("contacts"), "{e}");
    let bad = AsperityParams { compliance_per_pa: -1.0, ..p };
    assert!(ExplicitSolver::new(table1_surface(1), AdhesionLaw::Dmt, bad, SolverConfig::default()).is_err());
}
