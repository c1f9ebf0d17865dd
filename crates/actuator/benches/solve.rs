//! Criterion benchmarks of the pull-in and release solves (issue 4/6).
//! Run: `cargo bench -p stiction-actuator --bench solve`.

#![allow(missing_docs)] // criterion_group! generates an undocumented function

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use stiction_actuator::*;

fn gca() -> ArraySpec {
    let text = include_str!("../../../scenarios/gca-rauf2022.json");
    let v: serde_json::Value = serde_json::from_str(text).expect("scenario parses");
    serde_json::from_value(v["actuators"]["gca"].clone()).expect("spec parses")
}

fn benches(c: &mut Criterion) {
    let spec = gca();
    let mut rigid = spec.clone();
    if let Some(b) = rigid.finger_bending.as_mut() {
        b.enabled = false;
    }
    let model_rigid = rigid.to_model().expect("model");
    let model_bent = spec.to_model().expect("model");
    c.bench_function("pull_in rigid palmer+back", |b| b.iter(|| black_box(&model_rigid).pull_in()));
    c.bench_function("release rigid palmer+back", |b| b.iter(|| black_box(&model_rigid).release_voltage_v()));
    c.bench_function("pull_in with finger bending", |b| b.iter(|| black_box(&model_bent).pull_in()));
    c.bench_function("release with finger bending", |b| b.iter(|| black_box(&model_bent).release_voltage_v()));
    c.bench_function("sweep 200 steps rigid", |b| b.iter(|| black_box(&model_rigid).sweep(40.0, 200)));
    let data = parse_measurements(include_str!("../../../data/gca-pullin-release/measured.csv"), "measured.csv")
        .expect("data");
    c.bench_function("validate gca (9 lengths, bending)", |b| b.iter(|| validate(black_box(&spec), &data)));
}

criterion_group!(solve, benches);
criterion_main!(solve);
