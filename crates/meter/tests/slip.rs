//! The light slip path (energy criterion + RK4) against the rapier rigid-body trajectory of
//! `stiction_actuator::simulate_slip` and against the closed-form undamped dynamic pull-in
//! voltage (energy balance, `stiction_actuator::undamped_dynamic_pull_in_voltage_v`), on the pull
//! array of the paper's scenario (scenarios/tas2000.json: 15 plates, k = 1 N/m, stop at 2 um,
//! m = 107 ng, c = 2.1e-7 N s/m).

use std::path::Path;

use stiction_actuator::{
    GapClosingActuator, SlipDynamics, dynamic_pull_in_voltage, simulate_slip, undamped_dynamic_pull_in_voltage_v,
};
use stiction_meter::slip::{SlipPath, light_trajectory, slip_outcome};
use stiction_meter::{Meter, MeterResult};
use stiction_scenario::Scenario;

/// Shuttle mass of scenarios/tas2000.json: 107 ng = 1.07e-10 kg.
const MASS_KG: f64 = 107e-9 * 1e-3;
/// Damping of scenarios/tas2000.json, N s/m: with k = 1 N/m and m = 107 ng the damping ratio
/// c / (2 sqrt(k m)) is 0.0102 (nearly undamped).
const DAMPING: f64 = 2.1e-7;

fn scenario_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json")
}

fn pull() -> GapClosingActuator {
    let s = Scenario::load(&scenario_path(), &[]).expect("tas2000.json");
    s.actuators["pull"].to_model().expect("pull array")
}

/// Linear interpolation of a trajectory `(t, x, v)` at time t: `(x, v)` (also used with `(x, v, _)`).
fn at(traj: &[(f64, f64, f64)], t: f64) -> (f64, f64) {
    let i = traj.partition_point(|s| s.0 < t).clamp(1, traj.len() - 1);
    let (a, b) = (traj[i - 1], traj[i]);
    let w = if b.0 > a.0 { ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0) } else { 1.0 };
    (a.1 + w * (b.1 - a.1), a.2 + w * (b.2 - a.2))
}

/// Same outcome, same time to the stop and impact speed, and the same state along the way.
/// Damping ratios c / (2 sqrt(k m)) covered: 0, 0.010 (the scenario's, nearly undamped) and 0.041.
/// Tolerances: rapier's step is T/2000 (T = 2 pi sqrt(m/k) = 65 us, so 32 ns) with a first-order
/// (symplectic Euler) update; near the stop rapier's state is off by up to ~1e-3 of the travel,
/// while the light path's RK4 (fourth order) is accurate to ~1e-6. Rapier's implicit damping adds a
/// first-order error of about dt c/m (2.6e-4 for the heaviest damping below). State (further than 5 % from the
/// threshold): x(t) up to 80 % of the time to the stop within (5e-3 + 2 dt c/m) x_c, v(x) within
/// (2e-2 + 2 dt c/m) of the largest speed; time to the stop
/// 0.5 %, impact speed 1 %.
#[test]
fn light_path_follows_the_rapier_trajectory() {
    let pull = pull();
    let xc = pull.stop_travel_m.expect("the pull array has a stop");
    let v_pi = pull.pull_in().unwrap().voltage_v;
    let mut runaways = 0;
    let mut settles = 0;
    for &(damping, kinetic) in &[(0.0, 0.0), (DAMPING, 0.0), (DAMPING, 2e-6), (4.0 * DAMPING, 1e-6)] {
        let d = SlipDynamics::with_defaults(&pull, MASS_KG, damping, kinetic).unwrap();
        let threshold = dynamic_pull_in_voltage(&pull, &d).unwrap();
        for factor in [0.6, 0.9, 0.97, 1.03, 1.2, 1.6, 2.5] {
            let v = factor * threshold;
            let rigid = simulate_slip(&pull, v, &d).unwrap();
            let (light, traj) = light_trajectory(&pull, v, &d).unwrap();
            let what =
                format!("c = {damping:e}, F_k = {kinetic:e}, V = {v:.3} V ({factor} x threshold, V_pi {v_pi:.2})");
            assert_eq!(light.runs_away, rigid.runs_away, "{what}");
            if rigid.runs_away {
                runaways += 1;
                let (tl, tr) = (light.time_to_stop_s.unwrap(), rigid.time_to_stop_s.unwrap());
                assert!((tl - tr).abs() <= 5e-3 * tr, "{what}: time to stop {tl:e} vs rapier {tr:e}");
                let (vl, vr) = (light.impact_velocity_m_per_s.unwrap(), rigid.impact_velocity_m_per_s.unwrap());
                assert!((vl - vr).abs() <= 1e-2 * vr, "{what}: impact speed {vl:e} vs rapier {vr:e}");
                let vmax = rigid.samples.iter().fold(0.0f64, |m, s| m.max(s.2.abs()));
                // Within 5 % of the threshold the slow passage past the saddle turns rapier's step error
                // into a time shift; there only the outcome and the time to the stop are compared.
                let near = (factor - 1.0f64).abs() < 0.05;
                // Rapier's implicit damping v <- v / (1 + dt c/m) is first order: relative error ~ dt c/m.
                let damp_err = 2.0 * d.time_step_s * damping / MASS_KG;
                for &(t, x, vel) in rigid.samples.iter().filter(|s| !near && s.0 <= 0.8 * tl.min(tr)) {
                    let (xl, _) = at(&traj, t);
                    assert!((xl - x).abs() <= (5e-3 + damp_err) * xc, "{what}: x({t:e}) = {xl:e} vs rapier {x:e}");
                    // v against x (phase plane): free of the small time shift near the stop.
                    let by_x: Vec<(f64, f64, f64)> = traj.iter().map(|s| (s.1, s.2, 0.0)).collect();
                    let (vl, _) = at(&by_x, x);
                    assert!(
                        (vl - vel).abs() <= (2e-2 + damp_err) * vmax,
                        "{what}: v(x = {x:e}) = {vl:e} vs rapier {vel:e}"
                    );
                }
            } else {
                settles += 1;
                assert!(light.time_to_stop_s.is_none() && light.impact_velocity_m_per_s.is_none(), "{what}");
            }
        }
    }
    assert!(runaways >= 12 && settles >= 12, "both outcomes covered: {runaways} runaways, {settles} settles");
}

/// Undamped, frictionless: the energy criterion is exact, so the light path must switch from
/// "stays" to "runs away" at the closed-form threshold V_dyn^2 = max_x k x^2 / (C(x) - C(0))
/// (relative 1e-4 on both sides).
#[test]
fn energy_criterion_switches_at_the_closed_form_threshold() {
    let pull = pull();
    let d = SlipDynamics::with_defaults(&pull, MASS_KG, 0.0, 0.0).unwrap();
    let v_dyn = undamped_dynamic_pull_in_voltage_v(&pull, 0.0, d.contact_gap_m).unwrap();
    let below = slip_outcome(SlipPath::Light, &pull, v_dyn * (1.0 - 1e-4), MASS_KG, 0.0, 0.0).unwrap();
    let above = slip_outcome(SlipPath::Light, &pull, v_dyn * (1.0 + 1e-4), MASS_KG, 0.0, 0.0).unwrap();
    assert!(!below.runs_away && above.runs_away, "V_dyn = {v_dyn} V: below {below:?}, above {above:?}");
}

fn run(path: SlipPath, seed: u64) -> MeterResult {
    let sets = vec![format!("surface.seed={seed}")];
    let s = Scenario::load(&scenario_path(), &sets).unwrap();
    let mut m = Meter::from_scenario(&s, Path::new(".")).unwrap();
    m.set_slip_path(path);
    m.run(&mut |_, _| {}).unwrap()
}

/// The whole experiment of the paper's scenario with either path: the same slips, the same
/// mu_e,a and F_a0 (the slip path does not enter them), the same runaway decisions, times to the
/// stop within 0.5 %.
#[test]
fn the_meter_reports_the_same_slips_with_either_path() {
    for seed in [2000, 7] {
        let (a, b) = (run(SlipPath::RigidBody, seed), run(SlipPath::Light, seed));
        assert_eq!(a.mu_apparent, b.mu_apparent);
        assert_eq!(a.apparent_adhesion_force_n, b.apparent_adhesion_force_n);
        let mut slips = 0;
        for (p, q) in a.points.iter().zip(&b.points) {
            assert_eq!(p.v_pull, q.v_pull);
            assert_eq!(p.pull_in_at_slip, q.pull_in_at_slip, "V_clamp {}", p.v_clamp);
            match (p.slip_time_to_stop_s, q.slip_time_to_stop_s) {
                (Some(x), Some(y)) => {
                    slips += 1;
                    assert!((x - y).abs() <= 5e-3 * x, "V_clamp {}: {x:e} vs {y:e}", p.v_clamp)
                }
                (None, None) => {}
                other => panic!("V_clamp {}: {other:?}", p.v_clamp),
            }
        }
        assert!(slips > 5, "seed {seed}: {slips} slips");
    }
}
