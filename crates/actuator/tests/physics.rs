//! Closed-form and consistency checks of the actuator model (issue 4). Each test names its
//! source and tolerance.

use stiction_actuator::*;

const UM: f64 = 1e-6;

fn plates(fringing: Fringing, back: Option<BackElectrode>) -> PlateArray {
    // The paper's clamp array geometry (section 5): 30 plates, 100 um x 5 um, gap 2 um.
    PlateArray {
        plate_count: 30,
        overlap_length_m: 100.0 * UM,
        thickness_m: 5.0 * UM,
        front_gap_m: 2.0 * UM,
        back,
        fringing,
        relative_permittivity: 1.0,
        comb: None,
    }
}

#[test]
fn pull_in_matches_closed_form_to_1e_9() {
    // Parallel plate, linear spring, no back gap, no fringing:
    // x_pi = g/3, V_pi = sqrt(8 k g^3 / (27 n eps0 A)) (issue 4; e.g. Senturia, Microsystem Design, eq. 6.41).
    for (k, g) in [(1.0, 2.0 * UM), (7.3, 4.83 * UM), (250.0, 0.7 * UM)] {
        let mut p = plates(Fringing::Off, None);
        p.front_gap_m = g;
        let act = GapClosingActuator::new(p, Suspension::linear(k), None, None).unwrap();
        let pi = act.pull_in().unwrap();
        let area = p.overlap_length_m * p.thickness_m;
        let v = (8.0 * k * g.powi(3) / (27.0 * 30.0 * VACUUM_PERMITTIVITY * area)).sqrt();
        assert!((pi.travel_m / (g / 3.0) - 1.0).abs() < 1e-9, "travel {} vs {}", pi.travel_m, g / 3.0);
        assert!((pi.voltage_v / v - 1.0).abs() < 1e-9, "voltage {} vs {v}", pi.voltage_v);
        assert!(!pi.limited_by_stop);
    }
}

#[test]
fn force_is_the_derivative_of_the_coenergy() {
    // F = dW*/dx at constant V (voltage drive), central difference, relative 1e-6.
    let back = Some(BackElectrode { gap_m: 3.5 * UM, potential: BackPotential::SameAsFront });
    for fr in [Fringing::Off, Fringing::Palmer] {
        for b in [None, back] {
            let p = plates(fr, b);
            for x in [0.0, 0.3 * UM, 1.1 * UM] {
                let h = 1e-10;
                let num = (p.coenergy_j(x + h, 20.0) - p.coenergy_j(x - h, 20.0)) / (2.0 * h);
                let ana = p.force_n(x, 20.0);
                assert!((num / ana - 1.0).abs() < 1e-6, "{fr:?} back={} x={x}: {num} vs {ana}", b.is_some());
                // and df/dx against a central difference of f
                let (_, df) = p.force_per_volt2_and_slope(x);
                let dnum = (p.force_per_volt2(x + h) - p.force_per_volt2(x - h)) / (2.0 * h);
                assert!((dnum / df - 1.0).abs() < 1e-5, "slope {dnum} vs {df}");
            }
        }
    }
}

#[test]
fn palmer_tends_to_parallel_plate_as_gap_over_size_vanishes() {
    // Palmer's factor -> 1 as g/t, g/l -> 0; the force excess is about g/(pi t) + g/(pi l)
    // (derivative of Palmer's formula), so it must shrink linearly with the gap.
    let mut last = f64::INFINITY;
    for g in [1.0 * UM, 0.1 * UM, 0.01 * UM, 0.001 * UM] {
        let mut pp = plates(Fringing::Off, None);
        pp.front_gap_m = g;
        let mut pa = pp;
        pa.fringing = Fringing::Palmer;
        let excess = pa.force_per_volt2(0.0) / pp.force_per_volt2(0.0) - 1.0;
        // Exact from C = eps l t p_t p_l / g: F/F_pp = p - g p' = 1 + a_t + a_l + a_t a_l (1 - L_t L_l),
        // a_d = g/(pi d), L_d = ln(2 pi d/g). The first-order part is a_t + a_l.
        let pi = std::f64::consts::PI;
        let (a_t, a_l) = (g / (pi * pp.thickness_m), g / (pi * pp.overlap_length_m));
        let (l_t, l_l) = ((2.0 * pi * pp.thickness_m / g).ln(), (2.0 * pi * pp.overlap_length_m / g).ln());
        let exact = a_t + a_l + a_t * a_l * (1.0 - l_t * l_l);
        assert!(excess > 0.0 && excess < last);
        assert!((excess / exact - 1.0).abs() < 1e-6, "g={g}: {excess} vs {exact}");
        assert!((excess / (a_t + a_l) - 1.0).abs() < 10.0 * a_l.max(a_t) * l_t * l_l);
        last = excess;
    }
    assert!(last < 1e-3);
}

#[test]
fn release_is_below_pull_in_and_sweeps_show_the_hysteresis() {
    let p = plates(Fringing::Palmer, None);
    let act = GapClosingActuator::new(p, Suspension::linear(5.0), Some(1.5 * UM), None).unwrap();
    let h = act.hysteresis().unwrap();
    assert!(h.release_voltage_v < h.pull_in_voltage_v && h.width_v > 0.0);
    // Release: spring force at the stop equals the electrostatic force there.
    let fs = act.suspension.force_n(1.5 * UM);
    assert!((act.electrostatic_force_n(1.5 * UM, h.release_voltage_v) / fs - 1.0).abs() < 1e-12);
    let s = act.sweep(1.2 * h.pull_in_voltage_v, 240).unwrap();
    let first_stop = s.loading.iter().find(|q| q.at_stop).unwrap().voltage_v;
    let last_stop = s.unloading.iter().filter(|q| q.at_stop).map(|q| q.voltage_v).fold(f64::INFINITY, f64::min);
    assert!(first_stop >= h.pull_in_voltage_v && first_stop <= h.pull_in_voltage_v * (1.0 + 1.2 / 240.0 + 1e-12));
    assert!(
        last_stop >= h.release_voltage_v
            && last_stop <= h.release_voltage_v + 1.2 * h.pull_in_voltage_v / 240.0 + 1e-12
    );
    // Free points are in force balance; stop points push on the stop.
    for q in s.loading.iter().chain(&s.unloading) {
        if q.at_stop {
            assert!(q.stop_force_n >= -1e-15);
        } else {
            assert!((q.electrostatic_force_n - q.spring_force_n).abs() <= 1e-9 * q.spring_force_n.max(1e-12));
        }
    }
}

#[test]
fn stop_before_pull_in_travel_gives_no_hysteresis() {
    let p = plates(Fringing::Off, None);
    let act = GapClosingActuator::new(p, Suspension::linear(5.0), Some(0.4 * UM), None).unwrap();
    let h = act.hysteresis().unwrap();
    assert_eq!(h.width_v, 0.0);
    // V to reach the stop: k x_s = f(x_s) V^2 with f = n eps A / (2 (g - x_s)^2).
    let a = 30.0 * VACUUM_PERMITTIVITY * 100.0 * UM * 5.0 * UM / (2.0 * (1.6 * UM).powi(2));
    assert!((h.pull_in_voltage_v / (5.0 * 0.4 * UM / a).sqrt() - 1.0).abs() < 1e-12);
}

#[test]
fn finger_bending_lowers_pull_in_and_vanishes_for_stiff_fingers() {
    let p = plates(Fringing::Off, None);
    let rigid = GapClosingActuator::new(p, Suspension::linear(5.0), Some(1.5 * UM), None).unwrap();
    let soft = FingerBending { root_length_m: 10.0 * UM, width_m: 2.0 * UM, youngs_modulus_pa: 160e9 };
    let stiff = FingerBending { width_m: 50.0 * UM, ..soft };
    let bent = GapClosingActuator { bending: Some(soft), ..rigid };
    let hard = GapClosingActuator { bending: Some(stiff), ..rigid };
    let (vr, vb, vh) =
        (rigid.pull_in().unwrap().voltage_v, bent.pull_in().unwrap().voltage_v, hard.pull_in().unwrap().voltage_v);
    assert!(vb < vr, "bending must lower pull-in: {vb} vs {vr}");
    // A 50 um wide finger is ~1.6e4 times stiffer: effect below 1e-4 relative.
    assert!((vh / vr - 1.0).abs() < 1e-4, "{vh} vs {vr}");
    // Tip deflection of a cantilever under uniform load q over its whole length: q L^4 / (8 EI).
    let no_root = FingerBending { root_length_m: 0.0, ..soft };
    let mut weak = p;
    weak.plate_count = 1;
    let v = 0.5; // tiny voltage: the load hardly depends on the deflection
    let (f, tip) = no_root.force_and_tip_deflection(&weak, 0.0, v);
    let q = f / weak.overlap_length_m;
    let ei = 160e9 * 5.0 * UM * (2.0 * UM).powi(3) / 12.0;
    let expect = q * weak.overlap_length_m.powi(4) / (8.0 * ei);
    assert!((tip / expect - 1.0).abs() < 0.01, "{tip} vs {expect}");
}

#[test]
fn beam_stiffness_formulas() {
    // Clamped-guided: k = E t w^3 / L^3 per beam (Roark, guided cantilever). GCA suspension of
    // Rauf et al.: 2 beams, 241 um x (3.00 - 0.8) um x 40 um, E/(1-nu^2), nu = 0.069.
    let b = BeamSuspension {
        kind: BeamKind::ClampedGuided,
        count: 2,
        length_m: 241.0 * UM,
        width_m: 3.0 * UM,
        thickness_m: 40.0 * UM,
        youngs_modulus_pa: 169e9,
        plane_strain_poisson: Some(0.069),
    }
    .with_undercut(0.4 * UM)
    .unwrap();
    let e = 169e9 / (1.0 - 0.069f64.powi(2));
    let k = 2.0 * e * 40.0 * UM * (2.2 * UM).powi(3) / (241.0 * UM).powi(3);
    assert!((b.stiffness_n_per_m() / k - 1.0).abs() < 1e-12);
    let f = BeamSuspension { kind: BeamKind::Folded, ..b };
    assert!((f.stiffness_n_per_m() / (k / 2.0) - 1.0).abs() < 1e-12);
    // Series and parallel extras: 1/(1/(k1 + kp) + 1/ks).
    let s = Suspension {
        main_stiffness_n_per_m: 3.0,
        parallel_stiffness_n_per_m: 1.0,
        series_stiffness_n_per_m: Some(4.0),
    };
    assert!((s.stiffness_n_per_m() - 2.0).abs() < 1e-15);
}

#[test]
fn gap_inferred_from_conversion_factor() {
    // Parallel plate: g = sqrt(n eps0 A / (2 a)); the paper's a_clamp = 1.4e-8 N/V^2 with 30
    // plates of 100 um x 5 um gives 2.18 um.
    let p = plates(Fringing::Off, None);
    let g = stiction_actuator::conversion::infer_front_gap_m(&p, 0.0, 1.4e-8).unwrap();
    let closed = (30.0 * VACUUM_PERMITTIVITY * 100.0 * UM * 5.0 * UM / (2.0 * 1.4e-8)).sqrt();
    assert!((g / closed - 1.0).abs() < 1e-12, "{g} vs {closed}");
    assert!((closed - 2.178e-6).abs() < 0.005e-6);
    // With fringing the same force needs a larger gap.
    let gp = stiction_actuator::conversion::infer_front_gap_m(&plates(Fringing::Palmer, None), 0.0, 1.4e-8).unwrap();
    assert!(gp > g);
    let mut back = plates(Fringing::Palmer, None);
    back.front_gap_m = gp;
    assert!((back.force_per_volt2(0.0) / 1.4e-8 - 1.0).abs() < 1e-10);
}

#[test]
fn meter_clamp_force_and_pull_runaway() {
    // Clamp: L = a(x_c) V^2 - k x_c (paper section 5).
    let clamp = GapClosingActuator::new(plates(Fringing::Off, None), Suspension::linear(8.0), None, None).unwrap();
    let xc = 0.5 * UM;
    let c = clamp_force(&clamp, xc, 40.0).unwrap();
    assert!(c.in_contact);
    let expect = clamp.conversion_factor_n_per_v2(xc) * 1600.0 - 8.0 * xc;
    assert!((c.clamp_force_n / expect - 1.0).abs() < 1e-12);
    assert!((c.spring_force_n - 4e-6).abs() < 1e-18);
    let below = clamp_force(&clamp, xc, 0.5 * c.contact_voltage_v).unwrap();
    assert!(!below.in_contact && below.clamp_force_n == 0.0);
    // Pull: while stuck F = a(0) V^2; after slip with no resistance it runs away iff V > V_pi.
    let pull =
        GapClosingActuator::new(plates(Fringing::Off, None), Suspension::linear(2.0), Some(1.5 * UM), None).unwrap();
    let vpi = pull.pull_in().unwrap().voltage_v;
    assert!(
        (pull_force_stuck_n(&pull, 10.0).unwrap() / (pull.conversion_factor_n_per_v2(0.0) * 100.0) - 1.0).abs() < 1e-15
    );
    assert!(matches!(slip_response(&pull, 1.01 * vpi, 0.0).unwrap(), SlipResponse::RunsAway { .. }));
    match slip_response(&pull, 0.9 * vpi, 0.0).unwrap() {
        SlipResponse::Settles { travel_m } => {
            let x = pull.stable_travel_m(0.9 * vpi, &pull.pull_in().unwrap()).unwrap();
            assert!((travel_m / x - 1.0).abs() < 1e-9);
        }
        other => panic!("expected to settle, got {other:?}"),
    }
}

#[test]
fn paper_conversion_factors_imply_gaps() {
    // Paper section 5: clamp 30 plates, pull 15 plates, 100 um x 5 um each;
    // a_clamp = (1.4 +/- 0.5)e-8 N/V^2, a_pull = (3.8 +/- 0.8)e-9 N/V^2. Parallel plate:
    // g = sqrt(n eps0 A / (2a)): clamp 2.18 um (1.87..2.72), pull 2.96 um (2.69..3.33).
    let infer = |n: u32, a: f64, fr: Fringing| {
        let mut p = plates(fr, None);
        p.plate_count = n;
        stiction_actuator::conversion::infer_front_gap_m(&p, 0.0, a).unwrap()
    };
    for fr in [Fringing::Off, Fringing::Palmer] {
        let c: Vec<f64> = [1.9e-8, 1.4e-8, 0.9e-8].iter().map(|&a| infer(30, a, fr) * 1e6).collect();
        let p: Vec<f64> = [4.6e-9, 3.8e-9, 3.0e-9].iter().map(|&a| infer(15, a, fr) * 1e6).collect();
        println!(
            "{fr:?}: clamp gap {:.3} ({:.3}..{:.3}) um, pull gap {:.3} ({:.3}..{:.3}) um",
            c[1], c[0], c[2], p[1], p[0], p[2]
        );
        if fr == Fringing::Off {
            assert!((c[1] - 2.178).abs() < 0.002 && (p[1] - 2.956).abs() < 0.002);
            assert!((c[0] - 1.870).abs() < 0.002 && (c[2] - 2.717).abs() < 0.002);
            assert!((p[0] - 2.687).abs() < 0.002 && (p[2] - 3.327).abs() < 0.002);
        }
        // The clamp gap (after the shoe travel) is smaller than the pull gap.
        assert!(c[1] < p[1]);
    }
}

/// Calibration from the pull-in voltage inverts the pull-in closed form: for a parallel-plate array
/// with a linear spring, V_pi = sqrt(8 k g^3 / (27 n eps0 A)), so a device with gap g pulls in at
/// V_pi(g), and calibrating the nominal spec (another gap) from that voltage recovers g (to the
/// bisection's 1e-9) and the conversion factor n eps0 A / (2 g^2) (relative 1e-9).
#[test]
fn calibration_from_pull_in_recovers_the_gap() {
    use stiction_actuator::{ArraySpec, calibrate_from_pull_in};
    let spec = |gap: &str| -> ArraySpec {
        serde_json::from_value(serde_json::json!({
            "plate_count": 15, "overlap_length": "100 um", "thickness": "5 um", "front_gap": gap,
            "fringing": "off", "spring": {"stiffness": "1 N/m"}
        }))
        .unwrap()
    };
    let (k, n, area, eps0) = (1.0f64, 15.0f64, 100e-6 * 5e-6, 8.854_187_812_8e-12);
    let true_gap = 3.1e-6f64;
    let v_pi = (8.0 * k * true_gap.powi(3) / (27.0 * n * eps0 * area)).sqrt();
    let cal = calibrate_from_pull_in(&spec("2.96 um"), v_pi).unwrap();
    assert!((cal.front_gap_m / true_gap - 1.0).abs() < 1e-9, "{}", cal.front_gap_m);
    let a = n * eps0 * area / (2.0 * true_gap * true_gap);
    assert!((cal.conversion_factor_n_per_v2 / a - 1.0).abs() < 1e-8, "{} vs {a}", cal.conversion_factor_n_per_v2);
    // A voltage no gap can give is an error, not a guess.
    assert!(calibrate_from_pull_in(&spec("2.96 um"), 1e6).is_err());
}
