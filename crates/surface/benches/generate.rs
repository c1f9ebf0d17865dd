//! Criterion benchmarks of summit generation and `.npy` summit input (docs/performance.md).
//!
//! `cargo bench -p stiction-surface --bench generate`

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_surface::{FaceParams, Layout, Placement, generate};

/// The surface of benches/numpy-1e6.json: 1 mm x 0.25 mm at Table 1's statistics (1 001 098 summits).
fn layout_1e6() -> Layout {
    Layout { apparent_length_m: 1e-3, apparent_width_m: 0.25e-3, placement: Placement::Poisson, seed: 2000 }
}

fn bench_generate(c: &mut Criterion) {
    let mut g = c.benchmark_group("surface");
    g.sample_size(20);
    let face = FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6);
    g.bench_function("generate_1e6", |b| b.iter(|| generate(&layout_1e6(), &face).unwrap()));
    g.finish();
}

criterion_group!(benches, bench_generate);
criterion_main!(benches);
