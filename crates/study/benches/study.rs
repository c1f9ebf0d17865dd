//! Study throughput on the paper's scenario as shipped (scenarios/tas2000.json, slip dynamics on):
//! one virtual experiment (draw, parse, assemble, 13 clamp voltages with slip detection and the
//! slip dynamics, eq. 10 fit) with the light and the rigid-body slip path, and 400 experiments
//! through the streamed log on 1 and 2 threads.
//!
//! `cargo bench -p stiction-study --bench study`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_meter::SlipPath;
use stiction_study::log::LogWriter;
use stiction_study::{Calibration, Study, StudyConfig};

fn study(samples: usize, slip_path: SlipPath) -> Study {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/tas2000.json");
    let config = StudyConfig {
        samples,
        seed: 1,
        vary_surface: true,
        shard_index: 0,
        shard_count: 1,
        calibration: Calibration::Nominal,
        slip_path,
    };
    Study::prepare(&path, &[], &config).expect("tas2000.json")
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("study");
    for (name, path) in [("light", SlipPath::Light), ("rigid-body", SlipPath::RigidBody)] {
        let s = study(1_000_000, path);
        let i = AtomicUsize::new(0);
        g.bench_function(format!("tas2000 one experiment, {name} slip path"), |b| {
            b.iter(|| s.run_sample(i.fetch_add(1, Ordering::Relaxed) % 1000))
        });
    }
    g.sample_size(10);
    let s = study(400, SlipPath::Light);
    let dir = std::env::temp_dir().join(format!("stiction-bench-{}", std::process::id()));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        g.bench_function(format!("tas2000 400 experiments streamed to the log, {threads} thread(s)"), |b| {
            b.iter(|| {
                let _ = std::fs::remove_dir_all(&dir);
                std::fs::create_dir_all(&dir).unwrap();
                let mut log = LogWriter::create(&dir, &s.header()).unwrap();
                pool.install(|| s.run_into(&mut log, 0, &|_| {})).unwrap();
            })
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
