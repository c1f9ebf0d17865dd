//! Criterion benchmarks of the instrument-file readers on a 4096 x 4096 map, each against a plain
//! `std::fs::read` of the same file (the floor: the bytes must come in):
//!
//! * `formats/nanoscope_int16_4096` (32 MiB), `formats/sdf_binary_int16_4096` (32 MiB),
//!   `formats/ibw_float32_4096` (64 MiB), `formats/metropro_int32_4096` (Zygo, 64 MiB),
//!   `formats/plu_float32_4096` (Sensofar, 64 MiB): `read_file` (detection, header, decoding into a map of
//!   float64 metres, the checks of every height);
//! * `formats/fs_read_*`: `std::fs::read` of the same file;
//! * `formats/write_f64_4096`, `formats/write_f64_huge_pages_4096`: only writing a new vector of
//!   4096^2 float64 (128 MiB, four times an int16 file's samples), in 4 KiB pages and with huge
//!   pages asked for (`stiction_units::io::advise_huge_pages`): the floor of any reader that hands
//!   over float64;
//! * `formats/fs_read_then_widen_int16_4096`: `std::fs::read` and each int16 sample widened into a
//!   new float64 vector (the whole-file route without header or checks).
//!
//! The baseline, "a plain read", is `std::fs::read` of the same file, which is in the page cache
//! (each file is read once before it is timed): a new vector of the file's size, filled by the
//! kernel's copy from the page cache. `read_file` is the whole read of a map as the command line
//! does it (`stiction topography FILE` calls `read_file_channel`).
//!
//! Run: `cargo bench -p stiction-topography --bench formats`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_topography::*;

#[path = "../tests/support/synth.rs"]
mod synth;

const N: usize = 4096;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("formats");
    g.sample_size(10);
    let dir = std::env::temp_dir().join(format!("stiction-bench-formats-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ints: Vec<i32> = (0..N * N).map(|k| ((k as i64 * 7919) % 60001 - 30000) as i32).collect();
    let files = [
        ("nanoscope_int16_4096", "map.spm", synth::nanoscope(N, N, 40960.0, 20.0, 10.0, 2, &ints)),
        (
            "sdf_binary_int16_4096",
            "map.sdf",
            synth::sdf_binary(N, N, 1e-8, 1e-8, 1e-11, &ints.iter().map(|&v| v as i16).collect::<Vec<_>>()),
        ),
        (
            "ibw_float32_4096",
            "map.ibw",
            synth::ibw(
                N,
                N,
                1,
                1e-8,
                "m",
                "m",
                &["Height"],
                &ints.iter().map(|&v| v as f32 * 1e-12).collect::<Vec<_>>(),
            ),
        ),
        ("metropro_int32_4096", "map.dat", synth::metropro(N, N, 1e-8, &ints)),
        (
            "plu_float32_4096",
            "map.plu",
            synth::plu(N, N, 0.01, &ints.iter().map(|&v| Some(v as f32 * 1e-6)).collect::<Vec<_>>()),
        ),
    ];
    drop(ints);
    let meta = MapMetadata::default();
    for (name, file, bytes) in files {
        let path = dir.join(file);
        std::fs::write(&path, &bytes).unwrap();
        drop(bytes);
        let (m, _) = read_file(&path, None, &meta).unwrap();
        assert_eq!((m.nx(), m.ny()), (N, N));
        drop(m);
        g.bench_function(name, |b| b.iter(|| read_file(black_box(&path), None, &meta).unwrap().0.nx()));
        g.bench_function(format!("fs_read_{name}"), |b| b.iter(|| std::fs::read(black_box(&path)).unwrap().len()));
        if name.starts_with("nanoscope") {
            // The floors of any reader that hands over float64: only writing a new 128 MiB vector
            // of N x N values (no file), in 4 KiB pages and with huge pages asked for; and the
            // whole-file route of before: read the bytes, then widen every int16 sample into a new
            // vector (no header, no checks).
            g.bench_function("write_f64_4096", |b| {
                b.iter(|| {
                    let mut v: Vec<f64> = Vec::with_capacity(N * N);
                    v.extend((0..N * N).map(|k| k as f64));
                    black_box(v).len()
                })
            });
            g.bench_function("write_f64_huge_pages_4096", |b| {
                b.iter(|| {
                    let mut v: Vec<f64> = Vec::with_capacity(N * N);
                    stiction_units::io::advise_huge_pages(v.spare_capacity_mut());
                    v.extend((0..N * N).map(|k| k as f64));
                    black_box(v).len()
                })
            });
            g.bench_function("fs_read_then_widen_int16_4096", |b| {
                b.iter(|| {
                    let bytes = std::fs::read(black_box(&path)).unwrap();
                    let v: Vec<f64> =
                        bytes[8192..].chunks_exact(2).map(|c| f64::from(i16::from_le_bytes([c[0], c[1]]))).collect();
                    v.len()
                })
            });
        }
        std::fs::remove_file(&path).ok();
    }
    g.finish();
    std::fs::remove_dir_all(&dir).ok();
}

criterion_group!(benches, bench);
criterion_main!(benches);
