//! Study throughput on the paper's scenario as shipped (scenarios/tas2000.json, slip dynamics on):
//! one virtual experiment (draw, parse, assemble, 13 clamp voltages with slip detection and the
//! slip dynamics, eq. 10 fit) with the light and the rigid-body slip path, and 400 experiments
//! through the streamed log on 1 and 2 threads; then the study rate as the command line runs it,
//! every experiment with the lab's eq. 10 intervals (`stiction_fit::with_lab_intervals`, 2000
//! calibration draws each), in experiments per second on 2 threads: a single study of 400
//! experiments and a 2 x 2 design study (clamp plates 30, 60 x pull spring 1, 3 N/m) of 100
//! experiments per design.
//!
//! `cargo bench -p stiction-study --bench study`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use stiction_meter::SlipPath;
use stiction_study::log::LogWriter;
use stiction_study::{Calibration, Study, StudyConfig};

fn study(samples: usize, slip_path: SlipPath) -> Study {
    study_with(samples, slip_path, &[])
}

fn study_with(samples: usize, slip_path: SlipPath, sets: &[String]) -> Study {
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
    Study::prepare(&path, sets, &config).expect("tas2000.json")
}

/// Runs `studies` one after the other (as a design study does) on `pool`, each into a fresh log.
fn run_all(studies: &[Study], pool: &rayon::ThreadPool, dir: &Path) {
    for s in studies {
        let _ = std::fs::remove_dir_all(dir);
        std::fs::create_dir_all(dir).unwrap();
        let mut log = LogWriter::create(dir, &s.header()).unwrap();
        pool.install(|| s.run_into(&mut log, 0, &|_| {})).unwrap();
    }
}

/// The study rate with the lab's intervals in every experiment, on 2 threads.
fn bench_rate(c: &mut Criterion) {
    let mut g = c.benchmark_group("study rate");
    g.sample_size(10);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let dir = std::env::temp_dir().join(format!("stiction-bench-rate-{}", std::process::id()));
    let lab = |s: Study| stiction_fit::with_lab_intervals(s).expect("intervals");
    let one = lab(study(1_000_000, SlipPath::Light));
    let i = AtomicUsize::new(0);
    g.throughput(Throughput::Elements(1));
    g.bench_function("tas2000 one experiment with the lab's intervals", |b| {
        b.iter(|| one.run_sample(i.fetch_add(1, Ordering::Relaxed) % 1000))
    });
    let single = [lab(study(400, SlipPath::Light))];
    g.throughput(Throughput::Elements(400));
    g.bench_function("tas2000 single study, 400 experiments with intervals, 2 threads", |b| {
        b.iter(|| run_all(&single, &pool, &dir))
    });
    let designs: Vec<Study> = [("30", "1 N/m"), ("30", "3 N/m"), ("60", "1 N/m"), ("60", "3 N/m")]
        .iter()
        .map(|(p, k)| {
            let sets = [format!("actuators.clamp.plate_count={p}"), format!("actuators.pull.spring.stiffness={k}")];
            lab(study_with(100, SlipPath::Light, &sets))
        })
        .collect();
    g.bench_function("tas2000 2x2 design study, 4 x 100 experiments with intervals, 2 threads", |b| {
        b.iter(|| run_all(&designs, &pool, &dir))
    });
    let _ = std::fs::remove_dir_all(&dir);
    g.finish();
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

criterion_group!(benches, bench, bench_rate);
criterion_main!(benches);
