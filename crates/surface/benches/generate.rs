//! Criterion benchmarks of summit generation and `.npy` summit input (docs/performance.md).
//!
//! `cargo bench -p stiction-surface --bench generate` (`-- generate` for the generators only;
//! `RAYON_NUM_THREADS=1` for generator 2 on one core).

use criterion::{Criterion, criterion_main};
use stiction_surface::{
    FaceParams, Layout, Placement, generate, generate_v2, npy_surface, read_npy_summits, read_npy_summits_file,
};

/// The surface of benches/numpy-1e6.json: 1 mm x 0.25 mm at Table 1's statistics (1 001 098 summits).
fn layout_1e6() -> Layout {
    Layout { apparent_length_m: 1e-3, apparent_width_m: 0.25e-3, placement: Placement::Poisson, seed: 2000 }
}

fn bench_generate(c: &mut Criterion) {
    let mut g = c.benchmark_group("surface");
    g.sample_size(20);
    let face = FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6);
    g.bench_function("generate_1e6", |b| b.iter(|| generate(&layout_1e6(), &face).unwrap()));
    g.bench_function("generate_v2_1e6", |b| b.iter(|| generate_v2(&layout_1e6(), &face).unwrap()));
    g.finish();
    // About 1e7 summits (3.16 mm x 0.79 mm): fewer samples, each run takes 0.2-0.5 s.
    let mut g = c.benchmark_group("surface");
    g.sample_size(10);
    let layout_1e7 =
        Layout { apparent_length_m: 3.162e-3, apparent_width_m: 0.7906e-3, placement: Placement::Poisson, seed: 2000 };
    g.bench_function("generate_1e7", |b| b.iter(|| generate(&layout_1e7, &face).unwrap()));
    g.bench_function("generate_v2_1e7", |b| b.iter(|| generate_v2(&layout_1e7, &face).unwrap()));
    g.finish();
}

fn bench_npy(c: &mut Criterion) {
    let mut g = c.benchmark_group("surface");
    g.sample_size(20);
    let face = FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6);
    let s = generate(&layout_1e6(), &face).unwrap();
    let bytes = s.to_npy_bytes();
    let build = |summits| npy_surface(summits, "bench", 1e-3, 0.25e-3, None, |_| unreachable!()).unwrap();
    g.bench_function("npy_parse_1e6_in_memory", |b| b.iter(|| build(read_npy_summits(&bytes, "bench").unwrap())));
    let path = std::env::temp_dir().join(format!("stiction-bench-{}.npy", std::process::id()));
    std::fs::write(&path, &bytes).unwrap();
    g.bench_function("npy_read_1e6_file", |b| b.iter(|| build(read_npy_summits_file(&path, 1 << 30).unwrap())));
    let _ = std::fs::remove_file(&path);
    g.finish();
}

// criterion_group! expands to an undocumented function.
#[allow(missing_docs)]
mod group {
    criterion::criterion_group!(benches, super::bench_generate, super::bench_npy);
}
criterion_main!(group::benches);
