//! Pull-in protocol `step` (crate::protocol): shuttle mass and air damping from geometry, the step
//! pull-in against an independent RK4 of the same 1-DOF equation, the stop criterion, and the
//! effect on the Rauf et al. (JMEMS 2022) GCA validation with its sensitivity to mass and damping.
//! `cargo test -p stiction-actuator --release --test step_protocol -- --nocapture` prints the numbers
//! quoted in docs/actuators.md.

use stiction_actuator::*;

mod common;
use common::{at_length, gca_spec, root};

fn data() -> Vec<MeasuredPoint> {
    read_measurements(&root().join("data/gca-pullin-release/measured.csv")).unwrap()
}

#[test]
fn squeeze_film_closed_forms() {
    // Long strip limit beta(0) = 1; square plate beta(1) = 0.4218 (Senturia, Microsystem Design,
    // sec. 13.4 quotes 0.42); beta(1/2) = 0.6860 from the series by hand (0.6274 * 0.5 * 0.99928 ...).
    assert_eq!(squeeze_film_aspect_factor(0.0), 1.0);
    assert!((squeeze_film_aspect_factor(1.0) - 0.4218).abs() < 1e-4, "{}", squeeze_film_aspect_factor(1.0));
    let half = 1.0
        - 192.0 / std::f64::consts::PI.powi(5)
            * 0.5
            * ((std::f64::consts::PI).tanh()
                + (3.0 * std::f64::consts::PI).tanh() / 243.0
                + 1.0 / 3125.0
                + 1.0 / 16807.0);
    assert!((squeeze_film_aspect_factor(0.5) - half).abs() < 1e-5);
    // Long strip: c = mu L s^3 / h^3 (Reynolds, 1D) for L >> s.
    let c = rectangular_squeeze_film_damping_n_s_per_m(1.81e-5, 1e-3, 10e-6, 2e-6).unwrap();
    let strip = 1.81e-5 * 1e-3 * 1e-15 / 8e-18;
    // beta(0.01) = 1 - 0.627404 * 0.01 * (1 + 1/3^5 + 1/5^5 + ...) = 1 - 0.0062740 * 1.0045238 = 0.993698
    assert!((c / strip - 0.993698).abs() < 1e-6, "{}", c / strip);
    // Veijola: continuum limit, and Kn = 0.1 -> 1 + 9.638 * 0.1^1.159 = 1.6682.
    assert_eq!(veijola_effective_viscosity_pa_s(1.81e-5, 0.0, 1e-6).unwrap(), 1.81e-5);
    let mu = veijola_effective_viscosity_pa_s(1.0, 0.1, 1.0).unwrap();
    assert!((1.0 / mu - (1.0 + 9.638 * 0.1f64.powf(1.159))).abs() < 1e-12);
    assert!(veijola_effective_viscosity_pa_s(1.0, 0.1, 0.0).is_err());
}

#[test]
fn gca_mass_and_damping_from_geometry() {
    // 76.5 um fingers, u = 0.4 um: by hand from layouts/fawn.csv (see the scenario):
    // fingers 70 x (76.1 + 10) x 4.21 um^2 = 25 373.67 um^2; spine 19.2 x 859.2 - 61 x 8.8^2 = 11 772.80 um^2;
    // bumpers 821 um^2; beams 13/35 x 2 x 241 x 2.2 um^2 = 393.87 um^2. Times 40 um x 2329 kg/m^3.
    let spec = gca_spec();
    let sh = Shuttle::from_spec(&spec).unwrap();
    let by_hand = (25_373.67 + 11_772.80 + 821.0 + 13.0 / 35.0 * 2.0 * 241.0 * 2.2) * 1e-12 * 40e-6 * 2329.0;
    assert!((sh.mass_kg / by_hand - 1.0).abs() < 1e-6, "{} vs {}", sh.mass_kg, by_hand);
    let m = spec.to_model().unwrap();
    // Squeeze film at rest, by hand: front gap 5.63 um (Kn 0.01208), back 8.55 um; plate 76.1 x 40 um.
    let mu = 1.81e-5;
    let film = |h: f64| {
        let mu_eff = mu / (1.0 + 9.638 * (68e-9 / h).powf(1.159));
        mu_eff * 76.1e-6 * 40e-6f64.powi(3) / h.powi(3) * squeeze_film_aspect_factor(40.0 / 76.1)
    };
    let c0 = 70.0 * (film(5.63e-6) + film(8.55e-6));
    assert!((sh.squeeze_film_n_s_per_m(&m, 0.0) / c0 - 1.0).abs() < 1e-9);
    // Couette under the planform, 2 um + 2 x 68 nm slip.
    assert!((sh.couette_n_s_per_m / (mu * sh.planform_area_m2 / 2.136e-6) - 1.0).abs() < 1e-12);
    // Front-gap film grows as 1/(g - x)^3 (a bit less with rarefaction).
    assert!(sh.squeeze_film_n_s_per_m(&m, 2.8e-6) > 5.0 * c0);
    // The step protocol without a shuttle is an error naming it.
    let mut s = spec.clone();
    s.shuttle = None;
    assert!(matches!(Shuttle::from_spec(&s), Err(ActuatorError::NotAvailable(msg)) if msg.contains("shuttle")));
}

/// Independent RK4 of m x'' = F_e(x, V) - k x - c(x) x' from rest: does the shuttle reach `x_c`?
fn rk4_reaches(m: &GapClosingActuator, sh: &Shuttle, v: f64) -> bool {
    let mass = sh.mass_kg;
    let k = m.stiffness_n_per_m();
    let xc = m.stop_travel_m.unwrap();
    let acc = |x: f64, xd: f64| (m.electrostatic_force_n(x, v) - k * x - sh.damping_n_s_per_m(m, x) * xd) / mass;
    let period = 2.0 * std::f64::consts::PI * (mass / k).sqrt();
    let h = period / 20_000.0;
    let (mut x, mut xd) = (0.0f64, 0.0f64);
    for _ in 0..(40.0 * period / h) as usize {
        let (k1x, k1v) = (xd, acc(x, xd));
        let (k2x, k2v) = (xd + 0.5 * h * k1v, acc(x + 0.5 * h * k1x, xd + 0.5 * h * k1v));
        let (k3x, k3v) = (xd + 0.5 * h * k2v, acc(x + 0.5 * h * k2x, xd + 0.5 * h * k2v));
        let (k4x, k4v) = (xd + h * k3v, acc(x + h * k3x, xd + h * k3v));
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        xd += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if x >= xc {
            return true;
        }
        if xd < 0.0 {
            return false; // turned back short of the stop
        }
    }
    false
}

#[test]
fn damped_step_pull_in_matches_independent_rk4() {
    // Rigid fingers (bending changes the GCA force by < 1e-4, docs) so the RK4 is cheap; same
    // force law, same damping law c(x), same mass. Tolerance 1e-3: the rapier integration is first
    // order in dt (docs: energy at impact -8e-4 at T/2000), the threshold sits on the energy
    // balance, the undamped check in tests/dynamics.rs agrees to 3.2e-5.
    for l in [15.30e-6, 76.50e-6] {
        let mut s = at_length(&gca_spec(), l);
        s.finger_bending = None;
        let m = s.to_model().unwrap();
        let sh = Shuttle::from_spec(&s).unwrap();
        let step = step_pull_in(&m, &sh).unwrap();
        let (mut lo, mut hi) = (0.8 * step.quasi_static_voltage_v, 1.01 * step.quasi_static_voltage_v);
        assert!(!rk4_reaches(&m, &sh, lo) && rk4_reaches(&m, &sh, hi));
        while hi - lo > 1e-6 * hi {
            let mid = 0.5 * (lo + hi);
            if rk4_reaches(&m, &sh, mid) { hi = mid } else { lo = mid }
        }
        let rk4 = 0.5 * (lo + hi);
        println!(
            "L = {:5.2} um: rapier {:.4} V, RK4 {:.4} V ({:+.1e}); quasi-static {:.4} V; zeta(0) = {:.4}",
            l * 1e6,
            step.reach_voltage_v,
            rk4,
            step.reach_voltage_v / rk4 - 1.0,
            step.quasi_static_voltage_v,
            step.damping_ratio_at_rest
        );
        assert!((step.reach_voltage_v / rk4 - 1.0).abs() < 1e-3);
        // Damping raises the threshold above the undamped energy criterion, below quasi-static.
        let undamped = undamped_dynamic_pull_in_voltage_v(&m, 0.0, 1e-9).unwrap();
        assert!(undamped < step.reach_voltage_v && step.reach_voltage_v < step.quasi_static_voltage_v);
    }
}

#[test]
fn stop_before_the_dynamic_barrier_needs_the_release_voltage() {
    // Parallel plates, no back gap, no fringing, stop at 0.4 g (between g/3 and g/2), negligible
    // damping. The step reaches the stop from V_reach^2 = k x_c g (g - x_c)/(n eps A) (energy at x_c,
    // no instability on the way) but stays only if V >= V_r, V_r^2 = 2 k x_c (g - x_c)^2/(n eps A),
    // which is larger for x_c < g/2 (ratio 2 (g - x_c)/g = 1.2): observed = V_r.
    let (g, k, n, l, t) = (2e-6, 1.0, 10u32, 100e-6, 5e-6);
    let plates = PlateArray {
        plate_count: n,
        overlap_length_m: l,
        thickness_m: t,
        front_gap_m: g,
        back: None,
        fringing: Fringing::Off,
        relative_permittivity: 1.0,
        comb: None,
    };
    let xc = 0.4 * g;
    let m = GapClosingActuator::new(plates, Suspension::linear(k), Some(xc), None).unwrap();
    let sh = Shuttle {
        mass_kg: 1e-10,
        mass_breakdown: MassBreakdown { fingers_kg: 1e-10, spine_kg: 0.0, extra_kg: 0.0, beams_effective_kg: 0.0 },
        planform_area_m2: 1e-9,
        viscosity_pa_s: 1e-30,
        mean_free_path_m: 0.0,
        couette_n_s_per_m: 0.0,
    };
    let nea = f64::from(n) * VACUUM_PERMITTIVITY * l * t;
    let reach = (k * xc * g * (g - xc) / nea).sqrt();
    let release = (2.0 * k * xc * (g - xc).powi(2) / nea).sqrt();
    let step = step_pull_in(&m, &sh).unwrap();
    println!(
        "stop 0.4 g: reach {:.5} (closed form {reach:.5}), release {:.5}, observed {:.5}",
        step.reach_voltage_v, step.release_voltage_v, step.voltage_v
    );
    assert!((step.reach_voltage_v / reach - 1.0).abs() < 2e-4);
    assert!((step.release_voltage_v / release - 1.0).abs() < 1e-9);
    assert_eq!(step.voltage_v, step.release_voltage_v);
    assert!(step.voltage_v < step.quasi_static_voltage_v);
}

#[test]
fn step_pull_in_does_not_depend_on_the_fitted_stop_standoff() {
    // The GCA's dynamic barrier (~2.8 um) lies before the stop (4.49 or 4.63 um): the fitted
    // standoff stays a release-only parameter. 1e-5: bisection tolerance 1e-6 plus the
    // step-size change with the horizon.
    let mut s = at_length(&gca_spec(), 38.25e-6);
    s.finger_bending = None;
    let with = step_pull_in(&s.to_model().unwrap(), &Shuttle::from_spec(&s).unwrap()).unwrap();
    s.stop.as_mut().unwrap().contact_standoff = 0.0;
    let without = step_pull_in(&s.to_model().unwrap(), &Shuttle::from_spec(&s).unwrap()).unwrap();
    assert!((with.voltage_v / without.voltage_v - 1.0).abs() < 1e-5, "{} {}", with.voltage_v, without.voltage_v);
}

fn step_report(spec: &ArraySpec) -> ValidationReport {
    let mut s = spec.clone();
    s.pull_in_protocol = PullInProtocol::Step;
    rigid_report(&s)
}

fn rigid_report(spec: &ArraySpec) -> ValidationReport {
    let mut s = spec.clone();
    // Rigid fingers: the bending switch changes pull-in by < 0.01 % here (docs) and costs 10x.
    if let Some(b) = s.finger_bending.as_mut() {
        b.enabled = false;
    }
    validate(&s, &data()).unwrap()
}

fn signed(r: &ValidationReport) -> f64 {
    r.points.iter().map(|p| p.pull_in_rel_error).sum::<f64>() / r.points.len() as f64
}

#[test]
fn step_protocol_on_the_gca_with_sensitivity() {
    let spec = gca_spec();
    let d = data();
    let mut ramp = spec.clone();
    ramp.pull_in_protocol = PullInProtocol::QuasiStatic;
    let with_bending = validate(&ramp, &d).unwrap();
    let quasi = rigid_report(&ramp);
    // Bending off changes the quasi-static pull-in by < 1e-4 relative (docs: 8.98 % either way).
    for (a, b) in with_bending.points.iter().zip(&quasi.points) {
        assert!((a.pull_in_v_model / b.pull_in_v_model - 1.0).abs() < 1e-4);
    }
    let step = step_report(&spec);
    println!("  L (um)   m (ng)  zeta(0) sigma(0)  V_qs    V_step  step/qs  meas   err_qs  err_step");
    for (p, q) in step.points.iter().zip(&quasi.points) {
        let mut s = at_length(&spec, p.finger_length_m);
        s.finger_bending = None;
        let m = s.to_model().unwrap();
        let st = step_pull_in(&m, &Shuttle::from_spec(&s).unwrap()).unwrap();
        println!(
            "  {:6.2} {:7.3} {:7.4} {:8.1e} {:7.2} {:7.2} {:7.4} {:6.2} {:+7.2}% {:+7.2}%",
            p.finger_length_m * 1e6,
            st.mass_kg * 1e12,
            st.damping_ratio_at_rest,
            st.squeeze_number_at_rest,
            q.pull_in_v_model,
            p.pull_in_v_model,
            p.pull_in_v_model / q.pull_in_v_model,
            p.pull_in_v_measured,
            100.0 * q.pull_in_rel_error,
            100.0 * p.pull_in_rel_error
        );
        // A step never needs more than the quasi-static voltage, and stays above the undamped
        // bound sqrt(27/32) ~ 0.919 of it (parallel plate; Palmer + back gap move it a little).
        assert!(p.pull_in_v_model < q.pull_in_v_model && p.pull_in_v_model > 0.90 * q.pull_in_v_model);
        assert!(st.squeeze_number_at_rest < 0.1, "incompressible film");
        assert_eq!(p.release_v_model, q.release_v_model);
    }
    println!(
        "quasi-static: pull-in {:.2} % ({:+.2}); step: {:.2} % ({:+.2}); release {:.2} % both",
        100.0 * quasi.pull_in_mean_abs_rel_error,
        100.0 * signed(&quasi),
        100.0 * step.pull_in_mean_abs_rel_error,
        100.0 * signed(&step),
        100.0 * step.release_mean_abs_rel_error
    );
    assert!(step.pull_in_mean_abs_rel_error < quasi.pull_in_mean_abs_rel_error);
    assert_eq!(step.release_mean_abs_rel_error, quasi.release_mean_abs_rel_error);

    // Sensitivity (inputs changed one at a time, nothing fitted).
    let variant = |name: &str, f: &dyn Fn(&mut ShuttleSpec)| {
        let mut s = spec.clone();
        f(s.shuttle.as_mut().unwrap());
        let r = step_report(&s);
        let m76 = Shuttle::from_spec(&s).unwrap().mass_kg;
        println!(
            "  {name:42} m(76.5) {:6.3} ng  pull-in {:.2} % ({:+.2})",
            m76 * 1e12,
            100.0 * r.pull_in_mean_abs_rel_error,
            100.0 * signed(&r)
        );
        r.pull_in_mean_abs_rel_error
    };
    let base = variant("scenario (spine 20 um, 61 holes)", &|_| {});
    let narrow = variant("spine 10 um wide, no holes", &|s| {
        s.spine_width = 10e-6;
        s.spine_hole_count = 0;
    });
    let wide = variant("spine 40 um wide, no holes", &|s| {
        s.spine_width = 40e-6;
        s.spine_hole_count = 0;
    });
    let half_c = variant("damping x 0.5 (viscosity x 0.5)", &|s| s.viscosity *= 0.5);
    let double_c = variant("damping x 2 (viscosity x 2)", &|s| s.viscosity *= 2.0);
    let continuum = variant("continuum (no rarefaction, no slip)", &|s| s.mean_free_path = 0.0);
    let no_couette = variant("no Couette under the shuttle", &|s| s.substrate_gap = None);
    let undamped = variant("nearly undamped (viscosity x 1e-6)", &|s| s.viscosity *= 1e-6);
    for v in [narrow, wide, half_c, double_c, continuum, no_couette, undamped] {
        assert!(v.is_finite() && v < quasi.pull_in_mean_abs_rel_error);
    }
    assert!(base < 0.06);
}
