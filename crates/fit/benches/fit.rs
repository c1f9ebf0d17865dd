//! Benchmarks of `stiction fit`: the discrete and GW fits, the explicit solver with a 100-surface
//! band, and reading 1e6 data rows. Numbers in docs/performance.md.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_fit::{FitOptions, ModelKind, analyse, parse_measured_voltages, synth};
use stiction_scenario::Scenario;

fn setup(name: &str) -> (Scenario, serde_json::Value, std::path::PathBuf, stiction_fit::Dataset) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios").join(name);
    let s = Scenario::load(&path, &[]).unwrap();
    let j = Scenario::load_json(&path, &[]).unwrap();
    let base = path.parent().unwrap().to_path_buf();
    let volts: Vec<f64> = (0..13).map(|k| 23.0 + 0.5 * k as f64).collect();
    let rows = synth::from_meter(&s, &base, &volts, 3, 0.3, 7).unwrap();
    let data = parse_measured_voltages(synth::to_csv(&rows, "bench").unwrap().as_bytes(), "bench.csv").unwrap();
    (s, j, base, data)
}

fn fits(c: &mut Criterion) {
    let (s, j, base, data) = setup("tas2000.json");
    let mut g = c.benchmark_group("fit");
    g.sample_size(10);
    for (label, models) in [
        ("discrete_n3", vec![ModelKind::Discrete(3)]),
        ("discrete_n1_n2_n3", vec![ModelKind::Discrete(1), ModelKind::Discrete(2), ModelKind::Discrete(3)]),
        ("gw_dmt", vec![ModelKind::Gw]),
        ("explicit", vec![ModelKind::Explicit]),
        ("explicit_ensemble_100", vec![ModelKind::ExplicitEnsemble]),
    ] {
        let opts = FitOptions { models, ..FitOptions::default() };
        g.bench_function(label, |b| b.iter(|| black_box(analyse(&data, &s, &j, &base, &opts).unwrap())));
    }
    let opts = FitOptions {
        models: vec![ModelKind::Discrete(3)],
        free: stiction_fit::Free::parse("s,R,F_spring", "--free").unwrap(),
        ..FitOptions::default()
    };
    g.bench_function("discrete_n3_free_s_r_fspring", |b| {
        b.iter(|| black_box(analyse(&data, &s, &j, &base, &opts).unwrap()))
    });
    g.finish();
}

fn read(c: &mut Criterion) {
    let mut text = String::from("# bench\nv_clamp_v,v_pull_v\n");
    for k in 0..1_000_000u32 {
        text.push_str(&format!("{},{}\n", 23.0 + (k % 13) as f64 * 0.5, 30.0 + (k % 97) as f64 * 0.01));
    }
    let dir = std::env::temp_dir().join(format!("stiction-fit-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("rows.csv");
    std::fs::write(&file, &text).unwrap();
    let mut g = c.benchmark_group("read");
    g.sample_size(10);
    g.bench_function("1e6_rows", |b| {
        b.iter(|| black_box(stiction_fit::read_measured_voltages(&file).unwrap().rows.len()))
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, fits, read);
criterion_main!(benches);
