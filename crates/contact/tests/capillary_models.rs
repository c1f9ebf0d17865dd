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

/// Per-summit meniscus pull summed over the Gaussian heights by direct quadrature: in contact
/// (u > h) the constant `F_sphere(R, 0)`, bridged (h - k < u < h, k = h_m/sigma) the
/// circular-meniscus force at the gap sigma (h - u).
fn capillary_quadrature(s: &GwSurface, c: &Capillarity, h: f64) -> f64 {
    let (r, sigma) = (s.summit_radius_m, s.summit_sd_m);
    let k = c.meniscus_height_m() / sigma;
    let in_contact = tail(|_| c.sphere_flat_force_n(r, 0.0), h);
    let bridged = simpson(|u| c.sphere_flat_force_n(r, sigma * (h - u)) * phi(u), h - k, h, 2000);
    s.summit_density_per_m2 * s.apparent_area_m2 * (in_contact + bridged)
}

/// GW + DMT + menisci in equilibrium with the vapour: at the solved separation, the per-summit
/// sum by direct quadrature (Hertz `delta^3/2 R^1/2 / D` minus DMT `2 pi dgamma R` over the
/// summits in contact, minus the meniscus of every summit within h_m of the counter face) gives
/// back the applied load, and the capillary part equals the quadrature of the meniscus force.
/// Tolerance 1e-8 relative (Simpson with 40 000 intervals after the t^2 substitution is good to
/// ~1e-12). Deliberate bug caught: the bridged summits left out of `capillary_load_n` (the
/// contact-only `k F_0(h)` in place of `F_1(h - k) - F_1(h)`): capillary load 5 % low at 0.5 uN.
#[test]
fn gw_wet_loading_equals_direct_summit_sum() {
    let s = GwSurface::table1();
    let scale_n = s.summit_density_per_m2 * s.apparent_area_m2;
    for (rh, theta) in [(0.35, 0.0), (0.05, 0.0), (0.9, 20.0)] {
        let c = cap(rh, theta);
        for load in [0.5e-6, 3e-6, 20e-6] {
            let wet = s.solve_load_wet(load, true, Some(&c)).unwrap();
            let h = wet.separation_m / s.summit_sd_m;
            let sigma = s.summit_sd_m;
            let r = s.summit_radius_m;
            let hertz = scale_n * tail(|u| (sigma * (u - h)).powf(1.5) * r.sqrt() / s.compliance_per_pa, h);
            let dmt = scale_n * tail(|_| 2.0 * PI * s.work_of_adhesion_j_per_m2 * r, h);
            let capq = capillary_quadrature(&s, &c, h);
            let what = format!("RH {rh} L {load}");
            assert!((wet.capillary_load_n - capq).abs() <= 1e-8 * capq, "{what}: {} vs {capq}", wet.capillary_load_n);
            let balance = hertz - dmt - capq;
            assert!((balance - load).abs() <= 1e-8 * hertz, "{what}: {balance} vs {load}");
            assert!((wet.adhesive_load_n - (dmt + capq)).abs() <= 1e-8 * (dmt + capq), "{what}");
            // A wet contact pulls harder: more real area than dry at the same load.
            let dry = s.solve_load(load, true).unwrap();
            assert!(wet.real_area_m2 > dry.real_area_m2, "{what}");
            assert_eq!(dry.capillary_load_n, 0.0);
        }
    }
}

/// The GW capillary integral `F_1(h - k) - F_1(h)` against direct quadrature over a wide range of
/// separations, also the far tail where `F_1` is 1e-20 and the difference of two close values
/// would have lost every digit. Tolerance 1e-9 relative. In the limit k -> 0 (RH -> 0) it tends to
/// the contact-only load `eta A_a 2 pi R gamma (cos th1 + cos th2) F_0(h)`: ratio 1 + O(k h).
#[test]
fn gw_capillary_integral_matches_direct_quadrature() {
    let s = GwSurface::table1();
    for (rh, theta) in [(0.35, 0.0), (0.9, 20.0), (0.01, 0.0)] {
        let c = cap(rh, theta);
        for h in [-1.0, 0.3, 1.3, 2.5, 4.0, 9.0] {
            let direct = capillary_quadrature(&s, &c, h);
            let f = s.capillary_load_n(&c, h).unwrap();
            assert!((f - direct).abs() <= 1e-9 * direct, "rh {rh} h {h}: {f} vs {direct}");
        }
    }
    // RH -> 0: h_m -> 0 and the bridged band vanishes.
    let c = cap(1e-6, 0.0);
    let k = c.meniscus_height_m() / s.summit_sd_m;
    let h = 2.5;
    let contact_only = s.summit_density_per_m2
        * s.apparent_area_m2
        * 2.0
        * PI
        * s.summit_radius_m
        * c.flat_work_of_adhesion_j_per_m2()
        * stiction_contact::gw::f_n(0.0, h).unwrap();
    let f = s.capillary_load_n(&c, h).unwrap();
    assert!(f > contact_only && (f / contact_only - 1.0) < 2.0 * k * h, "{f} vs {contact_only} (k = {k:e})");
}

/// Without a meniscus `solve_load_wet` is `solve_load`, bit for bit.
#[test]
fn gw_dry_is_unchanged() {
    let s = GwSurface::table1();
    for load in [0.1e-6, 3e-6] {
        assert_eq!(s.solve_load_wet(load, true, None).unwrap(), s.solve_load(load, true).unwrap());
    }
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

/// Single asperity out of solid contact: the load that holds it at a gap D is minus the
/// circular-meniscus force `2 pi R gamma (cos th1 + cos th2 - D / r_K)` (Butt & Kappl, Adv. Colloid
/// Interface Sci. 146 (2009) 48; Israelachvili ch. 17), written out here from gamma, r_K and the
/// angles; 0 beyond h_m and when dry. Relative 1e-12. Deliberate bug caught: the gap divided by
/// h_m instead of r_K (twice the decay for hydrophilic faces).
#[test]
fn single_summit_load_at_a_gap_is_the_circular_meniscus_force() {
    let p = AsperityParams::table1();
    for (rh, theta) in [(0.35, 0.0), (0.7, 40.0)] {
        let c = cap(rh, theta);
        let (g, rk) = (c.surface_tension_n_per_m, c.kelvin_radius_m);
        let cos_sum = 2.0 * theta.to_radians().cos();
        for frac in [0.0, 0.25, 0.5, 0.9] {
            let d = frac * rk * cos_sum;
            let want = 2.0 * PI * p.radius_m * g * (cos_sum - d / rk);
            let got = -single::separated_load_wet_n(&p, d, Some(&c));
            assert!((got - want).abs() <= 1e-12 * want, "rh {rh} D {d}: {got} vs {want}");
        }
        assert_eq!(single::separated_load_wet_n(&p, 1.001 * rk * cos_sum, Some(&c)), 0.0);
    }
    assert_eq!(single::separated_load_wet_n(&p, 0.1e-9, None), 0.0);
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
