//! The meter's protocol against closed forms: the clamp load, the discrete model's friction
//! (eq. 12), the pull ramp's slip voltage, the slip criteria and the lab's reduction (section 5).

use std::f64::consts::PI;
use std::path::Path;

use stiction_meter::{Meter, Reduction};
use stiction_scenario::Scenario;

const S: f64 = 1.4e9; // shear strength, Pa
const D: f64 = 9.1e-12; // compliance, 1/Pa
const R: f64 = 0.5e-6; // summit radius, m
const DG: f64 = 0.1; // work of adhesion, J/m^2
const A_CLAMP: f64 = 1.4e-8;
const A_PULL: f64 = 3.8e-9;
const F_SPRING: f64 = 7e-6;

fn scenario(slip: &str) -> Scenario {
    let json = format!(
        r#"{{
        "format_version": 1,
        "surface": {{"apparent_length": "20 um", "apparent_width": "5 um", "summit_density": "4e12 m^-2", "summit_sd": "40 nm", "summit_radius": "0.5 um", "seed": 3}},
        "material": {{"compliance": "9.1e-12 1/Pa", "work_of_adhesion": "0.1 J/m^2", "shear_strength": "1.4 GPa", "hardness": "9 GPa"}},
        "contact": {{"model": "discrete", "contacts": 3}},
        "actuators": {{
            "clamp": {{"plate_count": 30, "overlap_length": "100 um", "thickness": "5 um", "conversion_factor": "1.4e-8 N/V^2", "operating_travel": "0.9 um", "fringing": "off", "spring": {{"stiffness": "7.8 N/m"}}}},
            "pull": {{"plate_count": 15, "overlap_length": "100 um", "thickness": "5 um", "conversion_factor": "3.8e-9 N/V^2", "fringing": "off", "spring": {{"stiffness": "1 N/m"}}}}
        }},
        "meter": {{"spring_force": "7 uN", "contact_travel": "0.9 um", "clamp_voltages": ["20 V", "23 V", "25 V", "27 V", "29 V"], "pull_voltage_step": "0.05 V", "slip": {slip}}}
    }}"#
    );
    Scenario::from_str_with_sets(&json, Path::new("meter-test.json"), &[]).expect("test scenario")
}

/// Eq. 12 with DMT: each of 3 summits carries L/3, a^3 = R D (L/3 + 2 pi dgamma R), A_r = 3 pi a^2.
fn real_area(load: f64) -> f64 {
    let a = (R * D * (load / 3.0 + 2.0 * PI * DG * R)).cbrt();
    3.0 * PI * a * a
}

fn run(slip: &str) -> stiction_meter::MeterResult {
    let s = scenario(slip);
    Meter::from_scenario(&s, Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap()
}

#[test]
fn clamp_load_friction_and_slip_voltage_follow_the_closed_forms() {
    let r = run(r#"{"kind": "shear-area"}"#);
    assert_eq!(r.points.len(), 5);
    // 20 V: a_clamp V^2 = 5.6 uN < F_spring: no contact, no slip.
    assert!(!r.points[0].in_contact && r.points[0].v_pull.is_none());
    for p in &r.points[1..] {
        let load = A_CLAMP * p.v_clamp * p.v_clamp - F_SPRING;
        // The conversion factor is defined at the contact travel, so F_elec = a V^2 to rounding.
        assert!((p.true_load_n - load).abs() < 1e-12 * A_CLAMP * p.v_clamp * p.v_clamp, "{} vs {load}", p.true_load_n);
        let capacity = S * real_area(load);
        assert!(
            (p.friction_capacity_n / capacity - 1.0).abs() < 1e-9,
            "capacity {} vs {capacity}",
            p.friction_capacity_n
        );
        // The ramp stops at the first 0.05 V step whose force reaches the capacity.
        let v = p.v_pull.unwrap();
        assert!(A_PULL * v * v >= capacity * (1.0 - 1e-12));
        assert!(A_PULL * (v - 0.05) * (v - 0.05) < capacity);
        assert!((v / 0.05 - (v / 0.05).round()).abs() < 1e-9, "V_pull {v} is not on the 0.05 V grid");
        // Adhesive load of 3 DMT contacts: 3 x 2 pi dgamma R (eq. 4).
        assert!((p.adhesive_load_n - 3.0 * 2.0 * PI * DG * R).abs() < 1e-12);
        assert_eq!(p.pull_in_at_slip, Some(true));
    }
}

#[test]
fn the_eq_10_fit_is_the_least_squares_line_of_the_reported_points() {
    let r = run(r#"{"kind": "shear-area"}"#);
    let pts: Vec<(f64, f64)> =
        r.points.iter().filter(|p| p.load_n > 0.0).map(|p| (p.load_n, p.friction_n.unwrap())).collect();
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let slope =
        pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>() / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
    let intercept = my - slope * mx;
    assert!((r.mu_apparent.unwrap() - slope).abs() < 1e-12);
    assert!((r.apparent_adhesion_force_n.unwrap() - intercept / slope).abs() < 1e-15);
    // Fig. 7 region: the discrete model's apparent mu over 1-4 uN is near the paper's 0.7 (+/- 0.15).
    assert!((slope - 0.7).abs() < 0.15, "{slope}");
}

#[test]
fn plastic_and_pressure_dependent_criteria() {
    let plastic = run(r#"{"kind": "plastic"}"#);
    let pressure = run(r#"{"kind": "pressure-dependent", "alpha": 0.1}"#);
    for (p, q) in plastic.points.iter().zip(&pressure.points).skip(1) {
        let load = p.true_load_n;
        let total = load + 3.0 * 2.0 * PI * DG * R;
        // Plastic limit mu_p = s / H on the total load (section 3.3).
        assert!((p.friction_capacity_n - S / 9e9 * total).abs() < 1e-9 * total);
        // s = s0 + alpha p summed over the contacts: s0 A_r + alpha (L + adhesive load).
        let want = S * real_area(load) + 0.1 * total;
        assert!((q.friction_capacity_n / want - 1.0).abs() < 1e-9);
    }
}

#[test]
fn the_lab_reduces_with_nominal_factors() {
    let s = scenario(r#"{"kind": "shear-area"}"#);
    let mut meter = Meter::from_scenario(&s, Path::new(".")).unwrap();
    let own = meter.device_reduction().unwrap();
    assert!((own.a_clamp_n_per_v2 / A_CLAMP - 1.0).abs() < 1e-12 && (own.a_pull_n_per_v2 / A_PULL - 1.0).abs() < 1e-12);
    // A lab that believes a_pull is twice what it is reports twice the friction; the physics is unchanged.
    meter.set_reduction(Reduction { a_pull_n_per_v2: 2.0 * A_PULL, ..own });
    let r = meter.run(&mut |_, _| {}).unwrap();
    for p in r.points.iter().filter(|p| p.v_pull.is_some()) {
        assert!((p.friction_n.unwrap() / p.true_friction_n.unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(p.load_n, p.true_load_n);
    }
}

#[test]
fn slip_dynamics_run_the_shuttle_to_its_stop() {
    // With a pull stop and shuttle dynamics, every slip far above the pull array's pull-in voltage
    // (about 10.7 V here, slips at 23-40 V) runs away to the stop; the energy bound
    // 1/2 m v^2 <= work of the electrostatic force over the stop travel caps the impact speed.
    let json =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json")).unwrap();
    let s = Scenario::from_str_with_sets(&json, Path::new("tas2000.json"), &[]).unwrap();
    let r = Meter::from_scenario(&s, Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap();
    let mass = 107e-12;
    for p in r.points.iter().filter(|p| p.v_pull.is_some()) {
        assert_eq!(p.pull_in_at_slip, Some(true));
        let t = p.slip_time_to_stop_s.expect("time to stop");
        let v = p.slip_impact_velocity_m_per_s.expect("impact speed");
        assert!(t > 0.0 && t < 1e-3, "{t}");
        // Upper bound on the work: the force at the stop (largest; parallel plates, gap 2.956 um as
        // inferred from a_pull in docs/actuators.md) times the stop travel (2 um).
        let f_max = p.true_friction_n.unwrap() / (1.0f64 - 2.0 / 2.956).powi(2);
        assert!(
            0.5 * mass * v * v <= f_max * 2e-6,
            "impact energy {} above the bound {}",
            0.5 * mass * v * v,
            f_max * 2e-6
        );
    }
}
