//! Criterion benchmarks of the slip dynamics (rapier, one rigid body + a stop collider).
//! Run: `cargo bench -p stiction-actuator --bench dynamics`.

#![allow(missing_docs)] // criterion_group! generates an undocumented function

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use stiction_actuator::dynamics::{POLYSILICON_DENSITY_KG_PER_M3, shuttle_mass_kg};
use stiction_actuator::*;

/// The paper's pull array (15 plates, 100 um x 5 um, gap 2.96 um, k = 1 N/m), stop at 0.8 g.
fn pull(fringing: Fringing) -> GapClosingActuator {
    let plates = PlateArray {
        plate_count: 15,
        overlap_length_m: 100e-6,
        thickness_m: 5e-6,
        front_gap_m: 2.96e-6,
        back: None,
        fringing,
        relative_permittivity: 1.0,
        comb: None,
    };
    GapClosingActuator::new(plates, Suspension::linear(1.0), Some(0.8 * 2.96e-6), None).expect("model")
}

fn benches(c: &mut Criterion) {
    let m = shuttle_mass_kg(4.5e-14, 1e-15, POLYSILICON_DENSITY_KG_PER_M3).expect("mass");
    let act = pull(Fringing::Palmer);
    let v_pi = act.pull_in().expect("pull-in").voltage_v;
    let d = SlipDynamics::with_defaults(&act, m, 1.3e-7, 0.05e-6).expect("dynamics");
    // Runaway at 1.2 V_pi: about 1100 steps to the stop.
    c.bench_function("simulate_slip runaway 1.2 V_pi (Palmer)", |b| {
        b.iter(|| simulate_slip(black_box(&act), 1.2 * v_pi, &d))
    });
    // Below pull-in without friction: the full 20 periods (40 000 steps) of a damped oscillation.
    let no_friction = SlipDynamics { kinetic_friction_n: 0.0, ..d };
    c.bench_function("simulate_slip 0.8 V_pi, 40k steps (Palmer)", |b| {
        b.iter(|| simulate_slip(black_box(&act), 0.8 * v_pi, &no_friction))
    });
    // With kinetic friction the same oscillation sticks again early.
    c.bench_function("simulate_slip 0.8 V_pi, sticks again (Palmer)", |b| {
        b.iter(|| simulate_slip(black_box(&act), 0.8 * v_pi, &d))
    });
    let undamped = SlipDynamics { damping_n_s_per_m: 0.0, kinetic_friction_n: 0.0, ..d };
    let pp = pull(Fringing::Off);
    let mut group = c.benchmark_group("pull-in thresholds");
    group.sample_size(10);
    group.bench_function("dynamic_pull_in_voltage undamped (bisection, 1e-6)", |b| {
        b.iter(|| dynamic_pull_in_voltage(black_box(&pp), &undamped))
    });
    group.bench_function("dynamic_pull_in_voltage zeta=0.1 (Palmer)", |b| {
        b.iter(|| dynamic_pull_in_voltage(black_box(&act), &d))
    });
    group.bench_function("undamped_dynamic_pull_in_voltage_v (energy)", |b| {
        b.iter(|| undamped_dynamic_pull_in_voltage_v(black_box(&pp), 0.0, 1e-8))
    });
    group.finish();
}

criterion_group!(dynamics, benches);
criterion_main!(dynamics);
