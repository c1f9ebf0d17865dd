//! Criterion benchmarks of the height-map pipeline on a 4096 x 4096 map (one core, release):
//!
//! * `topography/read_level_summits_4096`: read a float64 `.npy` file (128 MiB) through the checked
//!   reader, level a plane, find the summits;
//! * `topography/psd_4096`: the radially averaged PSD (Hann window);
//! * `topography/generate_4096`: generate a self-affine map (portable scalar FFT).
//!
//! Run: `cargo bench -p stiction-topography --bench topography`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_topography::*;

const N: usize = 4096;

fn spec() -> GeneratorSpec {
    GeneratorSpec {
        nx: N,
        ny: N,
        pixel_size_m: 10e-9,
        rms_height_m: 5e-9,
        spectrum: Spectrum::SelfAffine {
            hurst: 0.8,
            rolloff_wavelength_m: 2e-6,
            short_cutoff_wavelength_m: None,
            long_cutoff_wavelength_m: None,
        },
        seed: 1,
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("topography");
    g.sample_size(10);
    let map = generate(&spec()).unwrap();
    let path = std::env::temp_dir().join(format!("stiction-bench-{}.npy", std::process::id()));
    std::fs::write(&path, map.to_npy_bytes(NpyDtype::F64, false)).unwrap();
    let meta = MapMetadata { pixel_size_x_m: Some(10e-9), height_unit_m: Some(1.0), ..Default::default() };
    g.bench_function("read_level_summits_4096", |b| {
        b.iter(|| {
            let (m, _) = read_file(black_box(&path), None, &meta).unwrap();
            let (p, _) = prepare(&m, &Preparation::default()).unwrap();
            find_summits(&p).len()
        })
    });
    g.bench_function("psd_4096", |b| b.iter(|| radial_psd(black_box(&map), PsdWindow::Hann).f_per_m.len()));
    drop(map);
    g.bench_function("generate_4096", |b| b.iter(|| generate(black_box(&spec())).unwrap().nx()));
    g.finish();
    std::fs::remove_file(&path).ok();
}

criterion_group!(benches, bench);
criterion_main!(benches);
