//! Capillary adhesion in the analytic contact models (single asperity, GW, discrete) against closed
//! forms and against direct quadrature of the per-summit meniscus force over the Gaussian summit
//! heights (written here, independent of the `F_n` machinery of `gw`).

use std::f64::consts::PI;

use stiction_contact::capillary::{Capillarity, Liquid};
use stiction_contact::discrete::DiscreteModel;
use stiction_contact::gw::GwSurface;
use stiction_contact::single::{self, AdhesionLaw, AsperityParams};

const T25: f64 = 298.15;

fn cap(rh: f64, theta_deg: f64) -> Capillarity {
    let t = theta_deg.to_radians();
    Capillarity::new(Liquid::water(T25), T25, rh, t, t).unwrap().unwrap()
}

fn phi(u: f64) -> f64 {
    (-0.5 * u * u).exp() / (2.0 * PI).sqrt()
}

/// Composite Simpson on [a, b] with `n` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let h = (b - a) / n as f64;
    let mut s = f(a) + f(b);
    for i in 1..n {
        s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    s * h / 3.0
}

/// `int_lo^inf g(u) phi(u) du` for an integrand with a square-root edge at `lo`: u = lo + t^2.
fn tail(g: impl Fn(f64) -> f64, lo: f64) -> f64 {
    simpson(|t| 2.0 * t * g(lo + t * t) * phi(lo + t * t), 0.0, 14.0f64.sqrt(), 40_000)
}

/// GW + DMT + meniscus on the loading branch: at the solved separation, the per-summit sum by
/// direct quadrature (Hertz `delta^3/2 R^1/2 / D` minus DMT `2 pi dgamma R` minus the meniscus at
/// contact `F_sphere(R, 0)`, over the summits in contact) gives back the applied load, and the
/// capillary part equals the quadrature of the meniscus force over the summits in contact.
/// Tolerance 1e-8 relative (Simpson with 40 000 intervals after the t^2 substitution is good to
/// ~1e-12). Deliberate bug caught: the capillary load counted with `gamma cos theta` (one face)
/// instead of `gamma (cos th1 + cos th2)` in `solve_load_wet`, or the meniscus left out of the
/// equilibrium.
#[test]
fn gw_wet_loading_equals_direct_summit_sum() {
    let s = GwSurface::table1();
    let c = cap(0.35, 0.0);
    let scale_n = s.summit_density_per_m2 * s.apparent_area_m2;
    for load in [0.5e-6, 3e-6, 20e-6] {
        let wet = s.solve_load_wet(load, true, Some(&c)).unwrap();
        let h = wet.separation_m / s.summit_sd_m;
        let sigma = s.summit_sd_m;
        let r = s.summit_radius_m;
        let hertz = scale_n * tail(|u| (sigma * (u - h)).powf(1.5) * r.sqrt() / s.compliance_per_pa, h);
        let dmt = scale_n * tail(|_| 2.0 * PI * s.work_of_adhesion_j_per_m2 * r, h);
        let capq = scale_n * tail(|u| c.sphere_flat_force_n(r, sigma * (h - u)), h);
        assert!((wet.capillary_load_n - capq).abs() <= 1e-8 * capq, "{load}: {} vs {capq}", wet.capillary_load_n);
        let balance = hertz - dmt - capq;
        assert!((balance - load).abs() <= 1e-8 * hertz, "{load}: {balance} vs {load}");
        assert!((wet.adhesive_load_n - (dmt + capq)).abs() <= 1e-8 * (dmt + capq));
        // A wet contact pulls harder: more real area than dry at the same load.
        let dry = s.solve_load(load, true).unwrap();
        assert!(wet.real_area_m2 > dry.real_area_m2);
        assert_eq!(dry.capillary_load_n, 0.0);
    }
    // The approach-branch function is the same sum.
    let h = 1.3;
    let direct = scale_n * tail(|u| c.sphere_flat_force_n(s.summit_radius_m, s.summit_sd_m * (h - u)), h);
    let f = s.capillary_load_approach_n(&c, h).unwrap();
    assert!((f - direct).abs() <= 1e-9 * direct, "{f} vs {direct}");
}

/// Without a meniscus `solve_load_wet` is `solve_load`, bit for bit.
#[test]
fn gw_dry_is_unchanged() {
    let s = GwSurface::table1();
    for load in [0.1e-6, 3e-6] {
        assert_eq!(s.solve_load_wet(load, true, None).unwrap(), s.solve_load(load, true).unwrap());
    }
}

/// Retraction: summits that touched (height above h_min) keep their menisci up to the rupture gap
/// h_m; the closed form with F_0, F_1 against direct quadrature of the per-summit force over the
/// wetted heights. Tolerance 1e-9 relative. Deliberate bug caught: a wrong sign of the
/// `(l - h + k) F_0(l)` term when h_min limits the wetted range.
#[test]
fn gw_retraction_capillary_matches_direct_quadrature() {
    let s = GwSurface::table1();
    let scale_n = s.summit_density_per_m2 * s.apparent_area_m2;
    let r = s.summit_radius_m;
    let sigma = s.summit_sd_m;
    for (rh, theta) in [(0.35, 0.0), (0.9, 20.0)] {
        let c = cap(rh, theta);
        let k = c.meniscus_height_m() / sigma;
        for (h, h_min) in [(1.0, 0.5), (2.0, 2.0 - 0.3 * k), (2.0, 2.0), (0.3, -1.0), (4.0, 3.99)] {
            let l = (h - k).max(h_min);
            // in contact (u > h): constant; bridged (l < u < h): linear decay.
            let in_contact = tail(|_| c.sphere_flat_force_n(r, 0.0), h);
            let bridged = simpson(|u| c.sphere_flat_force_n(r, sigma * (h - u)) * phi(u), l, h, 2000);
            let direct = scale_n * (in_contact + bridged);
            let f = s.capillary_load_retraction_n(&c, h, h_min).unwrap();
            assert!((f - direct).abs() <= 1e-9 * direct, "rh {rh} h {h} h_min {h_min}: {f} vs {direct}");
            // at h = h_min nothing is bridged: the approach value.
            if h == h_min {
                let a = s.capillary_load_approach_n(&c, h).unwrap();
                assert!((f - a).abs() <= 1e-12 * a);
            }
        }
    }
    assert!(s.capillary_load_retraction_n(&cap(0.35, 0.0), 1.0, 1.5).is_err());
}

/// Single asperity: the pull-off with a meniscus, closed forms. DMT: 2 pi R (dgamma + 2 gamma cos
/// theta); JKR: 1.5 pi dgamma R + 4 pi R gamma cos theta (Table 1 summit, R = 0.5 um, dgamma =
/// 0.1 J/m^2; water at 25 C, 35 %, theta = 0: the meniscus adds 0.452 uN to DMT's 0.314 uN).
/// Tolerance 1e-9 relative (JKR's pull-off is computed by the law's own solve). Deliberate bug
/// caught: the meniscus at the rupture gap (0) instead of at contact.
#[test]
fn single_pull_off_with_meniscus() {
    let p = AsperityParams::table1();
    let c = cap(0.35, 0.0);
    let g = c.surface_tension_n_per_m;
    let dmt = single::pull_off_force_wet(AdhesionLaw::Dmt, &p, Some(&c)).unwrap();
    let want = 2.0 * PI * p.radius_m * (p.work_of_adhesion_j_per_m2 + 2.0 * g);
    assert!((dmt - want).abs() <= 1e-12 * want, "{dmt} vs {want}");
    assert!((dmt - 0.7664e-6).abs() < 0.001e-6, "{dmt}");
    let jkr = single::pull_off_force_wet(AdhesionLaw::Jkr, &p, Some(&c)).unwrap();
    let want = 1.5 * PI * p.work_of_adhesion_j_per_m2 * p.radius_m + 4.0 * PI * p.radius_m * g;
    assert!((jkr - want).abs() <= 1e-9 * want, "{jkr} vs {want}");
    assert_eq!(
        single::pull_off_force_wet(AdhesionLaw::Dmt, &p, None).unwrap(),
        single::pull_off_force(AdhesionLaw::Dmt, &p).unwrap()
    );
    // The meniscus force with separation: 0 beyond h_m.
    assert_eq!(single::meniscus_force_n(&c, &p, 1.01 * c.meniscus_height_m()), 0.0);
}

/// Discrete model with DMT and a meniscus at each contact: eq. 12 with dgamma -> dgamma + 2 gamma
/// cos theta, `a^3 = R D (L/N + 2 pi R (dgamma + 2 gamma cos theta))`. Tolerance 1e-12 relative.
/// Deliberate bug caught: the meniscus pull added to the total load once instead of per contact.
#[test]
fn discrete_wet_is_eq12_with_meniscus_work() {
    let m = DiscreteModel::fig7();
    let c = cap(0.35, 10.0);
    let p = m.params;
    for load in [0.0, 3e-6, 10e-6] {
        let pt = m.at_load_wet(load, Some(&c)).unwrap();
        let w = p.work_of_adhesion_j_per_m2 + c.flat_work_of_adhesion_j_per_m2();
        let a3 = p.radius_m * p.compliance_per_pa * (load / 3.0 + 2.0 * PI * w * p.radius_m);
        let want = 1.4e9 * 3.0 * PI * a3.cbrt().powi(2);
        assert!((pt.friction_n - want).abs() <= 1e-12 * want, "{load}: {} vs {want}", pt.friction_n);
    }
    assert!((m.capillary_load_n(Some(&c)) - 3.0 * c.sphere_flat_force_n(p.radius_m, 0.0)).abs() < 1e-20);
    assert_eq!(m.at_load_wet(3e-6, None).unwrap(), m.at_load(3e-6).unwrap());
    assert_eq!(m.capillary_load_n(None), 0.0);
}
