//! Time per simulated transient point (issue 13 floor: at most 10 ms per point) on the Rauf et al.
//! GCA of `scenarios/gca-rauf2022.json`: the slowest measured pull-in (76.5 um, 20 V, ~90 us), a
//! fast one (80 V), a release (76.5 um, 60 us), and the whole measured file (199 points).
//! `cargo bench -p stiction-actuator --bench transients`.

#![allow(missing_docs)] // criterion_group! generates an undocumented function

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_actuator::{
    ArraySpec, TransientEvent, TransientModel, TransientPhysics, compare_transients, parse_transients,
};

fn gca(length_m: f64) -> ArraySpec {
    let text = include_str!("../../../scenarios/gca-rauf2022.json");
    let v: serde_json::Value = serde_json::from_str(text).expect("scenario parses");
    let mut s: ArraySpec = serde_json::from_value(v["actuators"]["gca"].clone()).expect("spec parses");
    s.overlap_length = length_m;
    s
}

fn transient_benches(c: &mut Criterion) {
    let model = TransientModel::from_spec(&gca(76.5e-6), TransientPhysics::default()).expect("model");
    c.bench_function("transient pull-in 76.5 um, 20 V (slowest measured, ~90 us)", |b| {
        b.iter(|| model.time_s(TransientEvent::PullIn, std::hint::black_box(20.0), 0.0).expect("runs"))
    });
    c.bench_function("transient pull-in 76.5 um, 80 V (~13 us)", |b| {
        b.iter(|| model.time_s(TransientEvent::PullIn, std::hint::black_box(80.0), 0.0).expect("runs"))
    });
    c.bench_function("transient release 76.5 um from 40 V (~57 us)", |b| {
        b.iter(|| model.time_s(TransientEvent::Release, std::hint::black_box(40.0), 0.0).expect("runs"))
    });
    let data =
        parse_transients(include_bytes!("../../../data/gca-transients/measured_times.csv"), "measured_times.csv")
            .expect("data parses");
    let spec = gca(76.5e-6);
    let mut group = c.benchmark_group("transients");
    group.sample_size(10);
    group.bench_function("all 199 measured points (models built per length)", |b| {
        b.iter(|| compare_transients(&spec, TransientPhysics::default(), &data).expect("runs"))
    });
    group.finish();
}

criterion_group!(benches, transient_benches);
criterion_main!(benches);
