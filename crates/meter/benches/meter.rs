//! The friction meter on the paper's scenario: one whole experiment (13 clamp voltages), with the
//! explicit solver and with the discrete model, assembly included.
//!
//! `cargo bench -p stiction-meter --bench meter`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_meter::Meter;
use stiction_scenario::Scenario;

fn scenario(sets: &[&str]) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&path, &sets).expect("tas2000.json")
}

fn bench(c: &mut Criterion) {
    let explicit = scenario(&[]);
    c.bench_function("meter/tas2000 explicit, assemble + 13 clamp voltages", |b| {
        b.iter(|| Meter::from_scenario(&explicit, Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap())
    });
    let discrete = scenario(&["contact.model=\"discrete\"", "contact.contacts=3"]);
    c.bench_function("meter/tas2000 discrete N=3, assemble + 13 clamp voltages", |b| {
        b.iter(|| Meter::from_scenario(&discrete, Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap())
    });
    // Capillarity (environment.relative_humidity = 0.35) against dry, same scenario otherwise;
    // slip dynamics off so that the contact model's share is visible.
    let wet = "environment.relative_humidity=0.35";
    let nodyn = "meter.slip_dynamics=null";
    for (name, sets) in [
        ("explicit dry", vec![nodyn]),
        ("explicit 35 % RH", vec![nodyn, wet]),
        ("gw dry", vec![nodyn, "contact.model=\"gw\""]),
        ("gw 35 % RH", vec![nodyn, "contact.model=\"gw\"", wet]),
        ("discrete N=3 dry", vec![nodyn, "contact.model=\"discrete\"", "contact.contacts=3"]),
        ("discrete N=3 35 % RH", vec![nodyn, "contact.model=\"discrete\"", "contact.contacts=3", wet]),
    ] {
        let s = scenario(&sets);
        c.bench_function(&format!("meter/capillarity/{name}, assemble + 13 clamp voltages"), |b| {
            b.iter(|| Meter::from_scenario(&s, Path::new(".")).unwrap().run(&mut |_, _| {}).unwrap())
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
