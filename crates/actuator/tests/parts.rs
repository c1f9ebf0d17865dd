//! The other structures' actuators against their closed forms (docs/actuators.md, "Other
//! actuators"): lateral comb force and side instability (Legtenberg et al., J. Micromech.
//! Microeng. 6 (1996) 320), the plate electrode through a dielectric stack, the released spring.

use stiction_actuator::{DielectricLayer, LateralComb, PlateElectrode, ReleasedSpring, VACUUM_PERMITTIVITY};

const EPS0: f64 = 8.8541878128e-12;

fn comb() -> LateralComb {
    // 50 fingers, 2 um thick, 2 um gaps, 10 um engagement, k_x = 1 N/m, k_y = 100 N/m.
    LateralComb::new(50, 2e-6, 2e-6, 10e-6, 1.0, 1.0, Some(100.0)).unwrap()
}

/// F = N eps0 t V^2 / g, the textbook comb force, and the same at every travel: the derivative of
/// the co-energy 1/2 C V^2 by central difference at two travels (relative 1e-7: the difference
/// step's rounding on a force linear in x is far below that).
#[test]
fn comb_force_is_n_eps0_t_v2_over_g_at_every_travel() {
    let c = comb();
    assert!((VACUUM_PERMITTIVITY - EPS0).abs() < 1e-21);
    let v = 30.0;
    let closed = 50.0 * EPS0 * 2e-6 * v * v / 2e-6;
    assert!((c.force_n(v) - closed).abs() <= 1e-12 * closed, "{} vs {closed}", c.force_n(v));
    for x in [0.0, 5e-6] {
        let h = 1e-9;
        let f = 0.5 * v * v * (c.capacitance_f(x + h, 0.0) - c.capacitance_f(x - h, 0.0)) / (2.0 * h);
        assert!((f - closed).abs() <= 1e-7 * closed, "travel {x}: {f} vs {closed}");
    }
    // The fringing factor scales the drive force and nothing else.
    let f2 = LateralComb::new(50, 2e-6, 2e-6, 10e-6, 1.3, 1.0, Some(100.0)).unwrap();
    assert!((f2.force_n(v) / c.force_n(v) - 1.3).abs() < 1e-14);
    assert_eq!(f2.lateral_electrostatic_stiffness_n_per_m(1e-6, v), c.lateral_electrostatic_stiffness_n_per_m(1e-6, v));
}

/// The lateral negative stiffness 2 N eps0 t (x0 + x) V^2 / g^3 against the second derivative of
/// the co-energy in the offset y (relative 1e-5, the central difference's truncation at h = 1 nm
/// on a 2 um gap is (h/g)^2 ~ 2.5e-7).
#[test]
fn comb_lateral_stiffness_is_the_co_energy_curvature() {
    let c = comb();
    let (x, v) = (3e-6, 40.0);
    let h = 1e-9;
    let w = |y: f64| 0.5 * v * v * c.capacitance_f(x, y);
    let curvature = (w(h) - 2.0 * w(0.0) + w(-h)) / (h * h);
    let k_e = c.lateral_electrostatic_stiffness_n_per_m(x, v);
    let closed = 2.0 * 50.0 * EPS0 * 2e-6 * 13e-6 * v * v / 8e-18;
    assert!((k_e - closed).abs() <= 1e-12 * closed);
    assert!((curvature - k_e).abs() <= 1e-5 * k_e, "{curvature} vs {k_e}");
}

/// The free comb's side pull-in (Legtenberg's closed form) against a bisection on the stability
/// condition k_y = k_e(x(V), V) with x(V) = F(V)/k_x, for fringing factors 1 and 1.4 and
/// engagements 0, 10 um and 100 um (relative 1e-9). At a fixed travel the closed form
/// k_y g^3 / (2 N eps0 t (x0 + x)) is checked the same way.
#[test]
fn comb_side_pull_in_matches_the_stability_condition() {
    for alpha in [1.0, 1.4] {
        for x0 in [0.0, 10e-6, 100e-6] {
            let c = LateralComb::new(50, 2e-6, 2e-6, x0, alpha, 1.0, Some(100.0)).unwrap();
            let margin = |v: f64| 100.0 - c.lateral_electrostatic_stiffness_n_per_m(c.free_travel_m(v), v);
            let (mut lo, mut hi) = (0.0f64, 1e4f64);
            assert!(margin(lo) > 0.0 && margin(hi) < 0.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if margin(mid) > 0.0 { lo = mid } else { hi = mid }
            }
            let v_si = c.side_pull_in_voltage_v().unwrap();
            assert!((v_si - lo).abs() <= 1e-9 * lo, "alpha {alpha} x0 {x0}: {v_si} vs {lo}");
            let held = c.side_pull_in_voltage_at_v(5e-6).unwrap();
            let k_at = c.lateral_electrostatic_stiffness_n_per_m(5e-6, held);
            assert!((k_at - 100.0).abs() < 1e-9 * 100.0);
        }
    }
    // Without a lateral stiffness there is no side pull-in to report.
    let free = LateralComb::new(50, 2e-6, 2e-6, 1e-5, 1.0, 1.0, None).unwrap();
    assert!(free.side_pull_in_voltage_v().is_none());
}

/// Plate through a dielectric stack: F = eps0 A V^2 / (2 (g + sum t/eps_r)^2); a 100 um x 100 um
/// plate 2 um above its electrode at 10 V pulls with 1.1068e-6 N (hand value,
/// 8.8541878e-12 * 1e-8 * 100 / (2 * 4e-12)); a 150 nm nitride (eps_r 7.5) plus 100 nm oxide
/// (3.9) acts as 20 nm + 25.64 nm of air; the force is -dW/dg of the series capacitance (1e-7).
#[test]
fn plate_force_through_a_dielectric_stack() {
    let bare = PlateElectrode::new(1e-8, 2e-6, vec![], 0.0, 0.0).unwrap();
    let f = bare.force_n(2e-6, 10.0);
    assert!((f - 1.106_773_5e-6).abs() < 1e-13, "{f}");
    let stack = vec![
        DielectricLayer { thickness: 150e-9, relative_permittivity: 7.5 },
        DielectricLayer { thickness: 100e-9, relative_permittivity: 3.9 },
    ];
    let p = PlateElectrode::new(1e-8, 0.0, stack, 1.5e-6, 2.0).unwrap();
    let d = 150e-9 / 7.5 + 100e-9 / 3.9;
    assert!((p.dielectric_equivalent_gap_m() - d).abs() < 1e-22);
    let v = 5.0;
    let closed = EPS0 * 1e-8 * v * v / (2.0 * d * d);
    assert!((p.force_n(0.0, v) - closed).abs() <= 1e-12 * closed);
    let h = 1e-12;
    let fd = 0.5 * v * v * (p.capacitance_f(h) - p.capacitance_f(-h)) / (2.0 * h);
    assert!((-fd - closed).abs() <= 1e-6 * closed, "{fd} vs {closed}");
    // Normal load at contact: a V^2 - k_z g0.
    assert!((p.normal_load_n(v) - (closed - 2.0 * 1.5e-6)).abs() <= 1e-12 * closed);
}

/// Pull-in of the plate through its dielectric: the maximum of V_eq(z)^2 = 2 k z (G - z)^2/(eps0 A)
/// found by a golden-section search equals sqrt(8 k G^3 / (27 eps0 A)) (1e-9); when G/3 lies past
/// contact, the contact voltage is the stable branch's value at contact.
#[test]
fn plate_pull_in_through_the_dielectric() {
    let stack = vec![DielectricLayer { thickness: 150e-9, relative_permittivity: 7.5 }];
    let p = PlateElectrode::new(1e-8, 0.0, stack.clone(), 2e-6, 1.0).unwrap();
    let big_g = 2e-6 + 20e-9;
    let v2 = |z: f64| 2.0 * 1.0 * z * (big_g - z).powi(2) / (EPS0 * 1e-8);
    let (mut a, mut b) = (0.0f64, 2e-6f64);
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if v2(c) > v2(d) { b = d } else { a = c }
    }
    let v_max = v2(0.5 * (a + b)).sqrt();
    assert!((p.contact_voltage_v() - v_max).abs() <= 1e-9 * v_max, "{} vs {v_max}", p.contact_voltage_v());
    // Dimples 1.5 um tall and a 0.5 um travel: G/3 = 0.673 um > 0.5 um, no pull-in before contact.
    let q = PlateElectrode::new(1e-8, 1.5e-6, stack, 0.5e-6, 1.0).unwrap();
    let gc = 1.5e-6 + 20e-9;
    let at_contact = (2.0 * 0.5e-6 * gc * gc / (EPS0 * 1e-8)).sqrt();
    assert!((q.contact_voltage_v() - at_contact).abs() <= 1e-12 * at_contact);
    // A plate that would touch its electrode is refused.
    assert!(PlateElectrode::new(1e-8, 0.0, vec![], 1e-6, 1.0).is_err());
}

/// Released spring: F_t = k x, and k = m (2 pi f)^2 from a resonance: 1 ug at 10 kHz is
/// 3.9478 N/m (hand value, 1e-9 kg * (2 pi 1e4)^2).
#[test]
fn released_spring_load_and_resonance() {
    let s = ReleasedSpring::from_resonance(1e-9, 1e4).unwrap();
    assert!((s.stiffness_n_per_m - 3.947_841_760_4).abs() < 1e-9, "{}", s.stiffness_n_per_m);
    assert!((s.tangential_load_n(2e-6) - 2e-6 * s.stiffness_n_per_m).abs() < 1e-20);
    assert!((s.displacement_for_load_m(s.tangential_load_n(3e-6)) - 3e-6).abs() < 1e-20);
    assert!(ReleasedSpring::new(0.0).is_err());
    assert!(ReleasedSpring::from_resonance(1e-9, -1.0).is_err());
}
