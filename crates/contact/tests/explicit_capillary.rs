//! The explicit solver with a meniscus in equilibrium with the vapour at every summit within the
//! meniscus height of the shoe (capillary condensation) against closed forms and the
//! Greenwood-Williamson statistics.
//!
//! Meniscus of water on a hydrophilic face (both contact angles 0): gamma = 0.072 N/m, Kelvin
//! radius r_K = 0.5 nm (water at 25 C, RH = 35 %), cos th1 + cos th2 = 2, so h_m = 1 nm and the
//! pull of a wetted summit in contact is 4 pi R gamma (Israelachvili, Intermolecular and Surface
//! Forces, 3rd ed. 2011, ch. 17: F = 4 pi R gamma cos theta for r_K << R), falling linearly with the
//! separation D as 2 pi R gamma (2 - D / r_K) until it ruptures at D = h_m.

use std::f64::consts::PI;

use stiction_contact::explicit::*;
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch};
use stiction_surface::*;

const GAMMA: f64 = 0.072;
const R_K: f64 = 0.5e-9;
const COS_SUM: f64 = 2.0;
const R: f64 = 0.5e-6;
const D: f64 = 9.1e-12;
const DGAMMA: f64 = 0.1;

fn meniscus() -> Meniscus {
    Meniscus { force_per_radius_n_per_m: 2.0 * PI * GAMMA * COS_SUM, height_m: R_K * COS_SUM }
}

/// Hertz load at interference z (eq. 3b), N.
fn hertz(z: f64) -> f64 {
    R.sqrt() * z.powf(1.5) / D
}

#[test]
fn one_wetted_summit_pulls_off_at_dmt_plus_four_pi_r_gamma() {
    // Pull-off under load control: the largest tension is at z -> 0+, where the summit carries
    // 2 pi dgamma R (DMT) + 4 pi R gamma (the meniscus); beyond contact the meniscus pull only falls.
    let f_cap = 4.0 * PI * R * GAMMA;
    let c = 2.0 * PI * DGAMMA * R;
    for mode in [ShoeMode::Flat, ShoeMode::TiltFree] {
        let lp = (f64::from(7e-6f32), f64::from(2e-6f32));
        let cfg = SolverConfig { mode, load_point_m: Some(lp), ..Default::default() };
        let surface = Surface::new(20e-6, 5e-6, vec![7e-6], vec![2e-6], vec![3e-8], Radii::Uniform(R)).unwrap();
        let mut s = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).unwrap();
        s.set_meniscus(Some(meniscus())).unwrap();
        for load in [0.0, 1e-6] {
            // In contact: Hertz(z) = L + c + 4 pi R gamma, relative 1e-9 (solver tolerance).
            let e = s.solve(load).unwrap();
            let z = 3e-8 - e.separation_m;
            assert!((hertz(z) / (load + c + f_cap) - 1.0).abs() < 1e-9, "{mode:?} L = {load}");
            assert!((e.capillary_load_n / f_cap - 1.0).abs() < 1e-12);
            assert_eq!((e.contacts, e.wetted_summits), (1, 1));
        }
        s.reset();
        let po = s.pull_off(0.0, 1e-7).unwrap();
        // Bisection to 1e-7 of the adhesion scale.
        let expected = -(c + f_cap);
        assert!((po.load_n / expected - 1.0).abs() < 1e-6, "{mode:?}: pull-off {} vs {expected}", po.load_n);
    }
}

/// Two summits under a flat shoe, B 5 nm below A. At the load where A has interference 4.6 nm, B
/// is separated by D = 0.4 nm < h_m and carries the meniscus condensed in its gap, pulling
/// 2 pi R gamma (2 - D / r_K) = 0.6 x 4 pi R gamma (circular meniscus, Kelvin equilibrium), whether
/// the shoe came down to that load or was unloaded to it from a load at which B touched: the same
/// equilibrium (relative 1e-9). Unloading further until B's gap exceeds h_m ruptures its meniscus.
/// Deliberate bug caught: the fast pass's join rule left at the dry one (a meniscus forms only on
/// touching): B has no meniscus on approach and z_A comes out 0.7 % short.
#[test]
fn a_meniscus_condenses_below_its_height_on_approach_and_on_retraction_alike() {
    let m = meniscus();
    let f_cap = 4.0 * PI * R * GAMMA;
    let c = 2.0 * PI * DGAMMA * R;
    let (ha, hb) = (30e-9, 25e-9);
    let surface =
        Surface::new(20e-6, 5e-6, vec![5e-6, 15e-6], vec![2.5e-6, 2.5e-6], vec![ha, hb], Radii::Uniform(R)).unwrap();
    let cfg = SolverConfig { mode: ShoeMode::Flat, detail: Detail::Full, ..Default::default() };
    let mut s = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).unwrap();
    s.set_meniscus(Some(m)).unwrap();
    let (za, gap) = (4.6e-9, 0.4e-9);
    let tail = 2.0 * PI * R * GAMMA * (COS_SUM - gap / R_K);
    let load2 = hertz(za) - c - f_cap - tail;
    let check = |e: &Equilibrium, what: &str| {
        assert!(((ha - e.separation_m) / za - 1.0).abs() < 1e-8, "{what}: z_A = {}", ha - e.separation_m);
        assert_eq!((e.contacts, e.wetted_summits), (1, 2), "{what}");
        let b = e.summits.iter().find(|x| x.index == 1).expect("B carries a meniscus");
        assert!((b.load_n + tail).abs() < 1e-9 * f_cap, "{what}: B carries {} instead of {}", b.load_n, -tail);
        assert!(((e.capillary_load_n - f_cap - tail) / f_cap).abs() < 1e-9, "{what}");
    };
    // Approach straight to load2.
    let a = s.solve(load2).unwrap();
    check(&a, "approach");
    // Load until both touch, then unload to load2.
    let up = s.solve(60e-6).unwrap();
    assert_eq!((up.contacts, up.wetted_summits), (2, 2));
    let e = s.solve(load2).unwrap();
    check(&e, "retraction");
    assert!((e.separation_m - a.separation_m).abs() < 1e-9 * za);
    // Unloading further until B's separation exceeds h_m ruptures its meniscus.
    let e3 = s.solve(hertz(3.5e-9) - c - f_cap).unwrap();
    assert_eq!((e3.contacts, e3.wetted_summits), (1, 1));
    assert!((e3.capillary_load_n / f_cap - 1.0).abs() < 1e-12);
}

/// F_n(h) = 1/sqrt(2 pi) int_h^inf (y - h)^n exp(-y^2/2) dy (Simpson in u = sqrt(y - h), as in
/// tests/explicit_gw.rs).
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

/// int_a^b g(y) phi(y) dy by Simpson (phi the standard normal density).
fn normal_integral(g: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let m = 20_000;
    let dx = (b - a) / m as f64;
    let f = |y: f64| g(y) * (-y * y / 2.0).exp() / (2.0 * PI).sqrt();
    let mut s = f(a) + f(b);
    for k in 1..m {
        s += f(a + k as f64 * dx) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * dx / 3.0
}

/// Table 1 statistics over 320 um x 80 um (about 1e5 summits), flat shoe (the GW situation): at
/// fixed separations the explicit sum of the menisci (in contact f R, bridged within h_m the
/// circular-meniscus tail) against the GW integral `GwSurface::capillary_load_n` on the same
/// statistics (eta A_a = M), and the total load against the GW balance with it, within 3 standard
/// errors of the sum over M iid summits; the GW integral itself against a direct quadrature here
/// (relative 1e-8). On retraction (loaded to d0, unloaded to d1 > d0) the menisci are those of
/// the pose d1, as on approach (equilibrium condensation): the exact sum over the heights
/// (relative 1e-12) and the same GW integral (3 SE). Deliberate bug caught: the fast pass's join
/// rule left at the dry one (menisci only on touching): the capillary load at h = 0.5 falls
/// 4.1 SE below the GW integral.
#[test]
fn flat_shoe_capillary_load_matches_the_gw_integral_on_approach_and_retraction() {
    use stiction_contact::capillary::Capillarity;
    use stiction_contact::gw::GwSurface;
    let (eta, sigma) = (4e12, 0.04e-6);
    let layout = Layout { apparent_length_m: 320e-6, apparent_width_m: 80e-6, placement: Placement::Poisson, seed: 7 };
    let surface = generate(&layout, &FaceParams::gaussian_fixed(eta, sigma, R)).unwrap();
    let heights: Vec<f64> = surface.heights_m().to_vec();
    let m_sum = heights.len() as f64;
    let men = meniscus();
    let f_r = men.force_per_radius_n_per_m * R;
    let hm = men.height_m;
    let k = hm / sigma;
    let c = 2.0 * PI * DGAMMA * R;
    let kappa = R.sqrt() * sigma.powf(1.5) / D;
    let cap = Capillarity { surface_tension_n_per_m: GAMMA, kelvin_radius_m: R_K, cos_angle_sum: COS_SUM };
    let gw = GwSurface {
        summit_density_per_m2: m_sum / (320e-6 * 80e-6),
        summit_radius_m: R,
        summit_sd_m: sigma,
        compliance_per_pa: D,
        work_of_adhesion_j_per_m2: DGAMMA,
        apparent_area_m2: 320e-6 * 80e-6,
    };
    // Per-summit meniscus pull of a summit of normalised height y at normalised separation h.
    let cap_of = |y: f64, h: f64| {
        if y >= h {
            f_r
        } else if y >= h - k {
            f_r * (1.0 - (h - y) / k)
        } else {
            0.0
        }
    };
    let cfg = SolverConfig { mode: ShoeMode::Flat, detail: Detail::Summary, ..Default::default() };
    let mut s = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).unwrap();
    s.set_meniscus(Some(men)).unwrap();
    let gw_check = |e: &Equilibrium, h: f64, with_load: bool| {
        let (f0, f15, f3) = (f_n(0.0, h), f_n(1.5, h), f_n(3.0, h));
        let gw_cap = gw.capillary_load_n(&cap, h).unwrap();
        // E[C], E[C^2] of the per-summit pull by quadrature (independent of gw.rs).
        let c1 = f_r * f0 + normal_integral(|y| cap_of(y, h), h - k, h);
        let c2 = f_r * f_r * f0 + normal_integral(|y| cap_of(y, h).powi(2), h - k, h);
        assert!(
            (gw_cap / (m_sum * c1) - 1.0).abs() < 1e-8,
            "h = {h}: GW integral {gw_cap:e} vs quadrature {:e}",
            m_sum * c1
        );
        let mut checks = vec![("capillary load", e.capillary_load_n, gw_cap, (m_sum * (c2 - c1 * c1)).sqrt())];
        if with_load {
            // P = A - C with A = kappa (y - h)^3/2 - c in contact, 0 else; E[A C] = f R E[A].
            let (a1, a2) = (kappa * f15 - c * f0, kappa * kappa * f3 - 2.0 * kappa * c * f15 + c * c * f0);
            let var = a2 - 2.0 * f_r * a1 + c2 - (a1 - c1).powi(2);
            checks.push(("load", e.load_n, m_sum * (kappa * f15 - c * f0) - gw_cap, (m_sum * var).sqrt()));
        }
        for (what, obs, mean, se) in checks {
            let zs = (obs - mean) / se;
            println!("h = {h:.4}: {what} explicit {obs:.6e} GW {mean:.6e} ({zs:+.2} SE)");
            assert!(zs.abs() < 3.0, "h = {h}: {what} explicit {obs:e} vs GW {mean:e} ({zs:.2} SE)");
        }
    };
    for h in [0.5, 1.0, 2.0, 3.0] {
        let e = s.evaluate_pose(h * sigma, 0.0, 0.0);
        gw_check(&e, h, true);
    }
    // Retraction: load to the pose h0 = 1, unload to the approach load of h0 + 0.5 nm.
    let d0 = sigma;
    let l0 = s.evaluate_pose(d0, 0.0, 0.0).load_n;
    let l1 = s.evaluate_pose(d0 + 0.5e-9, 0.0, 0.0).load_n;
    s.reset();
    let e0 = s.sweep(&[0.2 * l0, 0.6 * l0, l0], Branch::Loading).unwrap().points.pop().unwrap();
    let e1 = s.solve(l1).unwrap();
    let (d0, d1) = (e0.separation_m, e1.separation_m);
    assert!(d1 > d0 && d1 < d0 + hm, "d1 - d0 = {}", d1 - d0);
    // (a) The exact sum of the closed form over the summit heights (relative 1e-12: rounding).
    let direct: f64 = heights
        .iter()
        .map(|&h| {
            let z = h - d1;
            if z >= 0.0 {
                f_r
            } else if z >= -hm {
                f_r * (1.0 + z / hm)
            } else {
                0.0
            }
        })
        .sum();
    assert!((e1.capillary_load_n / direct - 1.0).abs() < 1e-12, "{} vs {direct}", e1.capillary_load_n);
    assert!(e1.wetted_summits > e1.contacts);
    // (b) The GW integral at h1 = d1/sigma, within 3 standard errors.
    gw_check(&e1, d1 / sigma, false);
}

#[test]
fn a_dry_solver_is_unchanged_by_clearing_the_meniscus() {
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 3 };
    let t1 = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, R)).unwrap();
    let run = |wet_then_dry: bool| {
        let mut s =
            ExplicitSolver::new(t1.clone(), AdhesionLaw::Dmt, AsperityParams::table1(), SolverConfig::default())
                .unwrap();
        if wet_then_dry {
            s.set_meniscus(Some(meniscus())).unwrap();
            s.solve(5e-6).unwrap();
            s.set_meniscus(None).unwrap();
        }
        let loads: Vec<f64> = (0..20).map(|k| k as f64 * 0.5e-6).collect();
        s.sweep(&loads, Branch::Loading).unwrap()
    };
    assert_eq!(run(false), run(true));
    let json = serde_json::to_string(&run(false)).unwrap();
    assert!(!json.contains("capillary") && !json.contains("wetted"));
}

#[test]
fn bad_meniscus_values_are_refused_naming_the_field() {
    let surface = Surface::new(20e-6, 5e-6, vec![7e-6], vec![2e-6], vec![3e-8], Radii::Uniform(R)).unwrap();
    let mut s =
        ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), SolverConfig::default()).unwrap();
    for (m, field) in [
        (Meniscus { force_per_radius_n_per_m: f64::NAN, height_m: 1e-9 }, "force_per_radius"),
        (Meniscus { force_per_radius_n_per_m: 0.9, height_m: -1e-9 }, "height_m"),
        (Meniscus { force_per_radius_n_per_m: 0.9, height_m: f64::INFINITY }, "height_m"),
    ] {
        let e = s.set_meniscus(Some(m)).unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
}

#[test]
fn the_meniscus_of_a_capillary_law_gives_its_sphere_flat_force() {
    // Water at 25 C, RH 35 %, contact angles 0 and 30 deg: the per-summit pull of the explicit
    // solver at separation D equals Capillarity::sphere_flat_force_n (relative 1e-12, rounding).
    use stiction_contact::capillary::{Capillarity, Liquid};
    let t = 298.15;
    let cap = Capillarity::new(Liquid::water(t), t, 0.35, 0.0, 30f64.to_radians()).unwrap().unwrap();
    let m = Meniscus::from_capillarity(&cap);
    let (h, lp) = (3e-8, (f64::from(7e-6f32), f64::from(2e-6f32)));
    let surface = Surface::new(20e-6, 5e-6, vec![7e-6], vec![2e-6], vec![h], Radii::Uniform(R)).unwrap();
    let cfg = SolverConfig { mode: ShoeMode::Flat, load_point_m: Some(lp), ..Default::default() };
    let mut s = ExplicitSolver::new(surface, AdhesionLaw::Hertz, AsperityParams::table1(), cfg).unwrap();
    s.set_meniscus(Some(m)).unwrap();
    let e = s.solve(1e-6).unwrap();
    let f0 = cap.sphere_flat_force_n(R, 0.0);
    assert!((e.capillary_load_n / f0 - 1.0).abs() < 1e-12);
    // At a gap D below h_m the summit carries the meniscus condensed there: the circular-meniscus
    // closed form 2 pi R gamma (cos th1 + cos th2 - D / r_K) (Butt & Kappl 2009; Israelachvili
    // ch. 17), to 1e-12 of the contact value; nothing beyond h_m. Deliberate bug caught: the fast pass's tail
    // with the sign of z flipped (1 - z/h_m), 1.7 x the closed form at 0.9 h_m.
    for frac in [0.0, 0.3, 0.9, 0.999, 1.001, 2.0] {
        let d = frac * cap.meniscus_height_m();
        let e = s.evaluate_pose(h + d, 0.0, 0.0);
        let want = 2.0 * PI * R * cap.surface_tension_n_per_m * (cap.cos_angle_sum - d / cap.kelvin_radius_m);
        if frac <= 1.0 {
            // (1e-12 of the contact value: z = h - (h + D) rounds to ulp(h), 1e-14 of h_m)
            assert!((e.capillary_load_n - want).abs() < 1e-12 * f0, "D = {frac} h_m: {} vs {want}", e.capillary_load_n);
            assert!((e.load_n + want).abs() < 1e-12 * f0, "D = {frac} h_m: load {}", e.load_n);
            // (no summit in solid contact: at D = 0 the contact radius is 0)
            assert_eq!((e.contacts, e.wetted_summits), (0, 1));
        } else {
            assert_eq!((e.capillary_load_n, e.wetted_summits), (0.0, 0));
        }
    }
    // Under load control a Hertz summit held by its meniscus stays in contact down to -F(0) (the
    // tail beyond contact has negative stiffness: unstable), and comes off below it.
    for (target, holds) in [(-0.5 * f0, true), (-0.99 * f0, true), (-1.01 * f0, false)] {
        s.reset();
        s.solve(1e-6).unwrap();
        match (s.solve(target), holds) {
            (Ok(e), true) => assert!((hertz(h - e.separation_m) / (target + f0) - 1.0).abs() < 1e-8),
            (Err(SolveError::NoEquilibrium { .. }), false) => {}
            (other, _) => panic!("load {target}: {other:?}"),
        }
    }
}

#[test]
fn the_fast_pass_and_the_generic_pass_agree_with_menisci() {
    // One radius (fast pass over blocks of 64) against the same radius given per summit (generic
    // pass): loading, unloading past the separation of wetted summits and reloading give the same
    // equilibria to the solver tolerance (1e-9 of the load scale; separations to 1e-6 of sigma).
    let layout = Layout { apparent_length_m: 40e-6, apparent_width_m: 10e-6, placement: Placement::Poisson, seed: 5 };
    let fast = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, R)).unwrap();
    let n = fast.len();
    let generic = Surface::new(
        40e-6,
        10e-6,
        (0..n).map(|i| fast.x_m(i) as f32).collect(),
        (0..n).map(|i| fast.y_m(i) as f32).collect(),
        fast.heights_m().to_vec(),
        Radii::PerSummit(vec![R; n]),
    )
    .unwrap();
    let mut loads: Vec<f64> = (0..=20).map(|k| k as f64 * 2e-6).collect();
    loads.extend((0..=20).rev().map(|k| k as f64 * 1e-6));
    let run = |s: Surface| {
        let mut sol =
            ExplicitSolver::new(s, AdhesionLaw::Dmt, AsperityParams::table1(), SolverConfig::default()).unwrap();
        sol.set_meniscus(Some(meniscus())).unwrap();
        loads.iter().map(|&l| sol.solve(l).unwrap()).collect::<Vec<_>>()
    };
    let (a, b) = (run(fast), run(generic));
    let mut tails = 0;
    for (x, y) in a.iter().zip(&b) {
        assert_eq!((x.contacts, x.wetted_summits), (y.contacts, y.wetted_summits), "L = {}", x.load_n);
        assert!((x.separation_m - y.separation_m).abs() < 1e-6 * 0.04e-6);
        assert!((x.capillary_load_n - y.capillary_load_n).abs() < 1e-9 * x.capillary_load_n);
        tails = tails.max(x.wetted_summits - x.contacts);
    }
    assert!(tails > 0, "the unloading branch has wetted summits out of contact");
}
